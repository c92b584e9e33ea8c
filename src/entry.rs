//! What a registered sampler is: the types of the facts each sampler's own file declares about
//! itself ([`Entry`], the counts it accepts ([`CountRule`]), its [`Rates`], its [`Family`], the
//! parameters it takes ([`ParameterSpec`]), the [`Params`] it is built from), and the count
//! arithmetic those need (squares, powers of two, Fibonacci numbers, the `q^t` of an orthogonal
//! array, [`MAX_FIXED_COUNT`]).
//!
//! A leaf of the crate: it imports no sampler and not the registry, only the error type, the
//! sampler traits and `alloc`, so every sampler can declare its entry here without `std`, and
//! `crate::registry` (the list of entries and the lookup by name) sits above the samplers. Its
//! items are public as `strata::registry::*` (and `strata::samplers::MAX_FIXED_COUNT`,
//! `strata::samplers::oa::MAX_PRIME_POWER`).

use core::fmt;

use crate::error::{Error, Result, nearest_squares};
use crate::prelude::*;
use crate::sampler::{Sampler, SamplerNd, Seed};

/// The largest count a fixed-count sampler accepts (`2^31`: indices within a block, and the
/// `m n` fine strata of a multi-jittered grid, stay 32-bit). Far beyond what a set built in
/// advance is useful for; progressive samplers go further.
pub const MAX_FIXED_COUNT: u64 = 1 << 31;

/// The families of samplers, as the lecture groups them (one panel each in `tradeoff`'s plots).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Family {
    /// Random, regular, jittered, N-rooks, multi-jittered.
    Classic,
    /// Progressive multi-jittered sequences.
    Pmj,
    /// Poisson disk, best candidate, relaxation, blue-noise nets.
    BlueNoise,
    /// Low-discrepancy sequences and lattices.
    Qmc,
    /// Patterns stratified in D dimensions at once (Latin hypercube, orthogonal arrays).
    Multidim,
}

impl Family {
    /// Every family, in display order.
    pub const ALL: [Family; 5] = [
        Family::Classic,
        Family::Pmj,
        Family::BlueNoise,
        Family::Qmc,
        Family::Multidim,
    ];

    /// A short display name.
    pub fn name(&self) -> &'static str {
        match self {
            Family::Classic => "classic",
            Family::Pmj => "PMJ",
            Family::BlueNoise => "blue noise",
            Family::Qmc => "QMC",
            Family::Multidim => "D-dimensional",
        }
    }
}

/// The kind of value a [`ParameterSpec`] takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Kind {
    /// A whole number (at most `u32::MAX`).
    Whole,
    /// A real number.
    Real,
}

impl Kind {
    /// `"whole number"` or `"number"`, for help texts and errors.
    pub fn name(&self) -> &'static str {
        match self {
            Kind::Whole => "whole number",
            Kind::Real => "number",
        }
    }
}

/// One end of a parameter's range.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Bound {
    /// The end itself is allowed.
    Closed(f64),
    /// Values up to (or from) the end, the end itself excluded.
    Open(f64),
}

impl Bound {
    fn value(&self) -> f64 {
        match *self {
            Bound::Closed(v) | Bound::Open(v) => v,
        }
    }
}

/// A parameter a sampler takes beyond the count and the seed, declared once, in the sampler's
/// own file: its name, kind, range, default and help line. Everything else reads it from
/// there: [`Entry::build`] checks values against it, the example programs take a `--NAME`
/// flag for every declared name and list them in `--help`, the Python binding checks its
/// keyword arguments with it, and the parameter table of `docs/cli.md`
/// ([`crate::registry::parameter_table`]) is written from it.
///
/// Several samplers may take a parameter of the same name (`iterations`), each with its own
/// range and default; the kind of one name is the same everywhere (a registry test checks).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ParameterSpec {
    /// The name: `--NAME` in the programs, `NAME=` in Python, and in error messages.
    pub name: &'static str,
    /// Whole or real.
    pub kind: Kind,
    /// The smallest value allowed.
    pub min: Bound,
    /// The largest value allowed.
    pub max: Bound,
    /// The value used when none is given.
    pub default: f64,
    /// One line: what it does.
    pub help: &'static str,
    /// A limit the range cannot express, which the sampler checks when it is built (`""`
    /// when there is none).
    pub note: &'static str,
    /// An older name accepted for the same parameter (`""` when there is none): read only
    /// when the name itself is not given.
    pub alias: &'static str,
}

