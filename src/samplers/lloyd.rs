//! Lloyd relaxation on the periodic Voronoi diagram.
//!
//! Lloyd, "Least Squares Quantization in PCM" (IEEE Trans. Inf. Theory 1982). Each iteration
//! moves every point to the centroid of its Voronoi cell on the unit torus; the energy
//! `E = sum_i int_{V_i} |x - p_i|^2 dx` never increases, and the points converge to a centroidal
//! Voronoi tessellation (CVT): very even spacing, a deep empty disc around DC in the spectrum,
//! but with enough iterations they drift toward hexagonal patches (peaks in the spectrum).
//!
//! The Voronoi diagram comes from `spade`'s Delaunay triangulation of the points plus copies of
//! those within a margin of the unit square's border, shifted by the periods. A cell is taken
//! as exact when all its vertices are finite and within half the margin of its point (then
//! every point of the periodic set that could shape it is present); otherwise the margin
//! doubles, up to full 3 x 3 copies. Coincident points are merged by `spade`; the duplicates
//! are moved by a tiny hashed offset so that the next iteration separates them.

use spade::{DelaunayTriangulation, HasPosition, Point2 as SPoint, Triangulation};

use super::{SetGenerator, Sets};
use crate::counts::CountRule;
use crate::entry::{BlueNoise, Built, Entry, Family, ParameterSpec};
use crate::grid::{relative_radius_max, wrap_unit as wrap};
use crate::{Error, Result};
use strata::float::{unit_f64_from_u32, unit_f64_from_u64};
use strata::hash::{hash_u64, stream_seed};

/// The stream of the jitter that separates coincident points.
const JITTER_STREAM: u64 = 0x110d;

/// The convergence tolerance: relaxation stops once the mean distance from a point to its
/// cell's centroid falls below this fraction of `r_max(N)`. At N = 1024 this takes a few
/// hundred iterations from random points (about 0.6 s per set) and reaches a mean spacing
/// `rho` of 0.80 and a mean nearest-neighbour distance of 0.94 `r_max` (8 seeds); a looser
/// 1e-3 stops at rho 0.79.
pub const TOLERANCE: f64 = 2.5e-4;

/// The default cap on the iterations (convergence usually stops them first).
pub const DEFAULT_ITERATIONS: u32 = 1000;

/// The most iterations accepted.
pub const MAX_ITERATIONS: u32 = 100_000;

/// Points closer than this (toroidally) to an earlier point are treated as duplicates.
pub const DUPLICATE: f64 = 1e-10;

/// The most points per relaxed set.
pub const MAX_LLOYD_COUNT: u64 = 1 << 22;

/// `--iterations`: the cap on the Lloyd steps.
const ITERATIONS: ParameterSpec = ParameterSpec::whole(
    "iterations",
    0,
    MAX_ITERATIONS,
    DEFAULT_ITERATIONS,
    "the most Lloyd steps (they stop earlier once no site moves more than the tolerance)",
);

/// The registry entry of `lloyd`.
pub(crate) const ENTRY: Entry = Entry {
    name: "lloyd",
    description: "Lloyd relaxation on the periodic Voronoi diagram from random points, to convergence (at most --iterations K, default 1000)",
    paper: "Lloyd 1982",
    family: Family::BlueNoise,
    counts: CountRule::Any,
    parameters: &[ITERATIONS],
    promise: "a centroidal Voronoi tessellation (near-hexagonal), converged",
    expensive: true,
    blue_noise: Some(BlueNoise::published(
        "not reported (Lloyd 1982 is on quantization; the method predates its use for blue noise)",
    )),
    build: |p| {
        let k = ENTRY.parameters[0].read_whole(p);
        Ok(Built::two(LloydSets::new(Lloyd::new(p.count, k)?, p.seed)?))
    },
    ..Entry::DEFAULT
};

#[derive(Clone, Copy, Debug)]
struct Site {
    p: SPoint<f64>,
    index: u32,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> SPoint<f64> {
        self.p
    }
}

/// One point's Voronoi cell on the torus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// The cell's centroid, in the coordinates of the point (it may lie just outside `[0,1)`).
    pub centroid: [f64; 2],
    /// The cell's area.
    pub area: f64,
    /// `int_cell |x - p|^2 dx`, the point's share of the quantization energy.
    pub energy: f64,
}

