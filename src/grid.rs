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

/// `r_max(N) = sqrt(2 / (sqrt(3) N))`: the distance between neighbours when `N` points are
/// packed hexagonally on the unit torus (Lagae and Dutré 2008). Poisson-disk radii and the PSA
/// distance measures are relative to it.
pub fn relative_radius_max(n: usize) -> f64 {
    (2.0 / (3f64.sqrt() * n.max(1) as f64)).sqrt()
}

/// `x` wrapped onto the unit torus, into `[0, 1)`: `x - floor(x)`, with the results that round to
/// 1.0 (tiny negative `x`) and NaN mapped to 0.
#[inline]
pub fn wrap_unit(x: f64) -> f64 {
    let y = x - x.floor();
    if y < 1.0 { y } else { 0.0 }
}

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

/// A cell index wrapped into `[0, res)`, for indices within one period of the range (no
/// division: this is on every query's path).
#[inline]
fn wrap_cell(i: isize, res: isize) -> isize {
    if i < 0 {
        i + res
    } else if i >= res {
        i - res
    } else {
        i
    }
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

    /// The points, in insertion order.
    pub fn points(&self) -> &[[f64; 2]] {
        &self.points
    }

    /// The cell of a coordinate in `[0, 1)` (values outside are wrapped).
    #[inline]
    fn cell_of(&self, c: f64) -> usize {
        // `floor` is a library call on baseline x86_64; truncation is exact for c >= 0.
        let c = if (0.0..1.0).contains(&c) {
            c
        } else {
            c - c.floor()
        };
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
        // ceil(r res) without the library call: truncation + 1 is never smaller
        let reach = ((r * self.res as f64) as isize + 1).min(self.res as isize / 2 + 1);
        let (cx, cy) = (self.cell_of(p[0]) as isize, self.cell_of(p[1]) as isize);
        let res = self.res as isize;
        let span = (2 * reach + 1).min(res);
        let (x0, y0) = (wrap_cell(cx - reach, res), wrap_cell(cy - reach, res));
        for dy in 0..span {
            let row = wrap_cell(y0 + dy, res) as usize;
            for dx in 0..span {
                let col = wrap_cell(x0 + dx, res) as usize;
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
        self.nearest_where(p, |i| Some(i) != exclude)
    }

    /// The nearest point to `p` among those for which `keep(index)` holds: its index and
    /// squared toroidal distance, or `None` when no point qualifies.
    pub fn nearest_where(
        &self,
        p: [f64; 2],
        mut keep: impl FnMut(usize) -> bool,
    ) -> Option<(usize, f64)> {
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
                let (col, row) = (wrap_cell(col, res) as usize, wrap_cell(row, res) as usize);
                let mut i = self.heads[row * self.res + col];
                while i != NONE {
                    if keep(i as usize) {
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
    use strata::hash::mix64;

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

/// A grid with at most one point per cell, for Poisson-disk sets of radius `r`: cells have side
/// at most `r / sqrt(2)`, so two points of the set can never share a cell, and every point
/// closer than `r` to a query lies in the `5 x 5` cells around it. Storage is one slot per cell,
/// contiguous, so a query is 25 loads (Bridson 2007's accelerator, on the torus).
#[derive(Clone, Debug)]
pub struct DiskGrid {
    res: usize,
    r2: f64,
    /// The point in each cell (NaN when empty).
    cells: Vec<[f64; 2]>,
}

impl DiskGrid {
    /// An empty grid for minimum distance `r` (`0 < r`); `None` when the grid would need more
    /// than `max_cells` cells.
    pub fn new(r: f64, max_cells: usize) -> Option<Self> {
        if r.is_nan() || r <= 0.0 {
            return None;
        }
        let res = (std::f64::consts::SQRT_2 / r).ceil().max(1.0);
        if res * res > max_cells as f64 {
            return None;
        }
        let res = res as usize;
        Some(DiskGrid {
            res,
            r2: r * r,
            cells: vec![[f64::NAN; 2]; res * res],
        })
    }

    /// Cells per axis.
    pub fn resolution(&self) -> usize {
        self.res
    }

    #[inline]
    fn cell_of(&self, c: f64) -> usize {
        ((c * self.res as f64) as usize).min(self.res - 1)
    }

    /// The point stored in cell `(x, y)`, if any.
    #[inline]
    pub fn cell(&self, x: usize, y: usize) -> Option<[f64; 2]> {
        let p = self.cells[y * self.res + x];
        (!p[0].is_nan()).then_some(p)
    }

    /// Stores a point (coordinates in `[0, 1)`); the caller guarantees its cell is empty, which
    /// holds for any point that does not [`conflict`](DiskGrid::conflicts).
    pub fn insert(&mut self, p: [f64; 2]) {
        let i = self.cell_of(p[1]) * self.res + self.cell_of(p[0]);
        self.cells[i] = p;
    }

    /// Calls `f` with every stored point in the `5 x 5` cells around `p` (all points within `r`
    /// among them); stops when `f` returns true, and returns whether it did.
    #[inline]
    pub fn any_near(&self, p: [f64; 2], mut f: impl FnMut([f64; 2]) -> bool) -> bool {
        let res = self.res as isize;
        let (cx, cy) = (self.cell_of(p[0]) as isize, self.cell_of(p[1]) as isize);
        let mut cols = [0usize; 5];
        for (k, c) in cols.iter_mut().enumerate() {
            *c = wrap_cell(wrap_cell(cx + k as isize - 2, res), res) as usize;
        }
        for dy in -2..=2 {
            let row = wrap_cell(wrap_cell(cy + dy, res), res) as usize * self.res;
            for &col in &cols {
                let q = self.cells[row + col];
                if !q[0].is_nan() && f(q) {
                    return true;
                }
            }
        }
        false
    }

    /// True when a stored point lies closer than `r` to `p` (toroidally).
    #[inline]
    pub fn conflicts(&self, p: [f64; 2]) -> bool {
        let r2 = self.r2;
        self.any_near(p, |q| torus_distance_squared(p, q) < r2)
    }
}
