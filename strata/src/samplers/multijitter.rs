//! Multi-jittered sampling: jittered in 2D *and* N-rooks in each 1D projection.
//!
//! * [`MultiJittered`]: Chiu, Shirley, Wang, "Multi-Jittered Sampling" (Graphics Gems IV, 1994).
//!   Start from the canonical arrangement (the point in cell `(i, j)` of the `n x n` grid sits in
//!   x sub-column `j` and y sub-row `i`), then shuffle the x sub-columns independently inside each
//!   column and the y sub-rows inside each row. `N = n^2`.
//! * [`Cmj`]: Kensler, "Correlated Multi-Jittered Sampling" (Pixar Technical Memo 13-01, 2013).
//!   The same construction on an `m x n` grid with `m = floor(sqrt(N))`, `n = ceil(N / m)`, but one
//!   shuffle shared by all columns and one by all rows (correlated), which lowers the
//!   variance further and makes any `N` possible; the sample order is shuffled too. For
//!   `N = m n` it is a full multi-jittered set; otherwise the last row is partly filled, and
//!   no two samples share a cell or a `1/(m n)` stratum in x or y.
//!
//! Both are computed point by point from hashed permutations ([`Permutation`]), with no tables.

use super::{Blocks, Fixed};
use crate::counts::CountRule;
use crate::float::Strata;
use crate::hash::{DivMod, Permutation, Stream, hash_u64, hash32};
use crate::prelude::*;
use crate::sampler::{Point2, Seed, StrataGrid};

/// The names of the samplers.
const MULTIJITTERED: &str = "multijittered";
const CMJ: &str = "cmj";

/// The point of cell `(col, row)` of an `m x n` grid whose x lies in sub-column `sub_x` (of `n`)
/// and y in sub-row `sub_y` (of `m`), jittered by the two halves of `h`; `fine` holds the
/// `m n` strata of each axis.
#[inline]
#[allow(clippy::too_many_arguments)]
fn multi_jittered_point(
    fine: &Strata,
    col: u32,
    row: u32,
    sub_x: u32,
    sub_y: u32,
    m: u32,
    n: u32,
    h: u64,
) -> Point2 {
    fine.place2(
        [col * n + sub_x, row * m + sub_y],
        [h as u32, (h >> 32) as u32],
    )
}

/// The grids a full `m x n` multi-jittered set is stratified in.
fn multi_jittered_grids(m: u32, n: u32) -> Vec<StrataGrid> {
    vec![
        StrataGrid {
            columns: m,
            rows: n,
        },
        StrataGrid {
            columns: m * n,
            rows: 1,
        },
        StrataGrid {
            columns: 1,
            rows: m * n,
        },
    ]
}

/// Chiu et al.'s multi-jittered sets of `N = n^2` points, in row-major cell order.
///
/// ```
/// use strata::{Sampler, Seed, samplers::MultiJittered};
/// let mut s = MultiJittered::new(16, Seed(5)).unwrap();
/// let mut rows = vec![0; 16];
/// for _ in 0..16 {
///     rows[(s.next_sample()[1] * 16.0) as usize] += 1;
/// }
/// assert!(rows.iter().all(|&r| r == 1)); // N-rooks in y
/// ```
#[derive(Clone, Debug)]
pub struct MultiJittered {
    side: DivMod,
    fine: Strata,
    key: u64,
    key_x: u32,
    key_y: u32,
}

impl MultiJittered {
    /// Multi-jittered sets of `count` points seeded by `seed`; `count` must be a perfect square.
    pub fn new(count: u64, seed: Seed) -> crate::Result<Fixed<Self>> {
        let n = CountRule::Square.check(MULTIJITTERED, count)?.isqrt();
        Fixed::new(
            MultiJittered {
                side: DivMod::new(n).expect("side >= 1"),
                fine: Strata::new(n as u64 * n as u64),
                key: 0,
                key_x: 0,
                key_y: 0,
            },
            seed,
        )
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.side.divisor() * self.side.divisor()
    }
}

impl Blocks for MultiJittered {
    const NAME: &'static str = MULTIJITTERED;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        self.key_x = Stream::MultiJitterX.key32(key);
        self.key_y = Stream::MultiJitterY.key32(key);
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let n = self.side.divisor();
        let (row, col) = self.side.div_rem(i);
        // Canonical sub-column of this point is `row`; shuffle it within column `col`.
        let sub_x = Permutation::with_divider(&self.side, hash32(col, self.key_x)).apply(row);
        let sub_y = Permutation::with_divider(&self.side, hash32(row, self.key_y)).apply(col);
        multi_jittered_point(
            &self.fine,
            col,
            row,
            sub_x,
            sub_y,
            n,
            n,
            hash_u64(i as u64, self.key),
        )
    }

    fn grids(&self) -> Vec<StrataGrid> {
        let n = self.side.divisor();
        multi_jittered_grids(n, n)
    }
}

