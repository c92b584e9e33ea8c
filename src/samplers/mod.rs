//! The sampler families, one per file.
//!
//! | name | type | kind | guarantee | source |
//! |---|---|---|---|---|
//! | `random` | [`Random`] | progressive | independent uniform points | - |
//! | `regular` | [`Regular`] | fixed `N = s^2` | cell centres of an `s x s` grid | - |
//! | `jittered` | [`Jittered`] | fixed `N = s^2` | one uniform point per cell of an `s x s` grid | Cook 1986 |
//! | `nrooks` | [`NRooks`] | fixed, any `N` | one point per row and per column of `N x N` (Latin hypercube) | Shirley 1991 |
//! | `multijittered` | [`MultiJittered`] | fixed `N = n^2` | jittered on `n x n` *and* N-rooks | Chiu, Shirley, Wang 1994 |
//! | `cmj` | [`Cmj`] | fixed, any `N` | multi-jittered on `m x n` (`m n >= N`), correlated shuffles | Kensler 2013 |
//! | `pmj`, `pmjbn`, `pmj02`, `pmj02bn` | [`Pmj`] | progressive | see [`pmj`] | Christensen et al. 2018, Pharr 2019 |
//! | `pmj02-stochastic` | [`Pmj02Stochastic`] | progressive | see [`pmj`] | Helmer et al. 2021 |
//! | `poisson`, `bridson` | [`PoissonDisk`], [`BridsonDisk`] | fixed, any `N` | see [`poisson`] | Cook 1986, Bridson 2007 |
//! | `best-candidate` | [`BestCandidate`] | progressive | see [`best_candidate`] | Mitchell 1991 |
//! | `lloyd` | `LloydSets` | fixed, any `N` | Lloyd relaxation (feature `lloyd`) | Lloyd 1982 |
//! | `ccvt` | [`CcvtSets`] | fixed, any `N` | see [`ccvt`] | Balzer et al. 2009 |
//! | `sobol` | [`Sobol`], [`SobolNd`] | progressive | see [`sobol`] | Sobol' 1967, Burley 2020 |
//! | `halton` | [`Halton`], [`HaltonNd`] | progressive | see [`halton`] | Halton 1960 |
//! | `latin` | [`LatinHypercube`] | fixed, any `N`, D dims | every 1D projection | McKay et al. 1979 |
//! | `uncorrelated` | [`UncorrelatedJitter`] | fixed `s^2`, D dims | jittered pairs | Cook 1986 |
//! | `oa-bose`, `oa-bush` | [`Bose`], [`Bush`] | fixed `q^t`, D dims | see [`oa`] | Jarosz et al. 2019 |
//!
//! Fixed-count samplers share one piece of machinery: a cursor that walks through blocks of
//! `N` samples and gives each block its own key, `stream_seed(seed, block)`. Every point is a
//! function of (block key, index in block), computed on demand with hashing and
//! [`Permutation`](crate::hash::Permutation)s: no tables, no allocation, O(1) per point.

pub mod best_candidate;
pub mod ccvt;
pub mod halton;
mod jittered;
mod latin;
#[cfg(feature = "lloyd")]
pub mod lloyd;
mod multijitter;
pub mod oa;
pub mod pmj;
pub mod poisson;
mod random;
mod regular;
pub mod sobol;
mod uncorrelated;

pub use best_candidate::BestCandidate;
pub use ccvt::{Ccvt, CcvtSets};
pub use halton::{Halton, HaltonNd};
pub use jittered::Jittered;
pub use latin::{LatinHypercube, NRooks};
#[cfg(feature = "lloyd")]
pub use lloyd::{Lloyd, LloydSets};
pub use multijitter::{Cmj, MultiJittered};
pub use oa::{Bose, Bush};
pub use pmj::{Pmj, Pmj02Stochastic};
pub use poisson::{Bridson, BridsonDisk, DartThrowing, PoissonDisk};
pub use random::{Random, RandomNd};
pub use regular::Regular;
pub use sobol::{Sobol, SobolNd};
pub use uncorrelated::UncorrelatedJitter;

use crate::error::{Error, Result};
use crate::hash::{Permutation, key32, stream_seed};

/// The largest count a fixed-count sampler accepts (`2^31`: indices within a block, and the
/// `m n` fine strata of a multi-jittered grid, stay 32-bit). Far beyond what a set built in
/// advance is useful for; progressive samplers go further.
pub const MAX_FIXED_COUNT: u64 = 1 << 31;

/// The most dimensions a D-dimensional sampler accepts (more than any integrand needs; the
/// limit bounds allocations sized by `D`).
pub const MAX_DIMENSIONS: u32 = 1 << 16;

/// Where a fixed-count sampler is in its stream: which block, which sample inside it.
#[derive(Clone, Debug)]
pub(crate) struct BlockCursor {
    seed: u64,
    count: u32,
    block: u64,
    index: u32,
}

impl BlockCursor {
    pub(crate) fn new(seed: u64, count: u32) -> Self {
        BlockCursor {
            seed,
            count,
            block: 0,
            index: 0,
        }
    }