impl ParameterSpec {
    /// A whole-number parameter in `min ..= max`.
    pub const fn whole(
        name: &'static str,
        min: u32,
        max: u32,
        default: u32,
        help: &'static str,
    ) -> Self {
        ParameterSpec {
            name,
            kind: Kind::Whole,
            min: Bound::Closed(min as f64),
            max: Bound::Closed(max as f64),
            default: default as f64,
            help,
            note: "",
            alias: "",
        }
    }

    /// A real parameter between `min` and `max`.
    pub const fn real(
        name: &'static str,
        min: Bound,
        max: Bound,
        default: f64,
        help: &'static str,
    ) -> Self {
        ParameterSpec {
            name,
            kind: Kind::Real,
            min,
            max,
            default,
            help,
            note: "",
            alias: "",
        }
    }

    /// The same with a limit the range cannot express (see [`ParameterSpec::note`]).
    pub const fn with_note(mut self, note: &'static str) -> Self {
        self.note = note;
        self
    }

    /// The same, also accepting the older name `alias` (see [`ParameterSpec::alias`]).
    pub const fn with_alias(mut self, alias: &'static str) -> Self {
        self.alias = alias;
        self
    }

    /// True when `name` is this parameter's name or its alias.
    pub fn is_named(&self, name: &str) -> bool {
        self.name == name || (!self.alias.is_empty() && self.alias == name)
    }

    /// What is allowed, in words: `"1 to 100000"`, `"0 < radius <= 0.78"`, and the note.
    pub fn allowed(&self) -> String {
        let (lo, hi) = (self.min.value(), self.max.value());
        let mut s = match (self.kind, self.min, self.max) {
            (Kind::Whole, _, _) => format!("{lo} to {hi}"),
            (Kind::Real, Bound::Closed(_), Bound::Closed(_)) => format!("{lo} to {hi}"),
            (Kind::Real, min, max) => {
                let op = |b: Bound| {
                    if matches!(b, Bound::Open(_)) {
                        "<"
                    } else {
                        "<="
                    }
                };
                format!("{lo} {} {} {} {hi}", op(min), self.name, op(max))
            }
        };
        if !self.note.is_empty() {
            s.push_str(", ");
            s.push_str(self.note);
        }
        s
    }

    /// True when `value` is of the parameter's kind and within its range.
    pub fn allows(&self, value: f64) -> bool {
        let above = match self.min {
            Bound::Closed(m) => value >= m,
            Bound::Open(m) => value > m,
        };
        let below = match self.max {
            Bound::Closed(m) => value <= m,
            Bound::Open(m) => value < m,
        };
        let kind = match self.kind {
            Kind::Whole => value == (value as i64) as f64,
            Kind::Real => value.is_finite(),
        };
        above && below && kind
    }

    /// `value` if [`allows`](ParameterSpec::allows) it, else an error naming `sampler`, the
    /// parameter, the value and what is allowed.
    pub fn check(&self, sampler: &'static str, value: f64) -> Result<f64> {
        if self.allows(value) {
            Ok(value)
        } else {
            Err(Error::parameter(
                sampler,
                self.name,
                value,
                format!("{} {}", self.kind.name(), self.allowed()),
            ))
        }
    }

    /// The value `params` gives this parameter, or its default.
    pub fn read(&self, params: &Params) -> f64 {
        params
            .get(self.name)
            .or_else(|| {
                (!self.alias.is_empty())
                    .then(|| params.get(self.alias))
                    .flatten()
            })
            .unwrap_or(self.default)
    }

