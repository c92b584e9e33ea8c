//! What a registered sampler is: the facts each sampler's own file declares about itself.

use std::fmt;

use crate::analysis::Integrand;
use crate::error::{Error, Result};
use crate::sampler::{Sampler, SamplerNd};
use crate::samplers::MAX_FIXED_COUNT;

/// An optional parameter a sampler may take (beyond the count and the seed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Parameter {
    /// Relative Poisson-disk radius (`--radius`).
    Radius,
    /// Relaxation iterations (`--iterations`).
    Iterations,
    /// Orthogonal-array strength (`--strength`).
    Strength,
    /// Best-candidate count (`--candidates`).
    Candidates,
    /// Discrete points per CCVT site (`--capacity`).
    Capacity,
}

impl Parameter {
    /// The name used on the command line and in error messages.
    pub fn name(&self) -> &'static str {
        match self {
            Parameter::Radius => "radius",
            Parameter::Iterations => "iterations",
            Parameter::Strength => "strength",
            Parameter::Candidates => "candidates",
            Parameter::Capacity => "capacity",
        }
    }
}

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

/// A parameter a sampler takes, with its default and what is allowed.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ParameterSpec {
    /// Which parameter.
    pub parameter: Parameter,
    /// The value used when none is given.
    pub default: f64,
    /// What is allowed, for help texts and tables.
    pub allowed: &'static str,
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
            CountRule::Fibonacci => crate::samplers::lattice::fibonacci_numbers().any(|f| f == n),
            CountRule::PowerOfTwo => n.is_power_of_two(),
        }
    }

    /// Checks a fixed-count sampler's count (also at most [`MAX_FIXED_COUNT`]): the count as
    /// `u32`, or an error naming `sampler` and the nearest allowed counts. Every fixed-count
    /// constructor checks its count through its entry's rule.
    pub fn check(&self, sampler: &'static str, count: u64) -> Result<u32> {
        if let CountRule::OaPower(t) = self {
            let q = crate::samplers::oa::check_oa_count(sampler, count, *t)?;
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
                    crate::error::nearest_squares(count)
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
            CountRule::Fibonacci => crate::samplers::lattice::fibonacci_numbers()
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
                .filter(|&(q, c)| c >= min && crate::samplers::oa::supported_symbols(q as u32))
                .map(|(_, c)| c)
                .collect(),
            CountRule::Fibonacci => crate::samplers::lattice::fibonacci_numbers()
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

/// `q` when `n = q^t` with a supported number of symbols `q`.
fn oa_root(n: u64, t: u32) -> Option<u64> {
    let q = (n as f64).powf(1.0 / t as f64).round() as u64;
    (q >= 2 && q.checked_pow(t) == Some(n) && crate::samplers::oa::supported_symbols(q as u32))
        .then_some(q)
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

    /// The rate on `integrand`, if published.
    pub fn on(&self, integrand: Integrand) -> Option<f64> {
        if integrand.dimensions() != 2 {
            self.higher
        } else if integrand.smooth() {
            self.smooth
        } else {
            self.discontinuous
        }
    }

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

/// Builds a sampler from parameters.
pub(crate) type Build = fn(&Params) -> Result<Box<dyn Sampler>>;
/// Builds a D-dimensional sampler from parameters and `D`.
pub(crate) type BuildNd = fn(&Params, u32) -> Result<Box<dyn SamplerNd>>;

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
    pub(crate) build: Build,
    pub(crate) nd: Option<BuildNd>,
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
    /// Builds the sampler, after checking that every optional parameter given is one it takes.
    pub fn build(&self, params: &Params) -> Result<Box<dyn Sampler>> {
        self.check_params(params)?;
        (self.build)(params)
    }

    /// The default of `parameter` (for samplers that take it).
    pub fn default_of(&self, parameter: Parameter) -> Option<f64> {
        self.parameters
            .iter()
            .find(|p| p.parameter == parameter)
            .map(|p| p.default)
    }

    /// True when the sampler takes `parameter`.
    pub fn takes(&self, parameter: Parameter) -> bool {
        self.default_of(parameter).is_some()
    }

    /// The checks common to both forms: every optional parameter given is one this sampler
    /// takes, and the count is not 0.
    fn check_params(&self, params: &Params) -> Result<()> {
        for (p, value) in params.given() {
            if !self.takes(p) {
                let takers: Vec<&str> = super::entries()
                    .iter()
                    .filter(|e| e.takes(p))
                    .map(|e| e.name)
                    .collect();
                let allowed = format!(
                    "{} takes no {}; samplers that do: {}",
                    self.name,
                    p.name(),
                    takers.join(", ")
                );
                return Err(Error::parameter(self.name, p.name(), value, allowed));
            }
        }
        if params.count == 0 {
            return Err(Error::count(
                self.name,
                0,
                format!("allowed counts: {}", self.counts),
            ));
        }
        Ok(())
    }

    /// True for the blue-noise samplers: every sampler of [`Family::BlueNoise`] and the
    /// blue-noise variants of other families (`pmjbn`, `pmj02bn`).
    pub fn is_blue_noise(&self) -> bool {
        self.blue_noise.is_some()
    }

    /// True when the sampler has points of more than 2 dimensions.
    pub fn has_dimensions(&self) -> bool {
        self.nd.is_some()
    }

    /// Builds the D-dimensional sampler: the sampler's own for those that have one, the 2D
    /// sampler itself for `D = 2`; otherwise an error naming the samplers that have D dims.
    pub fn build_nd(&self, params: &Params, dims: u32) -> Result<Box<dyn SamplerNd>> {
        if dims == 0 || dims > crate::samplers::MAX_DIMENSIONS {
            return Err(Error::parameter(
                self.name,
                "dims",
                dims,
                format!("1 to {} dimensions", crate::samplers::MAX_DIMENSIONS),
            ));
        }
        match self.nd {
            Some(build) => {
                self.check_params(params)?;
                build(params, dims)
            }
            None if dims == 2 => Ok(Box::new(self.build(params)?)),
            None => {
                let takers: Vec<&str> = super::entries()
                    .iter()
                    .filter(|e| e.has_dimensions())
                    .map(|e| e.name)
                    .collect();
                Err(Error::parameter(
                    self.name,
                    "dims",
                    dims,
                    format!(
                        "{} has 2-dimensional points only; samplers with D dimensions: {}",
                        self.name,
                        takers.join(", ")
                    ),
                ))
            }
        }
    }

    /// The entry's row of the samplers table (see [`super::table`]).
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

/// What a sampler is built from: the count, the seed, and optional parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// Samples per set for fixed-count samplers; the intended count for progressive ones.
    pub count: u64,
    /// Seed of all randomness (default 1, as in the example programs).
    pub seed: u64,
    /// Relative Poisson-disk radius.
    pub radius: Option<f64>,
    /// Relaxation iterations.
    pub iterations: Option<u32>,
    /// Orthogonal-array strength.
    pub strength: Option<u32>,
    /// Best-candidate count.
    pub candidates: Option<u32>,
    /// Discrete points per CCVT site.
    pub capacity: Option<u32>,
}

impl Params {
    /// `count` samples, seed 1, no optional parameters.
    pub fn new(count: u64) -> Self {
        Params {
            count,
            seed: 1,
            radius: None,
            iterations: None,
            strength: None,
            candidates: None,
            capacity: None,
        }
    }

    /// The same with another seed.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// The seed, as the samplers take it.
    pub fn sampler_seed(&self) -> crate::Seed {
        crate::Seed(self.seed)
    }

    /// The optional parameters that are set, with their values formatted.
    pub fn given(&self) -> Vec<(Parameter, String)> {
        let mut v = Vec::new();
        if let Some(x) = self.radius {
            v.push((Parameter::Radius, x.to_string()));
        }
        if let Some(x) = self.iterations {
            v.push((Parameter::Iterations, x.to_string()));
        }
        if let Some(x) = self.strength {
            v.push((Parameter::Strength, x.to_string()));
        }
        if let Some(x) = self.candidates {
            v.push((Parameter::Candidates, x.to_string()));
        }
        if let Some(x) = self.capacity {
            v.push((Parameter::Capacity, x.to_string()));
        }
        v
    }
}
