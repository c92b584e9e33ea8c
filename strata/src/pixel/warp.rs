//! Mappings of one 2D draw onto the shapes a renderer samples, each consuming exactly one
//! [`get_2d`](super::PixelSampler::get_2d): what replaces `rand_distr`'s rejection samplers,
//! whose variable number of draws would shift every later dimension.
//!
//! Each mapping is measure-preserving up to the stated density, and continuous on the interior
//! of the square (so that stratified draws stay stratified on the shape). Formulas as in Pharr,
//! Jakob and Humphreys, *Physically Based Rendering*, 4th ed., appendix A.5.

use crate::float::ONE_MINUS_EPSILON;
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

/// The index `floor(u n)` among `n` items (for `random_range(0..n)`: a light, a triangle),
/// computed exactly, and the position inside the chosen interval rescaled to `[0, 1)` for
/// reuse: `(k, u n - k)`. `u` outside `[0, 1)` (or NaN) is taken as its nearest end; `n = 0`
/// gives index 0.
///
/// **At most `2^24` items.** A draw's `f32` carries 24 bits (every value of the sampler is a
/// multiple of `2^-24`), so it names at most `2^24` intervals: up to `n = 2^24` each index has
/// the probability `floor` or `ceil` of `2^24 / n` over `2^24`; past it some indices can never be
/// picked. For more items use [`pick_u32`] with the draw's 32-bit value
/// ([`PixelSampler::sample_2d_u32`](super::PixelSampler::sample_2d_u32)).
#[inline]
pub fn pick(u: f32, n: u32) -> (u32, f32) {
    // u = m 2^-s exactly (m < 2^24, s >= 24 below 1), so u n = (m n) 2^-s, m n < 2^56
    let u = if u >= 1.0 { ONE_MINUS_EPSILON } else { u };
    if u.is_nan() || u <= 0.0 || n == 0 {
        return (0, 0.0);
    }
    let bits = u.to_bits();
    let e = (bits >> 23) as i32;
    let (m, s) = if e == 0 {
        (bits & 0x7f_ffff, 149)
    } else {
        ((bits & 0x7f_ffff) | 0x80_0000, 150 - e)
    };
    let p = m as u64 * n as u64;
    if s >= 64 {
        // u n < 2^56 2^-64 < 1
        return (0, crate::float::unit_f32_from_f64(p as f64 * pow2_neg(s)));
    }
    let k = (p >> s) as u32;
    let rest = p & ((1u64 << s) - 1);
    // the remainder as a fraction, rounded down to an f32 below 1
    let f = crate::float::unit_f32_from_f64(rest as f64 * pow2_neg(s));
    (k, f)
}

/// `2^-s` for `0 <= s <= 1022`, exactly.
#[inline]
fn pow2_neg(s: i32) -> f64 {
    f64::from_bits(((1023 - s) as u64) << 52)
}

