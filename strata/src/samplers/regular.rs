//! Regular sampling: the centres of an `s x s` grid of cells.
//!
//! Deterministic (the seed is ignored): zero variance, but biased for any integrand with
//! detail at the grid's frequency, and its power spectrum is a lattice of peaks of height `N` at
//! the multiples of `s = sqrt(N)` in each axis (aliasing). It is here as the lecture's reference
//! point, not as a sampler to render with.

use super::{Blocks, Fixed};
use crate::counts::CountRule;
use crate::float::Strata;
use crate::hash::DivMod;
use crate::prelude::*;
use crate::sampler::{Point2, Seed, StrataGrid};

/// The name of the sampler.
const NAME: &str = "regular";

/// The `N = s^2` cell centres `((i + 1/2) / s, (j + 1/2) / s)`, in row-major order.
///
/// ```
/// use strata::{Sampler, samplers::Regular};
/// let mut s = Regular::new(4).unwrap();
/// assert_eq!(s.next_sample(), [0.25, 0.25]);
/// assert!(Regular::new(5).is_err()); // not a square: the error names 4 and 9
/// ```
#[derive(Clone, Debug)]
pub struct Regular {
    side: DivMod,
    strata: Strata,
}

impl Regular {
    /// A regular grid of `count` points; `count` must be a perfect square.
    pub fn new(count: u64) -> crate::Result<Fixed<Self>> {
        let n = CountRule::Square.check(NAME, count)?;
        let s = n.isqrt();
        Fixed::new(
            Regular {
                side: DivMod::new(s).expect("side >= 1"),
                strata: Strata::new(s as u64),
            },
            Seed(0),
        )
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.side.divisor() * self.side.divisor()
    }
}

impl Blocks for Regular {
    const NAME: &'static str = NAME;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn begin_block(&mut self, _key: u64) {}

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let (row, col) = self.side.div_rem(i);
        // jitter 2^31 is the offset 1/2: the cell centre.
        self.strata.place2([col, row], [1 << 31, 1 << 31])
    }

    fn grids(&self) -> Vec<StrataGrid> {
        let s = self.side.divisor();
        vec![StrataGrid {
            columns: s,
            rows: s,
        }]
    }
}
