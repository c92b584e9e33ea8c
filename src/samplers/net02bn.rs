//! `net02bn`: blue-noise (0,m,2)-nets of `N = 2^m` points, optimized by net-preserving swaps.
//!
//! Ahmed and Wonka ("Optimizing Dyadic Nets", SIGGRAPH 2021) observe that a (0,m,2)-net can be
//! optimized for blue noise without ever leaving the set of nets, by moves that map nets to
//! nets. This file uses their simplest move: in a dyadic box of area `2/N` (shape
//! `2^-a x 2^-(m-1-a)`, `a = 0 .. m-1`) a net has exactly two points, and swapping their x
//! coordinates keeps every elementary interval of area `1/N` holding exactly one point.
//!
//! Why: split the box into halves along x; the two points lie in different halves (each half is
//! an elementary interval), and likewise along y. An elementary interval `E` of shape
//! `2^-b x 2^-(m-b)` with `b <= a` constrains only x digits the two points share, so swapping
//! their x keeps each point in its `E`; with `b > a` it constrains only y digits they share
//! (beyond the box's own), so the swapped points trade their `E`s. Either way every `E` keeps
//! one point.
//!
//! The start is an Owen-scrambled Sobol' (0,m,2)-net; the swaps minimise a Gaussian repulsion
//! energy `sum exp(-d^2 / (2 sigma^2))` over toroidal distances, `sigma = SIGMA r_max(N)`,
//! greedily: sweeps visit every box of every shape in a random order and keep a swap that
//! lowers the energy, until a sweep keeps less than [`STOP_FRACTION`] of the points' swaps or
//! after `--sweeps` sweeps (`--iterations`, its older name, is an alias).
//!
//! Guaranteed: every set is a (0,m,2)-net in base 2 (each of the `m + 1` families of
//! elementary intervals of area `1/N` holds exactly one point per interval; tested). Measured
//! (`tests/blue_noise.rs`, `docs/results.md`): larger nearest-neighbour distances and a weaker
//! low-frequency band than `pmj02` or Sobol'.

use crate::counts::CountRule;
use crate::entry::{BlueNoise, Built, Entry, Family, ParameterSpec, Rates};
use crate::grid::relative_radius_max;
use crate::rng::streams;
use crate::samplers::{SetGenerator, Sets};
use crate::{Error, Result};
use strata::hash::{hash_u64, stream_seed};
use strata::samplers::sobol;

/// The kernel width relative to `r_max(N)`.
pub(crate) const SIGMA: f64 = 0.5;

/// Optimisation stops once a sweep keeps fewer swaps than this fraction of the points.
pub const STOP_FRACTION: f64 = 0.002;

/// The default cap on the sweeps (the stopping rule usually ends earlier).
pub const DEFAULT_SWEEPS: u32 = 64;

/// The most sweeps accepted.
pub const MAX_SWEEPS: u32 = 10_000;

/// The largest `m` (`N = 2^m` points).
pub const MAX_LOG2_COUNT: u32 = 20;

/// `--sweeps`: the cap on the sweeps of swaps.
const SWEEPS: ParameterSpec = ParameterSpec::whole(
    "sweeps",
    0,
    MAX_SWEEPS,
    DEFAULT_SWEEPS,
    "the most sweeps of the net-preserving swaps (a stopping rule usually ends them first)",
)
.with_alias("iterations");

/// The registry entry of `net02bn`.
pub(crate) const ENTRY: Entry = Entry {
    name: "net02bn",
    description: "a (0,m,2)-net of N = 2^m points made blue by net-preserving swaps in the boxes of area 2/N (--sweeps K caps them, default 64)",
    paper: "Ahmed, Wonka 2021",
    family: Family::BlueNoise,
    counts: CountRule::PowerOfTwo,
    parameters: &[SWEEPS],
    promise: "a (0,m,2)-net with blue-noise spacing",
    rates: Rates {
        discontinuous: Some(-1.5),
        smooth: Some(-3.0),
        higher: None,
    },
    expensive: true,
    blue_noise: Some(BlueNoise::published(
        "none found (Ahmed and Wonka 2021 could not be checked here)",
    )),
    build: |p| {
        let k = ENTRY.parameters[0].read_whole(p);
        Ok(Built::two(Net02BnSets::new(
            Net02Bn::new(p.count, k)?,
            p.seed,
        )?))
    },
    ..Entry::DEFAULT
};