/// [`pick`] from a draw's 32-bit value `v` (the fraction `v / 2^32`): the index
/// `floor(v n / 2^32)` among up to `2^32 - 1` items, each of them the probability `floor` or
/// `ceil` of `2^32 / n` over `2^32` (Lemire's multiply-shift), and the position inside the chosen
/// interval rescaled to `[0, 1)` (24 bits). `n = 0` gives index 0.
#[inline]
pub fn pick_u32(v: u32, n: u32) -> (u32, f32) {
    let p = v as u64 * n as u64;
    ((p >> 32) as u32, crate::float::unit_f32_from_u32(p as u32))
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
        assert_eq!(pick(f32::NAN, 7), (0, 0.0));
        assert_eq!(pick(-1.0, 7), (0, 0.0));
        assert_eq!(pick(1.0, 7).0, 6);
        assert_eq!(pick(2.0, u32::MAX), pick(ONE_MINUS_EPSILON, u32::MAX));
    }

    #[test]
    fn pick_is_the_exact_floor() {
        // against u n computed exactly in u128 (u = (u 2^150) 2^-150, an integer below 2^150),
        // at f32 values of every exponent and counts up to 2^32 - 1
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for t in 0..200_000 {
            let r = next();
            let u = match t % 4 {
                0 => f32::from_bits((r as u32) % 0x3f80_0000), // any f32 in [0, 1)
                1 => (r >> 40) as f32 / 16_777_216.0,          // a sampler's value
                _ => 1.0 - f32::EPSILON / 2.0 * (1 + r % 8) as f32,
            };
            let n = match t % 3 {
                0 => (r >> 32) as u32,
                1 => (r >> 32) as u32 >> (r % 32),
                _ => u32::MAX - (r % 5) as u32,
            };
            let (k, f) = pick(u, n);
            assert!((0.0..1.0).contains(&f), "{u:e} {n}: {f}");
            if u < 2f32.powi(-72) {
                // u n < 2^-40: index 0, the rest u n itself
                let rest = u as f64 * n as f64;
                assert_eq!(k, 0);
                assert!(
                    (f as f64 - rest).abs() <= rest * 1.2e-7 + f32::MIN_POSITIVE as f64,
                    "{u:e} {n}: {f} {rest}"
                );
                continue;
            }
            // u 2^96 is an integer below 2^96 (u's last bit is at 2^-95 or above), u n 2^96
            // one below 2^128
            let scaled = (u as f64 * 2f64.powi(96)) as u128;
            let exact = (scaled * n as u128) >> 96;
            assert_eq!(
                k as u128,
                exact.min(n.saturating_sub(1) as u128),
                "{u:e} {n}"
            );
            // the remainder, to f32 precision
            let rest = (scaled * n as u128 - (exact << 96)) as f64 * 2f64.powi(-96);
            assert!(
                (f as f64 - rest).abs() <= rest * 1.2e-7 + 1e-38,
                "{u:e} {n}: {f} {rest}"
            );
        }
    }

    #[test]
    fn pick_gives_every_index_its_share_up_to_two_to_the_24() {
        // the 2^24 values a sampler's f32 can take, over n items: each index floor or ceil of
        // 2^24 / n times (rounding u n in f32 left a quarter of them out at 2^24 - 1)
        for n in [3u32, 1_000_003, 3 << 22, (1 << 24) - 1, 1 << 24] {
            let mut hits = vec![0u32; n as usize];
            for j in 0..1u32 << 24 {
                let k = pick(j as f32 / 16_777_216.0, n).0;
                hits[k as usize] += 1;
            }
            let lo = ((1u64 << 24) / n as u64) as u32;
            let hi = lo + u32::from(!(1u64 << 24).is_multiple_of(n as u64));
            let bad = hits.iter().position(|&h| h < lo || h > hi);
            assert!(
                bad.is_none(),
                "n {n}: index {bad:?} picked {:?} times",
                bad.map(|b| hits[b])
            );
        }
    }

    #[test]
    fn pick_u32_reaches_every_index_in_intervals_of_equal_length() {
        // for n up to 2^32 - 1: the first value of each index's interval is ceil(k 2^32 / n), the
        // value before it picks k - 1; so every index is picked, by floor or ceil(2^32 / n) values
        for n in [20_000_000u32, 3 << 23, 100_000_000, u32::MAX, 7, 1] {
            for k in [0u32, 1, n / 3, n / 2 + 1, n - 1]
                .into_iter()
                .filter(|&k| k < n)
            {
                let first = ((k as u64) << 32).div_ceil(n as u64) as u32;
                assert_eq!(pick_u32(first, n).0, k, "n {n} k {k}");
                if k > 0 {
                    assert_eq!(pick_u32(first - 1, n).0, k - 1, "n {n} k {k}");
                }
            }
            assert_eq!(pick_u32(u32::MAX, n).0, n - 1);
        }
        assert_eq!(pick_u32(u32::MAX, 0).0, 0);
        let (k, f) = pick_u32(1 << 31, 3);
        assert_eq!(k, 1);
        assert!((f - 0.5).abs() < 1e-6);
    }
}
