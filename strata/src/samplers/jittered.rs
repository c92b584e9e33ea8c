//! Jittered (stratified) sampling: one uniform point in each cell of an `s x s` grid.
//!
//! Cook, "Stochastic Sampling in Computer Graphics" (ACM TOG 1986). Unbiased, and it provably
//! cannot increase variance over random sampling; in 2D its variance falls as `N^-1.5` for
//! integrands with discontinuities and `N^-2` for smooth ones. Its expected power spectrum is
//! `1 - sinc^2(u/s) sinc^2(v/s)` away from the lattice of multiples of `s` (Subr and Kautz 2013):
//! low power near DC, no peaks. The cost is a count fixed in advance, and a square one.

use super::{Blocks, Fixed};
use crate::counts::CountRule;
use crate::float::Strata;
use crate::hash::{DivMod, hash_u64};
use crate::prelude::*;
use crate::sampler::{Point2, Seed, StrataGrid};

/// The name of the sampler.
const NAME: &str = "jittered";

/// One uniform point per cell of an `s x s` grid (`N = s^2`), cells in row-major order.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Jittered};
/// let mut s = Jittered::new(9, Seed(1)).unwrap();
/// let p = s.next_sample(); // the first cell is [0, 1/3) x [0, 1/3)
/// assert!(p[0] < 1.0 / 3.0 && p[1] < 1.0 / 3.0);
/// ```
#[derive(Clone, Debug)]
pub struct Jittered {
    side: DivMod,
    strata: Strata,
    key: u64,
}

impl Jittered {
    /// Jittered sets of `count` points seeded by `seed`; `count` must be a perfect square.
    pub fn new(count: u64, seed: Seed) -> crate::Result<Fixed<Self>> {
        let n = CountRule::Square.check(NAME, count)?;
        let s = n.isqrt();
        Fixed::new(
            Jittered {
                side: DivMod::new(s).expect("side >= 1"),
                strata: Strata::new(s as u64),
                key: 0,
            },
            seed,
        )
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.side.divisor() * self.side.divisor()
    }
}

impl Blocks for Jittered {
    const NAME: &'static str = NAME;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let (row, col) = self.side.div_rem(i);
        let h = hash_u64(i as u64, self.key);
        self.strata.place2([col, row], [h as u32, (h >> 32) as u32])
    }

    fn grids(&self) -> Vec<StrataGrid> {
        let s = self.side.divisor();
        vec![StrataGrid {
            columns: s,
            rows: s,
        }]
    }
}
