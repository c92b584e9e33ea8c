//! Discrepancy: how far a point set's counts in boxes deviate from the boxes' volumes.
//!
//! * [`l2_star`]: the L2 norm of the local discrepancy over anchored boxes `[0, y)`, by Warnock's
//!   formula (Warnock 1972), `O(N^2 D)`. Equal to `scipy.stats.qmc.discrepancy(method="L2-star")`
//!   (which takes the square root too).
//! * [`wrap_around_squared`] (and its root [`wrap_around`]): Hickernell's wrap-around L2
//!   discrepancy (Hickernell 1998), the L2 norms of the local discrepancy over all boxes of the
//!   torus, summed over every projection onto a nonempty subset of the coordinates; invariant
//!   under toroidal shifts. The squared value equals scipy's `method="WD"`.
//! * [`centered_squared`]: Hickernell's centered L2 discrepancy, squared (boxes anchored at the
//!   corner of the unit cube nearest to each point, over every projection; invariant under
//!   reflections `x -> 1 - x`). Equal to scipy's `method="CD"`.
//! * [`mixture_squared`]: Zhou, Fang and Ning's mixture discrepancy (2013), squared (a mixture
//!   of the centered and wrap-around kernels that avoids both one's blind spots). Equal to
//!   scipy's `method="MD"`.
//! * [`net_t_value`]: the quality parameter `t` of a 2D base-2 net of `2^m` points: the
//!   smallest `t` for which every elementary interval `2^-a x 2^-(m - t - a)` holds `2^t`
//!   points (`t = 0`: a (0,m,2)-net, as pmj02 and Sobol' prefixes are).
//! * [`star_2d`]: the exact star discrepancy `sup_y |#{x in [0,y)}/N - vol([0,y))|` of a 2D set,
//!   evaluated at the critical boxes (corners at point coordinates and 1, open and closed),
//!   `O(N^2 log N)`; for sets of at most [`MAX_EXACT_STAR`] points.
//!
//! The closed forms (Zhou, Fang, Ning 2013, equations 9, 10 and 18), with `a_ik = |x_ik - 1/2|`
//! and the double sums over all ordered pairs including `i = j`:
//!
//! ```text
//! CD^2 = (13/12)^D - (2/N) sum_i prod_k (1 + a_ik/2 - a_ik^2/2)
//!        + N^-2 sum_ij prod_k (1 + a_ik/2 + a_jk/2 - |x_ik - x_jk|/2)
//! WD^2 = -(4/3)^D + N^-2 sum_ij prod_k (3/2 - |x_ik - x_jk| + |x_ik - x_jk|^2)
//! MD^2 = (19/12)^D - (2/N) sum_i prod_k (5/3 - a_ik/4 - a_ik^2/4)
//!        + N^-2 sum_ij prod_k (15/8 - a_ik/4 - a_jk/4 - 3|x_ik - x_jk|/4 + |x_ik - x_jk|^2/2)
//! ```
//!
//! Points are point-major slices of `f32` or `f64`, coordinates in `[0, 1]`.

use crate::{Error, Result};

/// The largest set [`star_2d`] accepts.
pub const MAX_EXACT_STAR: usize = 1 << 14;

fn check<T: Copy + Into<f64>>(points: &[T], dims: usize) -> Result<usize> {
    if dims == 0 || points.is_empty() || !points.len().is_multiple_of(dims) {
        return Err(Error::input(
            "analysis::discrepancy",
            format!(
                "{} values do not make points of {dims} dimensions; at least one point is needed",
                points.len()
            ),
        ));
    }
    if let Some(v) = points
        .iter()
        .map(|v| (*v).into())
        .find(|v: &f64| !(0.0..=1.0).contains(v))
    {
        return Err(Error::input(
            "analysis::discrepancy",
            format!("coordinate {v} is outside [0, 1]"),
        ));
    }
    Ok(points.len() / dims)
}

/// The points as `f64` rows.
fn rows<T: Copy + Into<f64>>(points: &[T], dims: usize) -> Vec<Vec<f64>> {
    points
        .chunks_exact(dims)
        .map(|c| c.iter().map(|v| (*v).into()).collect())
        .collect()
}

