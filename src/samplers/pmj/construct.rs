//! The constructive PMJ generators (pmj, pmjbn, pmj02): one doubling at a time.

use rand::Rng;
use rand_pcg::Pcg32;

use crate::grid::{TorusGrid, torus_distance_squared};
use crate::occupancy::{ElementaryIntervals, Strata1D, top_bits};
use crate::rng::streams;
use strata::float::unit_f64_from_u32;
use strata::hash::{hash_u64, stream_seed};
use strata::morton::{morton, unmorton};

/// Which constraints a new point obeys, and how many best-candidate candidates it draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Variant {
    /// 1D strata plus the squarest grids (by the sub-quadrant structure).
    Pmj { candidates: u32 },
    /// Every elementary interval.
    Pmj02 { candidates: u32 },
}

impl Variant {
    fn candidates(self) -> u32 {
        match self {
            Variant::Pmj { candidates } | Variant::Pmj02 { candidates } => candidates,
        }
    }
}

/// Which half each cell's third point flips: `(1, 0)` flips x, `(0, 1)` flips y.
enum Flips {
    /// The same for every cell (pmj02).
    All((u32, u32)),
    /// Per cell owner (pmj).
    Each(Vec<(u32, u32)>),
}

impl Flips {
    #[inline]
    fn get(&self, owner: usize) -> (u32, u32) {
        match self {
            Flips::All(f) => *f,
            Flips::Each(v) => v[owner],
        }
    }
}

/// The state of a construction between doublings.
#[derive(Clone, Debug)]
pub(crate) struct Construction {
    variant: Variant,
    /// Structural decisions: the first point, pass orders, sub-quadrant flips.
    rng: Pcg32,
    /// Candidates draw their randomness from `hash(candidate_key, point, candidate)`, so that the
    /// first candidate of a best-candidate sequence is the point of the plain sequence with the
    /// same seed, and the structural stream above never depends on the candidate count.
    candidate_key: u64,
    intervals: ElementaryIntervals,
    strata: Strata1D,
    grid: Option<TorusGrid>,
    xs: Vec<u32>,
    ys: Vec<u32>,
    /// Best-candidate neighbours: nearest images relative to `origin` when `local`, else points.
    near: Vec<[f64; 2]>,
    origin: [f64; 2],
    local: bool,
}

fn to_f64(p: [u32; 2]) -> [f64; 2] {
    p.map(unit_f64_from_u32)
}

impl Construction {
    pub(crate) fn new(variant: Variant, key: u64) -> Self {
        Construction {
            variant,
            rng: crate::rng::pcg(key, streams::PMJ),
            candidate_key: stream_seed(streams::PMJ_CANDIDATES, key),
            intervals: ElementaryIntervals::default(),
            strata: Strata1D::default(),
            grid: (variant.candidates() > 1).then(|| TorusGrid::new(1)),
            xs: Vec::new(),
            ys: Vec::new(),
            near: Vec::new(),
            origin: [0.0; 2],
            local: false,
        }
    }

    /// A uniform integer in `[0, len)`.
    fn below(&mut self, len: usize) -> usize {
        ((self.rng.next_u32() as u64 * len as u64) >> 32) as usize
    }

    /// Doubles the sequence (or creates its first point).
    ///
    /// New point `n + t` goes to the sub-quadrant of the cell of old point `t ^ mask` (a random
    /// mask per pass, the paper's order). The points are then *decided* cell by cell along a
    /// randomly reflected Z curve over the cells, not in index order: consecutive decisions
    /// then read and mark neighbouring bits of every occupancy shape, so the memory they touch
    /// stays in cache at any size (in index order they jump across megabytes, and the time
    /// per point grew as `N^0.26`). Every aligned block is a net either way.
    pub(crate) fn extend(&mut self, pts: &mut Vec<[u32; 2]>) {
        let n = pts.len();
        if n == 0 {
            let p = [self.rng.next_u32(), self.rng.next_u32()];
            pts.push(p);
            if let Some(g) = &mut self.grid {
                g.insert(to_f64(p));
            }
            return;
        }
        debug_assert!(n.is_power_of_two());
        let log = n.trailing_zeros();
        pts.resize(2 * n, [0, 0]);
        if log.is_multiple_of(2) {
            // 4^k -> 2 4^k: the sub-quadrant diagonally opposite each point.
            let k = log / 2;
            let (m, h) = (2 * k + 1, k + 1);
            self.set_level(m, h, &pts[..n]);
            let mask = self.below(n);
            for (s, [cx, cy]) in self.z_order(&pts[..n], k) {
                self.place(pts, n + (s ^ mask), cx ^ 1, cy ^ 1, m, h);
            }
        } else {
            // 2 4^k -> 4^(k+1): one of the two remaining sub-quadrants of each cell, then the last.
            let k = (log - 1) / 2;
            let q = n / 2;
            let (m, h) = (2 * k + 2, k + 1);
            self.set_level(m, h, &pts[..n]);
            let flips = self.choose_flips(&pts[..n], q, k, h);
            let mask = self.below(q);
            for (s, [cx, cy]) in self.z_order(&pts[..q], k) {
                let (fx, fy) = flips.get(s);
                self.place(pts, n + (s ^ mask), cx ^ fx, cy ^ fy, m, h);
            }
            // the last sub-quadrant: diagonally opposite the points just placed
            let mask = self.below(q);
            for (s, [cx, cy]) in self.z_order(&pts[n..n + q], k) {
                self.place(pts, n + q + (s ^ mask), cx ^ 1, cy ^ 1, m, h);
            }
        }
    }

