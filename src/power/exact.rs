//! Exact geometric predicates for power diagrams, filtered by floating-point error bounds.
//!
//! A power cell is built in coordinates relative to its site `s_i`. Another site's periodic copy
//! `s_j + k` (`k` an integer shift) with weight `w_j` bounds it by the half-plane
//! `2 x . p <= c`, with `p = s_j + k - s_i` and `c = |p|^2 - (w_j - w_i)`: the points whose power
//! distance `|x - s_i|^2 - w_i` is at most the one to `s_j + k`. A cell vertex is the meeting point
//! of two such lines `a` and `b`; whether it lies inside, on, or outside a third line `c` is the
//! sign of
//!
//! ```text
//! t = 2 x . p_c - c_c = -det3 / det2,   det3 = | p_a  c_a |      det2 = det(p_a, p_b)
//!                                              | p_b  c_b |
//!                                              | p_c  c_c |
//! ```
//!
//! (`det3` is the lifted `orient3d` of the four weighted points, i.e. the power test). The sign
//! is decided in three stages:
//!
//! 1. from the vertex's floating-point coordinates and a rigorous bound on their error
//!    (a few flops; decides all but near-degenerate cases);
//! 2. from `det3` evaluated in floating point against a bound proportional to its permanent;
//! 3. exactly, with Shewchuk's floating-point expansions built from the *input* coordinates,
//!    shifts and weights (so the decision is that of the true, unrounded configuration).
//!
//! Stage 3 is exact provided no product underflows, which the input validation guarantees
//! (coordinates are 0 or at least 2^-200, weights are 0 or at least 2^-200 in magnitude and at
//! most 2^100).
//!
//! Reference: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
//! Geometric Predicates", Discrete & Computational Geometry 18 (1997).

use core::cmp::Ordering;

/// The unit roundoff of `f64`, 2^-53.
const U: f64 = f64::EPSILON / 2.0;

/// Below this the floating-point error bounds could themselves underflow; go exact.
const TINY: f64 = 1e-280;

// ---------------------------------------------------------------------------------------------
// Error-free transformations and expansions.

#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let x = a + b;
    let bv = x - a;
    let av = x - bv;
    (x, (a - av) + (b - bv))
}

#[inline]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    // Requires |a| >= |b| (or a == 0).
    let x = a + b;
    (x, b - (x - a))
}

#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let x = a * b;
    (x, a.mul_add(b, -x))
}

/// A nonoverlapping expansion: the exact value is the sum of its components, which are sorted
/// by increasing magnitude with zeros removed (the empty expansion is zero).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Expansion(Vec<f64>);

impl Expansion {
    #[cfg(test)]
    pub(crate) fn from_f64(x: f64) -> Self {
        if x == 0.0 {
            Expansion(Vec::new())
        } else {
            Expansion(vec![x])
        }
    }

    /// `a - b`, exactly.
    pub(crate) fn diff(a: f64, b: f64) -> Self {
        let (x, y) = two_sum(a, -b);
        let mut v = Vec::with_capacity(2);
        if y != 0.0 {
            v.push(y);
        }
        if x != 0.0 {
            v.push(x);
        }
        Expansion(v)
    }

    /// `self + b`, exactly (Shewchuk's GROW-EXPANSION with zero elimination).
    pub(crate) fn grow(&self, b: f64) -> Self {
        let mut q = b;
        let mut h = Vec::with_capacity(self.0.len() + 1);
        for &e in &self.0 {
            let (s, err) = two_sum(q, e);
            q = s;
            if err != 0.0 {
                h.push(err);
            }
        }
        if q != 0.0 {
            h.push(q);
        }
        Expansion(h)
    }

    pub(crate) fn add(&self, other: &Self) -> Self {
        let mut r = self.clone();
        for &f in &other.0 {
            r = r.grow(f);
        }
        r
    }

    pub(crate) fn neg(&self) -> Self {
        Expansion(self.0.iter().map(|x| -x).collect())
    }

    pub(crate) fn sub(&self, other: &Self) -> Self {
        self.add(&other.neg())
    }