/// `sum_i prod_k single(x_ik)` and `sum_ij prod_k pair(x_ik, x_jk)` over the points (the pair
/// sum over all ordered pairs, `i = j` included, using its symmetry).
fn kernel_sums(
    p: &[Vec<f64>],
    single: impl Fn(f64) -> f64,
    pair: impl Fn(f64, f64) -> f64,
) -> (f64, f64) {
    let s1: f64 = p
        .iter()
        .map(|x| x.iter().map(|&v| single(v)).product::<f64>())
        .sum();
    let mut s2 = 0.0;
    for (i, a) in p.iter().enumerate() {
        s2 += a.iter().map(|&u| pair(u, u)).product::<f64>();
        for b in &p[i + 1..] {
            s2 += 2.0 * a.iter().zip(b).map(|(&u, &v)| pair(u, v)).product::<f64>();
        }
    }
    (s1, s2)
}

/// Warnock's formula for the L2-star discrepancy of `points` (point-major, `dims` per point):
/// `D^2 = 3^-D - (2^(1-D) / N) sum_i prod_k (1 - x_ik^2) + N^-2 sum_ij prod_k (1 - max(x_ik, x_jk))`.
pub fn l2_star<T: Copy + Into<f64>>(points: &[T], dims: u32) -> Result<f64> {
    let dims = dims as usize;
    let n = check(points, dims)? as f64;
    let (s1, s2) = kernel_sums(
        &rows(points, dims),
        |v| (1.0 - v * v) / 2.0,
        |u, v| 1.0 - u.max(v),
    );
    let d2 = 3f64.powi(-(dims as i32)) - 2.0 * s1 / n + s2 / (n * n);
    Ok(d2.max(0.0).sqrt())
}

/// Hickernell's wrap-around L2 discrepancy, squared (scipy's `WD`; see the module docs).
pub fn wrap_around_squared<T: Copy + Into<f64>>(points: &[T], dims: u32) -> Result<f64> {
    let dims = dims as usize;
    let n = check(points, dims)? as f64;
    let (_, s2) = kernel_sums(
        &rows(points, dims),
        |_| 0.0,
        |u, v| {
            let d = (u - v).abs();
            1.5 - d + d * d
        },
    );
    Ok(s2 / (n * n) - (4.0f64 / 3.0).powi(dims as i32))
}

/// Hickernell's wrap-around L2 discrepancy (the root of [`wrap_around_squared`]).
pub fn wrap_around<T: Copy + Into<f64>>(points: &[T], dims: u32) -> Result<f64> {
    Ok(wrap_around_squared(points, dims)?.max(0.0).sqrt())
}

/// Hickernell's centered L2 discrepancy, squared (scipy's `CD`; see the module docs).
pub fn centered_squared<T: Copy + Into<f64>>(points: &[T], dims: u32) -> Result<f64> {
    let dims = dims as usize;
    let n = check(points, dims)? as f64;
    let (s1, s2) = kernel_sums(
        &rows(points, dims),
        |v| {
            let a = (v - 0.5).abs();
            1.0 + a / 2.0 - a * a / 2.0
        },
        |u, v| 1.0 + (u - 0.5).abs() / 2.0 + (v - 0.5).abs() / 2.0 - (u - v).abs() / 2.0,
    );
    Ok((13.0f64 / 12.0).powi(dims as i32) - 2.0 * s1 / n + s2 / (n * n))
}

/// The mixture discrepancy of Zhou, Fang and Ning (2013), squared (scipy's `MD`; see the
/// module docs).
pub fn mixture_squared<T: Copy + Into<f64>>(points: &[T], dims: u32) -> Result<f64> {
    let dims = dims as usize;
    let n = check(points, dims)? as f64;
    let (s1, s2) = kernel_sums(
        &rows(points, dims),
        |v| {
            let a = (v - 0.5).abs();
            5.0 / 3.0 - a / 4.0 - a * a / 4.0
        },
        |u, v| {
            let d = (u - v).abs();
            15.0 / 8.0 - (u - 0.5).abs() / 4.0 - (v - 0.5).abs() / 4.0 - 0.75 * d + 0.5 * d * d
        },
    );
    Ok((19.0f64 / 12.0).powi(dims as i32) - 2.0 * s1 / n + s2 / (n * n))
}

