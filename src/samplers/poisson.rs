//! Poisson-disk sampling on the unit torus: dart throwing (Cook 1986) to an exact count, and
//! Bridson's fast algorithm (Bridson 2007).
//!
//! Radii are relative: `r = rho * r_max(N)`, `r_max(N) = sqrt(2 / (sqrt(3) N))` the neighbour
//! distance of `N` points packed hexagonally (Lagae and Dutré 2008, "A Comparison of Methods for
//! Generating Poisson Disk Distributions"). Every pair of points is at least `r` apart
//! (toroidally, and still after the conversion to `f32`).
//!
//! **Dart throwing** ([`DartThrowing`]) places uniform darts and keeps those farther than `r`
//! from every point so far, until exactly `N` are placed. Near saturation most darts miss, so it
//! throws only into cells that still have room, refined as it goes (after Ebeida et al. 2011,
//! "Efficient Maximal Poisson-Disk Sampling"): a round throws one dart per active cell, then
//! every active cell is split into four and the quarters covered by a single disk are dropped.
//! Darts stay uniform over the uncovered area (cells of a round have equal size; misses are
//! rejected), so the result is unbiased dart throwing, and the work is bounded (at most
//! `MAX_LEVELS` (12) refinements): a radius the set cannot reach stops with
//! [`Error::Unreachable`] after bounded work. Random sequential
//! adsorption jams at `rho` about 0.77; above [`MAX_DART_RHO`] the request is refused at once.
//!
//! **Bridson** ([`Bridson`]) grows the set from a random seed point: each active point tries 30
//! candidates in the annulus `[r, 2r)` and retires when all fail. Its sets are not maximal and
//! their size is not chosen; to give exactly `N` points, a larger set loses its most crowded
//! points (weighted sample elimination, Yuksel 2015; a random subset would add white noise at
//! low frequencies) and a smaller one is completed by dart throwing. Both keep the radius.

use rand_pcg::Pcg32;

use super::{SetGenerator, Sets};
use crate::counts::CountRule;
use crate::entry::{BlueNoise, Bound, Built, Entry, Family, ParameterSpec, Rates};
use crate::grid::{DiskGrid, relative_radius_max, torus_distance_squared, wrap_unit as wrap};
use crate::rng::{below, pcg, streams, uniform};
use crate::{Error, Result};

/// The default relative radius.
pub const DEFAULT_RHO: f64 = 0.7;

/// Dart throwing's radius parameter.
const DART_RADIUS: ParameterSpec = ParameterSpec::real(
    "radius",
    Bound::Open(0.0),
    Bound::Closed(MAX_DART_RHO),
    DEFAULT_RHO,
    "the smallest distance between two points, relative to r_max(N) (dart throwing jams near 0.77)",
)
.with_note("random dart throwing jams near 0.77 (random sequential adsorption)");

/// Bridson's radius parameter (capped as dart throwing's: the top-up throws darts).
const BRIDSON_RADIUS: ParameterSpec = ParameterSpec::real(
    "radius",
    Bound::Open(0.0),
    Bound::Closed(MAX_DART_RHO),
    DEFAULT_RHO,
    "the smallest distance between two points, relative to r_max(N)",
)
.with_note("the top-up by dart throwing jams near 0.77 (random sequential adsorption)");

/// Poisson disk: random sampling's rate (Pilleboue et al. 2015), for 2D integrands.
const POISSON_RATES: Rates = Rates {
    discontinuous: Some(-1.0),
    smooth: Some(-1.0),
    higher: None,
};

/// The registry entry of `poisson`.
pub(crate) const POISSON: Entry = Entry {
    name: "poisson",
    description: "Poisson disk by dart throwing to exactly N points (--radius RHO, default 0.7)",
    paper: "Cook 1986; Ebeida et al. 2011",
    family: Family::BlueNoise,
    counts: CountRule::Any,
    parameters: &[DART_RADIUS],
    promise: "exactly `N` points at least `rho r_max(N)` apart",
    rates: POISSON_RATES,
    blue_noise: Some(BlueNoise::published(
        "rho about 0.75-0.76, the largest dart throwing reaches (Lagae and Dutré 2008), quoted second-hand; not checked against the paper",
    )),
    build: |p| {
        let rho = DART_RADIUS.read(p);
        Ok(Built::two(PoissonDisk::new(
            DartThrowing::new(p.count, rho)?,
            p.seed,
        )?))
    },
    ..Entry::DEFAULT
};