    /// [`read`](ParameterSpec::read) as a whole number (saturating; the value was checked
    /// against the range when the sampler was built through its entry).
    pub fn read_whole(&self, params: &Params) -> u32 {
        self.read(params) as u32
    }
}

/// Which sample counts a sampler accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CountRule {
    /// Any count `>= 1`.
    Any,
    /// Perfect squares `s^2`.
    Square,
    /// `q^t` for a prime `q` or a prime power `q <= 256` (orthogonal arrays of strength `t`).
    OaPower(u32),
    /// Fibonacci numbers `1, 2, 3, 5, 8, ...` (Fibonacci lattices).
    Fibonacci,
    /// Powers of two `2^m` (digital nets).
    PowerOfTwo,
}

impl CountRule {
    /// Whether `n` is allowed.
    pub fn allows(&self, n: u64) -> bool {
        match self {
            CountRule::Any => n >= 1,
            CountRule::Square => n >= 1 && n.isqrt().pow(2) == n,
            CountRule::OaPower(t) => oa_root(n, *t).is_some(),
            CountRule::Fibonacci => fibonacci_numbers().any(|f| f == n),
            CountRule::PowerOfTwo => n.is_power_of_two(),
        }
    }

    /// Checks a fixed-count sampler's count (also at most [`MAX_FIXED_COUNT`]): the count as
    /// `u32`, or an error naming `sampler` and the nearest allowed counts. Every fixed-count
    /// constructor checks its count through its entry's rule.
    pub fn check(&self, sampler: &'static str, count: u64) -> Result<u32> {
        if let CountRule::OaPower(t) = self {
            let q = check_oa_count(sampler, count, *t)?;
            return Ok(q.pow(*t));
        }
        if count == 0 || count > MAX_FIXED_COUNT {
            return Err(Error::count(
                sampler,
                count,
                format!("the count must be between 1 and {MAX_FIXED_COUNT}"),
            ));
        }
        if !self.allows(count) {
            let allowed = match self {
                CountRule::Square => format!(
                    "the count must be a perfect square (nearest allowed: {})",
                    nearest_squares(count)
                ),
                other => format!(
                    "allowed counts: {other} (nearest: {})",
                    other.nearest(count)
                ),
            };
            return Err(Error::count(sampler, count, allowed));
        }
        Ok(count as u32)
    }

    /// The allowed count nearest to `n` (the smaller one on a tie): a count [`check`] accepts,
    /// so at least 1 and at most [`MAX_FIXED_COUNT`], for every `n`.
    ///
    /// [`check`]: CountRule::check
    pub fn nearest(&self, n: u64) -> u64 {
        let n = n.clamp(1, MAX_FIXED_COUNT);
        match self {
            CountRule::Any => n,
            CountRule::Square => {
                let r = n.isqrt();
                let (lo, hi) = (r * r, (r + 1) * (r + 1));
                if hi > MAX_FIXED_COUNT || (lo >= 1 && n - lo <= hi - n) {
                    lo
                } else {
                    hi
                }
            }
            CountRule::OaPower(_) => {
                let all = self.counts_between(1, n.saturating_mul(4).max(1 << 12));
                all.into_iter().min_by_key(|&c| c.abs_diff(n)).unwrap_or(4)
            }
            CountRule::Fibonacci => fibonacci_numbers()
                .min_by_key(|&f| f.abs_diff(n))
                .unwrap_or(1),
            CountRule::PowerOfTwo => {
                let lo = 1u64 << (63 - n.leading_zeros());
                if n - lo <= lo || lo << 1 > MAX_FIXED_COUNT {
                    lo
                } else {
                    lo << 1
                }
            }
        }
    }

