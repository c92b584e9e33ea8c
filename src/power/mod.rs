//! Periodic power diagrams with exact predicates: the cells of
//! weighted sites on the unit torus, the machinery under the [`bnot`](crate::samplers::bnot)
//! sampler.
//!
//! The power diagram (weighted Voronoi diagram, Laguerre diagram; Aurenhammer, "Power
//! diagrams: properties, algorithms and applications", SIAM J. Comput. 16, 1987) of weighted
//! sites on the unit torus `[0,1)^2`.
//!
//! ```
//! use strata_lab::power::PowerDiagram;
//!
//! // A 2 x 2 grid: every vertex is shared by four co-circular sites; the cells are exact squares.
//! let sites = [[0.25, 0.25], [0.75, 0.25], [0.25, 0.75], [0.75, 0.75]];
//! let d = PowerDiagram::voronoi(&sites)?;
//! assert!(d.areas().iter().all(|&a| a == 0.25));
//! assert_eq!(d.cell(3).centroid(), Some([0.75, 0.75]));
//! assert_eq!(d.power_nearest([0.9, 0.1])?, 1);
//! # Ok::<(), strata_lab::Error>(())
//! ```
//!
//! # What is guaranteed
//!
//! * **Exact combinatorics.** Every side test is decided exactly for the true (unrounded)
//!   periodic configuration of the input coordinates and weights, so the cells, their
//!   neighbours and which cells are empty are those of the exact diagram, whatever the
//!   degeneracy (co-circular sites, regular grids, collinear sites, nearly coincident sites).
//! * **Accurate geometry.** Vertices, areas, centroids and edge lengths are floating point,
//!   accurate to about `1e-12` relative; the areas sum to 1 to about `1e-12`.
//! * **No panic, NaN or hang on valid input**: the search for each cell terminates (no site
//!   copy beyond `sqrt 2` ever matters); invalid input is an [`Error`].
//!
//! The power distance from `x` to site `i` is `|x - s_i|^2 - w_i`, measured to the nearest of the
//! site's periodic copies `s_i + k`, `k` in `Z^2` (all copies share the weight). The cell of `i`
//! is the set of points no farther (in power distance) from `s_i` than from any other site.
//!
//! # How it is computed
//!
//! Each cell is built on its own by clipping, in coordinates relative to its site:
//!
//! 1. Start from the unit square centred on the site. That square is exactly the intersection
//!    of the half-planes of the site's four axis-aligned copies `s_i + (±1, 0)`, `s_i + (0, ±1)`
//!    (copies share the weight, so their bisectors are the plain perpendicular bisectors), so it
//!    contains the cell of the central copy. The projection of that cell onto the torus is the
//!    torus cell, and the square's sides are bisectors like any other.
//! 2. Clip by the bisector of every other site's copy, nearest first, found ring by ring in a
//!    uniform bucket grid on the torus.
//! 3. Stop when no remaining copy can reach the cell: with `R` the distance from the site to the
//!    farthest vertex, a copy at distance `d` can only clip when `d^2 - 2 R d <= w_j - w_i`, so
//!    none at `d > R + sqrt(R^2 + w_max - w_i)` can; and copies beyond `sqrt 2` never matter
//!    (for any point of the square, the nearest copy of each site is within `sqrt 2` of `s_i`).
//!    This is the "security radius" of Voronoi cells by clipping (Lévy and Bonneel,
//!    "Variational anisotropic surface meshing with Voronoi parallel linear enumeration", IMR
//!    2012; Ray, Sokolov, Lefebvre and Lévy, "Meshless Voronoi on the GPU", ACM TOG 2018),
//!    extended to weights.
//!
//! Every side test ("is this vertex inside, on, or outside that bisector?") is decided exactly
//! (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric
//! Predicates", Discrete Comput. Geom. 18, 1997): floating-point filters with rigorous error bounds,
//! falling back to exact expansion arithmetic (Shewchuk's expansions) on the input coordinates,
//! shifts and weights; the test is the lifted `orient3d` of four weighted points, i.e. the power
//! test of the regular triangulation. A vertex exactly on the line is kept as it is
//! (not cut), so each polygon is exactly the closed cell and no zero-length edge is ever made:
//! with four or more power-cocircular sites (a regular grid, say), the diagonal neighbours that
//! only touch at a point are *not* neighbours. Because every cell is the exact cell, neighbour
//! relations are symmetric (an edge of `i` with the copy `s_j + k` is an edge of `j` with
//! `s_i - k`) and edges agree in length up to rounding. When two bisectors of a cell coincide
//! (collinear sites whose weights put their bisectors on the same line), the edge belongs to the
//! farther site, which is the one actually adjacent across it.
//!
//! Vertex coordinates are computed in floating point (Cramer's rule on two bisectors) with an
//! error bound; when the two bisectors are nearly parallel (a site seen next to two nearly
//! coincident sites), the vertex is recomputed from exact numerators and denominator, so that
//! areas, centroids and edge lengths stay accurate to about 1e-12 relative in every case.
//!
//! Cost: about one microsecond per cell for well-spaced sites (a dozen candidate bisectors,
//! six clips), a few for uniform random ones. Pathological weights (one site's weight far above
//! the others') widen the search radius of every cell, up to `O(N)` candidates per cell.
//!
//! # Special cases
//!
//! * `N = 1`: the cell is the whole torus (area 1, centroid the site); its four "neighbours"
//!   are the site itself across the seams (`site == i`, shifts `(±1, 0)`, `(0, ±1)`, each edge
//!   of length 1 at distance 1).
//! * `N = 2`: two regions; with equal weights they are two strips when the sites share a
//!   coordinate, or two diamonds (squares turned by 45 degrees) when they are `(1/2, 1/2)` apart.
//!   Edges a cell shares with itself across the seam are listed with `site == i`.
//! * A site whose weight is too small has an empty cell (area 0, no polygon, no neighbours);
//!   that is reported, not an error. Cells that would have zero area (a segment or a point) are
//!   reported empty too.
//!
//! The weights that give every cell a prescribed area (semi-discrete optimal transport:
//! Aurenhammer, Hoffmann and Aronov 1998, damped Newton after Kitagawa, Mérigot and Thibert
//! 2019) are solved inside the crate for the [`bnot`](crate::samplers::bnot) sampler; that
//! solver is not public.
//!
//! # Errors
//!
//! [`strata::Error::InvalidInput`], each message saying what is allowed: no sites, more than
//! [`MAX_SITES`], a coordinate outside `[0, 1)` (sites must lie on the torus) or non-finite,
//! a nonzero coordinate below [`MIN_MAGNITUDE`], a weight non-finite, beyond [`MAX_WEIGHT`] or
//! nonzero below [`MIN_MAGNITUDE`], a weight count different from the site count, and two
//! coincident sites (`-0.0` counts as `0.0`). Sites `1e-15` apart are not an error: their cells
//! are split exactly.

