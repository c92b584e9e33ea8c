//! The [`Sampler`] traits (2D and D-dimensional), the point type, and the shape of a stream.

use crate::prelude::*;
/// A 2D sample point in `[0,1)^2`: `[x, y]` (`glam::Vec2::from(p)` and the like convert it).
pub type Point2 = [f32; 2];

/// The seed of a sampler: every random choice it makes is derived from it, and the same seed
/// gives the same bits on every platform. A type of its own, so that a count and a seed cannot
/// be swapped in a constructor: `Jittered::new(64, Seed(7))`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Seed(pub u64);

/// How a sampler's stream is organised.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Progression {
    /// An endless sequence whose prefixes are well distributed (which prefixes, and how well,
    /// is documented per sampler: for PMJ every power of two, for random every prefix).
    Progressive,
    /// A set built for `count` samples: each complete block of `count` consecutive samples is
    /// one well-distributed set, independent of the other blocks.
    FixedCount {
        /// The number of samples in each set.
        count: u64,
    },
}

impl Progression {
    /// True for [`Progression::Progressive`].
    pub fn is_progressive(&self) -> bool {
        matches!(self, Progression::Progressive)
    }
}

/// A grid of strata (`columns` x `rows` equal cells of the unit square) in which a sampler places
/// its samples, one per cell, for drawing and for tests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct StrataGrid {
    /// Cells along x.
    pub columns: u32,
    /// Cells along y.
    pub rows: u32,
}

impl StrataGrid {
    /// The grids of the elementary intervals of a (0,m,2)-net of `n = 2^m` points (`n` at most
    /// `2^31`; none otherwise): the squarest shape first (both, when `m` is odd), then every
    /// other shape `2^a x 2^(m-a)` (`all_shapes`) or only the 1D ones `n x 1` and `1 x n`;
    /// none with more than `2^24` cells along a side, which `f32` values cannot fill.
    pub fn net(n: u64, all_shapes: bool) -> Vec<StrataGrid> {
        if n == 0 || !n.is_power_of_two() || n > 1 << 31 {
            return Vec::new();
        }
        let mut grids = Self::net_shapes(n, all_shapes);
        grids.retain(StrataGrid::resolvable);
        grids
    }

    /// The finest side a promise names: `2^24` cells (an `f32` in `[1/2, 1)` is a multiple of
    /// `2^-24`, so a finer column or row near 1 can hold no value).
    pub(crate) const MAX_SIDE: u32 = 1 << 24;

    /// True when `f32` values can fill every cell (both sides at most [`Self::MAX_SIDE`]).
    pub(crate) fn resolvable(&self) -> bool {
        self.columns <= Self::MAX_SIDE && self.rows <= Self::MAX_SIDE
    }

    /// Every grid of [`net`](Self::net), resolvable or not.
    fn net_shapes(n: u64, all_shapes: bool) -> Vec<StrataGrid> {
        if n == 0 || !n.is_power_of_two() || n > 1 << 31 {
            return Vec::new();
        }
        let m = n.trailing_zeros();
        let g = |a: u32| StrataGrid {
            columns: 1 << a,
            rows: 1 << (m - a),
        };
        let mut grids = vec![g(m / 2)];
        if m % 2 == 1 {
            grids.push(g(m / 2 + 1));
        }
        if all_shapes {
            grids.extend(
                (0..=m)
                    .filter(|&a| a != m / 2 && !(m % 2 == 1 && a == m / 2 + 1))
                    .map(g),
            );
        } else if m > 0 {
            grids.push(g(m));
            grids.push(g(0));
        }
        grids
    }

    /// The two 1D stratifications of `n` points: `n x 1` and `1 x n` (a Latin-hypercube
    /// promise, one point per `1/n` along each axis).
    pub(crate) fn axes(n: u32) -> Vec<StrataGrid> {
        if n > Self::MAX_SIDE {
            return Vec::new();
        }
        vec![
            StrataGrid {
                columns: n,
                rows: 1,
            },
            StrataGrid {
                columns: 1,
                rows: n,
            },
        ]
    }
}

/// A source of 2D sample points in `[0,1)^2`.
///
/// The trait is object safe, so samplers can be chosen at run time
/// (`Box<dyn Sampler>`; the lab's registry builds every sampler by name).
///
/// [`next_sample`](Sampler::next_sample) is an endless stream. A progressive sampler
/// ([`Progression::Progressive`]) is well distributed at every prefix it documents; a fixed-count
/// sampler is well distributed in each complete block of its count and starts a new, independent
/// set after each block.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Jittered};
/// let mut s = Jittered::new(16, Seed(7)).unwrap();
/// let mut pts = vec![[0.0f32; 2]; 16];
/// s.fill(&mut pts);
/// // one point in each cell of the 4 x 4 grid
/// let mut cells: Vec<_> = pts.iter().map(|p| ((p[0] * 4.0) as u32, (p[1] * 4.0) as u32)).collect();
/// cells.sort();
/// cells.dedup();
/// assert_eq!(cells.len(), 16);
/// ```
pub trait Sampler: Send {
    /// The registered name (`"jittered"`, `"pmj02"`, ...).
    fn name(&self) -> &'static str;

