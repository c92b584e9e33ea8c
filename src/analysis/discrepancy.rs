//! Discrepancy: how far a point set's counts in boxes deviate from the boxes' volumes.
//!
//! * [`l2_star`]: the L2 norm of the local discrepancy over anchored boxes `[0, y)`, by Warnock's
//!   formula (Warnock 1972), `O(N^2 D)`.
//! * [`wrap_around`]: Hickernell's wrap-around L2 discrepancy (Hickernell 1998): the L2 norms of
//!   the local discrepancy over all boxes of the torus, summed over every projection onto a
//!   nonempty subset of the coordinates; invariant under toroidal shifts, `O(N^2 D)`.
//! * [`star_2d`]: the exact star discrepancy `sup_y |#{x in [0,y)}/N - vol([0,y))|` of a 2D set,
//!   evaluated at the critical boxes (corners at point coordinates and 1, open and closed),
//!   `O(N^2 log N)`; for sets of at most [`MAX_EXACT_STAR`] points.

use crate::error::{Error, Result};

/// The largest set [`star_2d`] accepts.
pub const MAX_EXACT_STAR: usize = 1 << 14;

fn check(points: &[f32], dims: usize) -> Result<usize> {
    if dims == 0 || points.is_empty() || !points.len().is_multiple_of(dims) {
        return Err(Error::input(
            "discrepancy",
            format!(
                "{} values do not make points of {dims} dimensions; at least one point is needed",
                points.len()
            ),
        ));
    }
    if let Some(v) = points.iter().find(|v| !(0.0..=1.0).contains(*v)) {
        return Err(Error::input(
            "discrepancy",
            format!("coordinate {v} is outside [0, 1]"),
        ));
    }
    Ok(points.len() / dims)
}

/// Warnock's formula for the L2-star discrepancy of `points` (point-major, `dims` per point):
/// `D^2 = 3^-D - (2^(1-D) / N) sum_i prod_k (1 - x_ik^2) + N^-2 sum_ij prod_k (1 - max(x_ik, x_jk))`.
pub fn l2_star(points: &[f32], dims: usize) -> Result<f64> {
    let n = check(points, dims)?;
    let p: Vec<&[f32]> = points.chunks_exact(dims).collect();
    let term1 = 3f64.powi(-(dims as i32));
    let term2: f64 = p
        .iter()
        .map(|x| {
            x.iter()
                .map(|&v| (1.0 - (v as f64).powi(2)) / 2.0)
                .product::<f64>()
        })
        .sum::<f64>()
        * 2.0
        / n as f64;
    let mut term3 = 0.0;
    for a in &p {
        for b in &p {
            term3 += a
                .iter()
                .zip(b.iter())
                .map(|(&u, &v)| 1.0 - (u.max(v) as f64))
                .product::<f64>();
        }
    }
    Ok((term1 - term2 + term3 / (n * n) as f64).max(0.0).sqrt())
}

/// Hickernell's wrap-around L2 discrepancy:
/// `WD^2 = -(4/3)^D + N^-2 sum_ij prod_k (3/2 - |x_ik - x_jk| (1 - |x_ik - x_jk|))`.
pub fn wrap_around(points: &[f32], dims: usize) -> Result<f64> {
    let n = check(points, dims)?;
    let p: Vec<&[f32]> = points.chunks_exact(dims).collect();
    let mut sum = 0.0;
    for a in &p {
        for b in &p {
            sum += a
                .iter()
                .zip(b.iter())
                .map(|(&u, &v)| {
                    let d = (u as f64 - v as f64).abs();
                    1.5 - d * (1.0 - d)
                })
                .product::<f64>();
        }
    }
    Ok((sum / (n * n) as f64 - (4.0f64 / 3.0).powi(dims as i32))
        .max(0.0)
        .sqrt())
}