/// The registry entry of `bridson`.
pub(crate) const BRIDSON: Entry = Entry {
    name: "bridson",
    description: "Poisson disk by Bridson's algorithm, periodic, N points (--radius RHO, default 0.7)",
    paper: "Bridson 2007",
    family: Family::BlueNoise,
    counts: CountRule::Any,
    parameters: &[BRIDSON_RADIUS, ATTEMPTS],
    promise: "exactly `N` points at least `rho r_max(N)` apart",
    rates: POISSON_RATES,
    blue_noise: Some(BlueNoise::NOT_REPORTED),
    build: |p| {
        let rho = BRIDSON_RADIUS.read(p);
        let bridson = Bridson::new(p.count, rho)?.with_attempts(ATTEMPTS.read_whole(p));
        Ok(Built::two(BridsonDisk::new(bridson, p.seed)?))
    },
    ..Entry::DEFAULT
};

/// The largest relative radius dart throwing accepts (random sequential adsorption jams near
/// 0.77, so larger radii cannot be reached at the requested count).
pub const MAX_DART_RHO: f64 = 0.78;

/// The largest number of points per Poisson-disk set (memory: about 60 bytes per point).
pub const MAX_POISSON_COUNT: u64 = 1 << 22;

/// How many times dart throwing refines its active cells before giving up.
pub(crate) const MAX_LEVELS: u32 = 12;

/// Bridson's candidates per active point (his `k`), the default of `--attempts`.
pub(crate) const BRIDSON_CANDIDATES: u32 = 30;

/// Bridson's `--attempts`: the candidates tried around an active point before it is retired.
const ATTEMPTS: ParameterSpec = ParameterSpec::whole(
    "attempts",
    1,
    1000,
    BRIDSON_CANDIDATES,
    "candidates tried around an active point before it is retired (Bridson's k; more: denser before the top-up)",
);

/// Slack added to the radius so that the guarantee survives rounding coordinates to `f32`
/// (each coordinate moves by less than `2^-24`).
const F32_SLACK: f64 = 1.0 / (1u64 << 22) as f64;

/// Validates the count and the relative radius (by its declaration) of a Poisson-disk sampler.
fn check(name: &'static str, count: u64, rho: f64, radius: &ParameterSpec) -> Result<u32> {
    super::check_count(name, count, MAX_POISSON_COUNT)?;
    radius.check(name, rho)?;
    Ok(count as u32)
}

/// Dart throwing to exactly `count` points at relative radius `rho`.
#[derive(Clone, Debug)]
pub struct DartThrowing {
    count: u32,
    rho: f64,
}

impl DartThrowing {
    /// `count` points (1 to [`MAX_POISSON_COUNT`]) at relative radius `0 < rho <= MAX_DART_RHO`.
    pub fn new(count: u64, rho: f64) -> Result<Self> {
        let count = check(POISSON.name, count, rho, &DART_RADIUS)?;
        Ok(DartThrowing { count, rho })
    }

    /// The absolute radius `rho * r_max(N)`.
    pub fn radius(&self) -> f64 {
        self.rho * relative_radius_max(self.count as usize)
    }
}

impl SetGenerator for DartThrowing {
    const NAME: &'static str = POISSON.name;

    fn count(&self) -> u32 {
        self.count
    }

    fn generate(&self, key: u64) -> Result<Vec<[f64; 2]>> {
        let r = self.radius() + F32_SLACK;
        let mut rng = pcg(key, streams::DART_THROWING);
        if DiskGrid::new(r, MAX_GRID_CELLS).is_none() {
            // A radius so small that one cell per r / sqrt 2 would not fit: the disks cover
            // almost nothing, so plain darts checked on the general neighbour grid suffice.
            return tiny_radius_darts(self.count as usize, r, &mut rng)
                .ok_or_else(|| saturated(POISSON.name, 0, self.count, self.rho));
        }
        let mut grid = disk_grid(POISSON.name, r)?;
        let mut points = Vec::with_capacity(self.count as usize);
        throw_darts(&mut points, &mut grid, self.count as usize, r, &mut rng);
        if points.len() < self.count as usize {
            return Err(saturated(POISSON.name, points.len(), self.count, self.rho));
        }
        Ok(points)
    }
}

