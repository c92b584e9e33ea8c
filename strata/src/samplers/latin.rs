//! Latin hypercube sampling (N-rooks): one sample in every row and every column.
//!
//! Shirley, "Discrepancy as a Quality Measure for Sample Distributions" (Eurographics 1991), after
//! McKay, Beckman, Conover (1979). Each coordinate is a 1D jittered set of `N` strata; the
//! coordinates are paired in an independent random order. Every 1D projection is perfectly
//! stratified for any `N`, but 2D can show large gaps; its spectrum has the dark cross along the
//! axes (low power at `u = 0` or `v = 0`) and is white elsewhere.

use super::{Blocks, Fixed, MAX_DIMENSIONS, block_permutations, check_dims};
use crate::counts::CountRule;
use crate::float::Strata;
use crate::hash::{Permutation, Stream, hash_u64};
use crate::prelude::*;
use crate::sampler::{Point2, Seed, StrataGrid};

/// The names of the samplers.
const NROOKS: &str = "nrooks";
const LATIN: &str = "latin";

/// N-rooks (2D Latin hypercube): any `N >= 1`, one point per `1/N` column and per `1/N` row.
///
/// Sample `i` of a set takes column `px(i)` and row `py(i)` for two independent hashed
/// permutations `px`, `py`, so the sequence order is random too and any point is computed in
/// O(1) without tables.
///
/// ```
/// use strata::{Sampler, Seed, samplers::NRooks};
/// let mut s = NRooks::new(7, Seed(3)).unwrap(); // any count
/// let mut cols = vec![false; 7];
/// for _ in 0..7 {
///     cols[(s.next_sample()[0] * 7.0) as usize] = true;
/// }
/// assert!(cols.iter().all(|&c| c));
/// ```
#[derive(Clone, Debug)]
pub struct NRooks {
    count: u32,
    strata: Strata,
    px: Permutation,
    py: Permutation,
    key: u64,
}

impl NRooks {
    /// N-rooks sets of `count >= 1` points seeded by `seed`.
    pub fn new(count: u64, seed: Seed) -> crate::Result<Fixed<Self>> {
        let n = CountRule::Any.check(NROOKS, count)?;
        let identity = Permutation::new(n, 0).expect("n >= 1");
        Fixed::new(
            NRooks {
                count: n,
                strata: Strata::new(n as u64),
                px: identity,
                py: identity,
                key: 0,
            },
            seed,
        )
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.count
    }
}

impl Blocks for NRooks {
    const NAME: &'static str = NROOKS;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        self.px = Permutation::new(self.count, Stream::NRooksX.key32(key)).expect("n >= 1");
        self.py = Permutation::new(self.count, Stream::NRooksY.key32(key)).expect("n >= 1");
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let h = hash_u64(i as u64, self.key);
        self.strata.place2(
            [self.px.apply(i), self.py.apply(i)],
            [h as u32, (h >> 32) as u32],
        )
    }

    fn grids(&self) -> Vec<StrataGrid> {
        StrataGrid::axes(self.count)
    }
}

/// Latin hypercube sampling in `D` dimensions (McKay, Beckman, Conover 1979; Shirley 1991): any
/// `N >= 1`, each coordinate a jittered set of `N` strata, the coordinates paired by independent
/// hashed permutations; every 1D projection has one point per `1/N` stratum.
///
/// ```
/// use strata::{SamplerNd, Seed, samplers::LatinHypercube};
/// let mut s = LatinHypercube::new(10, 4, Seed(1)).unwrap();
/// let mut p = [0.0f32; 4];
/// s.next_point(&mut p);
/// assert!(p.iter().all(|&x| (0.0..1.0).contains(&x)));
/// ```
#[derive(Clone, Debug)]
pub struct LatinHypercube {
    count: u32,
    dims: u32,
    strata: Strata,
    perms: Vec<Permutation>,
    key: u64,
}

impl LatinHypercube {
    /// Sets of `count >= 1` points in `dims` (1 to [`MAX_DIMENSIONS`]) dimensions.
    pub fn new(count: u64, dims: u32, seed: Seed) -> crate::Result<Fixed<Self>> {
        let n = CountRule::Any.check(LATIN, count)?;
        check_dims(LATIN, dims, MAX_DIMENSIONS, "")?;
        Fixed::new(
            LatinHypercube {
                count: n,
                dims,
                strata: Strata::new(n as u64),
                perms: Vec::new(),
                key: 0,
            },
            seed,
        )
    }

    /// Points per set.
    pub fn count(&self) -> u32 {
        self.count
    }
}

impl Blocks for LatinHypercube {
    const NAME: &'static str = LATIN;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn set_dims(&self) -> u32 {
        self.dims
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        block_permutations(&mut self.perms, self.count, key, self.dims);
    }

    /// Pairs of dimensions are N-rooks (one point per row and column), not stratified on a
    /// grid of equal cells.
    fn pair_strata(&self, _x: u32, _y: u32) -> Option<StrataGrid> {
        None
    }

    fn point(&self, i: u32) -> Point2 {
        let mut p = [0.0f32; 2];
        self.point_into(i, &mut p);
        p
    }

    fn point_into(&self, i: u32, out: &mut [f32]) {
        for (d, (o, perm)) in out.iter_mut().zip(&self.perms).enumerate() {
            let h = hash_u64((i as u64) << 16 | d as u64, self.key);
            *o = self.strata.place(perm.apply(i), h as u32);
        }
    }
}