    /// The allowed counts in `[min, max]`, in increasing order (none above
    /// [`MAX_FIXED_COUNT`], which [`check`](CountRule::check) refuses).
    pub fn counts_between(&self, min: u64, max: u64) -> Vec<u64> {
        let min = min.max(1);
        let max = max.min(MAX_FIXED_COUNT);
        if min > max {
            return Vec::new();
        }
        match self {
            CountRule::Any => (min..=max).collect(),
            CountRule::Square => {
                let lo = {
                    let r = min.isqrt();
                    if r * r == min { r } else { r + 1 }
                };
                (lo..=max.isqrt()).map(|s| s * s).collect()
            }
            CountRule::OaPower(t) => (2u64..)
                .map_while(|q| q.checked_pow(*t).filter(|&c| c <= max).map(|c| (q, c)))
                .filter(|&(q, c)| c >= min && supported_symbols(q as u32))
                .map(|(_, c)| c)
                .collect(),
            CountRule::Fibonacci => fibonacci_numbers()
                .filter(|&f| f >= min && f <= max)
                .collect(),
            CountRule::PowerOfTwo => (0..64)
                .map(|m| 1u64 << m)
                .filter(|&c| c >= min && c <= max)
                .collect(),
        }
    }
}

impl fmt::Display for CountRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CountRule::Any => f.write_str("any N >= 1"),
            CountRule::Square => f.write_str("perfect squares"),
            CountRule::OaPower(t) => write!(f, "q^{t}, q prime (power)"),
            CountRule::Fibonacci => f.write_str("Fibonacci numbers"),
            CountRule::PowerOfTwo => f.write_str("powers of two"),
        }
    }
}

// The count arithmetic of the rules, in integers (exact, and without `std`'s `powf`).

/// The Fibonacci numbers that fit a fixed-count set (`F_2 = 1` to below `2^31`).
pub(crate) fn fibonacci_numbers() -> impl Iterator<Item = u64> {
    core::iter::successors(Some((1u64, 2u64)), |&(a, b)| Some((b, a + b)))
        .map(|(a, _)| a)
        .take_while(|&f| f <= MAX_FIXED_COUNT)
}

/// The largest prime power (not prime) supported as the number of symbols of an orthogonal
/// array.
pub const MAX_PRIME_POWER: u32 = 256;

/// `(p, n)` when `q = p^n` with `p` prime, `n >= 1` (trial division up to `sqrt q`).
pub(crate) fn prime_power(q: u32) -> Option<(u32, u32)> {
    if q < 2 {
        return None;
    }
    let p = (2u32..)
        .take_while(|d| (*d as u64) * (*d as u64) <= q as u64)
        .find(|&d| q.is_multiple_of(d))
        .unwrap_or(q);
    let (mut m, mut n) = (q, 0);
    while m.is_multiple_of(p) {
        m /= p;
        n += 1;
    }
    (m == 1).then_some((p, n))
}

/// True when `q` is a supported number of symbols: a prime, or a prime power up to
/// [`MAX_PRIME_POWER`].
pub(crate) fn supported_symbols(q: u32) -> bool {
    prime_power(q).is_some_and(|(_, n)| n == 1 || q <= MAX_PRIME_POWER)
}