use core::cmp::Ordering;

use crate::grid::wrap_unit;
use crate::{Error, Result};

mod exact;
mod linalg;
pub(crate) mod transport;

use exact::{Context, Plane, Vertex, farther, intersect, side};

/// The most sites in one diagram.
pub const MAX_SITES: usize = 1 << 24;

/// The smallest nonzero magnitude of a coordinate or weight, 2^-200: below it, exact products
/// could underflow.
pub const MIN_MAGNITUDE: f64 = 6.223015277861142e-61;

/// The largest magnitude of a weight, 2^100.
pub const MAX_WEIGHT: f64 = 1.2676506002282294e30;

/// A neighbour of a cell across one edge.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Neighbor {
    /// The neighbouring site (the cell's own site for an edge it shares with itself across the
    /// torus seam, which happens when a cell spans the torus: one or two sites, or a site whose
    /// weight dwarfs the others').
    pub site: usize,
    /// Which periodic copy of the neighbour is across the edge: `s_site + shift` (unwrapped)
    /// is the neighbour as seen from this cell's site.
    pub shift: [i8; 2],
    /// The length of the shared edge (positive).
    pub length: f64,
    /// `|s_site + shift - s_i|`: the distance to that copy, across the seam if need be.
    pub distance: f64,
}

/// One cell of a [`PowerDiagram`].
#[derive(Clone, Copy, Debug)]
pub struct Cell<'a> {
    site: [f64; 2],
    area: f64,
    centroid: [f64; 2],
    polygon: &'a [[f64; 2]],
    neighbors: &'a [Neighbor],
}

