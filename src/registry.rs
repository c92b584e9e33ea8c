//! Samplers by name, for the example programs, the benches and users' own tools.
//!
//! ```
//! use strata::registry::{self, Params};
//! let mut s = registry::build("cmj", &Params::new(100).seed(7)).unwrap();
//! let p = s.next_sample();
//! assert!(p.x < 1.0 && p.y < 1.0);
//!
//! let err = registry::build("jitter", &Params::new(16)).unwrap_err();
//! assert!(err.to_string().contains("jittered")); // the error lists the known names
//! ```

use std::fmt;

use crate::error::{Error, Result};
use crate::sampler::{Point2, Progression, Sampler, SamplerNd};
use crate::samplers;

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
}

impl Parameter {
    /// The name used on the command line and in error messages.
    pub fn name(&self) -> &'static str {
        match self {
            Parameter::Radius => "radius",
            Parameter::Iterations => "iterations",
            Parameter::Strength => "strength",
            Parameter::Candidates => "candidates",
        }
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
}

impl CountRule {
    /// Whether `n` is allowed.
    pub fn allows(&self, n: u64) -> bool {
        match self {
            CountRule::Any => n >= 1,
            CountRule::Square => n >= 1 && n.isqrt().pow(2) == n,
            CountRule::OaPower(t) => oa_root(n, *t).is_some(),
        }
    }

    /// The allowed count nearest to `n` (the smaller one on a tie), at least 1.
    pub fn nearest(&self, n: u64) -> u64 {
        let n = n.max(1);
        match self {
            CountRule::Any => n,
            CountRule::Square => {
                let r = n.isqrt();
                let (lo, hi) = (r * r, (r + 1) * (r + 1));
                if lo >= 1 && n - lo <= hi - n { lo } else { hi }
            }
            CountRule::OaPower(_) => {
                let all = self.counts_between(1, n.saturating_mul(4).max(1 << 12));
                all.into_iter().min_by_key(|&c| c.abs_diff(n)).unwrap_or(4)
            }
        }
    }

    /// The allowed counts in `[min, max]`, in increasing order.
    pub fn counts_between(&self, min: u64, max: u64) -> Vec<u64> {
        let min = min.max(1);
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
        }
    }
}

impl fmt::Display for CountRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CountRule::Any => f.write_str("any N >= 1"),
            CountRule::Square => f.write_str("perfect squares"),
            CountRule::OaPower(t) => write!(f, "q^{t}, q prime (power)"),
        }
    }
}

/// `q` when `n = q^t` with a supported number of symbols `q`.
fn oa_root(n: u64, t: u32) -> Option<u64> {
    let q = (n as f64).powf(1.0 / t as f64).round() as u64;
    (q >= 2 && q.checked_pow(t) == Some(n) && crate::samplers::oa::supported_symbols(q as u32))
        .then_some(q)
}

/// A D-dimensional sampler used as a 2D one (its first two dimensions).
struct FirstTwo(Box<dyn SamplerNd>);

impl Sampler for FirstTwo {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn progression(&self) -> Progression {
        self.0.progression()
    }
    fn next_sample(&mut self) -> Point2 {
        let mut p = [0.0f32; 2];
        self.0.next_point(&mut p);
        Point2::new(p[0], p[1])
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
        }
    }

    /// The same with another seed.
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
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
        v
    }
}

/// Builds a D-dimensional sampler from the parameters and `D`.
type NdBuilder = fn(&Params, u32) -> Result<Box<dyn SamplerNd>>;

/// A registered sampler: its name, what it is, and how to build it.
pub struct Entry {
    /// The name (`--sampler NAME`).
    pub name: &'static str,
    /// One line: what it is and where it comes from.
    pub description: &'static str,
    /// True for progressive sequences, false for fixed-count sets.
    pub progressive: bool,
    /// The counts it accepts.
    pub counts: CountRule,
    /// The optional parameters it takes.
    pub parameters: &'static [Parameter],
    /// True when generating a set takes long (relaxation, optimisation): tools use fewer
    /// realizations by default.
    pub expensive: bool,
    /// The D-dimensional constructor, for samplers that have more than 2 dimensions.
    nd: Option<NdBuilder>,
    build: fn(&Params) -> Result<Box<dyn Sampler>>,
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