/// Dart throwing for radii far below the spacing of the points (`rho` tiny): uniform darts,
/// rejected when closer than `r` to a point, at most `100 n` darts.
fn tiny_radius_darts(n: usize, r: f64, rng: &mut Pcg32) -> Option<Vec<[f64; 2]>> {
    let mut grid = crate::grid::TorusGrid::new((n as f64).sqrt() as usize);
    let mut points = Vec::with_capacity(n);
    for _ in 0..100 * n.max(1) {
        if points.len() == n {
            break;
        }
        let p = [uniform(rng), uniform(rng)];
        if !grid.any_closer_than(p, r) {
            grid.insert(p);
            points.push(p);
        }
    }
    (points.len() == n).then_some(points)
}

fn saturated(name: &'static str, got: usize, count: u32, rho: f64) -> Error {
    // The relative radius at which `got` points would have been asked for.
    let reachable = rho * (got as f64 / count as f64).sqrt();
    Error::Unreachable {
        context: name,
        message: format!(
            "the set saturated after {got} of {count} points at rho = {rho} (no room is left for \
             another disk); this seed reaches about rho = {reachable:.3} at {count} points, so \
             ask for a smaller radius"
        ),
    }
}

/// Adds uniform darts farther than `r` from every point until `points` holds `target` points or
/// no room is left (after [`MAX_LEVELS`] refinements). `grid` holds the same points.
pub(crate) fn throw_darts(
    points: &mut Vec<[f64; 2]>,
    grid: &mut DiskGrid,
    target: usize,
    r: f64,
    rng: &mut Pcg32,
) {
    if points.len() >= target {
        return;
    }
    // Start from the grid's cells (side <= r / sqrt(2): a point anywhere in a cell covers it).
    let base = grid.resolution() as u64;
    let mut size = 1.0 / base as f64;
    let mut active: Vec<(u64, u64)> = Vec::new();
    for y in 0..base {
        for x in 0..base {
            if grid.cell(x as usize, y as usize).is_none()
                && !covered(grid, x as f64 * size, y as f64 * size, size, r)
            {
                active.push((x, y));
            }
        }
    }
    for level in 0..=MAX_LEVELS {
        // One round: as many darts as active cells, each into a random active cell.
        let throws = active.len();
        for _ in 0..throws {
            if points.len() >= target || active.is_empty() {
                return;
            }
            let i = below(rng, active.len());
            let (cx, cy) = active[i];
            let p = [
                wrap((cx as f64 + uniform(rng)) * size),
                wrap((cy as f64 + uniform(rng)) * size),
            ];
            if !grid.conflicts(p) {
                grid.insert(p);
                points.push(p);
                active.swap_remove(i);
            }
        }
        if level == MAX_LEVELS || active.is_empty() {
            return;
        }
        // Refine: split every active cell, drop the quarters covered by a single disk.
        size *= 0.5;
        let mut next = Vec::with_capacity(active.len() * 2);
        for &(cx, cy) in &active {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (2 * cx + dx, 2 * cy + dy);
                if !covered(grid, x as f64 * size, y as f64 * size, size, r) {
                    next.push((x, y));
                }
            }
        }
        active = next;
    }
}

/// True when the square `[x0, x0 + s) x [y0, y0 + s)` lies inside one disk of radius `r`.
/// True when the square `[x0, x0 + s) x [y0, y0 + s)` (no larger than a grid cell) lies inside
/// one disk of radius `r`: that disk's centre is within `r` of the square's centre, so among
/// the `5 x 5` cells around it.
fn covered(grid: &DiskGrid, x0: f64, y0: f64, s: f64, r: f64) -> bool {
    let centre = [x0 + 0.5 * s, y0 + 0.5 * s];
    let corners =
        [[x0, y0], [x0 + s, y0], [x0, y0 + s], [x0 + s, y0 + s]].map(|c| [wrap(c[0]), wrap(c[1])]);
    let r2 = r * r;
    grid.any_near(centre, |q| {
        corners.iter().all(|&c| torus_distance_squared(c, q) < r2)
    })
}

/// The one-point-per-cell grid for radius `r`, or an error when it would be too large.
fn disk_grid(name: &'static str, r: f64) -> Result<DiskGrid> {
    DiskGrid::new(r, MAX_GRID_CELLS).ok_or_else(|| {
        let min_r = (2.0 / MAX_GRID_CELLS as f64).sqrt();
        Error::input(
            name,
            format!(
                "radius {r:e} is too small: the accelerating grid (one cell per r / sqrt 2) would need more than \
                 {MAX_GRID_CELLS} cells, and Bridson's set about 1 / r^2 points; allowed r >= {min_r:e}"
            ),
        )
    })
}