    /// `self * b`, exactly (Shewchuk's SCALE-EXPANSION with zero elimination).
    pub(crate) fn scale(&self, b: f64) -> Self {
        let e = &self.0;
        if e.is_empty() || b == 0.0 {
            return Expansion(Vec::new());
        }
        let mut h = Vec::with_capacity(2 * e.len());
        let (mut q, err) = two_prod(e[0], b);
        if err != 0.0 {
            h.push(err);
        }
        for &ei in &e[1..] {
            let (p1, p0) = two_prod(ei, b);
            let (sum, err) = two_sum(q, p0);
            if err != 0.0 {
                h.push(err);
            }
            let (nq, err) = fast_two_sum(p1, sum);
            q = nq;
            if err != 0.0 {
                h.push(err);
            }
        }
        if q != 0.0 {
            h.push(q);
        }
        Expansion(h)
    }

    pub(crate) fn mul(&self, other: &Self) -> Self {
        let mut r = Expansion(Vec::new());
        for &f in &other.0 {
            r = r.add(&self.scale(f));
        }
        r
    }

    /// The sign of the exact value: that of the largest component.
    pub(crate) fn sign(&self) -> Ordering {
        match self.0.last() {
            None => Ordering::Equal,
            Some(&x) if x > 0.0 => Ordering::Greater,
            Some(_) => Ordering::Less,
        }
    }

    /// An approximation of the value (the sum of the components, largest last).
    pub(crate) fn estimate(&self) -> f64 {
        self.0.iter().sum()
    }
}

// ---------------------------------------------------------------------------------------------
// Planes (bisectors) and vertices.

/// One bounding line of a cell under construction, relative to the cell's site `s_i`:
/// the half-plane `2 x . p <= c`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plane {
    /// The other site (equal to the cell's own site for the four copies that bound the
    /// fundamental square).
    pub site: u32,
    /// The periodic shift of the other site's copy.
    pub shift: [i8; 2],
    /// `s_j + k - s_i`, rounded (relative error at most 2.01 u per component).
    pub p: [f64; 2],
    /// `|p|^2 - (w_j - w_i)`, rounded (absolute error at most 8 u `cbar`).
    pub c: f64,
    /// `|p|^2 + |w_j - w_i|`: the magnitude that bounds the error of `c`.
    pub cbar: f64,
}

/// Where the exact arithmetic finds the cell's own site and the input data.
#[derive(Clone, Copy)]
pub(crate) struct Context<'a> {
    pub si: [f64; 2],
    pub wi: f64,
    pub sites: &'a [[f64; 2]],
    pub weights: &'a [f64],
}

/// `x_j + k - x_i` to within 2.01 u relative: the difference is split exactly, and adding the
/// integer shift to the leading part is exact whenever the result is below 1/2 (Sterbenz).
#[inline]
fn relative(xj: f64, xi: f64, k: i8) -> f64 {
    let (hi, lo) = two_sum(xj, -xi);
    (hi + f64::from(k)) + lo
}

impl Plane {
    /// The bisector between the cell's site `i` (at `ctx.si`, weight `ctx.wi`) and the copy of
    /// site `j` shifted by `shift`.
    #[inline]
    pub(crate) fn new(ctx: &Context<'_>, j: u32, shift: [i8; 2]) -> Self {
        let sj = ctx.sites[j as usize];
        let wj = ctx.weights[j as usize];
        let p = [
            relative(sj[0], ctx.si[0], shift[0]),
            relative(sj[1], ctx.si[1], shift[1]),
        ];
        let dw = wj - ctx.wi;
        let n2 = p[0] * p[0] + p[1] * p[1];
        Plane {
            site: j,
            shift,
            p,
            c: n2 - dw,
            cbar: n2 + dw.abs(),
        }
    }

    /// The exact relative position and lifted value `c` of this plane.
    fn exact(&self, ctx: &Context<'_>) -> ([Expansion; 2], Expansion) {
        let sj = ctx.sites[self.site as usize];
        let wj = ctx.weights[self.site as usize];
        let px = Expansion::diff(sj[0], ctx.si[0]).grow(f64::from(self.shift[0]));
        let py = Expansion::diff(sj[1], ctx.si[1]).grow(f64::from(self.shift[1]));
        let c = px
            .mul(&px)
            .add(&py.mul(&py))
            .sub(&Expansion::diff(wj, ctx.wi));
        ([px, py], c)
    }