    /// Progressive, or fixed-count and for which count.
    fn progression(&self) -> Progression;

    /// The next point of the stream. Never fails, never ends, never returns a coordinate >= 1.
    fn next_sample(&mut self) -> Point2;

    /// Fills `out` with the next `out.len()` points: the same points, in the same order, as
    /// calling [`next_sample`](Sampler::next_sample) that many times.
    fn fill(&mut self, out: &mut [Point2]) {
        for p in out {
            *p = self.next_sample();
        }
    }

    /// Moves `n` samples on in constant time, as `n` calls of
    /// [`next_sample`](Sampler::next_sample) would, where the sampler can (true: Sobol', the
    /// lattice); otherwise does nothing and returns false.
    fn skip(&mut self, n: u64) -> bool {
        let _ = n;
        false
    }

    /// The strata grids, coarsest first, in which the first `n` samples lie one per cell (empty
    /// when the sampler promises none at that count; never a grid of more than `2^24` cells
    /// along a side, which `f32` values cannot fill). Used to draw grids and by tests.
    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        let _ = n;
        Vec::new()
    }
}

/// A source of `D`-dimensional sample points in `[0,1)^D`, beside the 2D [`Sampler`]: the same
/// seeding, the same errors, the same float rules, the same progressive / fixed-count
/// organisation.
///
/// ```
/// use strata::{SamplerNd, Seed, samplers::SobolNd};
/// let mut s = SobolNd::new(5, Seed(1))?;
/// let mut p = [0.0f32; 5];
/// s.next_point(&mut p);
/// assert!(p.iter().all(|&v| (0.0..1.0).contains(&v)));
/// # Ok::<(), strata::Error>(())
/// ```
pub trait SamplerNd: Send {
    /// The registered name.
    fn name(&self) -> &'static str;

    /// `D`: the number of coordinates per point.
    fn dimensions(&self) -> u32;

    /// Progressive, or fixed-count and for which count.
    fn progression(&self) -> Progression;

    /// Writes the next point into `out[..D]` (`out` must hold at least `D` values).
    fn next_point(&mut self, out: &mut [f32]);

    /// Fills `out` (a multiple of `D` values) with consecutive points, point-major.
    fn fill(&mut self, out: &mut [f32]) {
        let d = self.dimensions() as usize;
        for chunk in out.chunks_exact_mut(d) {
            self.next_point(chunk);
        }
    }

    /// Moves `n` points on in constant time, as `n` calls of
    /// [`next_point`](SamplerNd::next_point) would, where the sampler can (true); otherwise
    /// does nothing and returns false. Lets a caller fill one long stream in parallel, each
    /// thread with its own sampler started at its own offset. Sobol' can.
    fn skip(&mut self, n: u64) -> bool {
        let _ = n;
        false
    }

    /// The grid on which the 2D projection onto dimensions `x` (columns) and `y` (rows) of a
    /// complete set is stratified, every cell holding the same number of points; `None` where
    /// the sampler promises no such grid (for drawing; the tests count the cells).
    fn projection_strata(&self, x: u32, y: u32) -> Option<StrataGrid> {
        let _ = (x, y);
        None
    }
}

impl core::fmt::Debug for dyn SamplerNd {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SamplerNd")
            .field("name", &self.name())
            .field("dimensions", &self.dimensions())
            .finish()
    }
}

impl core::fmt::Debug for dyn Sampler {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Sampler")
            .field("name", &self.name())
            .field("progression", &self.progression())
            .finish()
    }
}

/// A boxed sampler is a sampler.
impl Sampler for Box<dyn Sampler> {
    fn name(&self) -> &'static str {
        (**self).name()
    }
    fn progression(&self) -> Progression {
        (**self).progression()
    }
    fn next_sample(&mut self) -> Point2 {
        (**self).next_sample()
    }
    fn fill(&mut self, out: &mut [Point2]) {
        (**self).fill(out)
    }
    fn skip(&mut self, n: u64) -> bool {
        (**self).skip(n)
    }
    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        (**self).strata(n)
    }
}

/// A 2D sampler is a D-dimensional sampler with `D = 2`.
impl SamplerNd for Box<dyn Sampler> {
    fn name(&self) -> &'static str {
        (**self).name()
    }
    fn dimensions(&self) -> u32 {
        2
    }
    fn progression(&self) -> Progression {
        (**self).progression()
    }
    fn next_point(&mut self, out: &mut [f32]) {
        let p = (**self).next_sample();
        for (o, v) in out.iter_mut().zip(p) {
            *o = v;
        }
    }
    fn skip(&mut self, n: u64) -> bool {
        (**self).skip(n)
    }
}
