//! Samplers by name, for the example programs, the benches and users' own tools: the list of
//! entries, each declared in its sampler's own file, the lookup by name, and the building of an
//! entry's sampler from [`Params`] (whose errors name the other entries that would do).
//!
//! The registry sits above the samplers: it imports each sampler's `ENTRY`, and no sampler
//! imports it (the entry types are a leaf module of their own, re-exported here). Without the
//! `std` feature the list holds the samplers that build without it: `random`, `regular`,
//! `jittered`, `nrooks`, `multijittered`, `cmj`, `pmj02-stochastic`, `sobol`, `halton`,
//! `lattice`, `fibonacci`, `latin` and `uncorrelated`.
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

pub use crate::entry::{
    BlueNoise, CountRule, Entry, Family, Parameter, ParameterSpec, Params, Rates,
};

use crate::error::{Error, Result};
use crate::prelude::*;
use crate::sampler::{Sampler, SamplerNd};
#[cfg(feature = "std")]
use crate::samplers::{best_candidate, bnot, ccvt, net02bn, oa, poisson};
use crate::samplers::{
    halton, jittered, latin, lattice, multijitter, pmj, random, regular, sobol, uncorrelated,
};

/// Every registered sampler, in a stable order (simplest first).
static ENTRIES: &[Entry] = &[
    random::ENTRY,
    regular::ENTRY,
    jittered::ENTRY,
    latin::NROOKS,
    multijitter::MULTIJITTERED,
    multijitter::CMJ,
    #[cfg(feature = "std")]
    pmj::PMJ,
    #[cfg(feature = "std")]
    pmj::PMJBN,
    #[cfg(feature = "std")]
    pmj::PMJ02,
    #[cfg(feature = "std")]
    pmj::blue::ENTRY,
    pmj::stochastic::ENTRY,
    #[cfg(feature = "std")]
    net02bn::ENTRY,
    #[cfg(feature = "std")]
    poisson::POISSON,
    #[cfg(feature = "std")]
    poisson::BRIDSON,
    #[cfg(feature = "std")]
    best_candidate::ENTRY,
    #[cfg(feature = "lloyd")]
    crate::samplers::lloyd::ENTRY,
    #[cfg(feature = "std")]
    ccvt::ENTRY,
    #[cfg(feature = "std")]
    bnot::ENTRY,
    sobol::ENTRY,
    halton::ENTRY,
    lattice::LATTICE,
    lattice::FIBONACCI,
    latin::LATIN,
    uncorrelated::ENTRY,
    #[cfg(feature = "std")]
    oa::BOSE,
    #[cfg(feature = "std")]
    oa::BUSH,
];

/// Every registered sampler, in a stable order (simplest first).
pub fn entries() -> &'static [Entry] {
    ENTRIES
}

/// The blue-noise samplers ([`Entry::is_blue_noise`]), in the order of [`entries`].
pub fn blue_noise() -> impl Iterator<Item = &'static Entry> {
    ENTRIES.iter().filter(|e| e.is_blue_noise())
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

/// Builds the sampler registered under `name` (see [`Entry::build`]).
pub fn build(name: &str, params: &Params) -> Result<Box<dyn Sampler>> {
    find(name)?.build(params)
}

/// Builds the D-dimensional sampler registered under `name` (see [`Entry::build_nd`]).
pub fn build_nd(name: &str, params: &Params, dims: u32) -> Result<Box<dyn SamplerNd>> {
    find(name)?.build_nd(params, dims)
}

// Building from an entry lives here, above the samplers, because its errors list the other
// entries (the samplers that take a parameter, or have D dimensions).
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
            if !self.takes(p) {
                let takers: Vec<&str> = entries()
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
                let takers: Vec<&str> = entries()
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
}

/// The table of samplers, generated from the entries (the README and the crate docs show it;
/// a test keeps them equal): name, kind and counts, dimensions, the stratification each
/// promises, the published variance rates (discontinuous / smooth 2D integrands), and the paper.
pub fn table() -> String {
    let mut t = String::from(
        "| name | kind | dims | promises | variance (steps / smooth) | paper |\n\
         |---|---|---|---|---|---|\n",
    );
    for e in ENTRIES {
        t.push_str(&e.row());
        t.push('\n');
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_and_listed_counts_are_accepted_over_the_whole_range() {
        // issue 24, row 5: nearest(2^64 - 1) was 0 for squares and counts past the largest
        // allowed for the orthogonal arrays and n-rooks
        for e in entries().iter().filter(|e| !e.progressive) {
            for n in [
                0,
                1,
                2,
                1 << 31,
                (1 << 31) + 1,
                1 << 32,
                1 << 40,
                u64::MAX - 1,
                u64::MAX,
            ] {
                let c = e.counts.nearest(n);
                assert!(
                    e.counts.check(e.name, c).is_ok(),
                    "{}: nearest({n}) = {c} is refused",
                    e.name
                );
            }
            let listed = e.counts.counts_between(u64::MAX - 1000, u64::MAX);
            assert!(listed.is_empty(), "{}: {listed:?}", e.name);
            if !matches!(e.counts, CountRule::Any) {
                for c in e
                    .counts
                    .counts_between(0, u64::MAX)
                    .into_iter()
                    .rev()
                    .take(3)
                {
                    assert!(e.counts.check(e.name, c).is_ok(), "{}: lists {c}", e.name);
                }
            }
        }
    }

    #[test]
    #[cfg(feature = "std")] // the blue-noise samplers need `std`
    fn the_blue_noise_samplers_are_the_family_and_the_pmj_variants() {
        // every sampler of the blue-noise family is one, and so are the PMJ family's
        // blue-noise variants; `spectrum --blue-noise-table` has one row per sampler here
        for e in entries() {
            if e.family == Family::BlueNoise {
                assert!(e.is_blue_noise(), "{}", e.name);
            }
            if let Some(b) = e.blue_noise {
                assert!(!b.published.is_empty(), "{}", e.name);
            }
        }
        let names: Vec<&str> = blue_noise().map(|e| e.name).collect();
        for name in ["pmjbn", "pmj02bn", "net02bn", "poisson", "ccvt", "bnot"] {
            assert!(names.contains(&name), "{name} missing from {names:?}");
        }
        assert!(!names.contains(&"pmj02") && !names.contains(&"sobol"));
    }

    #[test]
    fn names_are_unique() {
        let mut n = names();
        n.sort();
        n.dedup();
        assert_eq!(n.len(), ENTRIES.len());
    }
}