/// Blue-noise (0,m,2)-nets of `2^m` points.
#[derive(Clone, Debug)]
pub struct Net02Bn {
    log2: u32,
    sweeps: u32,
}

/// What [`Net02Bn::optimize`] did.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Optimized {
    /// The points.
    pub points: Vec<[f64; 2]>,
    /// Sweeps run.
    pub sweeps: u32,
    /// Swaps kept in each sweep.
    pub kept: Vec<u32>,
    /// The energy before the first sweep and after each.
    pub energy: Vec<f64>,
}

impl Net02Bn {
    /// Nets of `count` points (a power of two, at most `2^20`), at most `sweeps` sweeps (0 to
    /// [`MAX_SWEEPS`]; 0 leaves the scrambled Sobol' net).
    pub fn new(count: u64, sweeps: u32) -> Result<Self> {
        ENTRY.counts.check(ENTRY.name, count)?;
        if count > 1 << MAX_LOG2_COUNT {
            return Err(Error::count(
                ENTRY.name,
                count,
                format!("at most 2^{MAX_LOG2_COUNT} points"),
            ));
        }
        SWEEPS.check(ENTRY.name, sweeps as f64)?;
        Ok(Net02Bn {
            log2: count.trailing_zeros(),
            sweeps,
        })
    }

    /// The optimised net for `key`, with the record of the optimisation.
    pub fn optimize(&self, key: u64) -> Optimized {
        let m = self.log2;
        let n = 1usize << m;
        let seed = stream_seed(streams::NET02BN, key);
        let points: Vec<[f64; 2]> = (0..n as u32)
            .map(|i| {
                let c =
                    |d| f64::from(sobol::owen_scrambled(i, d, strata::Seed(seed)).unwrap_or(0.0));
                [c(0), c(1)]
            })
            .collect();
        let mut state = State::new(points, m);
        let mut out = Optimized {
            points: Vec::new(),
            sweeps: 0,
            kept: Vec::new(),
            energy: vec![state.energy()],
        };
        if m >= 1 {
            let mut boxes: Vec<u32> = (0..m)
                .flat_map(|a| (0..(n as u32 / 2)).map(move |b| (a << 24) | b))
                .collect();
            for sweep in 0..self.sweeps {
                shuffle(
                    &mut boxes,
                    stream_seed(streams::NET02BN_SWEEPS + u64::from(sweep), key),
                );
                let kept = boxes.iter().filter(|&&b| state.try_swap(b)).count() as u32;
                out.sweeps += 1;
                out.kept.push(kept);
                out.energy.push(state.energy());
                if f64::from(kept) < STOP_FRACTION * n as f64 {
                    break;
                }
            }
        }
        out.points = state.points;
        out
    }
}

/// Fisher-Yates with a counter-based hash.
fn shuffle(v: &mut [u32], key: u64) {
    for i in (1..v.len()).rev() {
        let j = ((u128::from(hash_u64(i as u64, key)) * (i as u128 + 1)) >> 64) as usize;
        v.swap(i, j);
    }
}

/// The points, their strata and a cell grid for the energy.
struct State {
    m: u32,
    points: Vec<[f64; 2]>,
    /// The point in each x stratum of width `1/N` and each y stratum.
    by_x: Vec<u32>,
    by_y: Vec<u32>,
    /// Cells of the neighbour grid, `res x res`.
    cells: Vec<Vec<u32>>,
    res: usize,
    inv_two_sigma2: f64,
    cutoff2: f64,
}

