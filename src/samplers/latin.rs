//! Latin hypercube sampling (N-rooks): one sample in every row and every column.
//!
//! Shirley, "Discrepancy as a Quality Measure for Sample Distributions" (Eurographics 1991), after
//! McKay, Beckman, Conover (1979). Each coordinate is a 1D jittered set of `N` strata; the
//! coordinates are paired in an independent random order. Every 1D projection is perfectly
//! stratified for any `N`, but 2D can show large gaps; its spectrum has the dark cross along the
//! axes (low power at `u = 0` or `v = 0`) and is white elsewhere.

use super::{BlockCursor, check_count, fixed_count_sampler};
use crate::hash::{Permutation, hash_u64, key32};
use crate::sampler::{Point2, Strata, StrataGrid};

/// N-rooks (2D Latin hypercube): any `N >= 1`, one point per `1/N` column and per `1/N` row.
///
/// Sample `i` of a set takes column `px(i)` and row `py(i)` for two independent hashed
/// permutations `px`, `py`, so the sequence order is random too and any point is computed in
/// O(1) without tables.
///
/// ```
/// use strata::{Sampler, samplers::NRooks};
/// let mut s = NRooks::new(7, 3).unwrap(); // any count
/// let mut cols = vec![false; 7];
/// for _ in 0..7 {
///     cols[(s.next_sample().x * 7.0) as usize] = true;
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
    cursor: BlockCursor,
}

impl NRooks {
    /// N-rooks sets of `count >= 1` points seeded by `seed`.
    pub fn new(count: u64, seed: u64) -> crate::Result<Self> {
        let n = check_count("nrooks", count)?;
        let identity = Permutation::new(n, 0).expect("n >= 1");
        Ok(NRooks {
            count: n,
            strata: Strata::new(n as u64),
            px: identity,
            py: identity,
            key: 0,
            cursor: BlockCursor::new(seed, n),
        })
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.count
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        self.px = Permutation::new(self.count, key32(key ^ 0x6c61_7469_6e58)).expect("n >= 1");
        self.py = Permutation::new(self.count, key32(key ^ 0x6c61_7469_6e59)).expect("n >= 1");
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let h = hash_u64(self.key, i as u64);
        self.strata.place2(
            [self.px.apply(i), self.py.apply(i)],
            [h as u32, (h >> 32) as u32],
        )
    }

    fn grids(&self) -> Vec<StrataGrid> {
        vec![
            StrataGrid {
                columns: self.count,
                rows: 1,
            },
            StrataGrid {
                columns: 1,
                rows: self.count,
            },
        ]
    }
}

fixed_count_sampler!(NRooks, "nrooks");