    /// The plane's distance `|p|`.
    #[inline]
    pub(crate) fn distance(&self) -> f64 {
        (self.p[0] * self.p[0] + self.p[1] * self.p[1]).sqrt()
    }
}

/// A vertex of a cell: the meeting point of the lines `inp` (the edge arriving at it,
/// counter-clockwise) and `out` (the edge leaving it), with a bound on its coordinates' error.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Vertex {
    /// Index of the plane of the incoming edge.
    pub inp: u32,
    /// Index of the plane of the outgoing edge.
    pub out: u32,
    /// Coordinates relative to the site.
    pub x: [f64; 2],
    /// A bound on the absolute error of each coordinate (infinite if unreliable).
    pub err: f64,
}

/// The meeting point of lines `a` and `b` (Cramer's rule), with a rigorous error bound.
///
/// When the lines are nearly parallel (the bound exceeds 1e-12 of the coordinates: two nearly
/// coincident sites seen from a third), the point is recomputed from exact numerators and
/// denominator, so that it is accurate to a few ulps whatever the conditioning.
#[inline]
pub(crate) fn intersect(ctx: &Context<'_>, a: &Plane, b: &Plane) -> ([f64; 2], f64) {
    let d = a.p[0] * b.p[1] - a.p[1] * b.p[0];
    let dbar = (a.p[0] * b.p[1]).abs() + (a.p[1] * b.p[0]).abs();
    let nx = a.c * b.p[1] - b.c * a.p[1];
    let ny = b.c * a.p[0] - a.c * b.p[0];
    // y = 2x = (nx, ny) / d.
    let yx = nx / d;
    let yy = ny / d;
    let err_d = 8.0 * U * dbar;
    let den = d.abs() - err_d;
    if den.is_nan() || den <= 0.0 || !yx.is_finite() || !yy.is_finite() || dbar < TINY {
        return intersect_exact(ctx, a, b);
    }
    let nxbar = a.cbar * b.p[1].abs() + b.cbar * a.p[1].abs();
    let nybar = b.cbar * a.p[0].abs() + a.cbar * b.p[0].abs();
    let ex = (16.0 * U * nxbar + yx.abs() * err_d) / den + 2.0 * U * yx.abs();
    let ey = (16.0 * U * nybar + yy.abs() * err_d) / den + 2.0 * U * yy.abs();
    // Halve y, and pad the bound a little for the rounding of the bound itself.
    let x = [0.5 * yx, 0.5 * yy];
    let err = 0.5 * ex.max(ey) * (1.0 + 1e-6);
    if err > 1e-12 * x[0].abs().max(x[1].abs()) {
        return intersect_exact(ctx, a, b);
    }
    (x, err)
}

/// [`intersect`] from exact numerators and denominator: each coordinate is a quotient of two
/// exactly known values, rounded three times (two estimates and the division).
#[cold]
fn intersect_exact(ctx: &Context<'_>, a: &Plane, b: &Plane) -> ([f64; 2], f64) {
    let (pa, ca) = a.exact(ctx);
    let (pb, cb) = b.exact(ctx);
    let d = pa[0].mul(&pb[1]).sub(&pa[1].mul(&pb[0]));
    let nx = ca.mul(&pb[1]).sub(&cb.mul(&pa[1]));
    let ny = cb.mul(&pa[0]).sub(&ca.mul(&pb[0]));
    let (d, nx, ny) = (d.estimate(), nx.estimate(), ny.estimate());
    let x = [0.5 * (nx / d), 0.5 * (ny / d)];
    if !(x[0].is_finite() && x[1].is_finite()) {
        return (x, f64::INFINITY);
    }
    // Each estimate is within 2u of its exact value; the quotient within 5u.
    (x, 8.0 * U * x[0].abs().max(x[1].abs()) + 1e-300)
}