/// `floor(n^(1/t))` for `t >= 1`, exactly (bisection on `r^t <= n`).
fn root_floor(n: u64, t: u32) -> u64 {
    if t <= 1 || n < 2 {
        return n;
    }
    // r^t <= n < 2^64 gives r < 2^ceil(64/t)
    let (mut lo, mut hi) = (1u64, 1u64 << 64u32.div_ceil(t).min(63));
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if mid.checked_pow(t).is_some_and(|p| p <= n) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// `q` when `n = q^t` with a supported number of symbols `q`.
fn oa_root(n: u64, t: u32) -> Option<u64> {
    if t == 0 {
        return None;
    }
    let q = root_floor(n, t);
    let supported = u32::try_from(q).is_ok_and(supported_symbols);
    (q >= 2 && q.checked_pow(t) == Some(n) && supported).then_some(q)
}

/// The allowed symbol counts nearest to a requested sample count, for error messages: the
/// supported `q` with `q^t` just below and above `count`.
fn nearest_oa_counts(count: u64, t: u32) -> String {
    let supported = supported_symbols;
    let floor = root_floor(count, t);
    let ceil = if floor.checked_pow(t) == Some(count) {
        floor
    } else {
        floor + 1
    };
    let below = (2..=floor.max(2) as u32 + 1)
        .rev()
        .find(|&q| supported(q) && (q as u64).pow(t) <= count);
    let above = (ceil.max(2) as u32..).find(|&q| supported(q) && (q as u64).pow(t) >= count);
    match (below, above) {
        (Some(b), Some(a)) if b != a => format!(
            "{} ({b}^{t}) or {} ({a}^{t})",
            (b as u64).pow(t),
            (a as u64).pow(t)
        ),
        (_, Some(a)) => format!("{} ({a}^{t})", (a as u64).pow(t)),
        _ => "none".into(),
    }
}

/// Checks `count = q^t` for a supported `q`, returning `q` (the orthogonal arrays' check,
/// [`CountRule::OaPower`]).
pub(crate) fn check_oa_count(name: &'static str, count: u64, t: u32) -> Result<u32> {
    let rule = || {
        format!(
            "the count must be q^{t} for a prime q, or a prime power q <= {MAX_PRIME_POWER}, at most {MAX_FIXED_COUNT}"
        )
    };
    if count > MAX_FIXED_COUNT {
        // no search for the nearest counts up there: say the rule and the largest
        let largest = nearest_oa_counts(MAX_FIXED_COUNT, t);
        return Err(Error::count(
            name,
            count,
            format!("{} (the largest allowed are about {largest})", rule()),
        ));
    }
    match oa_root(count, t) {
        Some(q) if count >= 4 => Ok(q as u32),
        _ => Err(Error::count(
            name,
            count,
            format!(
                "{} (nearest allowed: {})",
                rule(),
                nearest_oa_counts(count, t)
            ),
        )),
    }
}

/// Published convergence rates: the exponent `r` in `variance ~ N^r` of the estimate of a 2D
/// integral, where a published rate exists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Rates {
    /// Integrands with discontinuities.
    pub discontinuous: Option<f64>,
    /// Smooth integrands.
    pub smooth: Option<f64>,
    /// Integrals of more than two dimensions.
    pub higher: Option<f64>,
}

impl Rates {
    /// The rate of random sampling everywhere.
    pub const RANDOM: Rates = Rates {
        discontinuous: Some(-1.0),
        smooth: Some(-1.0),
        higher: Some(-1.0),
    };
    /// No published rate.
    pub const NONE: Rates = Rates {
        discontinuous: None,
        smooth: None,
        higher: None,
    };
    /// Owen-scrambled (0,m,2)-nets (Owen 1997; Christensen et al. 2018).
    pub const NETS: Rates = Rates {
        discontinuous: Some(-1.5),
        smooth: Some(-3.0),
        higher: None,
    };

    fn cell(r: Option<f64>) -> String {
        r.map_or("-".to_string(), |r| format!("N^{r}"))
    }
}

/// What a blue-noise sampler's paper reports about the spacing of its point sets (the
/// published figures that `spectrum --blue-noise-table` sets beside its own measurements).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct BlueNoise {
    /// The figure with its reference (paper, year, table or figure, the count it was reported
    /// at, and whether it was checked against the paper), or why there is none: `"not
    /// reported"` when the paper has no such figure. Never a number that was not published.
    pub published: &'static str,
}

impl BlueNoise {
    /// A blue-noise sampler whose paper reports no spacing figure.
    pub const NOT_REPORTED: BlueNoise = BlueNoise {
        published: "not reported",
    };

    /// A blue-noise sampler with a published figure (or a note on why there is none).
    pub const fn published(text: &'static str) -> BlueNoise {
        BlueNoise { published: text }
    }
}

/// Builds a sampler from parameters (their dimension count included).
pub(crate) type Build = fn(&Params) -> Result<Built>;

/// A sampler built from its registry entry: 2D when [`Params::dims`] is 2 (the [`Sampler`]
/// the 2D tools use, with its strata), D-dimensional otherwise. Either way it is a
/// [`SamplerNd`], so a caller that wants points of any dimension count needs no `match`.
#[derive(Debug)]
#[non_exhaustive]
pub enum Built {
    /// A 2D sampler.
    Two(Box<dyn Sampler>),
    /// A D-dimensional sampler.
    Nd(Box<dyn SamplerNd>),
}