/// The exact star discrepancy of a 2D set (point-major `[x, y, x, y, ...]`).
pub fn star_2d(points: &[f32]) -> Result<f64> {
    let n = check(points, 2)?;
    if n > MAX_EXACT_STAR {
        return Err(Error::input(
            "discrepancy::star_2d",
            format!("{n} points; the exact star discrepancy takes at most {MAX_EXACT_STAR}"),
        ));
    }
    let mut pts: Vec<(f64, f64)> = points
        .chunks_exact(2)
        .map(|c| (c[0] as f64, c[1] as f64))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut ys: Vec<f64> = pts.iter().map(|p| p.1).chain([1.0]).collect();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let nf = n as f64;
    let mut worst = 0.0f64;
    // Sweep x over the point coordinates (and 1); for each corner x = a, the points with
    // x < a (open) and x <= a (closed) are a prefix of the sorted list.
    let mut xs: Vec<f64> = pts.iter().map(|p| p.0).chain([1.0]).collect();
    xs.dedup();
    let mut open_ys: Vec<f64> = Vec::with_capacity(n);
    let mut k = 0; // points with x < a
    for &a in &xs {
        while k < n && pts[k].0 < a {
            let y = pts[k].1;
            let at = open_ys.partition_point(|&v| v < y);
            open_ys.insert(at, y);
            k += 1;
        }
        // points with x <= a: the open ones plus those with x == a
        let mut closed = open_ys.clone();
        let mut j = k;
        while j < n && pts[j].0 == a {
            let y = pts[j].1;
            let at = closed.partition_point(|&v| v < y);
            closed.insert(at, y);
            j += 1;
        }
        for &b in &ys {
            let vol = a * b;
            let open_count = open_ys.partition_point(|&v| v < b) as f64;
            let closed_count = closed.partition_point(|&v| v <= b) as f64;
            worst = worst
                .max(vol - open_count / nf)
                .max(closed_count / nf - vol);
        }
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random(n: usize, seed: u64) -> Vec<f32> {
        let mut h = seed;
        (0..2 * n)
            .map(|_| {
                h = crate::hash::mix64(h + 1);
                crate::float::unit_f32_from_u32(h as u32)
            })
            .collect()
    }

    #[test]
    fn warnock_matches_the_integral_of_the_local_discrepancy() {
        for n in [1usize, 5, 20] {
            let p = random(n, n as u64);
            // brute force: midpoint rule for int_{[0,1]^2} (count([0,y))/N - y1 y2)^2 dy
            let m = 400;
            let mut sum = 0.0;
            for i in 0..m {
                for j in 0..m {
                    let (y1, y2) = ((i as f64 + 0.5) / m as f64, (j as f64 + 0.5) / m as f64);
                    let count = p
                        .chunks_exact(2)
                        .filter(|c| (c[0] as f64) < y1 && (c[1] as f64) < y2)
                        .count();
                    sum += (count as f64 / n as f64 - y1 * y2).powi(2);
                }
            }
            let brute = (sum / (m * m) as f64).sqrt();
            let w = l2_star(&p, 2).unwrap();
            assert!(
                (w - brute).abs() < 2e-3,
                "n={n}: Warnock {w}, brute force {brute}"
            );
        }
    }

    #[test]
    fn wrap_around_matches_its_definition() {
        // WD^2 = sum over the projections {x}, {y}, {x, y} of the mean squared discrepancy of the
        // wrapping boxes from u to v (midpoint rule over u, v)
        for n in [1usize, 4, 9] {
            let p = random(n, 100 + n as u64);
            let m = 24;
            let f = |i: usize| (i as f64 + 0.5) / m as f64;
            let inside = |x: f64, u: f64, v: f64| {
                if u <= v {
                    u <= x && x < v
                } else {
                    x >= u || x < v
                }
            };
            let len = |u: f64, v: f64| if u <= v { v - u } else { 1.0 - u + v };
            let mut one_d = [0.0f64; 2];
            let mut two_d = 0.0;
            for a in 0..m {
                for b in 0..m {
                    let (u1, v1) = (f(a), f(b));
                    for (k, acc) in one_d.iter_mut().enumerate() {
                        let count = p
                            .chunks_exact(2)
                            .filter(|q| inside(q[k] as f64, u1, v1))
                            .count();
                        *acc += (count as f64 / n as f64 - len(u1, v1)).powi(2);
                    }
                    for c in 0..m {
                        for d in 0..m {
                            let (u2, v2) = (f(c), f(d));
                            let count = p
                                .chunks_exact(2)
                                .filter(|q| {
                                    inside(q[0] as f64, u1, v1) && inside(q[1] as f64, u2, v2)
                                })
                                .count();
                            two_d += (count as f64 / n as f64 - len(u1, v1) * len(u2, v2)).powi(2);
                        }
                    }
                }
            }
            let brute =
                ((one_d[0] + one_d[1]) / (m * m) as f64 + two_d / (m as f64).powi(4)).sqrt();
            let w = wrap_around(&p, 2).unwrap();
            assert!(
                (w - brute).abs() < 0.03 * w,
                "n={n}: formula {w}, brute force {brute}"
            );
        }
    }

    #[test]
    fn exact_star_discrepancy_matches_a_fine_search() {
        for n in [1usize, 3, 10, 40] {
            let p = random(n, 7 + n as u64);
            let exact = star_2d(&p).unwrap();
            // every box corner on a fine grid gives a lower bound; corners at the points'
            // coordinates (open and closed) reach it
            let mut lower = 0.0f64;
            let m = 300;
            for i in 1..=m {
                for j in 1..=m {
                    let (a, b) = (i as f64 / m as f64, j as f64 / m as f64);
                    let count = p
                        .chunks_exact(2)
                        .filter(|c| (c[0] as f64) < a && (c[1] as f64) < b)
                        .count();
                    lower = lower.max((count as f64 / n as f64 - a * b).abs());
                }
            }
            assert!(
                exact >= lower - 1e-12,
                "n={n}: exact {exact} below a grid value {lower}"
            );
            assert!(
                exact - lower < 2.0 / m as f64 + 1.0 / n as f64 * 0.0 + 0.02,
                "n={n}: exact {exact}, grid {lower}"
            );
        }
        // one point at the origin: the box [0, 1] holds it (closed) and [0, y) holds nothing
        assert!((star_2d(&[0.0, 0.0]).unwrap() - 1.0).abs() < 1e-12);
    }
}