/// The t-value of a 2D point set of `2^m` points as a base-2 `(t,m,2)`-net (see the module
/// docs); `None` when the count is not a power of two. Coordinates in `[0, 1)`.
///
/// ```
/// use strata_lab::analysis::discrepancy::net_t_value;
/// // the 2^2 points (i/4, bitreverse(i)/4): a (0,2,2)-net
/// let hammersley = [0.0, 0.0, 0.25, 0.5, 0.5, 0.25, 0.75, 0.75];
/// assert_eq!(net_t_value(&hammersley)?, Some(0));
/// // all four in the lower half: only the whole square holds them evenly
/// assert_eq!(net_t_value(&[0.1, 0.1, 0.6, 0.2, 0.3, 0.3, 0.8, 0.4])?, Some(2));
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn net_t_value<T: Copy + Into<f64>>(points: &[T]) -> Result<Option<u32>> {
    // a net's cells are half-open: [0, 1) is checked first, whatever the count (the message
    // once said [0, 1], and 1.0 passed when the count was not a power of two)
    if let Some(v) = points
        .iter()
        .map(|v| (*v).into())
        .find(|v: &f64| !(0.0..1.0).contains(v))
    {
        return Err(Error::input(
            "analysis::discrepancy::net_t_value",
            format!("coordinate {v} is outside [0, 1), where a net's cells lie"),
        ));
    }
    let n = check(points, 2)?;
    if !n.is_power_of_two() {
        return Ok(None);
    }
    let m = n.trailing_zeros();
    let p: Vec<(f64, f64)> = points
        .chunks_exact(2)
        .map(|c| (c[0].into(), c[1].into()))
        .collect();
    let mut counts = vec![0u32; n];
    let t = (0..=m).find(|&t| {
        let k = m - t; // cells of area 2^-k
        (0..=k).all(|a| {
            counts[..1 << k].fill(0);
            for &(x, y) in &p {
                let (i, j) = (
                    (x * (1u64 << a) as f64) as usize,
                    (y * (1u64 << (k - a)) as f64) as usize,
                );
                counts[(j << a) | i] += 1;
            }
            counts[..1 << k].iter().all(|&c| c == 1 << t)
        })
    });
    Ok(t)
}

