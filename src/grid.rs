//! The uniform-grid neighbour accelerator on the unit torus.
//!
//! Points are bucketed into `res x res` square cells (linked lists: one head per cell, one link
//! per point, so insertion is O(1) and nothing is reallocated per cell). Queries visit the cells
//! in growing square rings around the query point and stop once no unvisited cell can hold a
//! closer point. Distances are toroidal (the unit square with opposite edges glued), so that
//! patterns have no boundary and their spectra are honest.
//!
//! Used by the point-set measures (nearest-neighbour distances), dart throwing, Bridson's
//! algorithm and best-candidate sampling.

/// No point / end of a cell's list.
const NONE: u32 = u32::MAX;

/// The squared toroidal distance between two points of the unit torus.
#[inline]
pub fn torus_distance_squared(a: [f64; 2], b: [f64; 2]) -> f64 {
    let mut dx = (a[0] - b[0]).abs();
    let mut dy = (a[1] - b[1]).abs();
    if dx > 0.5 {
        dx = 1.0 - dx;
    }
    if dy > 0.5 {
        dy = 1.0 - dy;
    }
    dx * dx + dy * dy
}

/// A dynamic set of points on the unit torus with fast neighbour queries.
#[derive(Clone, Debug)]
pub struct TorusGrid {
    res: usize,
    heads: Vec<u32>,
    next: Vec<u32>,
    points: Vec<[f64; 2]>,
}

impl TorusGrid {
    /// An empty grid of `res x res` cells (`res` is clamped to `1..=4096`).
    pub fn new(res: usize) -> Self {
        let res = res.clamp(1, 4096);
        TorusGrid {
            res,
            heads: vec![NONE; res * res],
            next: Vec::new(),
            points: Vec::new(),
        }
    }

    /// An empty grid whose cells are no smaller than `cell` (so that a disc of radius `cell`
    /// around a point touches at most the 3 x 3 cells around it).
    pub fn with_cell_size(cell: f64) -> Self {
        let res = if cell > 0.0 && cell.is_finite() {
            (1.0 / cell).floor() as usize
        } else {
            4096
        };
        Self::new(res.max(1))
    }

    /// A grid holding `points`, with about one point per cell.
    pub fn from_points(points: impl IntoIterator<Item = [f64; 2]>) -> Self {
        let points: Vec<[f64; 2]> = points.into_iter().collect();
        let res = (points.len() as f64).sqrt().floor() as usize;
        let mut g = Self::new(res.max(1));
        g.points.reserve(points.len());
        g.next.reserve(points.len());
        for p in points {
            g.insert(p);
        }
        g
    }

    /// Cells per axis.
    pub fn resolution(&self) -> usize {
        self.res
    }

    /// The number of points held.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when no point is held.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The points, in insertion order.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The cell of a coordinate in `[0, 1)` (values outside are wrapped).
    #[inline]
    fn cell_of(&self, c: f64) -> usize {
        let c = c - c.floor();
        ((c * self.res as f64) as usize).min(self.res - 1)
    }

    /// Adds a point (coordinates in `[0, 1)`) and returns its index.
    pub fn insert(&mut self, p: [f64; 2]) -> usize {
        let i = self.points.len();
        let cell = self.cell_of(p[1]) * self.res + self.cell_of(p[0]);
        self.points.push(p);
        self.next.push(self.heads[cell]);
        self.heads[cell] = i as u32;
        i
    }

    /// Calls `f(index, squared distance)` for every point within toroidal distance `r` of `p`
    /// (`r < 0.5`); stops early when `f` returns false. Returns false if stopped early.
    pub fn for_each_within(
        &self,
        p: [f64; 2],
        r: f64,
        mut f: impl FnMut(usize, f64) -> bool,
    ) -> bool {
        let r2 = r * r;
        let reach = ((r * self.res as f64).ceil() as isize).min(self.res as isize / 2 + 1);
        let (cx, cy) = (self.cell_of(p[0]) as isize, self.cell_of(p[1]) as isize);
        let res = self.res as isize;
        let span = (2 * reach + 1).min(res);
        let (x0, y0) = (cx - reach, cy - reach);
        for dy in 0..span {
            let row = (y0 + dy).rem_euclid(res) as usize;
            for dx in 0..span {
                let col = (x0 + dx).rem_euclid(res) as usize;
                let mut i = self.heads[row * self.res + col];
                while i != NONE {
                    let d2 = torus_distance_squared(p, self.points[i as usize]);
                    if d2 <= r2 && !f(i as usize, d2) {
                        return false;
                    }
                    i = self.next[i as usize];
                }
            }
        }
        true
    }