/// The side of the vertex `v` (meeting point of planes `a` and `b`) relative to plane `c`:
/// `Less` strictly inside (`2 x . p_c < c_c`), `Equal` on the line, `Greater` strictly outside.
pub(crate) fn side(ctx: &Context<'_>, v: &Vertex, a: &Plane, b: &Plane, c: &Plane) -> Ordering {
    // Stage 1: the vertex coordinates and their error bound.
    let tx = v.x[0] * c.p[0];
    let ty = v.x[1] * c.p[1];
    let t = 2.0 * (tx + ty) - c.c;
    let bound = 2.02 * v.err * (c.p[0].abs() + c.p[1].abs())
        + 12.0 * U * (tx.abs() + ty.abs() + c.cbar)
        + 2.0 * U * t.abs();
    if bound.is_finite() && bound > TINY && t.abs() > bound {
        return if t > 0.0 {
            Ordering::Greater
        } else {
            Ordering::Less
        };
    }
    side_det(ctx, a, b, c)
}

/// Stages 2 and 3 of [`side`]: the sign of `t = -det3 / det2` for the meeting point of `a` and
/// `b` against `c`, from `det3` in floating point with a permanent bound, else exactly.
pub(crate) fn side_det(ctx: &Context<'_>, a: &Plane, b: &Plane, c: &Plane) -> Ordering {
    let m_bc = b.p[0] * c.p[1] - b.p[1] * c.p[0];
    let m_ac = a.p[0] * c.p[1] - a.p[1] * c.p[0];
    let m_ab = a.p[0] * b.p[1] - a.p[1] * b.p[0];
    let mb_bc = (b.p[0] * c.p[1]).abs() + (b.p[1] * c.p[0]).abs();
    let mb_ac = (a.p[0] * c.p[1]).abs() + (a.p[1] * c.p[0]).abs();
    let mb_ab = (a.p[0] * b.p[1]).abs() + (a.p[1] * b.p[0]).abs();
    let det3 = a.c * m_bc - b.c * m_ac + c.c * m_ab;
    let perm = a.cbar * mb_bc + b.cbar * mb_ac + c.cbar * mb_ab;
    // det2 = m_ab is positive for consecutive edges of a counter-clockwise convex polygon;
    // check it with its own bound before relying on it.
    let det2_ok = m_ab > 8.0 * U * mb_ab && mb_ab > TINY;
    if det2_ok && perm > TINY && det3.abs() > 32.0 * U * perm {
        return if det3 > 0.0 {
            Ordering::Less
        } else {
            Ordering::Greater
        };
    }
    side_exact(ctx, a, b, c)
}

/// Stage 3: the exact sign, from the input coordinates, shifts and weights.
pub(crate) fn side_exact(ctx: &Context<'_>, a: &Plane, b: &Plane, c: &Plane) -> Ordering {
    let (pa, ca) = a.exact(ctx);
    let (pb, cb) = b.exact(ctx);
    let (pc, cc) = c.exact(ctx);
    let minor = |p: &[Expansion; 2], q: &[Expansion; 2]| p[0].mul(&q[1]).sub(&p[1].mul(&q[0]));
    let m_bc = minor(&pb, &pc);
    let m_ac = minor(&pa, &pc);
    let m_ab = minor(&pa, &pb);
    let det3 = ca.mul(&m_bc).sub(&cb.mul(&m_ac)).add(&cc.mul(&m_ab));
    // sign(t) = -sign(det3) * sign(det2).
    let s3 = det3.sign();
    match m_ab.sign() {
        Ordering::Greater => s3.reverse(),
        Ordering::Less => s3,
        // Parallel lines have no meeting point; cannot happen for a vertex of a convex polygon
        // without flat angles. Report "on the line", which leaves the polygon unchanged.
        Ordering::Equal => Ordering::Equal,
    }
}

