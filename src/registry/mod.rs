//! Samplers by name, for the example programs, the benches and users' own tools: the list of
//! entries, each declared in its sampler's own file, the lookup by name, and the building of an
//! entry's sampler from [`Params`] (whose errors name the other entries that would do).
//!
//! The registry sits above the samplers: it imports each lab sampler's `ENTRY`, and no sampler
//! imports it (the entry types are a leaf module of their own, re-exported here). The renderer
//! crate's samplers (`strata::samplers`) know nothing of the registry: their entries are
//! declared here, in `strata_entries.rs`.
//!
//! ```
//! use strata_lab::registry::{self, Params};
//! let mut s = registry::build("cmj", &Params::new(100).seed(strata::Seed(7))).unwrap();
//! let p = s.next_sample();
//! assert!(p[0] < 1.0 && p[1] < 1.0);
//!
//! let err = registry::build("jitter", &Params::new(16)).unwrap_err();
//! assert!(err.to_string().contains("jittered")); // the error lists the known names
//! ```

pub use crate::counts::{CountRule, MAX_OA_STRENGTH};
pub use crate::entry::{
    BlueNoise, Bound, Built, Entry, Family, Kind, ParameterSpec, Params, Rates,
};

mod strata_entries;

use crate::samplers::{best_candidate, bnot, ccvt, lloyd, net02bn, oa, pmj, poisson};
use crate::{Error, Result};
use strata::{Sampler, SamplerNd};

/// Every registered sampler, in a stable order (simplest first).
static ENTRIES: &[Entry] = &[
    strata_entries::RANDOM,
    strata_entries::REGULAR,
    strata_entries::JITTERED,
    strata_entries::NROOKS,
    strata_entries::MULTIJITTERED,
    strata_entries::CMJ,
    pmj::PMJ,
    pmj::PMJBN,
    pmj::PMJ02,
    pmj::blue::ENTRY,
    strata_entries::PMJ02_STOCHASTIC,
    net02bn::ENTRY,
    poisson::POISSON,
    poisson::BRIDSON,
    best_candidate::ENTRY,
    lloyd::ENTRY,
    ccvt::ENTRY,
    bnot::ENTRY,
    strata_entries::SOBOL,
    strata_entries::SOBOL12,
    strata_entries::FAURE4,
    strata_entries::HALTON,
    strata_entries::LATTICE,
    strata_entries::FIBONACCI,
    strata_entries::LATIN,
    strata_entries::UNCORRELATED,
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

/// What a build does with a parameter the sampler does not take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Strictness {
    /// Refuses it, naming the samplers that do take it ([`Entry::build`]).
    Strict,
    /// Drops it ([`Params::kept_for`]): what the programs do when one set of flags serves
    /// several samplers. A name that no registered sampler takes is still refused, and so is a
    /// value outside the range of a sampler that takes it.
    Lenient,
}

// Building from an entry lives here, above the samplers, because its errors list the other
// entries (the samplers that take a parameter, or have D dimensions).
impl Entry {
    /// Builds the sampler in 2D, refusing a parameter it does not take (the strict build);
    /// `params.dims` is ignored.
    pub fn build(&self, params: &Params) -> Result<Box<dyn Sampler>> {
        let params = params.clone().dims(2);
        match self.make(&params, Strictness::Strict)? {
            Built::Two(s) => Ok(s),
            Built::Nd(_) => Err(Error::input(
                self.name,
                "built a D-dimensional sampler for 2 dimensions (a registry bug)",
            )),
        }
    }

    /// Builds the sampler with `dims` coordinates per point, strictly (`params.dims` is
    /// ignored): [`Entry::make`] with `dims`, as a [`SamplerNd`].
    pub fn build_nd(&self, params: &Params, dims: u32) -> Result<Box<dyn SamplerNd>> {
        let params = params.clone().dims(dims);
        Ok(self.make(&params, Strictness::Strict)?.into_nd())
    }

