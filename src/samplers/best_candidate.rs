//! Mitchell's best-candidate sampling: Mitchell, "Spectrally Optimal Sampling for Distribution
//! Ray Tracing" (SIGGRAPH 1991).
//!
//! Progressive: point `n` (counting from 0) is the farthest, toroidally, from the points so far
//! among `k n` uniform candidates (at least one). Every prefix is an approximate Poisson-disk
//! set, so the spectrum is blue noise at every count, at a cost that grows with the count.
//! Candidates are scored with the neighbour grid (a uniform grid on the torus): a candidate that has a point
//! closer than the best score so far is dropped without computing its nearest distance.

use rand_pcg::Pcg32;

use crate::Result;
use crate::counts::CountRule;
use crate::entry::{BlueNoise, Built, Entry, Family, ParameterSpec};
use crate::grid::TorusGrid;
use crate::rng::{pcg, streams, uniform};
use strata::float::unit_f32_from_f64;
use strata::samplers::Epochs;
use strata::{Point2, Progression, Sampler, Seed};

/// The default candidate factor `k`.
pub const DEFAULT_FACTOR: u32 = 1;

/// The largest candidate factor.
pub const MAX_FACTOR: u32 = 1024;

/// The most points a best-candidate sequence generates before it starts over (each point costs
/// `k n` candidates).
pub const MAX_LEN: usize = 1 << 24;

/// `--candidates`: candidates per existing point.
const CANDIDATES: ParameterSpec = ParameterSpec::whole(
    "candidates",
    1,
    MAX_FACTOR,
    DEFAULT_FACTOR,
    "candidates per point, in units of the points placed so far (k n for the next point)",
);

/// The registry entry of `best-candidate`.
pub(crate) const ENTRY: Entry = Entry {
    name: "best-candidate",
    description: "Mitchell's best candidate, progressive (--candidates K per existing point, default 1)",
    paper: "Mitchell 1991",
    family: Family::BlueNoise,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[CANDIDATES],
    promise: "farthest of `k n` candidates",
    expensive: true,
    blue_noise: Some(BlueNoise::published(
        "none found (Mitchell 1991 could not be checked here)",
    )),
    build: |p| {
        let k = ENTRY.parameters[0].read_whole(p);
        Ok(Built::two(BestCandidate::new(k, p.seed)?))
    },
    ..Entry::DEFAULT
};

/// The best-candidate sequence (progressive).
///
/// ```
/// use strata::{Sampler, Seed};
/// use strata_lab::samplers::BestCandidate;
/// let mut s = BestCandidate::new(1, Seed(1)).unwrap();
/// let a = s.next_sample();
/// let b = s.next_sample();
/// let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
/// assert!(d > 0.1); // the second point is far from the first
/// ```
#[derive(Clone, Debug)]
pub struct BestCandidate {
    factor: u32,
    epochs: Epochs,
    rng: Pcg32,
    grid: TorusGrid,
}

impl BestCandidate {
    /// The sequence seeded by `seed` with `factor` (1 to [`MAX_FACTOR`]) candidates per existing
    /// point.
    pub fn new(factor: u32, seed: Seed) -> Result<Self> {
        CANDIDATES.check(ENTRY.name, factor as f64)?;
        let epochs = Epochs::new(MAX_LEN as u64, seed);
        let rng = Self::rng(epochs.key(0));
        Ok(BestCandidate {
            factor,
            epochs,
            rng,
            grid: TorusGrid::new(1),
        })
    }

    /// The candidates' generator of the epoch keyed by `key`.
    fn rng(key: u64) -> Pcg32 {
        pcg(key, streams::BEST_CANDIDATE)
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
        ENTRY.name
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let (i, new_epoch) = self.epochs.advance();
        if let Some(key) = new_epoch {
            self.rng = Self::rng(key);
            self.grid = TorusGrid::new(1);
        }
        let p = match self.grid.points().get(i as usize) {
            Some(&p) => p,
            None => self.grow(),
        };
        [unit_f32_from_f64(p[0]), unit_f32_from_f64(p[1])]
    }
}
