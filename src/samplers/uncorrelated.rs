//! Uncorrelated jitter: Cook, "Stochastic Sampling in Computer Graphics" (ACM TOG 1986).
//!
//! Full stratification of `D` dimensions needs `s^D` samples. Cook's answer: stratify the
//! dimensions in the pairs a renderer uses together (pixel, lens, light: (0,1), (2,3), ...) with
//! an `s x s` jittered set each, a trailing odd dimension with a 1D jittered set of `N = s^2`
//! strata, and combine the sets in independent random orders (here: an independent hashed
//! permutation of the sample index per pair). Each pair's 2D projection is jittered, each
//! trailing dimension stratified; across pairs the samples are uncorrelated, like Latin
//! hypercube sampling (of which this is a special case).

use super::{BlockCursor, MAX_DIMENSIONS, check_count, check_square, fixed_count_sampler_nd};
use crate::hash::{Permutation, hash_u64, key32, stream_seed};
use crate::sampler::Strata;

/// Uncorrelated jitter in `D` dimensions: `N = s^2` (any `N` when `D = 1`).
///
/// ```
/// use strata::{SamplerNd, samplers::UncorrelatedJitter};
/// let mut s = UncorrelatedJitter::new(16, 5, 1).unwrap();
/// let mut p = [0.0f32; 5];
/// s.next_point(&mut p);
/// assert!(p.iter().all(|&x| (0.0..1.0).contains(&x)));
/// ```
#[derive(Clone, Debug)]
pub struct UncorrelatedJitter {
    count: u32,
    side: u32,
    dims: u32,
    pairs: Strata,
    single: Strata,
    perms: Vec<Permutation>,
    key: u64,
    cursor: BlockCursor,
}

impl UncorrelatedJitter {
    /// Sets of `count` points in `dims` (1 to [`MAX_DIMENSIONS`]) dimensions; `count` must be a
    /// perfect square when `dims >= 2`.
    pub fn new(count: u64, dims: u32, seed: u64) -> crate::Result<Self> {
        if dims == 0 || dims > MAX_DIMENSIONS {
            return Err(crate::Error::parameter(
                "uncorrelated",
                "dims",
                dims,
                format!("1 to {MAX_DIMENSIONS}"),
            ));
        }
        let n = check_count("uncorrelated", count)?;
        let side = if dims >= 2 {
            check_square("uncorrelated", count)?
        } else {
            1
        };
        Ok(UncorrelatedJitter {
            count: n,
            side,
            dims,
            pairs: Strata::new(side as u64),
            single: Strata::new(n as u64),
            perms: Vec::new(),
            key: 0,
            cursor: BlockCursor::new(seed, n),
        })
    }

    /// Points per set.
    pub fn count(&self) -> u32 {
        self.count
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        let groups = self.dims.div_ceil(2) as u64;
        self.perms = (0..groups)
            .map(|g| Permutation::new(self.count, key32(stream_seed(key, g))).expect("n >= 1"))
            .collect();
    }

    fn point(&self, i: u32, out: &mut [f32]) {
        let s = self.side;
        for (g, perm) in self.perms.iter().enumerate() {
            let cell = perm.apply(i);
            let h = hash_u64(self.key, (i as u64) << 16 | g as u64);
            let d = 2 * g;
            if d + 1 < self.dims as usize {
                out[d] = self.pairs.place(cell % s, h as u32);
                out[d + 1] = self.pairs.place(cell / s, (h >> 32) as u32);
            } else {
                out[d] = self.single.place(cell, h as u32);
            }
        }
    }
}

fixed_count_sampler_nd!(UncorrelatedJitter, "uncorrelated");
