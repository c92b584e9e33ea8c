//! Mitchell's best-candidate sampling: Mitchell, "Spectrally Optimal Sampling for Distribution
//! Ray Tracing" (SIGGRAPH 1991).
//!
//! Progressive: point `n` (counting from 0) is the farthest, toroidally, from the points so far
//! among `k n` uniform candidates (at least one). Every prefix is an approximate Poisson-disk
//! set, so the spectrum is blue noise at every count, at a cost that grows with the count.
//! Candidates are scored with the neighbour grid ([`TorusGrid`]): a candidate that has a point
//! closer than the best score so far is dropped without computing its nearest distance.

use rand_pcg::Pcg32;

use super::poisson::uniform;
use crate::error::{Error, Result};
use crate::grid::TorusGrid;
use crate::hash::stream_seed;
use crate::sampler::{Point2, Progression, Sampler, unit_f32_from_f64};

/// The default candidate factor `k`.
pub const DEFAULT_FACTOR: u32 = 1;

/// The largest candidate factor.
pub const MAX_FACTOR: u32 = 1024;

/// The most points a best-candidate sequence generates before it starts over (each point costs
/// `k n` candidates).
pub const MAX_LEN: usize = 1 << 24;

/// The best-candidate sequence (progressive).
///
/// ```
/// use strata::{Sampler, samplers::BestCandidate};
/// let mut s = BestCandidate::new(1, 1).unwrap();
/// let a = s.next_sample();
/// let b = s.next_sample();
/// assert!(a.distance(b) > 0.1); // the second point is far from the first
/// ```
#[derive(Clone, Debug)]
pub struct BestCandidate {
    factor: u32,
    seed: u64,
    epoch: u64,
    rng: Pcg32,
    grid: TorusGrid,
    next: usize,
}

impl BestCandidate {
    /// The sequence seeded by `seed` with `factor` (1 to [`MAX_FACTOR`]) candidates per existing
    /// point.
    pub fn new(seed: u64, factor: u32) -> Result<Self> {
        if factor == 0 || factor > MAX_FACTOR {
            return Err(Error::parameter(
                "best-candidate",
                "candidates",
                factor,
                format!("1 to {MAX_FACTOR} candidates per existing point"),
            ));
        }
        Ok(Self::start(seed, 0, factor))
    }

    fn start(seed: u64, epoch: u64, factor: u32) -> Self {
        let key = stream_seed(seed, epoch);
        BestCandidate {
            factor,
            seed,
            epoch,
            rng: Pcg32::new(stream_seed(key, 9), stream_seed(key, 10)),
            grid: TorusGrid::new(1),
            next: 0,
        }
    }

    /// The points generated so far.
    pub fn generated(&self) -> &[[f64; 2]] {
        self.grid.points()
    }

    /// Generates the next point.
    fn grow(&mut self) -> [f64; 2] {
        let n = self.grid.len();
        // Keep about one point per cell.
        if n >= 2 * self.grid.resolution().pow(2) {
            let res = ((2 * n) as f64).sqrt() as usize;
            let pts: Vec<[f64; 2]> = self.grid.points().to_vec();
            self.grid = TorusGrid::new(res);
            for p in pts {
                self.grid.insert(p);
            }
        }
        let candidates = (self.factor as usize * n).max(1);
        let mut best = [uniform(&mut self.rng), uniform(&mut self.rng)];
        let mut best_d2 = self.grid.nearest(best, None).map_or(f64::INFINITY, |x| x.1);
        for _ in 1..candidates {
            let c = [uniform(&mut self.rng), uniform(&mut self.rng)];
            // Only a candidate with no point within the current best distance can win.
            if self.grid.any_closer_than(c, best_d2.sqrt()) {
                continue;
            }
            if let Some((_, d2)) = self.grid.nearest(c, None)
                && d2 > best_d2
            {
                (best, best_d2) = (c, d2);
            }
        }
        self.grid.insert(best);
        best
    }
}

impl Sampler for BestCandidate {
    fn name(&self) -> &'static str {
        "best-candidate"
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        if self.next == MAX_LEN {
            *self = Self::start(self.seed, self.epoch + 1, self.factor);
        }
        let p = if self.next < self.grid.len() {
            self.grid.points()[self.next]
        } else {
            self.grow()
        };
        self.next += 1;
        Point2::new(unit_f32_from_f64(p[0]), unit_f32_from_f64(p[1]))
    }
}