    /// Builds the sampler from `params`, dimension count included: the one way every form
    /// goes. Checks, in order, that the dimension count is one the sampler has, that every
    /// parameter given is declared by some sampler (and, when `strictness` is
    /// [`Strictness::Strict`], by this one), that each value this sampler takes is within its
    /// declared range ([`ParameterSpec::check`]), and that the count is not 0; then the
    /// sampler's own constructor checks the rest (its count rule, limits a range cannot say).
    pub fn make(&self, params: &Params, strictness: Strictness) -> Result<Built> {
        let dims = params.dims;
        if dims == 0 || dims > strata::samplers::MAX_DIMENSIONS {
            return Err(Error::parameter(
                self.name,
                "dims",
                dims,
                format!("1 to {} dimensions", strata::samplers::MAX_DIMENSIONS),
            ));
        }
        if dims != 2 && !self.has_dimensions() {
            let takers: Vec<&str> = entries()
                .iter()
                .filter(|e| e.has_dimensions())
                .map(|e| e.name)
                .collect();
            return Err(Error::parameter(
                self.name,
                "dims",
                dims,
                format!(
                    "{} has 2-dimensional points only; samplers with D dimensions: {}",
                    self.name,
                    takers.join(", ")
                ),
            ));
        }
        let mut kept = params.clone();
        for (name, value) in params.given() {
            match self.parameter(name) {
                Some(spec) => {
                    spec.check(self.name, value)?;
                }
                None => {
                    let Some(known) = parameter_names().into_iter().find(|n| *n == name) else {
                        return Err(Error::input(
                            self.name,
                            format!(
                                "no sampler takes a parameter named '{name}'; parameters: {}",
                                parameter_names().join(", ")
                            ),
                        ));
                    };
                    if strictness == Strictness::Lenient {
                        kept.unset(name);
                        continue;
                    }
                    let takers: Vec<&str> = entries()
                        .iter()
                        .filter(|e| e.takes(name))
                        .map(|e| e.name)
                        .collect();
                    let allowed = format!(
                        "{} takes no {known}; samplers that do: {}",
                        self.name,
                        takers.join(", ")
                    );
                    return Err(Error::parameter(self.name, known, value, allowed));
                }
            }
        }
        if params.count == 0 {
            return Err(Error::count(
                self.name,
                0,
                format!("allowed counts: {}", self.counts),
            ));
        }
        (self.build)(&kept)
    }
}

/// Every parameter declaration, sampler by sampler in the order of [`entries`], with the
/// entry that declares it.
pub fn parameters() -> impl Iterator<Item = (&'static Entry, &'static ParameterSpec)> {
    ENTRIES
        .iter()
        .flat_map(|e| e.parameters.iter().map(move |p| (e, p)))
}

/// The distinct parameter names and aliases ([`ParameterSpec::alias`]), in the order they are
/// first declared: the programs' flags and the Python keywords.
pub fn parameter_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = Vec::new();
    for (_, p) in parameters() {
        for n in [p.name, p.alias] {
            if !n.is_empty() && !names.contains(&n) {
                names.push(n);
            }
        }
    }
    names
}

/// The kind of the parameter named `name` (the same for every sampler that declares it), or
/// `None` when no sampler takes it.
pub fn parameter_kind(name: &str) -> Option<Kind> {
    parameters()
        .find(|(_, p)| p.is_named(name))
        .map(|(_, p)| p.kind)
}

