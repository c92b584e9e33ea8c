//! Samplers by name, for the example programs, the benches and users' own tools: the list of
//! entries, each declared in its sampler's own file, and the lookup by name.
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

mod entry;

pub use entry::{BlueNoise, CountRule, Entry, Family, Parameter, ParameterSpec, Params, Rates};

use crate::error::{Error, Result};
use crate::sampler::{Sampler, SamplerNd};
use crate::samplers::{
    best_candidate, bnot, ccvt, halton, jittered, latin, lattice, multijitter, net02bn, oa, pmj,
    poisson, random, regular, sobol, uncorrelated,
};

/// Every registered sampler, in a stable order (simplest first).
static ENTRIES: &[Entry] = &[
    random::ENTRY,
    regular::ENTRY,
    jittered::ENTRY,
    latin::NROOKS,
    multijitter::MULTIJITTERED,
    multijitter::CMJ,
    pmj::PMJ,
    pmj::PMJBN,
    pmj::PMJ02,
    pmj::blue::ENTRY,
    pmj::stochastic::ENTRY,
    net02bn::ENTRY,
    poisson::POISSON,
    poisson::BRIDSON,
    best_candidate::ENTRY,
    #[cfg(feature = "lloyd")]
    crate::samplers::lloyd::ENTRY,
    ccvt::ENTRY,
    bnot::ENTRY,
    sobol::ENTRY,
    halton::ENTRY,
    lattice::LATTICE,
    lattice::FIBONACCI,
    latin::LATIN,
    uncorrelated::ENTRY,
    oa::BOSE,
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
    }

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