    /// The key of the current block.
    pub(crate) fn block_key(&self) -> u64 {
        stream_seed(self.seed, self.block)
    }

    /// True when the next sample is the first of a block (its per-block state must be set up).
    pub(crate) fn at_block_start(&self) -> bool {
        self.index == 0
    }

    /// The index of the next sample inside its block, and how many remain in the block.
    pub(crate) fn position(&self) -> (u32, u32) {
        (self.index, self.count - self.index)
    }

    /// Moves `k` samples on (`k` at most the number remaining in the block).
    pub(crate) fn advance(&mut self, k: u32) {
        self.index += k;
        if self.index == self.count {
            self.index = 0;
            self.block = self.block.wrapping_add(1);
        }
    }
}

/// Validates a fixed-count sampler's count: at least 1, at most [`MAX_FIXED_COUNT`].
pub(crate) fn check_count(sampler: &'static str, count: u64) -> Result<u32> {
    if count == 0 || count > MAX_FIXED_COUNT {
        return Err(Error::count(
            sampler,
            count,
            format!("the count must be between 1 and {MAX_FIXED_COUNT}"),
        ));
    }
    Ok(count as u32)
}

/// Validates a dimension count: 1 to `max`; `note` (empty, or starting with a space) follows
/// the allowed range in the error.
pub(crate) fn check_dims(sampler: &'static str, dims: u32, max: u32, note: &str) -> Result<()> {
    if dims == 0 || dims > max {
        return Err(Error::parameter(
            sampler,
            "dims",
            dims,
            format!("1 to {max}{note}"),
        ));
    }
    Ok(())
}

/// Replaces `out` with `k` independent permutations of `[0, len)` for block key `key` (one per
/// dimension or group of dimensions, permutation `d` keyed by stream `d` of `key`).
pub(crate) fn block_permutations(out: &mut Vec<Permutation>, len: u32, key: u64, k: u32) {
    out.clear();
    out.extend(
        (0..k as u64).map(|d| Permutation::new(len, key32(stream_seed(key, d))).expect("len >= 1")),
    );
}

/// Validates a count that must be a perfect square `s^2`, returning `s`.
pub(crate) fn check_square(sampler: &'static str, count: u64) -> Result<u32> {
    check_count(sampler, count)?;
    let s = count.isqrt();
    if s * s != count {
        return Err(Error::count(
            sampler,
            count,
            format!(
                "the count must be a perfect square (nearest allowed: {})",
                crate::error::nearest_squares(count)
            ),
        ));
    }
    Ok(s as u32)
}

/// Implements [`Sampler`](crate::Sampler) for a fixed-count sampler struct that has a `cursor:
/// BlockCursor` field and the inherent methods `begin_block(&mut self, key: u64)`,
/// `point(&self, i: u32) -> Point2` and `grids(&self) -> Vec<StrataGrid>`.
///
/// With `paired`, the struct also has `point2(&self, i: u32) -> [Point2; 2]` (points `i` and
/// `i + 1`, identical to two calls of `point`), which `fill` uses so that the two points'
/// dependency chains overlap.
macro_rules! fixed_count_sampler {
    ($ty:ty, $name:literal) => {
        $crate::samplers::fixed_count_sampler!(@impl $ty, $name, |s: &$ty, out: &mut [$crate::Point2], start: u32| {
            for (p, i) in out.iter_mut().zip(start..) {
                *p = s.point(i);
            }
        });
    };
    ($ty:ty, $name:literal, paired) => {
        $crate::samplers::fixed_count_sampler!(@impl $ty, $name, |s: &$ty, out: &mut [$crate::Point2], start: u32| {
            let mut pairs = out.chunks_exact_mut(2);
            let mut i = start;
            for pair in &mut pairs {
                pair.copy_from_slice(&s.point2(i));
                i += 2;
            }
            if let [last] = pairs.into_remainder() {
                *last = s.point(i);
            }
        });
    };
    (@impl $ty:ty, $name:literal, $fill_run:expr) => {
        impl $crate::Sampler for $ty {
            fn name(&self) -> &'static str {
                $name
            }

            fn progression(&self) -> $crate::Progression {
                $crate::Progression::FixedCount {
                    count: self.count() as u64,
                }
            }

            #[inline]
            fn next_sample(&mut self) -> $crate::Point2 {
                if self.cursor.at_block_start() {
                    let key = self.cursor.block_key();
                    self.begin_block(key);
                }
                let p = self.point(self.cursor.position().0);
                self.cursor.advance(1);
                p
            }

            fn fill(&mut self, mut out: &mut [$crate::Point2]) {
                let fill_run = $fill_run;
                while !out.is_empty() {
                    if self.cursor.at_block_start() {
                        let key = self.cursor.block_key();
                        self.begin_block(key);
                    }
                    let (start, remaining) = self.cursor.position();
                    let k = remaining.min(u32::try_from(out.len()).unwrap_or(u32::MAX));
                    let (head, tail) = out.split_at_mut(k as usize);
                    fill_run(self, head, start);
                    self.cursor.advance(k);
                    out = tail;
                }
            }

            fn strata(&self, n: u64) -> Vec<$crate::StrataGrid> {
                if n == self.count() as u64 {
                    self.grids()
                } else {
                    Vec::new()
                }
            }
        }
    };
}
pub(crate) use fixed_count_sampler;