/// The periodic Voronoi cells of `points` (coordinates in `[0,1)`); `None` for points that
/// coincide with an earlier one (closer than [`DUPLICATE`] on the torus: they have no cell of
/// their own).
pub fn voronoi_cells(points: &[[f64; 2]]) -> Result<Vec<Option<Cell>>> {
    let n = points.len();
    if n == 0 {
        return Err(Error::input(
            "lloyd::voronoi_cells",
            "no points; at least one is needed",
        ));
    }
    if let Some(i) = points
        .iter()
        .position(|p| !(0.0..1.0).contains(&p[0]) || !(0.0..1.0).contains(&p[1]))
    {
        return Err(Error::input(
            "lloyd::voronoi_cells",
            format!(
                "point {i} is {:?}; coordinates must be in [0, 1)",
                points[i]
            ),
        ));
    }
    // Points closer than DUPLICATE (toroidally) to an earlier one are duplicates: they get no
    // cell. Removing them here, rather than leaving the merge to the triangulation, matters on
    // the torus, where a point may coincide with another's periodic copy.
    let grid = crate::grid::TorusGrid::from_points(points.iter().copied());
    let mut keep = vec![true; n];
    for (i, &p) in points.iter().enumerate() {
        grid.for_each_within(p, DUPLICATE, |j, _| {
            if j < i && keep[j] {
                keep[i] = false;
                return false;
            }
            true
        });
    }
    // Start with a margin of a few typical spacings; grow until every cell is exact.
    let mut margin = (4.0 * relative_radius_max(n)).min(1.0);
    loop {
        let full = margin >= 1.0;
        let mut sites = Vec::with_capacity(n + n / 2);
        for (i, p) in points.iter().enumerate().filter(|(i, _)| keep[*i]) {
            for dy in -1i32..=1 {
                for dx in -1i32..=1 {
                    let q = [p[0] + dx as f64, p[1] + dy as f64];
                    let inside = (dx == 0 && dy == 0)
                        || (full
                            || (q[0] > -margin
                                && q[0] < 1.0 + margin
                                && q[1] > -margin
                                && q[1] < 1.0 + margin));
                    if inside {
                        sites.push(Site {
                            p: SPoint::new(q[0], q[1]),
                            index: if dx == 0 && dy == 0 {
                                i as u32
                            } else {
                                u32::MAX
                            },
                        });
                    }
                }
            }
        }
        let dt: DelaunayTriangulation<Site> =
            DelaunayTriangulation::bulk_load(sites).map_err(|e| {
                Error::input(
                    "lloyd::voronoi_cells",
                    format!("the triangulation failed: {e:?}"),
                )
            })?;
        let mut cells = vec![None; n];
        let mut exact = true;
        let mut polygon = Vec::new();
        for v in dt.vertices() {
            let site = v.data();
            if site.index == u32::MAX {
                continue;
            }
            let p = [site.p.x, site.p.y];
            polygon.clear();
            let mut bounded = true;
            for e in v.as_voronoi_face().adjacent_edges() {
                match e.from().position() {
                    Some(c) => polygon.push([c.x, c.y]),
                    None => {
                        bounded = false;
                        break;
                    }
                }
            }
            let reach = polygon
                .iter()
                .map(|c| ((c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2)).sqrt())
                .fold(0.0, f64::max);
            if !bounded || (!full && 2.0 * reach > margin) {
                exact = false;
                break;
            }
            cells[site.index as usize] = Some(cell_of_polygon(p, &polygon));
        }
        if exact {
            return Ok(cells);
        }
        if full {
            // Cannot happen with 3 x 3 copies of at least one point; fail loudly, not silently.
            return Err(Error::input(
                "lloyd::voronoi_cells",
                "a Voronoi cell stayed unbounded with full periodic copies",
            ));
        }
        margin = (margin * 2.0).min(1.0);
    }
}

/// Centroid, area and second moment about `p` of a convex polygon around `p`, by summing the
/// triangles `(p, a, b)` over its edges.
fn cell_of_polygon(p: [f64; 2], polygon: &[[f64; 2]]) -> Cell {
    let (mut area, mut cx, mut cy, mut energy) = (0.0, 0.0, 0.0, 0.0);
    for (k, a) in polygon.iter().enumerate() {
        let b = polygon[(k + 1) % polygon.len()];
        let (u, v) = ([a[0] - p[0], a[1] - p[1]], [b[0] - p[0], b[1] - p[1]]);
        let t = 0.5 * (u[0] * v[1] - u[1] * v[0]); // signed area of (p, a, b)
        area += t;
        cx += t * (u[0] + v[0]) / 3.0;
        cy += t * (u[1] + v[1]) / 3.0;
        energy += t / 6.0
            * (u[0] * u[0] + u[1] * u[1] + v[0] * v[0] + v[1] * v[1] + u[0] * v[0] + u[1] * v[1]);
    }
    let area_abs = area.abs();
    Cell {
        centroid: if area_abs > 0.0 {
            [p[0] + cx / area, p[1] + cy / area]
        } else {
            p
        },
        area: area_abs,
        energy: energy.abs(),
    }
}

