//! Mappings of one 2D draw onto the shapes a renderer samples, each consuming exactly one
//! [`get_2d`](super::PixelSampler::get_2d): what replaces `rand_distr`'s rejection samplers,
//! whose variable number of draws would shift every later dimension.
//!
//! Each mapping is measure-preserving up to the stated density, and continuous on the interior
//! of the square (so that stratified draws stay stratified on the shape). Formulas as in Pharr,
//! Jakob and Humphreys, *Physically Based Rendering*, 4th ed., appendix A.5.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, TAU};

use glam::{Vec2, Vec3};

/// A uniform point on the unit disc (Shirley and Chiu's concentric map), for `UnitDisc`.
#[inline]
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y))
    };
    r * Vec2::new(theta.cos(), theta.sin())
}

/// A uniform direction on the unit sphere, for `UnitSphere`: `z = 1 - 2u`, `phi = 2 pi v`.
#[inline]
pub fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A cosine-weighted direction on the hemisphere around `+z` (density `cos(theta) / pi`), by
/// Malley's method on the concentric disc.
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    Vec3::new(d.x, d.y, z)
}

/// Barycentric coordinates `(b0, b1)` of a uniform point in a triangle (Heitz's
/// low-distortion map; the third is `1 - b0 - b1`).
#[inline]
pub fn uniform_triangle(u: Vec2) -> Vec2 {
    if u.x < u.y {
        let b0 = u.x / 2.0;
        Vec2::new(b0, u.y - b0)
    } else {
        let b1 = u.y / 2.0;
        Vec2::new(u.x - b1, b1)
    }
}

/// Two independent standard normal values (Box-Muller), for `Normal` / `StandardNormal`.
/// `u.x` is moved away from 0 by half an `f32` step so that the logarithm stays finite.
#[inline]
pub fn normal_pair(u: Vec2) -> Vec2 {
    let r = (-2.0 * (u.x + f32::EPSILON / 4.0).min(1.0).ln()).sqrt();
    let phi = TAU * u.y;
    Vec2::new(r * phi.cos(), r * phi.sin())
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
    fn grid(n: u32) -> Vec<Vec2> {
        (0..n * n)
            .map(|k| Vec2::new((k % n) as f32 + 0.5, (k / n) as f32 + 0.5) / n as f32)
            .collect()
    }

    #[test]
    fn the_disc_map_preserves_area() {
        // mean of r^2 over the unit disc is 1/2; every quarter of the square maps to a quarter
        let pts: Vec<Vec2> = grid(256).into_iter().map(concentric_disk).collect();
        let mean_r2 = pts.iter().map(|p| p.length_squared() as f64).sum::<f64>() / pts.len() as f64;
        assert!((mean_r2 - 0.5).abs() < 1e-4, "{mean_r2}");
        assert!(pts.iter().all(|p| p.length() <= 1.0 + 1e-6));
        let inner = pts.iter().filter(|p| p.length() < 0.5).count() as f64 / pts.len() as f64;
        assert!((inner - 0.25).abs() < 2e-3, "{inner}");
    }

    #[test]
    fn sphere_and_hemisphere_have_their_densities() {
        let g = grid(256);
        let s: Vec<Vec3> = g.iter().map(|&u| uniform_sphere(u)).collect();
        let mean = s.iter().fold(Vec3::ZERO, |a, &v| a + v) / s.len() as f32;
        assert!(mean.length() < 1e-3);
        assert!(s.iter().all(|v| (v.length() - 1.0).abs() < 1e-5));
        // cosine-weighted: E[cos theta] = 2/3
        let c = g
            .iter()
            .map(|&u| cosine_hemisphere(u).z as f64)
            .sum::<f64>()
            / g.len() as f64;
        assert!((c - 2.0 / 3.0).abs() < 1e-3, "{c}");
    }

    #[test]
    fn triangle_normal_and_pick_maps() {
        let g = grid(128);
        let t: Vec<Vec2> = g.iter().map(|&u| uniform_triangle(u)).collect();
        assert!(
            t.iter()
                .all(|b| b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0)
        );
        let mean = t.iter().fold(Vec2::ZERO, |a, &b| a + b) / t.len() as f32;
        assert!((mean - Vec2::splat(1.0 / 3.0)).length() < 1e-3);
        let n: Vec<Vec2> = g.iter().map(|&u| normal_pair(u)).collect();
        let var = n.iter().map(|v| v.x as f64 * v.x as f64).sum::<f64>() / n.len() as f64;
        assert!((var - 1.0).abs() < 0.02, "{var}");
        assert!(normal_pair(Vec2::ZERO).is_finite());
        assert_eq!(pick(0.0, 3), (0, 0.0));
        assert_eq!(pick(1.0 - f32::EPSILON / 2.0, 3).0, 2);
        assert_eq!(pick(0.5, 4), (2, 0.0));
        assert_eq!(pick(0.3, 0).0, 0);
    }
}