impl<'a> Cell<'a> {
    /// The cell's site.
    pub fn site(&self) -> [f64; 2] {
        self.site
    }

    /// The cell's area (0 for an empty cell).
    pub fn area(&self) -> f64 {
        self.area
    }

    /// Whether the cell is empty (its site's weight is too small for it to own any area).
    pub fn is_empty(&self) -> bool {
        self.polygon.is_empty()
    }

    /// The centroid, unwrapped: in the coordinates of the site (it may lie outside `[0, 1)`
    /// when the cell crosses the seam). `None` for an empty cell.
    pub fn centroid_unwrapped(&self) -> Option<[f64; 2]> {
        (!self.is_empty()).then_some(self.centroid)
    }

    /// The centroid wrapped onto the torus, in `[0, 1)`. `None` for an empty cell.
    pub fn centroid(&self) -> Option<[f64; 2]> {
        self.centroid_unwrapped()
            .map(|c| [wrap_unit(c[0]), wrap_unit(c[1])])
    }

    /// The cell's vertices, counter-clockwise, in the site's (unwrapped) coordinates: the
    /// polygon may extend past the unit square's sides, and is then to be read modulo 1.
    /// Edge `k` runs from vertex `k` to vertex `k + 1` and is shared with `neighbors()[k]`.
    pub fn polygon(&self) -> &'a [[f64; 2]] {
        self.polygon
    }

    /// The neighbour across each edge of [`polygon`](Self::polygon), in the same order.
    pub fn neighbors(&self) -> &'a [Neighbor] {
        self.neighbors
    }

    /// The cell's perimeter.
    pub fn perimeter(&self) -> f64 {
        self.neighbors.iter().map(|n| n.length).sum()
    }
}

/// Counts of how the side tests were decided (for profiling and for the tests that check the
/// exact paths are exercised).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Stats {
    /// Candidate bisectors looked at.
    pub candidates: u64,
    /// Candidates rejected by the distance bound without any side test.
    pub rejected: u64,
    /// Side tests run.
    pub side_tests: u64,
    /// Clips that changed a polygon.
    pub clips: u64,
}

/// The power diagram of weighted sites on the unit torus. See the [module](self) docs.
///
/// ```
/// use strata_lab::power::PowerDiagram;
///
/// // Two sites on a horizontal line: two vertical strips; a weight widens its strip.
/// let d = PowerDiagram::new(&[[0.25, 0.5], [0.75, 0.5]], &[0.05, 0.0])?;
/// assert!((d.cell(0).area() - 0.6).abs() < 1e-15);
/// let nb = d.cell(0).neighbors();
/// assert!(nb.iter().any(|n| n.site == 1 && n.shift == [-1, 0])); // across the seam
/// # Ok::<(), strata_lab::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct PowerDiagram {
    sites: Vec<[f64; 2]>,
    weights: Vec<f64>,
    area: Vec<f64>,
    centroid: Vec<[f64; 2]>,
    poly_start: Vec<u32>,
    polys: Vec<[f64; 2]>,
    nb_start: Vec<u32>,
    nbs: Vec<Neighbor>,
    grid: TorusGrid,
    builder: CellBuilder,
    stats: Stats,
}

impl PowerDiagram {
    /// The power diagram of `sites` (each in `[0, 1)^2`) with `weights` (one per site).
    ///
    /// # Errors
    ///
    /// No sites, more than [`MAX_SITES`], mismatched lengths, a coordinate outside `[0, 1)` or
    /// non-finite, a weight non-finite or beyond [`MAX_WEIGHT`], a nonzero coordinate or weight
    /// below [`MIN_MAGNITUDE`], or two coincident sites.
    pub fn new(sites: &[[f64; 2]], weights: &[f64]) -> Result<Self> {
        let mut d = PowerDiagram::default();
        d.compute(sites, weights)?;
        Ok(d)
    }