impl State {
    fn new(points: Vec<[f64; 2]>, m: u32) -> Self {
        let n = points.len();
        let sigma = SIGMA * relative_radius_max(n);
        let cutoff = 3.0 * sigma;
        let res = ((1.0 / cutoff).floor() as usize).clamp(1, 1 << 12);
        let mut s = State {
            m,
            by_x: vec![0; n],
            by_y: vec![0; n],
            cells: vec![Vec::new(); res * res],
            res,
            inv_two_sigma2: 1.0 / (2.0 * sigma * sigma),
            cutoff2: cutoff * cutoff,
            points,
        };
        for (i, p) in s.points.iter().enumerate() {
            let [x, y] = s.strata(*p);
            s.by_x[x] = i as u32;
            s.by_y[y] = i as u32;
            let c = s.cell(*p);
            s.cells[c].push(i as u32);
        }
        s
    }

    fn strata(&self, p: [f64; 2]) -> [usize; 2] {
        let n = (1usize << self.m) as f64;
        [(p[0] * n) as usize, (p[1] * n) as usize]
    }

    fn cell(&self, p: [f64; 2]) -> usize {
        let r = self.res as f64;
        let cx = ((p[0] * r) as usize).min(self.res - 1);
        let cy = ((p[1] * r) as usize).min(self.res - 1);
        cy * self.res + cx
    }

    fn kernel(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        let d2 = crate::grid::torus_distance_squared(a, b);
        if d2 < self.cutoff2 {
            libm::exp(-d2 * self.inv_two_sigma2)
        } else {
            0.0
        }
    }

    /// The energy of a point at `p` against every point except `skip`.
    fn local(&self, p: [f64; 2], skip: [u32; 2]) -> f64 {
        let res = self.res as isize;
        let cx = ((p[0] * self.res as f64) as isize).min(res - 1);
        let cy = ((p[1] * self.res as f64) as isize).min(res - 1);
        let span: &[isize] = match res {
            1 => &[0],
            2 => &[0, 1],
            _ => &[-1, 0, 1],
        };
        let mut e = 0.0;
        for &dy in span {
            let y = (cy + dy).rem_euclid(res) as usize;
            for &dx in span {
                let x = (cx + dx).rem_euclid(res) as usize;
                for &j in &self.cells[y * self.res + x] {
                    if j != skip[0] && j != skip[1] {
                        e += self.kernel(p, self.points[j as usize]);
                    }
                }
            }
        }
        e
    }

    /// The total energy (each pair once).
    fn energy(&self) -> f64 {
        let total: f64 = (0..self.points.len() as u32)
            .map(|i| self.local(self.points[i as usize], [i, i]))
            .sum();
        total / 2.0
    }

    /// The two points of box `b` (shape `a = b >> 24`, index `b & 0xffffff`).
    fn pair(&self, b: u32) -> [u32; 2] {
        let m = self.m;
        let a = b >> 24;
        let idx = b & 0x00ff_ffff;
        // 2^a columns of width 2^(m-a) strata, 2^(m-1-a) rows of height 2^(a+1) strata
        let u = (idx >> (m - 1 - a)) as usize;
        let v = (idx & ((1 << (m - 1 - a)) - 1)) as usize;
        let (wx, wy) = (1usize << (m - a), 1usize << (a + 1));
        let mut found = [u32::MAX; 2];
        let mut k = 0;
        if wx <= wy {
            for x in u * wx..(u + 1) * wx {
                let i = self.by_x[x];
                if self.strata(self.points[i as usize])[1] / wy == v {
                    found[k] = i;
                    k += 1;
                }
            }
        } else {
            for y in v * wy..(v + 1) * wy {
                let i = self.by_y[y];
                if self.strata(self.points[i as usize])[0] / wx == u {
                    found[k] = i;
                    k += 1;
                }
            }
        }
        debug_assert_eq!(k, 2, "a box of area 2/N holds two points of a net");
        found
    }