    /// True when some point lies strictly closer than `r` to `p`.
    pub fn any_closer_than(&self, p: [f64; 2], r: f64) -> bool {
        let r2 = r * r;
        !self.for_each_within(p, r, |_, d2| d2 >= r2)
    }

    /// The nearest point to `p` other than point `exclude` (if given): its index and squared
    /// toroidal distance, or `None` when there is no other point.
    pub fn nearest(&self, p: [f64; 2], exclude: Option<usize>) -> Option<(usize, f64)> {
        let res = self.res as isize;
        let (cx, cy) = (self.cell_of(p[0]) as isize, self.cell_of(p[1]) as isize);
        let cell = 1.0 / self.res as f64;
        let mut best: Option<(usize, f64)> = None;
        let max_ring = res / 2 + 1;
        for ring in 0..=max_ring {
            // Every point in ring `ring` or beyond is at least (ring - 1) cells away.
            if let Some((_, d2)) = best {
                let gap = (ring - 1).max(0) as f64 * cell;
                if gap * gap > d2 {
                    break;
                }
            }
            let mut visit = |col: isize, row: isize| {
                let (col, row) = (col.rem_euclid(res) as usize, row.rem_euclid(res) as usize);
                let mut i = self.heads[row * self.res + col];
                while i != NONE {
                    if Some(i as usize) != exclude {
                        let d2 = torus_distance_squared(p, self.points[i as usize]);
                        if best.is_none_or(|(_, b)| d2 < b) {
                            best = Some((i as usize, d2));
                        }
                    }
                    i = self.next[i as usize];
                }
            };
            if ring == 0 {
                visit(cx, cy);
                continue;
            }
            if 2 * ring + 1 > res {
                // The ring wraps onto cells already visited: scan everything left once.
                for row in 0..res {
                    for col in 0..res {
                        let (ddx, ddy) = ((col - cx).rem_euclid(res), (row - cy).rem_euclid(res));
                        let ddx = ddx.min(res - ddx);
                        let ddy = ddy.min(res - ddy);
                        if ddx.max(ddy) >= ring {
                            visit(col, row);
                        }
                    }
                }
                break;
            }
            for d in -ring..=ring {
                visit(cx + d, cy - ring);
                visit(cx + d, cy + ring);
            }
            for d in -ring + 1..ring {
                visit(cx - ring, cy + d);
                visit(cx + ring, cy + d);
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::mix64;

    fn random_points(n: usize, seed: u64) -> Vec<[f64; 2]> {
        let mut h = seed;
        (0..n)
            .map(|_| {
                h = mix64(h.wrapping_add(1));
                [
                    (h >> 11) as f64 / (1u64 << 53) as f64,
                    ((h << 20) >> 11) as f64 / (1u64 << 53) as f64,
                ]
            })
            .collect()
    }

    #[test]
    fn torus_distance_wraps() {
        let d = torus_distance_squared([0.05, 0.5], [0.95, 0.5]).sqrt();
        assert!((d - 0.1).abs() < 1e-12);
    }

    #[test]
    fn nearest_matches_brute_force() {
        for (n, res) in [(1usize, 1usize), (2, 3), (50, 7), (500, 22), (300, 2)] {
            let pts = random_points(n, n as u64);
            let mut g = TorusGrid::new(res);
            for &p in &pts {
                g.insert(p);
            }
            for (i, &p) in pts.iter().enumerate() {
                let brute = pts
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != i)
                    .map(|(j, &q)| (j, torus_distance_squared(p, q)))
                    .min_by(|a, b| a.1.total_cmp(&b.1));
                let got = g.nearest(p, Some(i));
                assert_eq!(
                    got.map(|x| x.1),
                    brute.map(|x| x.1),
                    "n={n} res={res} i={i}"
                );
            }
        }
    }

    #[test]
    fn within_matches_brute_force() {
        let pts = random_points(400, 9);
        let g = TorusGrid::from_points(pts.iter().copied());
        for r in [0.01, 0.05, 0.2, 0.49] {
            for &p in pts.iter().take(40) {
                let mut found = Vec::new();
                g.for_each_within(p, r, |i, _| {
                    found.push(i);
                    true
                });
                found.sort();
                let brute: Vec<usize> = (0..pts.len())
                    .filter(|&j| torus_distance_squared(p, pts[j]) <= r * r)
                    .collect();
                assert_eq!(found, brute, "r={r}");
            }
        }
    }
}