    /// The (unweighted) Voronoi diagram of `sites` on the torus.
    ///
    /// # Errors
    ///
    /// As [`new`](Self::new).
    pub fn voronoi(sites: &[[f64; 2]]) -> Result<Self> {
        Self::new(sites, &vec![0.0; sites.len()])
    }

    /// Recomputes the diagram for new sites and weights, reusing this one's memory.
    ///
    /// # Errors
    ///
    /// As [`new`](Self::new); on error the diagram is left empty.
    pub fn compute(&mut self, sites: &[[f64; 2]], weights: &[f64]) -> Result<()> {
        self.clear();
        validate_sites(sites)?;
        validate_weights(sites.len(), weights)?;
        check_coincident(sites)?;
        self.sites.extend_from_slice(sites);
        self.weights.extend_from_slice(weights);
        self.grid.build(&self.sites);
        self.build_cells();
        Ok(())
    }

    /// Recomputes the diagram for new weights on the same sites (skips re-validating the sites
    /// and rebuilding the grid).
    ///
    /// # Errors
    ///
    /// Mismatched length or an invalid weight; on error the diagram is left unchanged.
    pub fn set_weights(&mut self, weights: &[f64]) -> Result<()> {
        validate_weights(self.sites.len(), weights)?;
        self.weights.clear();
        self.weights.extend_from_slice(weights);
        self.build_cells();
        Ok(())
    }

    fn clear(&mut self) {
        self.sites.clear();
        self.weights.clear();
        self.area.clear();
        self.centroid.clear();
        self.poly_start.clear();
        self.polys.clear();
        self.nb_start.clear();
        self.nbs.clear();
        self.stats = Stats::default();
    }

    fn build_cells(&mut self) {
        let n = self.sites.len();
        self.area.clear();
        self.centroid.clear();
        self.poly_start.clear();
        self.polys.clear();
        self.nb_start.clear();
        self.nbs.clear();
        self.stats = Stats::default();
        let w_max = self
            .weights
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        self.poly_start.push(0);
        self.nb_start.push(0);
        for i in 0..n {
            let ctx = Context {
                si: self.sites[i],
                wi: self.weights[i],
                sites: &self.sites,
                weights: &self.weights,
            };
            let nonempty = self
                .builder
                .build(&ctx, i as u32, &self.grid, w_max, &mut self.stats);
            let (area, centroid) = if nonempty {
                self.builder.emit(ctx.si, i, &mut self.polys, &mut self.nbs)
            } else {
                (0.0, ctx.si)
            };
            self.area.push(area);
            self.centroid.push(centroid);
            self.poly_start.push(self.polys.len() as u32);
            self.nb_start.push(self.nbs.len() as u32);
        }
    }

    /// The number of sites (cells, empty or not).
    pub fn len(&self) -> usize {
        self.sites.len()
    }

    /// Whether the diagram has no sites (only after a failed [`compute`](Self::compute)).
    pub fn is_empty(&self) -> bool {
        self.sites.is_empty()
    }

    /// The sites.
    pub fn sites(&self) -> &[[f64; 2]] {
        &self.sites
    }

    /// The weights.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Every cell's area, in site order.
    pub fn areas(&self) -> &[f64] {
        &self.area
    }

