//! What a registered sampler is: the types of the facts each sampler's own file declares about
//! itself ([`Entry`], the counts it accepts ([`CountRule`]), its [`Rates`], its [`Family`], the
//! parameters it takes ([`ParameterSpec`]), the [`Params`] it is built from).
//!
//! A leaf of the crate: it imports no sampler and not the registry, only the error type, the
//! sampler traits and `alloc`, so every sampler can declare its entry here without `std`, and
//! `crate::registry` (the list of entries and the lookup by name) sits above the samplers. Its
//! items are public as `strata_lab::registry::*` (and `strata::counts::MAX_FIXED_COUNT`,
//! `strata_lab::samplers::oa::MAX_PRIME_POWER`).

use core::fmt;

use crate::counts::CountRule;
use crate::{Error, Result};
use strata::{Sampler, SamplerNd, Seed};

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
    fn progression(&self) -> strata::Progression {
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
                let mut buffer = [[0.0f32; 2]; 256];
                for chunk in out.chunks_mut(2 * buffer.len()) {
                    let points = &mut buffer[..chunk.len() / 2];
                    Sampler::fill(&mut **s, points);
                    for (o, p) in chunk.chunks_exact_mut(2).zip(points.iter()) {
                        o[0] = p[0];
                        o[1] = p[1];
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
    fn projection_strata(&self, x: u32, y: u32) -> Option<strata::StrataGrid> {
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
    /// Whether the points depend on the seed (false for `regular`, whose cell centres do not:
    /// independent replicates of it are all the same set).
    pub seeded: bool,
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
    /// The fields most entries share, for `..Entry::DEFAULT`: fixed-count, seeded, no
    /// parameters, no published rates, not expensive, not blue noise, 2D only. Each entry writes
    /// its own name, description, paper, family, counts, promise and build (the registry's
    /// tests check that none keeps the empty texts or the construction of this value).
    pub(crate) const DEFAULT: Entry = Entry {
        name: "",
        description: "",
        paper: "",
        family: Family::Classic,
        progressive: false,
        seeded: true,
        counts: CountRule::Any,
        parameters: &[],
        promise: "",
        rates: Rates::NONE,
        expensive: false,
        blue_noise: None,
        any_dims: false,
        build: |_| {
            Err(Error::input(
                "Entry::DEFAULT",
                "no construction: an entry writes its own build",
            ))
        },
    };

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
/// use strata::Seed;
/// use strata_lab::registry::{self, Params};
/// let p = Params::new(256).seed(Seed(3)).with("radius", 0.7);
/// assert_eq!(p.get("radius"), Some(0.7));
/// let s = registry::build("poisson", &p)?; // strict: poisson takes a radius
/// assert!(registry::build("jittered", &p).is_err()); // jittered takes none
/// let jittered = registry::find("jittered")?;
/// let lenient = p.kept_for(jittered); // the lenient build drops it
/// assert!(jittered.build(&lenient).is_ok());
/// # let _ = s;
/// # Ok::<(), strata_lab::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Samples per set for fixed-count samplers; the intended count for progressive ones.
    pub count: u64,
    /// Seed of all randomness (default [`Seed::default()`]).
    pub seed: Seed,
    /// Coordinates per point (default 2); samplers with D dimensions read it, the others
    /// accept only 2.
    pub dims: u32,
    /// The parameters given, by name, in the order they were set (each name once).
    values: Vec<(String, f64)>,
}

impl Params {
    /// `count` samples, the default seed, 2 dimensions, no optional parameters.
    pub fn new(count: u64) -> Self {
        Params {
            count,
            seed: Seed::default(),
            dims: 2,
            values: Vec::new(),
        }
    }

    /// The same with another seed.
    pub fn seed(mut self, seed: Seed) -> Self {
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
}