    /// The points of `pts`, one in each cell of the `2^k x 2^k` grid, as (index in `pts`, cell
    /// at `k + 1` bits per axis), in the order of their cells along a Z curve reflected by a
    /// random mask per axis. Read once in index order; 4 bytes per point.
    fn z_order(
        &mut self,
        pts: &[[u32; 2]],
        k: u32,
    ) -> impl Iterator<Item = (usize, [u32; 2])> + use<> {
        let (rx, ry) = (self.below(1 << k) as u32, self.below(1 << k) as u32);
        // per cell: the index, and the point's next bit on each axis (a pass covers at most
        // 2^30 points below MAX_SEQUENCE_LEN = 2^32, so 30 + 2 bits fit)
        debug_assert!(pts.len() <= 1 << 30);
        let mut order = vec![0u32; pts.len()];
        for (i, &p) in pts.iter().enumerate() {
            let (x, y) = (top_bits(p[0], k + 1), top_bits(p[1], k + 1));
            order[morton((x >> 1) ^ rx, (y >> 1) ^ ry) as usize] =
                (i as u32) << 2 | (x & 1) << 1 | (y & 1);
        }
        order.into_iter().enumerate().map(move |(z, e)| {
            let [x, y] = unmorton(z as u32);
            let cell = [(x ^ rx) << 1 | (e >> 1) & 1, (y ^ ry) << 1 | e & 1];
            ((e >> 2) as usize, cell)
        })
    }

    /// Moves the occupancy structures (and the best-candidate grid) to level `m`.
    fn set_level(&mut self, m: u32, h: u32, pts: &[[u32; 2]]) {
        match self.variant {
            Variant::Pmj { .. } => self.strata.reset(m, pts),
            Variant::Pmj02 { .. } => self.intervals.reset(m, pts),
        }
        if let Some(g) = &mut self.grid {
            *g = TorusGrid::new(1usize << h.min(12));
            for &p in pts {
                g.insert(to_f64(p));
            }
        }
    }

    /// For each of the `q` cell owners `pts[0..q]`, which half to flip for the third point of
    /// its cell: `(1, 0)` flips x, `(0, 1)` flips y.
    fn choose_flips(&mut self, pts: &[[u32; 2]], q: usize, k: u32, h: u32) -> Flips {
        if let Variant::Pmj02 { .. } = self.variant {
            // One coin for the whole pass keeps every aligned block a (0,m,2)-net.
            let f = if self.rng.next_u32() & 1 == 0 {
                (1, 0)
            } else {
                (0, 1)
            };
            return Flips::All(f);
        }
        // PMJ: the paper's "ox-plowing": walk the cells column by column, up and down in turn,
        // choosing the flip that evens out the halves taken in the cell's row (then column).
        let side = 1usize << k;
        let mut owner = vec![0usize; q];
        for (s, p) in pts[..q].iter().enumerate() {
            owner[top_bits(p[1], k) as usize * side + top_bits(p[0], k) as usize] = s;
        }
        let mut flips = vec![(0, 0); q];
        for _attempt in 0..10 {
            let (mut row_bal, mut col_bal) = (vec![0i32; side], vec![0i32; side]);
            for cx in 0..side {
                for step in 0..side {
                    let cy = if cx % 2 == 0 { step } else { side - 1 - step };
                    let s = owner[cy * side + cx];
                    let (hx, hy) = (top_bits(pts[s][0], h) & 1, top_bits(pts[s][1], h) & 1);
                    let flip_x = if row_bal[cy] != 0 && step + 1 < side {
                        // keep hy (flip x) if that moves the row toward balance
                        let want_hy = u32::from(row_bal[cy] < 0);
                        hy == want_hy
                    } else if col_bal[cx] != 0 {
                        let want_hx = u32::from(col_bal[cx] < 0);
                        hx != want_hx
                    } else {
                        self.rng.next_u32() & 1 == 0
                    };
                    let (nx, ny) = if flip_x { (hx ^ 1, hy) } else { (hx, hy ^ 1) };
                    row_bal[cy] += if ny == 1 { 1 } else { -1 };
                    col_bal[cx] += if nx == 1 { 1 } else { -1 };
                    flips[s] = if flip_x { (1, 0) } else { (0, 1) };
                }
            }
            if row_bal.iter().all(|&b| b == 0) {
                break;
            }
        }
        Flips::Each(flips)
    }