    /// The checks common to both forms: every optional parameter given is one this sampler
    /// takes, and the count is not 0.
    fn check_params(&self, params: &Params) -> Result<()> {
        for (p, value) in params.given() {
            if !self.parameters.contains(&p) {
                let takers: Vec<&str> = ENTRIES
                    .iter()
                    .filter(|e| e.parameters.contains(&p))
                    .map(|e| e.name)
                    .collect();
                let allowed = if takers.is_empty() {
                    format!(
                        "{} takes no {}, and no registered sampler does",
                        self.name,
                        p.name()
                    )
                } else {
                    format!(
                        "{} takes no {}; samplers that do: {}",
                        self.name,
                        p.name(),
                        takers.join(", ")
                    )
                };
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
            None if dims == 2 => Ok(Box::new(TwoDimensional(self.build(params)?))),
            None => {
                let takers: Vec<&str> = ENTRIES
                    .iter()
                    .filter(|e| e.nd.is_some())
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
}

/// A 2D sampler seen as a D-dimensional one with `D = 2`.
struct TwoDimensional(Box<dyn Sampler>);

impl SamplerNd for TwoDimensional {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn dimensions(&self) -> u32 {
        2
    }
    fn progression(&self) -> Progression {
        self.0.progression()
    }
    fn next_point(&mut self, out: &mut [f32]) {
        let p: Point2 = self.0.next_sample();
        out[0] = p.x;
        out[1] = p.y;
    }
}

static ENTRIES: &[Entry] = &[
    Entry {
        name: "random",
        description: "independent uniform points (PCG32); progressive",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: Some(|p, d| Ok(Box::new(samplers::RandomNd::new(d, p.seed)?))),
        build: |p| Ok(Box::new(samplers::Random::new(p.seed))),
    },
    Entry {
        name: "regular",
        description: "cell centres of an s x s grid (N = s^2); deterministic",
        progressive: false,
        counts: CountRule::Square,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Regular::new(p.count)?)),
    },
    Entry {
        name: "jittered",
        description: "one uniform point per cell of an s x s grid (N = s^2), Cook 1986",
        progressive: false,
        counts: CountRule::Square,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Jittered::new(p.count, p.seed)?)),
    },
    Entry {
        name: "nrooks",
        description: "N-rooks / 2D Latin hypercube, one point per row and column, Shirley 1991",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::NRooks::new(p.count, p.seed)?)),
    },
    Entry {
        name: "multijittered",
        description: "jittered and N-rooks at once (N = n^2), Chiu, Shirley, Wang 1994",
        progressive: false,
        counts: CountRule::Square,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::MultiJittered::new(p.count, p.seed)?)),
    },
    Entry {
        name: "cmj",
        description: "correlated multi-jittered, any N, Kensler 2013",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Cmj::new(p.count, p.seed)?)),
    },
    Entry {
        name: "pmj",
        description: "progressive multi-jittered: 1D strata and squarest grid at every power of two, Christensen et al. 2018",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Pmj::new(p.seed))),
    },
    Entry {
        name: "pmjbn",
        description: "pmj with best-candidate blue noise (--candidates K, default 100)",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[Parameter::Candidates],
        expensive: false,
        nd: None,
        build: |p| {
            let k = p.candidates.unwrap_or(samplers::pmj::DEFAULT_CANDIDATES);
            Ok(Box::new(samplers::Pmj::pmjbn(p.seed, k)?))
        },
    },
    Entry {
        name: "pmj02",
        description: "progressive (0,m,2)-nets at every power of two (Pharr's strata enumeration), Christensen et al. 2018",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Pmj::pmj02(p.seed))),
    },
    Entry {
        name: "pmj02bn",
        description: "pmj02 with best-candidate placement (--candidates K, default 100)",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[Parameter::Candidates],
        expensive: false,
        nd: None,
        build: |p| {
            let k = p.candidates.unwrap_or(samplers::pmj::DEFAULT_CANDIDATES);
            Ok(Box::new(samplers::Pmj::pmj02bn(p.seed, k)?))
        },
    },
    Entry {
        name: "pmj02-stochastic",
        description: "pmj02 by stochastic generation, O(1) per sample, Helmer, Christensen, Kensler 2021",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: None,
        build: |p| Ok(Box::new(samplers::Pmj02Stochastic::new(p.seed))),
    },
    Entry {
        name: "poisson",
        description: "Poisson disk by dart throwing to exactly N points (--radius RHO, default 0.7), Cook 1986",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[Parameter::Radius],
        expensive: false,
        nd: None,
        build: |p| {
            let rho = p.radius.unwrap_or(samplers::poisson::DEFAULT_RHO);
            Ok(Box::new(samplers::PoissonDisk::new(
                samplers::DartThrowing::new(p.count, rho)?,
                p.seed,
            )?))
        },
    },
    Entry {
        name: "bridson",
        description: "Poisson disk by Bridson's algorithm, periodic, N points (--radius RHO, default 0.7), Bridson 2007",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[Parameter::Radius],
        expensive: false,
        nd: None,
        build: |p| {
            let rho = p.radius.unwrap_or(samplers::poisson::DEFAULT_RHO);
            Ok(Box::new(samplers::BridsonDisk::new(
                samplers::Bridson::new(p.count, rho)?,
                p.seed,
            )?))
        },
    },
    Entry {
        name: "best-candidate",
        description: "Mitchell's best candidate, progressive (--candidates K per existing point, default 1), Mitchell 1991",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[Parameter::Candidates],
        expensive: true,
        nd: None,
        build: |p| {
            let k = p
                .candidates
                .unwrap_or(samplers::best_candidate::DEFAULT_FACTOR);
            Ok(Box::new(samplers::BestCandidate::new(p.seed, k)?))
        },
    },
    #[cfg(feature = "lloyd")]
    Entry {
        name: "lloyd",
        description: "Lloyd relaxation on the periodic Voronoi diagram from random points (--iterations K, default 64), Lloyd 1982",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[Parameter::Iterations],
        expensive: true,
        nd: None,
        build: |p| {
            let k = p.iterations.unwrap_or(samplers::lloyd::DEFAULT_ITERATIONS);
            Ok(Box::new(samplers::LloydSets::new(
                samplers::Lloyd::new(p.count, k)?,
                p.seed,
            )?))
        },
    },
    Entry {
        name: "ccvt",
        description: "capacity-constrained Voronoi tessellation, 256 points per site (--iterations K, default 200), Balzer et al. 2009",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[Parameter::Iterations],
        expensive: true,
        nd: None,
        build: |p| {
            let k = p.iterations.unwrap_or(samplers::ccvt::DEFAULT_ITERATIONS);
            Ok(Box::new(samplers::CcvtSets::new(
                samplers::Ccvt::new(p.count, k)?,
                p.seed,
            )?))
        },
    },
    Entry {
        name: "sobol",
        description: "Sobol' (Joe-Kuo directions), Owen-scrambled by hashing, progressive, any --dims, Burley 2020",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: Some(|p, d| Ok(Box::new(samplers::SobolNd::new(d, p.seed)?))),
        build: |p| Ok(Box::new(samplers::Sobol::new(p.seed))),
    },
    Entry {
        name: "halton",
        description: "Halton, Owen-scrambled digits, progressive, any --dims up to 1000, Halton 1960",
        progressive: true,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: Some(|p, d| Ok(Box::new(samplers::HaltonNd::new(d, p.seed)?))),
        build: |p| Ok(Box::new(samplers::Halton::new(p.seed))),
    },
    Entry {
        name: "latin",
        description: "Latin hypercube in D dimensions (--dims D): one point per 1/N stratum of every axis, McKay et al. 1979",
        progressive: false,
        counts: CountRule::Any,
        parameters: &[],
        expensive: false,
        nd: Some(latin_nd),
        build: |p| Ok(Box::new(FirstTwo(latin_nd(p, 2)?))),
    },
    Entry {
        name: "uncorrelated",
        description: "uncorrelated jitter: jittered pairs (0,1), (2,3), ... in random orders (N = s^2), Cook 1986",
        progressive: false,
        counts: CountRule::Square,
        parameters: &[],
        expensive: false,
        nd: Some(uncorrelated_nd),
        build: |p| Ok(Box::new(FirstTwo(uncorrelated_nd(p, 2)?))),
    },
    Entry {
        name: "oa-bose",
        description: "orthogonal array, strength 2 (N = q^2, up to q+1 dims), multi-jittered, Jarosz et al. 2019",
        progressive: false,
        counts: CountRule::OaPower(2),
        parameters: &[],
        expensive: false,
        nd: Some(bose_nd),
        build: |p| Ok(Box::new(FirstTwo(bose_nd(p, 2)?))),
    },
    Entry {
        name: "oa-bush",
        description: "orthogonal array, strength T (--strength T, default 3; N = q^T, up to q dims), multi-jittered, Jarosz et al. 2019",
        progressive: false,
        counts: CountRule::OaPower(3),
        parameters: &[Parameter::Strength],
        expensive: false,
        nd: Some(bush_nd),
        build: |p| Ok(Box::new(FirstTwo(bush_nd(p, 2)?))),
    },
];