/// The most grid cells a Poisson-disk set may use (16 bytes each): enough for
/// [`MAX_POISSON_COUNT`] points at relative radius 0.3.
pub(crate) const MAX_GRID_CELLS: usize = 1 << 26;

/// Bridson's algorithm, periodic, at relative radius `rho`, adjusted to exactly `count` points.
#[derive(Clone, Debug)]
pub struct Bridson {
    count: u32,
    rho: f64,
    attempts: u32,
}

impl Bridson {
    /// `count` points (1 to [`MAX_POISSON_COUNT`]) at relative radius `0 < rho <= MAX_DART_RHO`.
    pub fn new(count: u64, rho: f64) -> Result<Self> {
        let count = check(BRIDSON.name, count, rho, &BRIDSON_RADIUS)?;
        Ok(Bridson {
            count,
            rho,
            attempts: BRIDSON_CANDIDATES,
        })
    }

    /// The same with `attempts` candidates around each active point (the registry's
    /// `--attempts`, checked there against its declared range, 1 to 1000).
    pub(crate) fn with_attempts(mut self, attempts: u32) -> Self {
        self.attempts = attempts.max(1);
        self
    }

    /// The absolute radius `rho * r_max(N)`.
    pub fn radius(&self) -> f64 {
        self.rho * relative_radius_max(self.count as usize)
    }
}

/// Bridson's algorithm at absolute radius `r` on the unit torus: the raw set (its size is
/// whatever the algorithm reaches), grown from one random point.
///
/// Returns an error when `r` is so small that the grid would exceed `2^26` cells.
pub fn bridson(r: f64, key: u64) -> Result<Vec<[f64; 2]>> {
    let mut rng = pcg(key, streams::BRIDSON);
    let mut grid = disk_grid(BRIDSON.name, r)?;
    let mut points = Vec::new();
    grow_bridson(&mut points, &mut grid, r, BRIDSON_CANDIDATES, &mut rng);
    Ok(points)
}

fn grow_bridson(
    points: &mut Vec<[f64; 2]>,
    grid: &mut DiskGrid,
    r: f64,
    attempts: u32,
    rng: &mut Pcg32,
) {
    let first = [uniform(rng), uniform(rng)];
    grid.insert(first);
    points.push(first);
    let mut active = vec![0usize];
    while !active.is_empty() {
        let i = below(rng, active.len());
        let p = points[active[i]];
        let mut found = false;
        for _ in 0..attempts {
            // uniform over the annulus' area, by rejection from its bounding square (no trig)
            let (dx, dy) = loop {
                let (dx, dy) = (
                    (uniform(rng) * 4.0 - 2.0) * r,
                    (uniform(rng) * 4.0 - 2.0) * r,
                );
                let d2 = dx * dx + dy * dy;
                if d2 >= r * r && d2 < 4.0 * r * r {
                    break (dx, dy);
                }
            };
            let q = [wrap(p[0] + dx), wrap(p[1] + dy)];
            if !grid.conflicts(q) {
                grid.insert(q);
                active.push(points.len());
                points.push(q);
                found = true;
                break;
            }
        }
        if !found {
            active.swap_remove(i);
        }
    }
}

impl SetGenerator for Bridson {
    const NAME: &'static str = BRIDSON.name;

    fn count(&self) -> u32 {
        self.count
    }

    fn generate(&self, key: u64) -> Result<Vec<[f64; 2]>> {
        let n = self.count as usize;
        let r = self.radius() + F32_SLACK;
        let mut rng = pcg(key, streams::BRIDSON);
        let mut grid = disk_grid(BRIDSON.name, r)?;
        let mut points = Vec::new();
        grow_bridson(&mut points, &mut grid, r, self.attempts, &mut rng);
        if points.len() < n {
            throw_darts(&mut points, &mut grid, n, r, &mut rng);
            if points.len() < n {
                return Err(saturated(BRIDSON.name, points.len(), self.count, self.rho));
            }
        }
        if points.len() > n {
            eliminate(&mut points, n, r);
        }
        // A random order: Fisher-Yates.
        for i in (1..points.len()).rev() {
            let j = below(&mut rng, i + 1);
            points.swap(i, j);
        }
        Ok(points)
    }
}