    /// Places point `index` in sub-quadrant `(cx, cy)` (`h` bits per axis) at level `m`.
    fn place(&mut self, pts: &mut [[u32; 2]], index: usize, cx: u32, cy: u32, m: u32, h: u32) {
        // The candidate strata: x in [x_lo, x_hi), y in [y_lo, y_hi) at resolution 2^m.
        let per = 1u32 << (m - h);
        let (x_lo, x_hi, y_lo, y_hi);
        match self.variant {
            Variant::Pmj02 { .. } => {
                self.xs.clear();
                self.ys.clear();
                self.intervals
                    .valid_strata(cx, cy, &mut self.xs, &mut self.ys);
                if self.xs.is_empty() || self.ys.is_empty() {
                    // Cannot happen for a sequence built by this construction (tested); stay
                    // inside the sub-quadrant rather than fail.
                    debug_assert!(false, "no valid strata in cell ({cx}, {cy}) at level {m}");
                    self.xs = (cx * per..(cx + 1) * per).collect();
                    self.ys = (cy * per..(cy + 1) * per).collect();
                }
                x_lo = *self.xs.iter().min().expect("non-empty");
                x_hi = *self.xs.iter().max().expect("non-empty") + 1;
                y_lo = *self.ys.iter().min().expect("non-empty");
                y_hi = *self.ys.iter().max().expect("non-empty") + 1;
            }
            Variant::Pmj { .. } => {
                (x_lo, x_hi) = (cx * per, (cx + 1) * per);
                (y_lo, y_hi) = (cy * per, (cy + 1) * per);
                if self.variant.candidates() > 1 {
                    // Many candidates share the point's free strata: list them once.
                    self.xs.clear();
                    self.ys.clear();
                    self.strata.free_strata(0, x_lo, x_hi, &mut self.xs);
                    self.strata.free_strata(1, y_lo, y_hi, &mut self.ys);
                }
            }
        }
        let candidates = self.variant.candidates();
        let mut best = self.candidate(index as u64, 0, m, x_lo, x_hi, y_lo, y_hi);
        if candidates > 1 && index > 1 {
            self.gather_neighbours(m, x_lo, x_hi, y_lo, y_hi);
            let mut best_d2 = self.min_distance_squared(to_f64(best), 0.0);
            for c in 1..candidates {
                let c = self.candidate(index as u64, c, m, x_lo, x_hi, y_lo, y_hi);
                let d2 = self.min_distance_squared(to_f64(c), best_d2);
                if d2 > best_d2 {
                    (best, best_d2) = (c, d2);
                }
            }
        }
        match self.variant {
            Variant::Pmj { .. } => self.strata.mark(best),
            Variant::Pmj02 { .. } => self.intervals.mark(best),
        }
        if let Some(g) = &mut self.grid {
            g.insert(to_f64(best));
        }
        pts[index] = best;
    }