impl Built {
    /// A 2D sampler, boxed.
    pub fn two(sampler: impl Sampler + 'static) -> Built {
        Built::Two(Box::new(sampler))
    }

    /// A D-dimensional sampler, boxed.
    pub fn nd(sampler: impl SamplerNd + 'static) -> Built {
        Built::Nd(Box::new(sampler))
    }

    /// The 2D sampler, or `None` for a D-dimensional one.
    pub fn into_2d(self) -> Option<Box<dyn Sampler>> {
        match self {
            Built::Two(s) => Some(s),
            Built::Nd(_) => None,
        }
    }

    /// The sampler as a D-dimensional one (a 2D sampler has `D = 2`).
    pub fn into_nd(self) -> Box<dyn SamplerNd> {
        match self {
            Built::Two(s) => Box::new(s),
            Built::Nd(s) => s,
        }
    }
}

impl SamplerNd for Built {
    fn name(&self) -> &'static str {
        match self {
            Built::Two(s) => Sampler::name(&**s),
            Built::Nd(s) => s.name(),
        }
    }
    fn dimensions(&self) -> u32 {
        match self {
            Built::Two(_) => 2,
            Built::Nd(s) => s.dimensions(),
        }
    }
    fn progression(&self) -> crate::sampler::Progression {
        match self {
            Built::Two(s) => Sampler::progression(&**s),
            Built::Nd(s) => s.progression(),
        }
    }
    fn next_point(&mut self, out: &mut [f32]) {
        match self {
            Built::Two(s) => SamplerNd::next_point(s, out),
            Built::Nd(s) => s.next_point(out),
        }
    }
    /// A 2D sampler fills through its own (batched) [`Sampler::fill`], in chunks.
    fn fill(&mut self, out: &mut [f32]) {
        match self {
            Built::Two(s) => {
                let mut buffer = [crate::sampler::Point2::ZERO; 256];
                for chunk in out.chunks_mut(2 * buffer.len()) {
                    let points = &mut buffer[..chunk.len() / 2];
                    Sampler::fill(&mut **s, points);
                    for (o, p) in chunk.chunks_exact_mut(2).zip(points.iter()) {
                        o[0] = p.x;
                        o[1] = p.y;
                    }
                }
            }
            Built::Nd(s) => s.fill(out),
        }
    }
    fn skip(&mut self, n: u64) -> bool {
        match self {
            Built::Two(s) => Sampler::skip(&mut **s, n),
            Built::Nd(s) => s.skip(n),
        }
    }
    fn projection_strata(&self, x: u32, y: u32) -> Option<crate::sampler::StrataGrid> {
        match self {
            Built::Two(_) => None,
            Built::Nd(s) => s.projection_strata(x, y),
        }
    }
}

/// A registered sampler: what it is, what it promises, and how to build it. Each sampler's
/// file declares its own.
#[derive(Clone, Copy)]
#[non_exhaustive]
pub struct Entry {
    /// The name (`--sampler NAME`).
    pub name: &'static str,
    /// One line: what it is.
    pub description: &'static str,
    /// Where it comes from.
    pub paper: &'static str,
    /// The family it belongs to (for grouped tables and plots).
    pub family: Family,
    /// True for progressive sequences, false for fixed-count sets.
    pub progressive: bool,
    /// The counts it accepts.
    pub counts: CountRule,
    /// The optional parameters it takes.
    pub parameters: &'static [ParameterSpec],
    /// The stratification it promises, in a few words.
    pub promise: &'static str,
    /// Published convergence rates.
    pub rates: Rates,
    /// True when generating a set takes long (relaxation, optimisation): tools use fewer
    /// realizations by default.
    pub expensive: bool,
    /// For blue-noise samplers (whatever their family), what their paper reports about the
    /// spacing of its sets; `None` for the samplers that are not blue noise.
    pub blue_noise: Option<BlueNoise>,
    /// True when the sampler has points of any dimension count (its build reads
    /// [`Params::dims`]); false for 2D-only samplers.
    pub(crate) any_dims: bool,
    pub(crate) build: Build,
}