/// What one Lloyd iteration measured before moving the points.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct LloydStep {
    /// The quantization energy of the configuration before the move.
    pub energy: f64,
    /// Mean distance from a point to its cell's centroid, relative to `r_max(N)`.
    pub mean_offset: f64,
}

/// Runs `iterations` Lloyd steps on `points` in place (coordinates in `[0,1)`), returning what
/// each step measured. Coincident points are separated by a tiny hashed offset.
pub fn relax(points: &mut [[f64; 2]], iterations: u32) -> Result<Vec<LloydStep>> {
    relax_until(points, 0.0, iterations)
}

/// Lloyd steps on `points` in place until a step finds the mean distance from a point to its
/// cell's centroid below `tolerance` times `r_max(N)` (that step still moves the points), or
/// `max_iterations` steps; returns what each step measured.
pub fn relax_until(
    points: &mut [[f64; 2]],
    tolerance: f64,
    max_iterations: u32,
) -> Result<Vec<LloydStep>> {
    let n = points.len();
    let r_max = relative_radius_max(n);
    let mut steps = Vec::new();
    for it in 0..max_iterations {
        let cells = voronoi_cells(points)?;
        let (mut energy, mut offset) = (0.0, 0.0);
        for (i, (p, cell)) in points.iter_mut().zip(&cells).enumerate() {
            match cell {
                Some(c) => {
                    energy += c.energy;
                    offset +=
                        ((c.centroid[0] - p[0]).powi(2) + (c.centroid[1] - p[1]).powi(2)).sqrt();
                    *p = [wrap(c.centroid[0]), wrap(c.centroid[1])];
                }
                None => {
                    // a duplicate: nudge it by up to 1e-3 r_max in a hashed direction
                    let h = hash_u64((it as u64) << 32 | i as u64, JITTER_STREAM);
                    let (dx, dy) = (
                        unit_f64_from_u32(h as u32) - 0.5,
                        unit_f64_from_u32((h >> 32) as u32) - 0.5,
                    );
                    *p = [
                        wrap(p[0] + dx * 1e-3 * r_max),
                        wrap(p[1] + dy * 1e-3 * r_max),
                    ];
                }
            }
        }
        let mean_offset = offset / n as f64 / r_max;
        steps.push(LloydStep {
            energy,
            mean_offset,
        });
        if mean_offset < tolerance {
            break;
        }
    }
    Ok(steps)
}

/// Lloyd-relaxed sets: `count` random points relaxed until converged ([`TOLERANCE`]) or for
/// at most `iterations` steps.
#[derive(Clone, Debug)]
pub struct Lloyd {
    count: u32,
    iterations: u32,
}

impl Lloyd {
    /// `count` points (1 to [`MAX_LLOYD_COUNT`]) relaxed until converged, at most `iterations`
    /// steps (0 to [`MAX_ITERATIONS`]).
    pub fn new(count: u64, iterations: u32) -> Result<Self> {
        super::check_count(ENTRY.name, count, MAX_LLOYD_COUNT)?;
        ITERATIONS.check(ENTRY.name, iterations as f64)?;
        Ok(Lloyd {
            count: count as u32,
            iterations,
        })
    }
}

/// `count` uniform random points for key `key` (the start of the relaxations).
pub(crate) fn random_start(count: usize, key: u64) -> Vec<[f64; 2]> {
    let k = stream_seed(crate::rng::streams::LLOYD_START, key);
    (0..count as u64)
        .map(|i| {
            [
                unit_f64_from_u64(hash_u64(2 * i, k)),
                unit_f64_from_u64(hash_u64(2 * i + 1, k)),
            ]
        })
        .collect()
}

impl SetGenerator for Lloyd {
    const NAME: &'static str = ENTRY.name;

    fn count(&self) -> u32 {
        self.count
    }

    fn generate(&self, key: u64) -> Result<Vec<[f64; 2]>> {
        let mut points = random_start(self.count as usize, key);
        relax_until(&mut points, TOLERANCE, self.iterations)?;
        Ok(points)
    }
}

/// Lloyd-relaxed sets (fixed count).
pub type LloydSets = Sets<Lloyd>;