    /// Candidate `c` for point `index`: strata drawn uniformly among the valid ones, jittered
    /// inside.
    #[allow(clippy::too_many_arguments)]
    fn candidate(
        &self,
        index: u64,
        c: u32,
        m: u32,
        x_lo: u32,
        x_hi: u32,
        y_lo: u32,
        y_hi: u32,
    ) -> [u32; 2] {
        let slot = (index << 16 | c as u64) << 1;
        let jitter = |s: u32, r: u32| {
            if m >= 32 {
                s
            } else {
                (s << (32 - m)) | (r >> m)
            }
        };
        let r1 = hash_u64(slot + 1, self.candidate_key);
        if let (Variant::Pmj02 { .. }, [sx], [sy]) =
            (self.variant, self.xs.as_slice(), self.ys.as_slice())
        {
            // pmj02's usual case: one valid stratum pair, only the jitter varies
            return [jitter(*sx, r1 as u32), jitter(*sy, (r1 >> 32) as u32)];
        }
        let r0 = hash_u64(slot, self.candidate_key);
        let below = |r: u32, len: usize| ((r as u64 * len as u64) >> 32) as usize;
        let (sx, sy) = match self.variant {
            Variant::Pmj02 { .. } => (
                self.xs[below(r0 as u32, self.xs.len())],
                self.ys[below((r0 >> 32) as u32, self.ys.len())],
            ),
            Variant::Pmj { .. }
                if !self.xs.is_empty() && !self.ys.is_empty() && self.variant.candidates() > 1 =>
            {
                (
                    self.xs[below(r0 as u32, self.xs.len())],
                    self.ys[below((r0 >> 32) as u32, self.ys.len())],
                )
            }
            Variant::Pmj { .. } => {
                let pick = |axis: usize, lo: u32, hi: u32, r: u32| {
                    let free = self.strata.free_count(axis, lo, hi);
                    if free == 0 {
                        debug_assert!(false, "no free stratum");
                        lo + below(r, (hi - lo) as usize) as u32
                    } else {
                        self.strata
                            .nth_free(axis, lo, hi, below(r, free))
                            .expect("counted")
                    }
                };
                (
                    pick(0, x_lo, x_hi, r0 as u32),
                    pick(1, y_lo, y_hi, (r0 >> 32) as u32),
                )
            }
        };
        [jitter(sx, r1 as u32), jitter(sy, (r1 >> 32) as u32)]
    }

    /// Collects into `near` every existing point that can be the nearest neighbour of some
    /// point of the candidate region (strata `[x_lo, x_hi) x [y_lo, y_hi)` at level `m`): those
    /// within `d0 + 2 r` of the region's centre, `d0` the centre's nearest-neighbour distance
    /// and `r` the region's half diagonal. Candidates are then scored against `near` only.
    fn gather_neighbours(&mut self, m: u32, x_lo: u32, x_hi: u32, y_lo: u32, y_hi: u32) {
        let cell = 0.5f64.powi(m as i32);
        let centre = [
            (x_lo + x_hi) as f64 * 0.5 * cell,
            (y_lo + y_hi) as f64 * 0.5 * cell,
        ];
        let half_diag =
            0.5 * cell * (((x_hi - x_lo) as f64).powi(2) + ((y_hi - y_lo) as f64).powi(2)).sqrt();
        self.near.clear();
        let grid = self.grid.as_ref().expect("best candidate has a grid");
        let Some((_, d0)) = grid.nearest(centre, None) else {
            return;
        };
        let reach = d0.sqrt() + 2.0 * half_diag;
        // Small regions (the usual case): keep each neighbour as its nearest image relative to
        // the centre, so candidates need no wrap-around; it is the nearest image for every
        // candidate too, because all of them are within `half_diag` of the centre.
        self.local = reach + half_diag < 0.25;
        self.origin = centre;
        let (near, local) = (&mut self.near, self.local);
        grid.for_each_within(centre, reach, |i, _| {
            let q = grid.points()[i];
            near.push(if local {
                let d = [q[0] - centre[0], q[1] - centre[1]];
                [d[0] - d[0].round(), d[1] - d[1].round()]
            } else {
                q
            });
            true
        });
    }

    /// The squared toroidal distance from `p` to the nearest gathered neighbour; stops early
    /// (returning something `<= floor`) once below `floor`.
    fn min_distance_squared(&self, p: [f64; 2], floor: f64) -> f64 {
        let mut best = f64::INFINITY;
        let local = [p[0] - self.origin[0], p[1] - self.origin[1]];
        for &q in &self.near {
            let d2 = if self.local {
                let (dx, dy) = (q[0] - local[0], q[1] - local[1]);
                dx * dx + dy * dy
            } else {
                torus_distance_squared(p, q)
            };
            if d2 < best {
                best = d2;
                if best <= floor {
                    break;
                }
            }
        }
        best
    }
}