    /// Cell `i`.
    ///
    /// # Panics
    ///
    /// If `i >= self.len()` (like slice indexing; [`get`](Self::get) does not panic).
    pub fn cell(&self, i: usize) -> Cell<'_> {
        let p = self.poly_start[i] as usize..self.poly_start[i + 1] as usize;
        let q = self.nb_start[i] as usize..self.nb_start[i + 1] as usize;
        Cell {
            site: self.sites[i],
            area: self.area[i],
            centroid: self.centroid[i],
            polygon: &self.polys[p],
            neighbors: &self.nbs[q],
        }
    }

    /// Cell `i`, or `None` if `i >= self.len()`.
    pub fn get(&self, i: usize) -> Option<Cell<'_>> {
        (i < self.len()).then(|| self.cell(i))
    }

    /// All cells, in site order.
    pub fn cells(&self) -> impl ExactSizeIterator<Item = Cell<'_>> + '_ {
        (0..self.len()).map(|i| self.cell(i))
    }

    /// The number of empty cells.
    pub fn empty_cells(&self) -> usize {
        (0..self.len())
            .filter(|&i| self.poly_start[i] == self.poly_start[i + 1])
            .count()
    }

    /// The site whose power distance `|x - s_i|^2 - w_i` to `x` (to the nearest periodic copy
    /// of `s_i`) is smallest: the cell that holds `x`. Ties (`x` on a cell boundary) go to the
    /// lowest index. Floating point, `O(N)` (a scan of every site; meant for queries and
    /// checks, not for assigning many points). `x` is read modulo 1, so any finite point is
    /// allowed.
    ///
    /// # Errors
    ///
    /// A non-finite coordinate, or an empty diagram (only after a failed
    /// [`compute`](Self::compute)).
    pub fn power_nearest(&self, x: [f64; 2]) -> Result<usize> {
        if !(x[0].is_finite() && x[1].is_finite()) {
            return Err(Error::input(
                CONTEXT,
                format!("the query point {x:?} is not finite; any finite point is allowed"),
            ));
        }
        if self.is_empty() {
            return Err(Error::input(
                CONTEXT,
                "the diagram has no sites (a compute failed); compute it again first",
            ));
        }
        let x = [wrap_unit(x[0]), wrap_unit(x[1])];
        let mut best = (f64::INFINITY, 0);
        for (i, (&s, &w)) in self.sites.iter().zip(&self.weights).enumerate() {
            let p = crate::grid::torus_distance_squared(x, s) - w;
            if p < best.0 {
                best = (p, i);
            }
        }
        Ok(best.1)
    }
}

// ---------------------------------------------------------------------------------------------
// Validation.

/// The context named in this module's errors.
const CONTEXT: &str = "power";

fn valid_coordinate(x: f64) -> bool {
    (0.0..1.0).contains(&x) && (x == 0.0 || x >= MIN_MAGNITUDE)
}

pub(crate) fn validate_sites(sites: &[[f64; 2]]) -> Result<()> {
    if sites.is_empty() {
        return Err(Error::input(
            CONTEXT,
            "no sites were given; at least one is needed",
        ));
    }
    if sites.len() > MAX_SITES {
        return Err(Error::input(
            CONTEXT,
            format!(
                "{} sites were given; at most {MAX_SITES} are supported",
                sites.len()
            ),
        ));
    }
    if let Some(index) = sites
        .iter()
        .position(|s| !valid_coordinate(s[0]) || !valid_coordinate(s[1]))
    {
        return Err(Error::input(
            CONTEXT,
            format!(
                "site {index} is {:?}; coordinates must be finite, in [0, 1) (the unit torus), \
                 and either 0 or at least 2^-200 (so that the exact predicates cannot underflow)",
                sites[index]
            ),
        ));
    }
    Ok(())
}

pub(crate) fn validate_weights(n: usize, weights: &[f64]) -> Result<()> {
    if weights.len() != n {
        return Err(Error::input(
            CONTEXT,
            format!(
                "{n} sites but {} weights; there must be exactly one weight per site",
                weights.len()
            ),
        ));
    }
    if let Some(index) = weights
        .iter()
        .position(|&w| w.is_nan() || w.abs() > MAX_WEIGHT || (w != 0.0 && w.abs() < MIN_MAGNITUDE))
    {
        return Err(Error::input(
            CONTEXT,
            format!(
                "weight {index} is {:e}; weights must be finite with |w| <= 2^100, and either 0 \
                 or |w| >= 2^-200 (so that the exact predicates cannot overflow or underflow)",
                weights[index]
            ),
        ));
    }
    Ok(())
}

/// The first pair of coincident sites (lower index first), if any (`-0.0` equals `0.0`).
pub(crate) fn find_coincident(sites: &[[f64; 2]]) -> Option<(usize, usize)> {
    // Adding +0.0 turns -0.0 into +0.0, so that `total_cmp` sorts equal values together.
    let key = |i: u32| {
        let s = sites[i as usize];
        [s[0] + 0.0, s[1] + 0.0]
    };
    let mut order: Vec<u32> = (0..sites.len() as u32).collect();
    order.sort_unstable_by(|&a, &b| {
        let (p, q) = (key(a), key(b));
        p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1]))
    });
    order
        .windows(2)
        .find(|w| key(w[0]) == key(w[1]))
        .map(|w| (w[0].min(w[1]) as usize, w[0].max(w[1]) as usize))
}