/// Removes points until `target` remain, always the most crowded one, so the set keeps its
/// blue-noise spectrum (a random subset would add white noise at low frequencies): weighted
/// sample elimination (Yuksel, "Sample Elimination for Generating Poisson Disk Sample Sets",
/// Eurographics 2015), weight `sum_j (1 - d_ij / 2r)^8` over the neighbours within `2r`.
fn eliminate(points: &mut Vec<[f64; 2]>, target: usize, r: f64) {
    use std::cmp::Ordering;
    use std::collections::BinaryHeap;

    #[derive(PartialEq)]
    struct Entry(f64, usize);
    impl Eq for Entry {}
    impl PartialOrd for Entry {
        fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Entry {
        fn cmp(&self, o: &Self) -> Ordering {
            self.0.total_cmp(&o.0).then(o.1.cmp(&self.1))
        }
    }

    let reach = 2.0 * r;
    let grid = crate::grid::TorusGrid::from_points(points.iter().copied());
    let weight_of = |d2: f64| (1.0 - d2.sqrt() / reach).max(0.0).powi(8);
    let mut weight = vec![0.0f64; points.len()];
    for (i, &p) in points.iter().enumerate() {
        grid.for_each_within(p, reach, |j, d2| {
            if j != i {
                weight[i] += weight_of(d2);
            }
            true
        });
    }
    let mut removed = vec![false; points.len()];
    let mut heap: BinaryHeap<Entry> = weight
        .iter()
        .enumerate()
        .map(|(i, &w)| Entry(w, i))
        .collect();
    let mut left = points.len();
    while left > target {
        let Some(Entry(w, i)) = heap.pop() else { break };
        if removed[i] || w != weight[i] {
            continue; // stale entry
        }
        removed[i] = true;
        left -= 1;
        grid.for_each_within(points[i], reach, |j, d2| {
            if j != i && !removed[j] {
                weight[j] -= weight_of(d2);
                heap.push(Entry(weight[j], j));
            }
            true
        });
    }
    let mut k = 0;
    points.retain(|_| {
        k += 1;
        !removed[k - 1]
    });
}

/// Dart-throwing Poisson-disk sets (fixed count).
pub type PoissonDisk = Sets<DartThrowing>;

/// Bridson Poisson-disk sets (fixed count).
pub type BridsonDisk = Sets<Bridson>;

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn bridson_attempts_change_the_raw_set_and_keep_the_radius() {
        // --attempts is Bridson's k: the default gives the values it always gave; fewer
        // attempts retire active points sooner, so the grown set is smaller before the top-up,
        // and every set keeps the radius
        use crate::entry::Params;
        let n = 1024;
        let take = |p: &Params| {
            let mut s = BRIDSON.build(p).unwrap();
            let mut v = vec![[0.0f32; 2]; n];
            s.fill(&mut v);
            v
        };
        let base = Params::new(n as u64).seed(strata::Seed(4));
        assert_eq!(take(&base), take(&base.clone().with("attempts", 30.0)));
        let few = take(&base.clone().with("attempts", 1.0));
        assert_ne!(few, take(&base));
        let r = Bridson::new(n as u64, DEFAULT_RHO).unwrap().radius();
        for (i, a) in few.iter().enumerate() {
            for b in &few[..i] {
                let d = [0, 1].map(|k| {
                    let d = (a[k] - b[k]).abs() as f64;
                    d.min(1.0 - d)
                });
                let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
                assert!(length >= r * (1.0 - 1e-6), "{a:?} {b:?}");
            }
        }
        let grown = |k: u32| {
            let b = Bridson::new(n as u64, DEFAULT_RHO)
                .unwrap()
                .with_attempts(k);
            let r = b.radius() + F32_SLACK;
            let mut grid = disk_grid(BRIDSON.name, r).unwrap();
            let mut rng = pcg(4, streams::BRIDSON);
            let mut points = Vec::new();
            grow_bridson(&mut points, &mut grid, r, k, &mut rng);
            points.len()
        };
        assert!(grown(1) < grown(30), "{} {}", grown(1), grown(30));
        let e = BRIDSON
            .build(&base.clone().with("attempts", 0.0))
            .unwrap_err();
        assert!(e.to_string().contains("1 to 1000"), "{e}");
        assert!(POISSON.build(&base.with("attempts", 5.0)).is_err());
    }
}