/// Kensler's correlated multi-jittered sets: any `N >= 1`, on an `m x n` grid with
/// `m = floor(sqrt(N))` columns and `n = ceil(N / m)` rows.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Cmj};
/// let mut s = Cmj::new(12, Seed(9)).unwrap(); // a 3 x 4 grid
/// let mut cells = vec![0; 12];
/// for _ in 0..12 {
///     let p = s.next_sample();
///     cells[(p[1] * 4.0) as usize * 3 + (p[0] * 3.0) as usize] += 1;
/// }
/// assert!(cells.iter().all(|&c| c == 1));
/// ```
#[derive(Clone, Debug)]
pub struct Cmj {
    count: u32,
    columns: DivMod,
    rows: u32,
    fine: Strata,
    order: Permutation,
    shuffle_x: Permutation,
    shuffle_y: Permutation,
    key: u64,
}

impl Cmj {
    /// Correlated multi-jittered sets of `count >= 1` points seeded by `seed`.
    pub fn new(count: u64, seed: Seed) -> crate::Result<Fixed<Self>> {
        let count = CountRule::Any.check(CMJ, count)?;
        let m = (count as u64).isqrt() as u32;
        let n = count.div_ceil(m);
        let identity = |len| Permutation::new(len, 0).expect("len >= 1");
        Fixed::new(
            Cmj {
                count,
                columns: DivMod::new(m).expect("m >= 1"),
                rows: n,
                fine: Strata::new(m as u64 * n as u64),
                order: identity(count),
                shuffle_x: identity(n),
                shuffle_y: identity(m),
                key: 0,
            },
            seed,
        )
    }

    /// The number of points in a set.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The grid: `(m, n)` columns and rows.
    pub fn grid(&self) -> (u32, u32) {
        (self.columns.divisor(), self.rows)
    }

    /// Points `i` and `i + 1`, with the permutations evaluated in lockstep.
    #[inline]
    fn point2(&self, i: u32) -> [Point2; 2] {
        let s = self.order.apply2([i, i + 1]);
        let (row0, col0) = self.columns.div_rem(s[0]);
        let (row1, col1) = self.columns.div_rem(s[1]);
        let sub_x = self.shuffle_x.apply2([row0, row1]);
        let sub_y = self.shuffle_y.apply2([col0, col1]);
        let (m, n) = self.grid();
        [
            multi_jittered_point(
                &self.fine,
                col0,
                row0,
                sub_x[0],
                sub_y[0],
                m,
                n,
                hash_u64(i as u64, self.key),
            ),
            multi_jittered_point(
                &self.fine,
                col1,
                row1,
                sub_x[1],
                sub_y[1],
                m,
                n,
                hash_u64(i as u64 + 1, self.key),
            ),
        ]
    }
}

impl Blocks for Cmj {
    const NAME: &'static str = CMJ;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn begin_block(&mut self, key: u64) {
        let (m, n) = self.grid();
        self.key = key;
        self.order = Permutation::new(self.count, Stream::CmjOrder.key32(key)).expect("count >= 1");
        // x sub-columns are indexed by row (n of them), y sub-rows by column (m of them).
        self.shuffle_x = Permutation::new(n, Stream::CmjX.key32(key)).expect("n >= 1");
        self.shuffle_y = Permutation::new(m, Stream::CmjY.key32(key)).expect("m >= 1");
    }

    #[inline]
    fn point(&self, i: u32) -> Point2 {
        let s = self.order.apply(i);
        let (row, col) = self.columns.div_rem(s);
        let sub_x = self.shuffle_x.apply(row);
        let sub_y = self.shuffle_y.apply(col);
        let (m, n) = self.grid();
        multi_jittered_point(
            &self.fine,
            col,
            row,
            sub_x,
            sub_y,
            m,
            n,
            hash_u64(i as u64, self.key),
        )
    }

    /// Two points at a time, so that their dependency chains overlap.
    fn fill_run(&self, start: u32, out: &mut [Point2]) {
        let mut pairs = out.chunks_exact_mut(2);
        let mut i = start;
        for pair in &mut pairs {
            pair.copy_from_slice(&self.point2(i));
            i += 2;
        }
        if let [last] = pairs.into_remainder() {
            *last = self.point(i);
        }
    }

    fn grids(&self) -> Vec<StrataGrid> {
        let (m, n) = self.grid();
        if m as u64 * n as u64 == self.count as u64 {
            multi_jittered_grids(m, n)
        } else {
            Vec::new()
        }
    }
}