impl fmt::Debug for Entry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Entry")
            .field("name", &self.name)
            .field("progressive", &self.progressive)
            .field("counts", &self.counts)
            .finish_non_exhaustive()
    }
}

impl Entry {
    /// The declaration of the parameter named `name`, for samplers that take it.
    pub fn parameter(&self, name: &str) -> Option<&'static ParameterSpec> {
        self.parameters.iter().find(|p| p.is_named(name))
    }

    /// The default of the parameter named `name` (for samplers that take it).
    pub fn default_of(&self, name: &str) -> Option<f64> {
        self.parameter(name).map(|p| p.default)
    }

    /// True when the sampler takes the parameter named `name`.
    pub fn takes(&self, name: &str) -> bool {
        self.parameter(name).is_some()
    }

    /// True for the blue-noise samplers: every sampler of [`Family::BlueNoise`] and the
    /// blue-noise variants of other families (`pmjbn`, `pmj02bn`).
    pub fn is_blue_noise(&self) -> bool {
        self.blue_noise.is_some()
    }

    /// True when the sampler has points of more than 2 dimensions.
    pub fn has_dimensions(&self) -> bool {
        self.any_dims
    }

    /// The entry's row of the samplers table (`registry::table` puts them together).
    pub(crate) fn row(&self) -> String {
        let kind = if self.progressive {
            "progressive".to_string()
        } else {
            format!("fixed, {}", self.counts)
        };
        let dims = if self.has_dimensions() { "D" } else { "2" };
        format!(
            "| `{}` | {kind} | {dims} | {} | {} / {} | {} |",
            self.name,
            self.promise,
            Rates::cell(self.rates.discontinuous),
            Rates::cell(self.rates.smooth),
            self.paper
        )
    }
}

/// What a sampler is built from: the count, the seed, the dimension count, and the values of
/// the optional parameters its entry declares ([`ParameterSpec`]), by name.
///
/// ```
/// use strata::registry::{self, Params};
/// let p = Params::new(256).seed(3).with("radius", 0.7);
/// assert_eq!(p.get("radius"), Some(0.7));
/// let s = registry::build("poisson", &p)?; // strict: poisson takes a radius
/// assert!(registry::build("jittered", &p).is_err()); // jittered takes none
/// let jittered = registry::find("jittered")?;
/// let lenient = p.kept_for(jittered); // the lenient build drops it
/// assert!(jittered.build(&lenient).is_ok());
/// # let _ = s;
/// # Ok::<(), strata::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Samples per set for fixed-count samplers; the intended count for progressive ones.
    pub count: u64,
    /// Seed of all randomness (default 1, as in the example programs).
    pub seed: u64,
    /// Coordinates per point (default 2); samplers with D dimensions read it, the others
    /// accept only 2.
    pub dims: u32,
    /// The parameters given, by name, in the order they were set (each name once).
    values: Vec<(String, f64)>,
}

impl Params {
    /// `count` samples, seed 1, 2 dimensions, no optional parameters.
    pub fn new(count: u64) -> Self {
        Params {
            count,
            seed: 1,
            dims: 2,
            values: Vec::new(),
        }
    }

    /// The same with another seed.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// The same with `dims` coordinates per point.
    pub fn dims(mut self, dims: u32) -> Self {
        self.dims = dims;
        self
    }

    /// The same with the parameter `name` set to `value` (replacing an earlier value).
    pub fn with(mut self, name: &str, value: f64) -> Self {
        self.set(name, value);
        self
    }

    /// Sets the parameter `name` to `value` (replacing an earlier value).
    pub fn set(&mut self, name: &str, value: f64) {
        match self.values.iter_mut().find(|(n, _)| n == name) {
            Some(slot) => slot.1 = value,
            None => self.values.push((name.to_string(), value)),
        }
    }

    /// Removes the parameter `name`, if it was set.
    pub fn unset(&mut self, name: &str) {
        self.values.retain(|(n, _)| n != name);
    }