// The D-dimensional constructors whose 2D form is their first two dimensions.
fn latin_nd(p: &Params, d: u32) -> Result<Box<dyn SamplerNd>> {
    Ok(Box::new(samplers::LatinHypercube::new(p.count, d, p.seed)?))
}
fn uncorrelated_nd(p: &Params, d: u32) -> Result<Box<dyn SamplerNd>> {
    Ok(Box::new(samplers::UncorrelatedJitter::new(
        p.count, d, p.seed,
    )?))
}
fn bose_nd(p: &Params, d: u32) -> Result<Box<dyn SamplerNd>> {
    Ok(Box::new(samplers::Bose::new(p.count, d, p.seed)?))
}
fn bush_nd(p: &Params, d: u32) -> Result<Box<dyn SamplerNd>> {
    let strength = p.strength.unwrap_or(3);
    Ok(Box::new(samplers::Bush::new(p.count, strength, d, p.seed)?))
}

/// Every registered sampler, in a stable order (simplest first).
pub fn entries() -> &'static [Entry] {
    ENTRIES
}

/// Every registered name, in the order of [`entries`].
pub fn names() -> Vec<&'static str> {
    ENTRIES.iter().map(|e| e.name).collect()
}

/// The entry registered under `name`; the error lists the known names.
pub fn find(name: &str) -> Result<&'static Entry> {
    ENTRIES
        .iter()
        .find(|e| e.name == name)
        .ok_or_else(|| Error::UnknownSampler {
            name: name.to_string(),
            known: names(),
        })
}

/// Builds the D-dimensional sampler registered under `name` (see [`Entry::build_nd`]).
pub fn build_nd(name: &str, params: &Params, dims: u32) -> Result<Box<dyn SamplerNd>> {
    find(name)?.build_nd(params, dims)
}

/// Builds the sampler registered under `name` (see [`Entry::build`]).
pub fn build(name: &str, params: &Params) -> Result<Box<dyn Sampler>> {
    find(name)?.build(params)
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
    }

    #[test]
    fn names_are_unique() {
        let mut n = names();
        n.sort();
        n.dedup();
        assert_eq!(n.len(), ENTRIES.len());
    }
}