/// Whether plane `c`'s other site is exactly farther from the cell's site than plane `e`'s
/// (`|p_c| > |p_e|`). Used to label an edge when two bisectors coincide.
pub(crate) fn farther(ctx: &Context<'_>, c: &Plane, e: &Plane) -> bool {
    let (pc, _) = c.exact(ctx);
    let (pe, _) = e.exact(ctx);
    let nc = pc[0].mul(&pc[0]).add(&pc[1].mul(&pc[1]));
    let ne = pe[0].mul(&pe[0]).add(&pe[1].mul(&pe[1]));
    nc.sub(&ne).sign() == Ordering::Greater
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expansions_are_exact() {
        // (1 + 2^-60)^2 = 1 + 2^-59 + 2^-120 exactly.
        let a = Expansion::from_f64(1.0).grow(2f64.powi(-60));
        let sq = a.mul(&a);
        let expected = Expansion::from_f64(1.0)
            .grow(2f64.powi(-59))
            .grow(2f64.powi(-120));
        assert_eq!(sq.sub(&expected).sign(), Ordering::Equal);
        assert_eq!(sq.sub(&Expansion::from_f64(1.0)).sign(), Ordering::Greater);
        assert!((sq.estimate() - 1.0).abs() < 1e-15);
        let d = Expansion::diff(0.1, 0.3);
        assert_eq!(
            d.grow(0.2).sign(),
            0.1f64.partial_cmp(&(0.3 - 0.2)).unwrap()
        );
    }

    #[test]
    fn relative_vector_is_accurate() {
        // 0.001 + 1 - 0.999 = 0.002 (in exact arithmetic on the doubles).
        let xi = 0.999;
        let xj = 0.001;
        let r = relative(xj, xi, 1);
        let exact = Expansion::diff(xj, xi).grow(1.0).estimate();
        assert!((r - exact).abs() <= 2.01 * U * exact.abs());
    }

    /// Integer model: coordinates in units of 2^-20, weights in units of 2^-40.
    struct Model {
        sites: Vec<[f64; 2]>,
        weights: Vec<f64>,
        // Integer relative positions (units 2^-20) and lifted values (units 2^-40) of planes.
        rel: Vec<[i128; 2]>,
        shifts: Vec<[i8; 2]>,
    }

    impl Model {
        /// Site 0 at integer position `xi` with weight `wi`; the others at relative integer
        /// positions `rel[k]` with weights `w[k]`.
        fn new(xi: [i64; 2], wi: i64, others: &[([i64; 2], i64)]) -> Self {
            let unit = 2f64.powi(-20);
            let wunit = 2f64.powi(-40);
            let mut sites = vec![[xi[0] as f64 * unit, xi[1] as f64 * unit]];
            let mut weights = vec![wi as f64 * wunit];
            let mut rel = vec![[0, 0]];
            let mut shifts = vec![[0, 0]];
            for &(p, w) in others {
                let abs = [xi[0] + p[0], xi[1] + p[1]];
                let m = 1i64 << 20;
                let pos = [abs[0].rem_euclid(m), abs[1].rem_euclid(m)];
                let k = [abs[0].div_euclid(m) as i8, abs[1].div_euclid(m) as i8];
                sites.push([pos[0] as f64 * unit, pos[1] as f64 * unit]);
                weights.push(w as f64 * wunit);
                rel.push([p[0] as i128, p[1] as i128]);
                shifts.push(k);
            }
            let _ = wi;
            Model {
                sites,
                weights,
                rel,
                shifts,
            }
        }

        fn ctx(&self) -> Context<'_> {
            Context {
                si: self.sites[0],
                wi: self.weights[0],
                sites: &self.sites,
                weights: &self.weights,
            }
        }

        fn plane(&self, k: usize) -> Plane {
            Plane::new(&self.ctx(), k as u32, self.shifts[k])
        }

        fn lifted(&self, k: usize, wi: i64, w: i64) -> i128 {
            let p = self.rel[k];
            p[0] * p[0] + p[1] * p[1] - (w as i128 - wi as i128)
        }

        /// The exact sign of t for the meeting point of planes a, b against c.
        fn expected(&self, a: usize, b: usize, c: usize, wi: i64, w: &[i64]) -> Ordering {
            let (pa, pb, pc) = (self.rel[a], self.rel[b], self.rel[c]);
            let (ca, cb, cc) = (
                self.lifted(a, wi, w[a]),
                self.lifted(b, wi, w[b]),
                self.lifted(c, wi, w[c]),
            );
            let m = |p: [i128; 2], q: [i128; 2]| p[0] * q[1] - p[1] * q[0];
            let det3 = ca * m(pb, pc) - cb * m(pa, pc) + cc * m(pa, pb);
            let det2 = m(pa, pb);
            let s = (-det3).cmp(&0);
            if det2 > 0 { s } else { s.reverse() }
        }
    }

    fn check_all(model: &Model, wi: i64, w: &[i64]) -> (bool, bool) {
        let ctx = model.ctx();
        let (a, b, c) = (model.plane(1), model.plane(2), model.plane(3));
        let expected = model.expected(1, 2, 3, wi, w);
        let (x, err) = intersect(&ctx, &a, &b);
        let v = Vertex {
            inp: 0,
            out: 1,
            x,
            err,
        };
        assert_eq!(side_exact(&ctx, &a, &b, &c), expected, "exact");
        assert_eq!(side_det(&ctx, &a, &b, &c), expected, "det filter");
        assert_eq!(side(&ctx, &v, &a, &b, &c), expected, "vertex filter");
        (expected == Ordering::Equal, err.is_finite())
    }

    #[test]
    fn predicates_agree_with_integer_arithmetic_near_degeneracy() {
        use rand::Rng;
        let mut g = rand_pcg::Pcg32::new(42, 54);
        let mut rnd = |lo: i64, hi: i64| lo + (g.next_u64() % (hi - lo) as u64) as i64;
        let (mut zeros, mut total) = (0, 0);
        for trial in 0..20_000 {
            let scale = [1i64 << 6, 1 << 12, 1 << 19][trial % 3];
            let xi = [rnd(0, 1 << 20), rnd(0, 1 << 20)];
            let wi = rnd(-(1 << 30), 1 << 30);
            let pa = [rnd(-scale, scale), rnd(-scale, scale)];
            let pb = [rnd(-scale, scale), rnd(-scale, scale)];
            if pa == [0, 0] || pb == [0, 0] || pa[0] * pb[1] - pa[1] * pb[0] == 0 {
                continue;
            }
            let wa = rnd(-(1 << 30), 1 << 30);
            let wb = rnd(-(1 << 30), 1 << 30);
            // Put c's line (nearly) through the meeting point of a and b: choose c's position,
            // then the weight that makes its power equal there, rounded to the grid, plus a
            // small offset.
            let pc = [rnd(-scale, scale), rnd(-scale, scale)];
            if pc == [0, 0] {
                continue;
            }
            let unit = 2f64.powi(-20);
            let wunit = 2f64.powi(-40);
            let f = |p: [i64; 2]| [p[0] as f64 * unit, p[1] as f64 * unit];
            let (fa, fb, fc) = (f(pa), f(pb), f(pc));
            let ca = fa[0] * fa[0] + fa[1] * fa[1] - (wa - wi) as f64 * wunit;
            let cb = fb[0] * fb[0] + fb[1] * fb[1] - (wb - wi) as f64 * wunit;
            let d = fa[0] * fb[1] - fa[1] * fb[0];
            let y = [(ca * fb[1] - cb * fa[1]) / d, (cb * fa[0] - ca * fb[0]) / d];
            // Line c through x = y / 2: 2 x . p_c = |p_c|^2 - (w_c - w_i).
            let wc_f = fc[0] * fc[0] + fc[1] * fc[1] - (y[0] * fc[0] + y[1] * fc[1]);
            let wc = (wc_f / wunit).round() as i64 + wi + rnd(-2, 3);
            if wc.abs() > 1 << 50 {
                continue;
            }
            let w = [wi, wa, wb, wc];
            let model = Model::new(xi, wi, &[(pa, wa), (pb, wb), (pc, wc)]);
            let (zero, _) = check_all(&model, wi, &w);
            zeros += zero as u32;
            total += 1;
        }
        assert!(total > 10_000);
        assert!(
            zeros > 10,
            "only {zeros} exactly degenerate cases out of {total}"
        );
    }

    #[test]
    fn predicates_on_exact_degeneracies() {
        // Rectangles (co-circular), with equal weights: exactly on the line; one unit of
        // weight either way decides.
        for &(xi, a, b, c) in &[
            (
                [0i64, 0i64],
                [1i64 << 18, 0i64],
                [1i64 << 18, 1i64 << 17],
                [0i64, 1i64 << 17],
            ),
            ([1 << 19, 3], [5, 0], [5, 7], [0, 7]),
            (
                [(1 << 20) - 1, (1 << 20) - 2],
                [-100, 0],
                [-100, 300],
                [0, 300],
            ),
        ] {
            for dw in [-1i64, 0, 1] {
                let w = [0, 0, 0, dw];
                let model = Model::new(xi, 0, &[(a, 0), (b, 0), (c, dw)]);
                let (zero, _) = check_all(&model, 0, &w);
                assert_eq!(zero, dw == 0);
            }
        }
    }
}