/// The parameters table, generated from the declarations (`docs/cli.md` shows it; a test
/// keeps it equal): parameter, sampler, kind, allowed values, default and what it does.
pub fn parameter_table() -> String {
    let mut t = String::from(
        "| parameter | sampler | kind | allowed | default | what it does |\n\
         |---|---|---|---|---|---|\n",
    );
    for name in parameter_names() {
        for (e, p) in parameters().filter(|(_, p)| p.name == name) {
            let alias = if p.alias.is_empty() {
                String::new()
            } else {
                format!(" (also `--{}`)", p.alias)
            };
            t.push_str(&format!(
                "| `--{}`{alias} | `{}` | {} | {} | {} | {} |\n",
                p.name,
                e.name,
                p.kind.name(),
                p.allowed(),
                p.default,
                p.help
            ));
        }
    }
    t
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
    fn every_entry_writes_its_own_facts_over_the_default() {
        let mut names = std::collections::BTreeSet::new();
        for e in entries() {
            for (field, text) in [
                ("name", e.name),
                ("description", e.description),
                ("paper", e.paper),
                ("promise", e.promise),
            ] {
                assert!(!text.is_empty(), "{}: no {field}", e.name);
            }
            assert!(names.insert(e.name), "{} twice", e.name);
            // its own construction, not the default's refusal
            let built = e.build(&Params::new(e.counts.nearest(64)));
            assert!(
                built.is_ok(),
                "{}: {}",
                e.name,
                built.err().map(|x| x.to_string()).unwrap_or_default()
            );
        }
        assert!((Entry::DEFAULT.build)(&Params::new(64)).is_err());
    }

    #[test]
    fn the_seeded_flag_says_whether_the_seed_changes_the_points() {
        // one home for the fact: the Python engine refuses the unseeded samplers from it
        for e in entries() {
            let n = e.counts.nearest(64);
            let draw = |seed: u64| {
                let mut s = e.build(&Params::new(n).seed(strata::Seed(seed))).unwrap();
                let mut v = vec![[0.0f32; 2]; n as usize];
                strata::Sampler::fill(&mut s, &mut v);
                v
            };
            assert_eq!(draw(1) != draw(2), e.seeded, "{}", e.name);
        }
        assert!(entries().iter().any(|e| !e.seeded));
    }

    #[test]
    fn nearest_and_listed_counts_are_accepted_over_the_whole_range() {
        // nearest(2^64 - 1) was once 0 for squares and counts past the largest
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
            let listed: Vec<u64> = e.counts.counts_between(u64::MAX - 1000, u64::MAX).collect();
            assert!(listed.is_empty(), "{}: {listed:?}", e.name);
            if !matches!(e.counts, CountRule::Any) {
                let all: Vec<u64> = e.counts.counts_between(0, u64::MAX).collect();
                for &c in all.iter().rev().take(3) {
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
    fn each_parameter_is_declared_consistently() {
        // one kind per name; each default inside its own range; a help line; and the range is
        // what `allows` enforces (its ends, and just outside them)
        assert!(!parameter_names().is_empty());
        for (e, p) in parameters() {
            assert_eq!(
                parameter_kind(p.name),
                Some(p.kind),
                "{}: {}",
                e.name,
                p.name
            );
            assert!(
                p.allows(p.default),
                "{}: {} default {}",
                e.name,
                p.name,
                p.default
            );
            assert!(!p.help.is_empty(), "{}: {}", e.name, p.name);
            for (bound, outward) in [(p.min, -1.0), (p.max, 1.0)] {
                let (v, closed) = match bound {
                    Bound::Closed(v) => (v, true),
                    Bound::Open(v) => (v, false),
                };
                assert_eq!(p.allows(v), closed, "{}: {} at {v}", e.name, p.name);
                let step = if p.kind == Kind::Whole { 1.0 } else { 1e-9 };
                assert!(!p.allows(v + outward * step), "{}: {}", e.name, p.name);
            }
            assert!(!p.allows(f64::NAN) && !p.allows(f64::INFINITY));
            if p.kind == Kind::Whole {
                assert!(!p.allows(p.default + 0.5), "{}: {}", e.name, p.name);
            }
            // the sampler builds with its default given explicitly, as without it
            let n = e.counts.nearest(64);
            let given = Params::new(n).with(p.name, p.default);
            if e.expensive {
                continue; // built in their own tests
            }
            let mut a = e.build(&given).unwrap();
            let mut b = e.build(&Params::new(n)).unwrap();
            let mut va = vec![[0.0f32; 2]; n as usize];
            let mut vb = va.clone();
            Sampler::fill(&mut a, &mut va);
            Sampler::fill(&mut b, &mut vb);
            assert_eq!(va, vb, "{}: {} given its default", e.name, p.name);
        }
    }

    #[test]
    fn the_strict_build_refuses_what_the_lenient_one_drops() {
        let jittered = find("jittered").unwrap();
        let p = Params::new(16).seed(strata::Seed(3)).with("radius", 0.5);
        let e = jittered.build(&p).unwrap_err().to_string();
        assert!(
            e.contains("takes no radius") && e.contains("poisson"),
            "{e}"
        );
        let e = jittered
            .make(&p, Strictness::Strict)
            .unwrap_err()
            .to_string();
        assert!(e.contains("takes no radius"), "{e}");
        // lenient: the same points as without the parameter
        let mut a = jittered.make(&p, Strictness::Lenient).unwrap();
        let mut b = jittered
            .make(&Params::new(16).seed(strata::Seed(3)), Strictness::Strict)
            .unwrap();
        let (mut va, mut vb) = (vec![0f32; 32], vec![0f32; 32]);
        a.fill(&mut va);
        b.fill(&mut vb);
        assert_eq!(va, vb);
        assert_eq!(p.kept_for(jittered), Params::new(16).seed(strata::Seed(3)));
        // a name nobody declares is refused by both, with the known names
        for s in [Strictness::Strict, Strictness::Lenient] {
            let e = jittered
                .make(&Params::new(16).with("radus", 0.5), s)
                .unwrap_err()
                .to_string();
            assert!(e.contains("'radus'") && e.contains("radius"), "{e}");
        }
        // a value outside the range of a sampler that takes it is refused by both, with it
        for s in [Strictness::Strict, Strictness::Lenient] {
            let poisson = find("poisson").unwrap();
            let e = poisson
                .make(&Params::new(16).with("radius", 0.9), s)
                .unwrap_err()
                .to_string();
            assert!(e.contains("0 < radius <= 0.78"), "{e}");
        }
    }

    #[test]
    fn an_alias_reaches_the_parameter_when_its_name_is_not_given() {
        // pmj02bn's `sweeps` was `iterations`: the old name still sets it, the new one wins
        let pmj02bn = find("pmj02bn").unwrap();
        assert!(pmj02bn.takes("sweeps") && pmj02bn.takes("iterations"));
        assert!(parameter_names().contains(&"sweeps"));
        assert_eq!(parameter_kind("sweeps"), Some(Kind::Whole));
        let take = |p: &Params| {
            let mut s = pmj02bn.make(p, Strictness::Strict).unwrap();
            let mut v = vec![0f32; 512];
            s.fill(&mut v);
            v
        };
        let p = Params::new(256).seed(strata::Seed(2));
        let zero = take(&p.clone().with("sweeps", 0.0));
        assert_ne!(zero, take(&p), "0 sweeps is a plain Owen scrambling");
        assert_eq!(zero, take(&p.clone().with("iterations", 0.0)));
        assert_eq!(
            take(&p),
            take(&p.clone().with("iterations", 0.0).with("sweeps", 2.0))
        );
        // the lenient build keeps an alias for a sampler that takes it
        assert_eq!(
            p.clone()
                .with("iterations", 0.0)
                .kept_for(pmj02bn)
                .get("iterations"),
            Some(0.0)
        );
        let e = pmj02bn
            .make(&p.with("iterations", 1001.0), Strictness::Strict)
            .unwrap_err()
            .to_string();
        assert!(e.contains("0 to 1000"), "{e}");
    }

    #[test]
    fn build_and_build_nd_are_one_path() {
        for e in entries() {
            let n = e.counts.nearest(27);
            if e.expensive {
                continue;
            }
            for dims in [1u32, 2, 3, 5] {
                let p = Params::new(n).seed(strata::Seed(9));
                let nd = e.build_nd(&p, dims);
                let made = e.make(&p.clone().dims(dims), Strictness::Strict);
                assert_eq!(nd.is_ok(), made.is_ok(), "{} in {dims}", e.name);
                if dims == 2 {
                    assert!(nd.is_ok(), "{} in 2", e.name);
                } else if !e.has_dimensions() {
                    assert!(nd.is_err(), "{} in {dims}", e.name);
                }
                let (Ok(mut nd), Ok(mut made)) = (nd, made) else {
                    continue;
                };
                assert_eq!(matches!(made, Built::Two(_)), dims == 2, "{}", e.name);
                let k = n as usize * dims as usize;
                let (mut a, mut b) = (vec![0f32; k], vec![0f32; k]);
                nd.fill(&mut a);
                made.fill(&mut b);
                assert_eq!(a, b, "{} in {dims}", e.name);
                if dims == 2 {
                    // and the 2D form gives the same points
                    let mut s = e.build(&p).unwrap();
                    let mut v = vec![[0.0f32; 2]; n as usize];
                    Sampler::fill(&mut s, &mut v);
                    let flat: Vec<f32> = v.iter().flat_map(|q| *q).collect();
                    assert_eq!(flat, a, "{}", e.name);
                }
            }
        }
    }

    #[test]
    fn names_are_unique() {
        let mut n = names();
        n.sort();
        n.dedup();
        assert_eq!(n.len(), ENTRIES.len());
    }
}
