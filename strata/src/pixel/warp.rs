//! Mappings of one 2D draw onto the shapes a renderer samples, each consuming exactly one
//! [`get_2d`](super::PixelSampler::get_2d): what replaces `rand_distr`'s rejection samplers,
//! whose variable number of draws would shift every later dimension.
//!
//! Each mapping is measure-preserving up to the stated density, and continuous on the interior
//! of the square (so that stratified draws stay stratified on the shape). Formulas as in Pharr,
//! Jakob and Humphreys, *Physically Based Rendering*, 4th ed., appendix A.5.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

/// A uniform point on the unit disc (Shirley and Chiu's concentric map), for `UnitDisc`.
#[inline]
pub fn concentric_disk(u: [f32; 2]) -> [f32; 2] {
    let o = [2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0];
    if o == [0.0, 0.0] {
        return [0.0, 0.0];
    }
    let (r, theta) = if o[0].abs() > o[1].abs() {
        (o[0], FRAC_PI_4 * (o[1] / o[0]))
    } else {
        (o[1], FRAC_PI_2 - FRAC_PI_4 * (o[0] / o[1]))
    };
    [r * theta.cos(), r * theta.sin()]
}

/// A uniform direction on the unit sphere, for `UnitSphere`: `z = 1 - 2u`, `phi = 2 pi v`.
#[inline]
pub fn uniform_sphere(u: [f32; 2]) -> [f32; 3] {
    let z = 1.0 - 2.0 * u[0];
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u[1];
    [r * phi.cos(), r * phi.sin(), z]
}

/// A cosine-weighted direction on the hemisphere around `+z` (density `cos(theta) / pi`), by
/// Malley's method on the concentric disc.
#[inline]
pub fn cosine_hemisphere(u: [f32; 2]) -> [f32; 3] {
    let [x, y] = concentric_disk(u);
    let z = (1.0 - (x * x + y * y)).max(0.0).sqrt();
    [x, y, z]
}

/// Barycentric coordinates `(b0, b1)` of a uniform point in a triangle (Heitz's
/// low-distortion map; the third is `1 - b0 - b1`).
#[inline]
pub fn uniform_triangle(u: [f32; 2]) -> [f32; 2] {
    if u[0] < u[1] {
        let b0 = u[0] / 2.0;
        [b0, u[1] - b0]
    } else {
        let b1 = u[1] / 2.0;
        [u[0] - b1, b1]
    }
}

/// Two independent standard normal values (Box-Muller), for `Normal` / `StandardNormal`.
/// `u[0]` is moved away from 0 by half an `f32` step so that the logarithm stays finite.
#[inline]
pub fn normal_pair(u: [f32; 2]) -> [f32; 2] {
    let r = (-2.0 * (u[0] + f32::EPSILON / 4.0).min(1.0).ln()).sqrt();
    let phi = TAU * u[1];
    [r * phi.cos(), r * phi.sin()]
}

/// The integer `floor(u n)` below `n` (for `random_range(0..n)`), with the value rescaled to
/// `[0, 1)` inside the chosen interval for reuse: `(k, u n - k)`.
#[inline]
pub fn pick(u: f32, n: u32) -> (u32, f32) {
    let x = u * n as f32;
    let k = (x as u32).min(n.saturating_sub(1));
    (k, (x - k as f32).clamp(0.0, 1.0 - f32::EPSILON / 2.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stratified `n x n` grid of cell centres.
    fn grid(n: u32) -> Vec<[f32; 2]> {
        (0..n * n)
            .map(|k| {
                [
                    ((k % n) as f32 + 0.5) / n as f32,
                    ((k / n) as f32 + 0.5) / n as f32,
                ]
            })
            .collect()
    }

    fn length(v: &[f32]) -> f64 {
        v.iter().map(|&x| x as f64 * x as f64).sum::<f64>().sqrt()
    }

    #[test]
    fn the_disc_map_preserves_area() {
        // mean of r^2 over the unit disc is 1/2; every quarter of the square maps to a quarter
        let pts: Vec<[f32; 2]> = grid(256).into_iter().map(concentric_disk).collect();
        let mean_r2 = pts.iter().map(|p| length(p).powi(2)).sum::<f64>() / pts.len() as f64;
        assert!((mean_r2 - 0.5).abs() < 1e-4, "{mean_r2}");
        assert!(pts.iter().all(|p| length(p) <= 1.0 + 1e-6));
        let inner = pts.iter().filter(|p| length(*p) < 0.5).count() as f64 / pts.len() as f64;
        assert!((inner - 0.25).abs() < 2e-3, "{inner}");
    }

    #[test]
    fn sphere_and_hemisphere_have_their_densities() {
        let g = grid(256);
        let s: Vec<[f32; 3]> = g.iter().map(|&u| uniform_sphere(u)).collect();
        let mean: Vec<f64> = (0..3)
            .map(|k| s.iter().map(|v| v[k] as f64).sum::<f64>() / s.len() as f64)
            .collect();
        assert!(length(&mean.iter().map(|&x| x as f32).collect::<Vec<_>>()) < 1e-3);
        assert!(s.iter().all(|v| (length(v) - 1.0).abs() < 1e-5));
        // cosine-weighted: E[cos theta] = 2/3
        let c = g
            .iter()
            .map(|&u| cosine_hemisphere(u)[2] as f64)
            .sum::<f64>()
            / g.len() as f64;
        assert!((c - 2.0 / 3.0).abs() < 1e-3, "{c}");
    }

    #[test]
    fn triangle_normal_and_pick_maps() {
        let g = grid(128);
        let t: Vec<[f32; 2]> = g.iter().map(|&u| uniform_triangle(u)).collect();
        assert!(
            t.iter()
                .all(|b| b[0] >= 0.0 && b[1] >= 0.0 && b[0] + b[1] <= 1.0)
        );
        for k in 0..2 {
            let mean = t.iter().map(|b| b[k] as f64).sum::<f64>() / t.len() as f64;
            assert!((mean - 1.0 / 3.0).abs() < 1e-3, "{mean}");
        }
        let n: Vec<[f32; 2]> = g.iter().map(|&u| normal_pair(u)).collect();
        let var = n.iter().map(|v| v[0] as f64 * v[0] as f64).sum::<f64>() / n.len() as f64;
        assert!((var - 1.0).abs() < 0.02, "{var}");
        assert!(normal_pair([0.0, 0.0]).iter().all(|v| v.is_finite()));
        assert_eq!(pick(0.0, 3), (0, 0.0));
        assert_eq!(pick(1.0 - f32::EPSILON / 2.0, 3).0, 2);
        assert_eq!(pick(0.5, 4), (2, 0.0));
        assert_eq!(pick(0.3, 0).0, 0);
    }
}