/// The exact star discrepancy of a 2D set (point-major `[x, y, x, y, ...]`).
pub fn star_2d<T: Copy + Into<f64>>(points: &[T]) -> Result<f64> {
    let n = check(points, 2)?;
    if n > MAX_EXACT_STAR {
        return Err(Error::input(
            "analysis::discrepancy::star_2d",
            format!("{n} points; the exact star discrepancy takes at most {MAX_EXACT_STAR}"),
        ));
    }
    let mut pts: Vec<(f64, f64)> = points
        .chunks_exact(2)
        .map(|c| (c[0].into(), c[1].into()))
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

    /// scipy 1.17.1's `qmc.discrepancy` on three sets (CD, WD, MD squared; L2-star not),
    /// printed with 17 digits: an independent implementation of the same definitions (the
    /// digits are kept as printed, hence the allowed excess precision).
    #[allow(clippy::excessive_precision)]
    const SCIPY: [(&[f64], u32, [f64; 4]); 3] = [
        (
            &[0.1, 0.2, 0.6, 0.7, 0.3, 0.9],
            2,
            [
                0.080855555555555236,
                0.087711111111111073,
                0.10775277777777736,
                0.14736575812130395,
            ],
        ),
        (
            &[
                0.0, 0.0, 0.125, 0.5, 0.25, 0.25, 0.375, 0.75, 0.5, 0.125, 0.625, 0.625, 0.75,
                0.375, 0.875, 0.875,
            ],
            2,
            [
                0.015255398220485938,
                0.0098809136284723209,
                0.015046013726127239,
                0.12351274517427789,
            ],
        ),
        (
            &[0.1, 0.2, 0.3, 0.6, 0.7, 0.05, 0.3, 0.9, 0.8],
            3,
            [
                0.14175853703703623,
                0.19470046296296362,
                0.27176414583333131,
                0.16255403659957149,
            ],
        ),
    ];

    #[test]
    fn the_discrepancies_equal_scipys() {
        for (points, dims, [cd, wd, md, l2]) in SCIPY {
            let ours = [
                centered_squared(points, dims).unwrap(),
                wrap_around_squared(points, dims).unwrap(),
                mixture_squared(points, dims).unwrap(),
                l2_star(points, dims).unwrap(),
            ];
            for (name, (a, b)) in ["CD", "WD", "MD", "L2-star"]
                .iter()
                .zip(ours.iter().zip([cd, wd, md, l2]))
            {
                assert!((a - b).abs() <= 1e-12 * b, "{name}: ours {a}, scipy {b}");
            }
        }
        // and the exact rationals of the first set (to the rounding of terms near (19/12)^2)
        let x3 = SCIPY[0].0;
        let close = |a: f64, b: f64| (a - b).abs() < 1e-14;
        assert!(close(centered_squared(x3, 2).unwrap(), 7277.0 / 90000.0));
        assert!(close(wrap_around_squared(x3, 2).unwrap(), 3947.0 / 45000.0));
        assert!(close(mixture_squared(x3, 2).unwrap(), 38791.0 / 360000.0));
        assert!(close(l2_star(x3, 2).unwrap().powi(2), 1303.0 / 60000.0));
    }

    #[test]
    fn t_values_of_nets_and_of_random_sets() {
        use strata::Sampler;
        // Sobol' prefixes are (0,m,2)-nets; two interleaved copies of one are a (1,m+1,2)-net
        let mut s = strata::samplers::Sobol::new(strata::Seed(3));
        let pts: Vec<f64> = (0..256)
            .flat_map(|_| {
                let p = s.next_sample();
                [p[0] as f64, p[1] as f64]
            })
            .collect();
        assert_eq!(net_t_value(&pts).unwrap(), Some(0));
        let doubled: Vec<f64> = pts.iter().chain(&pts).copied().collect();
        assert_eq!(net_t_value(&doubled).unwrap(), Some(1));
        // a random set of 256 is far from a net; 255 points are not a power of two
        let r: Vec<f64> = random(256, 9).iter().map(|&v| v as f64).collect();
        assert!(net_t_value(&r).unwrap().unwrap() >= 4);
        assert_eq!(net_t_value(&r[..510]).unwrap(), None);
    }

    #[test]
    fn centered_discrepancy_ignores_reflections_and_wrap_around_ignores_shifts() {
        let p: Vec<f64> = random(30, 3).iter().map(|&v| v as f64).collect();
        let reflected: Vec<f64> = p.iter().map(|v| 1.0 - v).collect();
        let shifted: Vec<f64> = p.iter().map(|v| (v + 0.37) % 1.0).collect();
        let (a, b) = (
            centered_squared(&p, 2).unwrap(),
            centered_squared(&reflected, 2).unwrap(),
        );
        assert!((a - b).abs() < 1e-12 * a);
        let (a, b) = (
            wrap_around_squared(&p, 2).unwrap(),
            wrap_around_squared(&shifted, 2).unwrap(),
        );
        assert!((a - b).abs() < 1e-12 * a);
        // and the centered one is not shift-invariant (the test can tell them apart)
        let c = centered_squared(&shifted, 2).unwrap();
        assert!((c - centered_squared(&p, 2).unwrap()).abs() > 1e-4);
    }

    fn random(n: usize, seed: u64) -> Vec<f32> {
        let mut h = seed;
        (0..2 * n)
            .map(|_| {
                h = strata::hash::mix64(h + 1);
                strata::float::unit_f32_from_u32(h as u32)
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
