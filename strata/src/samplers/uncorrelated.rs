//! Uncorrelated jitter: Cook, "Stochastic Sampling in Computer Graphics" (ACM TOG 1986).
//!
//! Full stratification of `D` dimensions needs `s^D` samples. Cook's answer: stratify the
//! dimensions in the pairs a renderer uses together (pixel, lens, light: (0,1), (2,3), ...) with
//! an `s x s` jittered set each, a trailing odd dimension with a 1D jittered set of `N = s^2`
//! strata, and combine the sets in independent random orders (here: an independent hashed
//! permutation of the sample index per pair). Each pair's 2D projection is jittered, each
//! trailing dimension stratified; across pairs the samples are uncorrelated, like Latin
//! hypercube sampling (of which this is a special case).

use super::{Blocks, Fixed, MAX_DIMENSIONS, block_permutations, check_dims};
use crate::counts::CountRule;
use crate::float::Strata;
use crate::hash::{DivMod, Permutation, hash_u64};
use crate::prelude::*;
use crate::sampler::{Point2, Seed, StrataGrid};

/// The name of the sampler.
const NAME: &str = "uncorrelated";

/// Uncorrelated jitter in `D` dimensions: `N = s^2` (any `N` when `D = 1`).
///
/// ```
/// use strata::{SamplerNd, Seed, samplers::UncorrelatedJitter};
/// let mut s = UncorrelatedJitter::new(16, 5, Seed(1)).unwrap();
/// let mut p = [0.0f32; 5];
/// s.next_point(&mut p);
/// assert!(p.iter().all(|&x| (0.0..1.0).contains(&x)));
/// ```
#[derive(Clone, Debug)]
pub struct UncorrelatedJitter {
    count: u32,
    side: DivMod,
    dims: u32,
    pairs: Strata,
    single: Strata,
    perms: Vec<Permutation>,
    key: u64,
}

impl UncorrelatedJitter {
    /// Sets of `count` points in `dims` (1 to [`MAX_DIMENSIONS`]) dimensions; `count` must be a
    /// perfect square when `dims >= 2`.
    pub fn new(count: u64, dims: u32, seed: Seed) -> crate::Result<Fixed<Self>> {
        check_dims(NAME, dims, MAX_DIMENSIONS, "")?;
        let (n, side) = if dims >= 2 {
            let n = CountRule::Square.check(NAME, count)?;
            (n, n.isqrt())
        } else {
            (CountRule::Any.check(NAME, count)?, 1)
        };
        Fixed::new(
            UncorrelatedJitter {
                count: n,
                side: DivMod::new(side).expect("side >= 1"),
                dims,
                pairs: Strata::new(side as u64),
                single: Strata::new(n as u64),
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

impl Blocks for UncorrelatedJitter {
    const NAME: &'static str = NAME;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn set_dims(&self) -> u32 {
        self.dims
    }

    /// The pairs (0,1), (2,3), ... are jittered on the `s x s` grid; other pairs are not
    /// stratified together.
    fn pair_strata(&self, x: u32, y: u32) -> Option<StrataGrid> {
        let s = self.side.divisor();
        (x / 2 == y / 2 && s > 1).then_some(StrataGrid {
            columns: s,
            rows: s,
        })
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        block_permutations(&mut self.perms, self.count, key, self.dims.div_ceil(2));
    }

    fn point(&self, i: u32) -> Point2 {
        let mut p = [0.0f32; 2];
        self.point_into(i, &mut p);
        p
    }

    fn point_into(&self, i: u32, out: &mut [f32]) {
        let groups = out.len().min(self.dims as usize).div_ceil(2);
        for (g, perm) in self.perms.iter().enumerate().take(groups) {
            let cell = perm.apply(i);
            let h = hash_u64((i as u64) << 16 | g as u64, self.key);
            let d = 2 * g;
            if d + 1 < self.dims as usize {
                let (row, col) = self.side.div_rem(cell);
                out[d] = self.pairs.place(col, h as u32);
                if let Some(o) = out.get_mut(d + 1) {
                    *o = self.pairs.place(row, (h >> 32) as u32);
                }
            } else {
                out[d] = self.single.place(cell, h as u32);
            }
        }
    }
}