/// A generator of whole point sets (Poisson disk, relaxation): each set is built at once from a
/// key, so a fixed-count sampler over it streams one set per block.
pub trait SetGenerator: Clone + Send {
    /// The registered name.
    fn name(&self) -> &'static str;
    /// Points per set.
    fn count(&self) -> u32;
    /// The set for `key` (a well-mixed seed), as `f64` points in `[0,1)^2`.
    fn generate(&self, key: u64) -> Result<Vec<[f64; 2]>>;
    /// The strata the set is stratified in (none for these patterns).
    fn grids(&self) -> Vec<crate::StrataGrid> {
        Vec::new()
    }
}

/// A fixed-count [`Sampler`](crate::Sampler) over a [`SetGenerator`]: block `b` is the set
/// generated from `stream_seed(seed, b)`.
///
/// The first set is generated by the constructor, so an impossible request fails there. If a
/// later block's generation fails (possible only for dart throwing close to saturation), up to
/// 8 further keys are tried; if all fail, that block repeats the first set.
#[derive(Clone, Debug)]
pub struct Sets<G: SetGenerator> {
    generator: G,
    seed: u64,
    block: u64,
    index: u32,
    first: Vec<crate::Point2>,
    current: Vec<crate::Point2>,
}

impl<G: SetGenerator> Sets<G> {
    /// Sets from `generator` seeded by `seed`; generates (and checks) the first set.
    pub fn new(generator: G, seed: u64) -> Result<Self> {
        let first = to_points(&generator.generate(stream_seed(seed, 0))?);
        Ok(Sets {
            generator,
            seed,
            block: 0,
            index: 0,
            current: first.clone(),
            first,
        })
    }

    /// The set of the current block.
    pub fn current_set(&self) -> &[crate::Point2] {
        &self.current
    }

    /// The generator.
    pub fn generator(&self) -> &G {
        &self.generator
    }

    fn next_block(&mut self) {
        self.block = self.block.wrapping_add(1);
        self.index = 0;
        let mut set = None;
        for attempt in 0..9u64 {
            let key = stream_seed(self.seed, self.block.wrapping_add(attempt << 56));
            if let Ok(s) = self.generator.generate(key) {
                set = Some(to_points(&s));
                break;
            }
        }
        self.current = set.unwrap_or_else(|| self.first.clone());
    }
}

/// `f64` points in `[0,1)^2` as `f32` points (rounding toward zero; never 1.0).
pub(crate) fn to_points(p: &[[f64; 2]]) -> Vec<crate::Point2> {
    use crate::sampler::unit_f32_from_f64;
    p.iter()
        .map(|q| crate::Point2::new(unit_f32_from_f64(q[0]), unit_f32_from_f64(q[1])))
        .collect()
}

impl<G: SetGenerator> crate::Sampler for Sets<G> {
    fn name(&self) -> &'static str {
        self.generator.name()
    }

    fn progression(&self) -> crate::Progression {
        crate::Progression::FixedCount {
            count: self.generator.count() as u64,
        }
    }

    fn next_sample(&mut self) -> crate::Point2 {
        if self.index as usize == self.current.len() {
            self.next_block();
        }
        let p = self.current[self.index as usize];
        self.index += 1;
        p
    }

    fn strata(&self, n: u64) -> Vec<crate::StrataGrid> {
        if n == self.generator.count() as u64 {
            self.generator.grids()
        } else {
            Vec::new()
        }
    }
}

/// Implements [`SamplerNd`] for a fixed-count D-dimensional sampler struct with fields
/// `cursor: BlockCursor`, `dims: u32` and methods `count()`, `begin_block(key)`,
/// `point(i, out)`.
macro_rules! fixed_count_sampler_nd {
    ($ty:ty, $name:literal) => {
        impl $crate::SamplerNd for $ty {
            fn name(&self) -> &'static str {
                $name
            }
            fn dimensions(&self) -> u32 {
                self.dims
            }
            fn progression(&self) -> $crate::Progression {
                $crate::Progression::FixedCount {
                    count: self.count() as u64,
                }
            }
            fn next_point(&mut self, out: &mut [f32]) {
                if self.cursor.at_block_start() {
                    let key = self.cursor.block_key();
                    self.begin_block(key);
                }
                self.point(self.cursor.position().0, out);
                self.cursor.advance(1);
            }
            fn projection_strata(&self, x: u32, y: u32) -> Option<$crate::StrataGrid> {
                if x == y || x >= self.dims || y >= self.dims {
                    return None;
                }
                self.pair_strata(x, y)
            }
        }
    };
}
pub(crate) use fixed_count_sampler_nd;