pub(crate) fn check_coincident(sites: &[[f64; 2]]) -> Result<()> {
    match find_coincident(sites) {
        None => Ok(()),
        Some((first, second)) => Err(Error::input(
            CONTEXT,
            format!(
                "sites {first} and {second} coincide at {:?}; all sites must be distinct \
                 (nearly coincident sites are fine)",
                sites[first]
            ),
        )),
    }
}

// ---------------------------------------------------------------------------------------------
// The bucket grid.

/// A uniform `g x g` bucket grid on the torus (about two sites per bucket).
#[derive(Clone, Debug, Default)]
struct TorusGrid {
    g: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl TorusGrid {
    fn bucket(&self, s: [f64; 2]) -> (usize, usize) {
        let g = self.g as f64;
        let b = |x: f64| ((x * g) as usize).min(self.g - 1);
        (b(s[0]), b(s[1]))
    }

    fn build(&mut self, sites: &[[f64; 2]]) {
        let n = sites.len();
        self.g = ((n as f64 / SITES_PER_BUCKET).sqrt() as usize).clamp(1, 4096);
        let cells = self.g * self.g;
        self.start.clear();
        self.start.resize(cells + 1, 0);
        for &s in sites {
            let (x, y) = self.bucket(s);
            self.start[y * self.g + x + 1] += 1;
        }
        for c in 0..cells {
            self.start[c + 1] += self.start[c];
        }
        self.items.clear();
        self.items.resize(n, 0);
        let mut fill = self.start.clone();
        for (i, &s) in sites.iter().enumerate() {
            let (x, y) = self.bucket(s);
            let c = y * self.g + x;
            self.items[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
    }

    /// Calls `f(site, shift)` for the sites in the (unwrapped) bucket `(bx, by)`.
    #[inline]
    fn for_bucket(&self, bx: isize, by: isize, mut f: impl FnMut(u32, [i8; 2])) {
        // Rings stay within a few periods, so a loop beats integer division.
        let wrap = |mut q: isize| {
            let g = self.g as isize;
            let mut k = 0i8;
            while q < 0 {
                q += g;
                k -= 1;
            }
            while q >= g {
                q -= g;
                k += 1;
            }
            (q as usize, k)
        };
        let (qx, kx) = wrap(bx);
        let (qy, ky) = wrap(by);
        let c = qy * self.g + qx;
        let shift = [kx, ky];
        for &j in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
            f(j, shift);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Building one cell.

enum Clip {
    Unchanged,
    Clipped,
    Empty,
}

#[derive(Clone, Debug, Default)]
struct CellBuilder {
    planes: Vec<Plane>,
    poly: Vec<Vertex>,
    next: Vec<Vertex>,
    signs: Vec<Ordering>,
    cand: Vec<(f64, u32, [i8; 2])>,
}

const U: f64 = f64::EPSILON / 2.0;

/// The bucket grid's mean occupancy.
const SITES_PER_BUCKET: f64 = 1.0;

impl CellBuilder {
    fn vertex(&self, ctx: &Context<'_>, inp: u32, out: u32) -> Vertex {
        let (x, err) = intersect(ctx, &self.planes[inp as usize], &self.planes[out as usize]);
        Vertex { inp, out, x, err }
    }

    /// The unit square around the site: the half-planes of its four axis-aligned copies.
    fn reset(&mut self, ctx: &Context<'_>, i: u32) {
        self.planes.clear();
        for shift in [[1, 0], [0, 1], [-1, 0], [0, -1]] {
            self.planes.push(Plane::new(ctx, i, shift));
        }
        self.poly.clear();
        for (inp, out) in [(3, 0), (0, 1), (1, 2), (2, 3)] {
            let v = self.vertex(ctx, inp, out);
            self.poly.push(v);
        }
    }

    /// A bound on the distance from the site to the farthest point of the polygon.
    fn radius(&self) -> f64 {
        let (mut r2, mut err) = (0.0f64, 0.0f64);
        for v in &self.poly {
            r2 = r2.max(v.x[0] * v.x[0] + v.x[1] * v.x[1]);
            err = err.max(v.err);
        }
        // sqrt is correctly rounded; the relative slack covers the rounding of r2.
        r2.sqrt() * (1.0 + 4.0 * U) + 1.5 * err
    }

    fn clip(&mut self, ctx: &Context<'_>, plane: Plane, stats: &mut Stats) -> Clip {
        self.signs.clear();
        let (mut any_out, mut any_in) = (false, false);
        for v in &self.poly {
            let s = side(
                ctx,
                v,
                &self.planes[v.inp as usize],
                &self.planes[v.out as usize],
                &plane,
            );
            any_out |= s == Ordering::Greater;
            any_in |= s == Ordering::Less;
            self.signs.push(s);
        }
        stats.side_tests += self.poly.len() as u64;
        let m = self.poly.len();
        if !any_out {
            // The line may contain a whole edge (two bisectors on one line): the edge then
            // belongs to the farther of the two sites.
            for k in 0..m {
                let k1 = if k + 1 == m { 0 } else { k + 1 };
                if self.signs[k] == Ordering::Equal && self.signs[k1] == Ordering::Equal {
                    let e = self.poly[k].out as usize;
                    if farther(ctx, &plane, &self.planes[e]) {
                        let ci = self.planes.len() as u32;
                        self.planes.push(plane);
                        self.poly[k] = self.vertex(ctx, self.poly[k].inp, ci);
                        self.poly[k1] = self.vertex(ctx, ci, self.poly[k1].out);
                    }
                    break;
                }
            }
            return Clip::Unchanged;
        }
        if !any_in {
            return Clip::Empty;
        }
        stats.clips += 1;
        let ci = self.planes.len() as u32;
        self.planes.push(plane);
        self.next.clear();
        for k in 0..m {
            let k1 = if k + 1 == m { 0 } else { k + 1 };
            let kp = if k == 0 { m - 1 } else { k - 1 };
            let (s, s1) = (self.signs[k], self.signs[k1]);
            if s != Ordering::Greater {
                let mut v = self.poly[k];
                if s == Ordering::Equal {
                    // A vertex on the line stays; it now meets the new edge.
                    if self.signs[kp] == Ordering::Greater {
                        v = self.vertex(ctx, ci, v.out);
                    } else if s1 == Ordering::Greater {
                        v = self.vertex(ctx, v.inp, ci);
                    }
                }
                self.next.push(v);
            }
            if s == Ordering::Less && s1 == Ordering::Greater {
                let v = self.vertex(ctx, self.poly[k].out, ci);
                self.next.push(v);
            } else if s == Ordering::Greater && s1 == Ordering::Less {
                let v = self.vertex(ctx, ci, self.poly[k].out);
                self.next.push(v);
            }
        }
        core::mem::swap(&mut self.poly, &mut self.next);
        Clip::Clipped
    }

    /// Clips by the candidates gathered in `self.cand`, nearest first. Returns false if the
    /// cell became empty.
    fn clip_candidates(&mut self, ctx: &Context<'_>, stats: &mut Stats) -> bool {
        let mut cand = core::mem::take(&mut self.cand);
        cand.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let mut r = self.radius();
        let mut alive = true;
        for &(_, j, shift) in &cand {
            stats.candidates += 1;
            let plane = Plane::new(ctx, j, shift);
            // No vertex can be outside when 2 |x| |p| < c for every point of the polygon
            // (squared, to avoid a square root: both sides are then positive).
            let c = plane.c - 8.0 * U * plane.cbar;
            let p2 = plane.p[0] * plane.p[0] + plane.p[1] * plane.p[1];
            if c > 0.0 && 4.0 * r * r * p2 * (1.0 + 1e-11) < c * c {
                stats.rejected += 1;
                continue;
            }
            match self.clip(ctx, plane, stats) {
                Clip::Unchanged => {}
                Clip::Clipped => r = self.radius(),
                Clip::Empty => {
                    alive = false;
                    break;
                }
            }
        }
        cand.clear();
        self.cand = cand;
        alive
    }

    /// Builds cell `i`; returns false if it is empty.
    fn build(
        &mut self,
        ctx: &Context<'_>,
        i: u32,
        grid: &TorusGrid,
        w_max: f64,
        stats: &mut Stats,
    ) -> bool {
        self.reset(ctx, i);
        let (bx, by) = grid.bucket(ctx.si);
        let (bx, by) = (bx as isize, by as isize);
        let h = 1.0 / grid.g as f64;
        let mut ring: isize = 0;
        // Distance bound (squared) beyond which no copy can clip; refined after each ring.
        let mut need2 = f64::INFINITY;
        loop {
            // Gather the ring's sites (rings 0 and 1 together).
            let lo = if ring == 0 { 0 } else { ring };
            let hi = if ring == 0 { 1 } else { ring };
            for r in lo..=hi {
                let mut visit = |dx: isize, dy: isize| {
                    // Skip buckets entirely beyond the bound (box distance from the site).
                    let gap = |b: isize, x: f64| {
                        let lo = b as f64 * h;
                        (lo - x).max(x - (lo + h)).max(0.0)
                    };
                    let gx = gap(bx + dx, ctx.si[0]);
                    let gy = gap(by + dy, ctx.si[1]);
                    if (gx * gx + gy * gy) * (1.0 - 1e-9) > need2 {
                        return;
                    }
                    grid.for_bucket(bx + dx, by + dy, |j, shift| {
                        if j != i {
                            let s = ctx.sites[j as usize];
                            let dxs = s[0] + f64::from(shift[0]) - ctx.si[0];
                            let dys = s[1] + f64::from(shift[1]) - ctx.si[1];
                            self.cand.push((dxs * dxs + dys * dys, j, shift));
                        }
                    });
                };
                if r == 0 {
                    visit(0, 0);
                } else {
                    for d in -r..=r {
                        visit(d, -r);
                        visit(d, r);
                    }
                    for d in -r + 1..r {
                        visit(-r, d);
                        visit(r, d);
                    }
                }
            }
            if !self.clip_candidates(ctx, stats) {
                return false;
            }
            ring = hi;
            // Every site not yet seen is farther than `ring * h` (minus rounding).
            let reach = (ring as f64 - 1e-6) * h;
            let r = self.radius();
            let need = (r + (r * r + (w_max - ctx.wi)).max(0.0).sqrt()) * (1.0 + 1e-9);
            need2 = need * need;
            if reach > need || reach > core::f64::consts::SQRT_2 * (1.0 + 1e-9) {
                return true;
            }
            ring += 1;
        }
    }

    /// Writes the built (non-empty) polygon and its neighbours; returns the area and the
    /// unwrapped centroid.
    fn emit(
        &self,
        si: [f64; 2],
        i: usize,
        polys: &mut Vec<[f64; 2]>,
        nbs: &mut Vec<Neighbor>,
    ) -> (f64, [f64; 2]) {
        let m = self.poly.len();
        let (mut a2, mut cx, mut cy) = (0.0, 0.0, 0.0);
        for k in 0..m {
            let p = self.poly[k].x;
            let q = self.poly[if k + 1 == m { 0 } else { k + 1 }].x;
            let cross = p[0] * q[1] - p[1] * q[0];
            a2 += cross;
            cx += (p[0] + q[0]) * cross;
            cy += (p[1] + q[1]) * cross;
            polys.push([si[0] + p[0], si[1] + p[1]]);
            let plane = &self.planes[self.poly[k].out as usize];
            let site = plane.site as usize;
            nbs.push(Neighbor {
                site,
                shift: plane.shift,
                length: {
                    let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
                    (ex * ex + ey * ey).sqrt()
                },
                distance: plane.distance(),
            });
            debug_assert!(site != i || plane.shift != [0, 0]);
        }
        let area = 0.5 * a2;
        let c = if area > 0.0 {
            [cx / (3.0 * a2), cy / (3.0 * a2)]
        } else {
            [0.0, 0.0]
        };
        (area.max(0.0), [si[0] + c[0], si[1] + c[1]])
    }
}