    /// Swaps the x coordinates of box `b`'s two points if that lowers the energy.
    fn try_swap(&mut self, b: u32) -> bool {
        let [i, j] = self.pair(b);
        let (p, q) = (self.points[i as usize], self.points[j as usize]);
        let (p2, q2) = ([q[0], p[1]], [p[0], q[1]]);
        let skip = [i, j];
        let before = self.local(p, skip) + self.local(q, skip) + self.kernel(p, q);
        let after = self.local(p2, skip) + self.local(q2, skip) + self.kernel(p2, q2);
        if after >= before {
            return false;
        }
        self.move_point(i, p2);
        self.move_point(j, q2);
        let [xi, _] = self.strata(p2);
        let [xj, _] = self.strata(q2);
        self.by_x[xi] = i;
        self.by_x[xj] = j;
        true
    }

    fn move_point(&mut self, i: u32, to: [f64; 2]) {
        let from = self.cell(self.points[i as usize]);
        let c = self.cell(to);
        if from != c {
            let list = &mut self.cells[from];
            if let Some(k) = list.iter().position(|&x| x == i) {
                list.swap_remove(k);
            }
            self.cells[c].push(i);
        }
        self.points[i as usize] = to;
    }
}

impl SetGenerator for Net02Bn {
    const NAME: &'static str = ENTRY.name;

    fn count(&self) -> u32 {
        1 << self.log2
    }

    fn generate(&self, key: u64) -> Result<Vec<[f64; 2]>> {
        Ok(self.optimize(key).points)
    }
}

/// Blue-noise (0,m,2)-nets (fixed count `2^m`).
pub type Net02BnSets = Sets<Net02Bn>;

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether every elementary interval of area `1/N` holds exactly one point.
    fn is_net(points: &[[f64; 2]]) -> bool {
        let n = points.len();
        let m = n.trailing_zeros();
        (0..=m).all(|a| {
            let mut seen = vec![false; n];
            points.iter().all(|p| {
                let x = (p[0] * (1u64 << a) as f64) as usize;
                let y = (p[1] * (1u64 << (m - a)) as f64) as usize;
                !std::mem::replace(&mut seen[(x << (m - a)) | y], true)
            })
        })
    }

    #[test]
    fn sets_stay_nets_and_the_energy_falls() {
        for m in [0u32, 1, 2, 5, 8] {
            let r = Net02Bn::new(1 << m, 16).unwrap().optimize(m as u64 + 3);
            assert!(is_net(&r.points), "m = {m}");
            for w in r.energy.windows(2) {
                assert!(w[1] <= w[0] + 1e-9, "m = {m}: energy rose {w:?}");
            }
            if m >= 5 {
                assert!(
                    r.kept[0] > 0 && r.energy.last() < r.energy.first(),
                    "m = {m}"
                );
            }
        }
    }

    #[test]
    fn the_net_check_catches_a_broken_net() {
        // swap the x of two points that do not share a box of area 2/N: the check must fail
        let mut p = Net02Bn::new(64, 0).unwrap().optimize(1).points;
        assert!(is_net(&p));
        let (i, j) = (0..64)
            .flat_map(|i| (0..64).map(move |j| (i, j)))
            .find(|&(i, j)| (p[i][0] - p[j][0]).abs() > 0.5 && (p[i][1] - p[j][1]).abs() > 0.5)
            .unwrap();
        let t = p[i][0];
        p[i][0] = p[j][0];
        p[j][0] = t;
        assert!(!is_net(&p));
    }

    #[test]
    fn bad_counts_are_errors() {
        for n in [0u64, 3, 1000, 1 << 21] {
            assert!(Net02Bn::new(n, 1).is_err(), "{n}");
        }
        assert!(Net02Bn::new(1024, MAX_SWEEPS + 1).is_err());
    }
}
