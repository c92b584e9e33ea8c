//! The registry entries of the renderer crate's samplers (`strata::samplers`): the facts the
//! lab keeps about each (name, description, paper, family, counts, promise, rates) and how it is
//! built from [`Params`]. The samplers themselves know nothing of the registry; a test checks
//! each entry against its sampler (the name it reports, the counts it accepts, its dimensions).

use crate::counts::CountRule;
use strata::samplers::{
    Cmj, Fibonacci, Halton, HaltonNd, Jittered, LatinHypercube, Lattice, LatticeNd, MultiJittered,
    NRooks, Pmj02Stochastic, Random, RandomNd, Regular, Sobol, SobolNd, UncorrelatedJitter,
};

#[allow(unused_imports)]
use crate::entry::Params;
use crate::entry::{Built, Entry, Family, Rates};

/// The registry entry of `random`.
pub(crate) const RANDOM: Entry = Entry {
    name: "random",
    description: "independent uniform points (PCG32); progressive",
    paper: "-",
    family: Family::Classic,
    progressive: true,
    counts: CountRule::Any,
    promise: "nothing (i.i.d. uniform)",
    rates: Rates::RANDOM,
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Random::new(p.seed)),
            d => Built::nd(RandomNd::new(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `regular`.
pub(crate) const REGULAR: Entry = Entry {
    name: "regular",
    description: "cell centres of an s x s grid (N = s^2); deterministic",
    paper: "-",
    family: Family::Classic,
    seeded: false,
    counts: CountRule::Square,
    promise: "cell centres (aliasing, zero variance, biased)",
    build: |p| Ok(Built::two(Regular::new(p.count)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `jittered`.
pub(crate) const JITTERED: Entry = Entry {
    name: "jittered",
    description: "one uniform point per cell of an s x s grid (N = s^2)",
    paper: "Cook 1986",
    family: Family::Classic,
    counts: CountRule::Square,
    promise: "one point per cell of `s x s`",
    rates: Rates {
        discontinuous: Some(-1.5),
        smooth: Some(-2.0),
        higher: None,
    },
    build: |p| Ok(Built::two(Jittered::new(p.count, p.seed)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `nrooks`.
pub(crate) const NROOKS: Entry = Entry {
    name: "nrooks",
    description: "N-rooks / 2D Latin hypercube, one point per row and column",
    paper: "Shirley 1991",
    family: Family::Classic,
    counts: CountRule::Any,
    promise: "one point per row and column",
    build: |p| Ok(Built::two(NRooks::new(p.count, p.seed)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `latin`.
pub(crate) const LATIN: Entry = Entry {
    name: "latin",
    description: "Latin hypercube in D dimensions (--dims D): one point per 1/N stratum of every axis",
    paper: "McKay et al. 1979",
    family: Family::Multidim,
    counts: CountRule::Any,
    promise: "every 1D projection into `N` strata",
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(LatinHypercube::new(p.count, 2, p.seed)?),
            d => Built::nd(LatinHypercube::new(p.count, d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `multijittered`.
pub(crate) const MULTIJITTERED: Entry = Entry {
    name: "multijittered",
    description: "jittered and N-rooks at once (N = n^2)",
    paper: "Chiu, Shirley, Wang 1994",
    family: Family::Classic,
    counts: CountRule::Square,
    promise: "jittered on `n x n` and N-rooks",
    build: |p| Ok(Built::two(MultiJittered::new(p.count, p.seed)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `cmj`.
pub(crate) const CMJ: Entry = Entry {
    name: "cmj",
    description: "correlated multi-jittered, any N",
    paper: "Kensler 2013",
    family: Family::Classic,
    counts: CountRule::Any,
    promise: "multi-jittered on `m x n`, correlated shuffles",
    build: |p| Ok(Built::two(Cmj::new(p.count, p.seed)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `uncorrelated`.
pub(crate) const UNCORRELATED: Entry = Entry {
    name: "uncorrelated",
    description: "uncorrelated jitter: jittered pairs (0,1), (2,3), ... in random orders (N = s^2)",
    paper: "Cook 1986",
    family: Family::Multidim,
    counts: CountRule::Square,
    promise: "every pair `(2k, 2k+1)` jittered on `s x s`",
    any_dims: true,
    build: |p| {
        let s = UncorrelatedJitter::new(p.count, p.dims, p.seed)?;
        Ok(match p.dims {
            2 => Built::two(s),
            _ => Built::nd(s),
        })
    },
    ..Entry::DEFAULT
};

pub(crate) const HALTON: Entry = Entry {
    name: "halton",
    description: "Halton, Owen-scrambled digits, progressive, any --dims up to 1000",
    paper: "Halton 1960",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    promise: "one point per cell of `2^a x 3^b` at `N = 2^a 3^b`; 1000 dims",
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Halton::new(p.seed)),
            d => Built::nd(HaltonNd::new(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `lattice`.
pub(crate) const LATTICE: Entry = Entry {
    name: "lattice",
    description: "extensible rank-1 lattice (Cools-Kuo-Nuyens vector), toroidally shifted, progressive, up to 100 --dims",
    paper: "Cools, Kuo, Nuyens 2006",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    promise: "a rank-1 lattice at every `2^m` (1D strata in every dimension)",
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Lattice::new(p.seed)),
            d => Built::nd(LatticeNd::new(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `fibonacci`.
pub(crate) const FIBONACCI: Entry = Entry {
    name: "fibonacci",
    description: "Fibonacci lattice, N = F_k points with z = (1, F_(k-1)), toroidally shifted",
    paper: "Niederreiter 1992",
    family: Family::Qmc,
    counts: CountRule::Fibonacci,
    promise: "a rank-1 lattice: 1D strata in x and y",
    build: |p| Ok(Built::two(Fibonacci::new(p.count, p.seed)?)),
    ..Entry::DEFAULT
};

/// The registry entry of `sobol`.
pub(crate) const SOBOL: Entry = Entry {
    name: "sobol",
    description: "Sobol' (Joe-Kuo directions), Owen-scrambled by hashing, progressive, any --dims",
    paper: "Sobol' 1967; Joe, Kuo 2008; Burley 2020",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    promise: "(0,m,2)-nets in dims 0-1 at every `2^m`; up to 1000 dims",
    rates: Rates::NETS,
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Sobol::new(p.seed)),
            d => Built::nd(SobolNd::new(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `sobol12`.
pub(crate) const SOBOL12: Entry = Entry {
    name: "sobol12",
    description: "(1,2)-Sobol': Sobol' whose dimension pairs (2k, 2k+1) are (1,2)-sequences, \
                  Owen-scrambled by hashing, progressive, up to 692 --dims",
    paper: "Bonneel, Coeurjolly, Iehl, Ostromoukhov 2025; Burley 2020",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    promise: "(0,m,2)-nets in dims 0-1, (1,m,2)-nets in dims 2k, 2k+1 at every `2^m`; up to 692 \
              dims",
    rates: Rates::NETS,
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Sobol::one_two(p.seed)),
            d => Built::nd(SobolNd::one_two(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `faure4`.
pub(crate) const FAURE4: Entry = Entry {
    name: "faure4",
    description: "Faure's (0,4)-sequence in base 4, binary form, Owen-scrambled by hashing, \
                  progressive, up to 4 dims",
    paper: "Faure 1982; Burley 2020",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    promise: "(0,k,4)-nets in base 4 at every `4^k`; dims 0-1 and 2-3 (0,m,2)-nets at `2^m`",
    rates: Rates::NETS,
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Sobol::faure4(p.seed)),
            d => Built::nd(SobolNd::faure4(d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `pmj02-stochastic`.
pub(crate) const PMJ02_STOCHASTIC: Entry = Entry {
    name: "pmj02-stochastic",
    description: "pmj02 by stochastic generation, O(1) per sample",
    paper: "Helmer, Christensen, Kensler 2021",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    promise: "as `pmj02`, O(1) per sample, stratified classes",
    rates: Rates::NETS,
    build: |p| Ok(Built::two(Pmj02Stochastic::new(p.seed))),
    ..Entry::DEFAULT
};