    /// The value given to the parameter `name`, if any.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.values.iter().find(|(n, _)| n == name).map(|&(_, v)| v)
    }

    /// The parameters given, by name, in the order they were first set.
    pub fn given(&self) -> impl Iterator<Item = (&str, f64)> + '_ {
        self.values.iter().map(|(n, v)| (n.as_str(), *v))
    }

    /// The lenient form for `entry`: the same without the parameters `entry` does not take
    /// (what the programs do when one set of flags serves many samplers; the strict
    /// [`Entry::build`] refuses them instead).
    pub fn kept_for(&self, entry: &Entry) -> Params {
        let mut p = self.clone();
        p.values.retain(|(n, _)| entry.takes(n));
        p
    }

    /// The seed, as the samplers take it.
    pub fn sampler_seed(&self) -> Seed {
        Seed(self.seed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_rules_list_allowed_counts() {
        assert_eq!(CountRule::Square.counts_between(2, 30), vec![4, 9, 16, 25]);
        assert_eq!(CountRule::Square.counts_between(16, 16), vec![16]);
        assert_eq!(CountRule::Any.counts_between(0, 3), vec![1, 2, 3]);
        assert!(CountRule::Square.counts_between(17, 24).is_empty());
        assert_eq!(CountRule::Square.nearest(1000), 1024);
        assert_eq!(CountRule::Square.nearest(12), 9);
        assert_eq!(CountRule::Square.nearest(0), 1);
        assert_eq!(CountRule::Any.nearest(7), 7);
        assert!(CountRule::Square.check("jittered", 10).is_err());
        assert_eq!(CountRule::Square.check("jittered", 9).unwrap(), 9);
        let f: Vec<u64> = fibonacci_numbers().take(10).collect();
        assert_eq!(f, [1, 2, 3, 5, 8, 13, 21, 34, 55, 89]);
        assert_eq!(CountRule::OaPower(3).counts_between(60, 130), vec![64, 125]);
    }

    #[test]
    fn integer_roots_are_exact() {
        let edges = [
            u32::MAX as u64,
            MAX_FIXED_COUNT,
            1 << 53,
            (1 << 53) + 1,
            u64::MAX - 1,
            u64::MAX,
        ];
        for t in 1..=70u32 {
            for n in (0..3000u64).chain(edges) {
                let r = root_floor(n, t);
                assert!(
                    r.checked_pow(t).is_some_and(|p| p <= n),
                    "{n}^(1/{t}) = {r}"
                );
                let above = r.checked_add(1).and_then(|r| r.checked_pow(t));
                assert!(above.is_none_or(|p| p > n), "{n}^(1/{t}) = {r}");
            }
        }
        for t in 2..=16u32 {
            for q in [2u64, 3, 5, 255, 256, 65521, 4_294_967_291] {
                if let Some(n) = q.checked_pow(t) {
                    assert_eq!(root_floor(n, t), q);
                    assert_eq!(root_floor(n - 1, t), q - 1);
                }
            }
        }
    }

    #[test]
    fn the_oa_rule_is_the_rounded_float_root_it_replaced() {
        // the rule as it was computed before it moved here, with `powf` (tests have `std`):
        // the same answer on every count next to a power, for every strength the arrays take
        let float_root = |n: u64, t: u32| (n as f64).powf(1.0 / t as f64).round() as u64;
        for t in 2..=16u32 {
            for q in 2u64.. {
                let Some(c) = q.checked_pow(t).filter(|&c| c <= MAX_FIXED_COUNT + 1) else {
                    break;
                };
                for n in [c - 1, c, c + 1] {
                    let q = float_root(n, t);
                    let old = q >= 2 && q.checked_pow(t) == Some(n) && supported_symbols(q as u32);
                    assert_eq!(oa_root(n, t).is_some(), old, "{n} = q^{t}");
                    if old && n >= 4 {
                        assert_eq!(check_oa_count("x", n, t).unwrap() as u64, q);
                    }
                }
            }
        }
    }
}
