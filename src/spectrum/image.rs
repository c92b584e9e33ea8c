//! The error image of a render, seen the way screen-space samplers are judged: how much of its
//! power sits at low spatial frequencies, and how much of it survives a blur.
//!
//! Samplers that order their sequences across pixels (Z-ordered Sobol': Ahmed and Wonka,
//! "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering
//! of Pixels", SIGGRAPH Asia 2020) keep each pixel's error but push the error *image* towards
//! high frequencies, which the eye and any denoiser remove. Belcour and Heitz (2021) judge them
//! by the error left after a Gaussian blur. For an error image `e` (signed, per pixel):
//!
//! * the **periodogram** `P(u, v) = |sum_xy e(x, y) exp(-2 pi i (u x / W + v y / H))|^2 / (W H)`
//!   at the integer frequencies, i.e. `u / W` and `v / H` cycles per pixel (white error: flat,
//!   its mean the error's mean square);
//! * the **low-band share**: the power at `0 < |f| < 1/8` cycle per pixel over the power at
//!   every `f != 0` (the mean error, at `f = 0`, is left out: it is bias, not distribution).
//!   The disc covers `pi / 64 = 4.9%` of the frequencies, so white error puts about 5% there;
//!   blue error much less;
//! * the **RMSE after a Gaussian blur** of standard deviation 1 and 2 pixels (kernel cut at 3
//!   sigma and renormalized at the image border).

use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

use crate::{Error, Result};

/// The radius of the low band, in cycles per pixel.
pub const LOW_BAND: f64 = 1.0 / 8.0;

/// The measures of an error image (see [`error_image`]).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ErrorImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The root mean square of the error.
    pub rmse: f64,
    /// The RMSE after a Gaussian blur of sigma = 1 pixel.
    pub blur1_rmse: f64,
    /// The RMSE after a Gaussian blur of sigma = 2 pixels.
    pub blur2_rmse: f64,
    /// The share of the error power (DC excluded) at `|f| < 1/8` cycle per pixel.
    pub lowband: f64,
    /// The periodogram, row-major, DC at `(width / 2, height / 2)`.
    pub spectrum: Vec<f64>,
    /// The radial mean: `(frequency in cycles per pixel, mean power)` for rings of width
    /// `1 / min(width, height)`, DC excluded.
    pub radial: Vec<(f64, f64)>,
}

/// Measures the error image `errors` (row-major, `width x height`, signed errors).
///
/// ```
/// use strata_lab::spectrum::error_image;
/// // white error: about 5% of its power in the low band, and a blur averages it away
/// let (w, h) = (64, 64);
/// let mut x = 1u64;
/// let e: Vec<f64> = (0..w * h)
///     .map(|_| {
///         x = strata::hash::mix64(x);
///         (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
///     })
///     .collect();
/// let m = error_image(&e, w as u32, h as u32)?;
/// assert!((m.lowband - 0.049).abs() < 0.02);
/// assert!(m.blur2_rmse < 0.3 * m.rmse);
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn error_image(errors: &[f64], width: u32, height: u32) -> Result<ErrorImage> {
    check(errors, width, height, "spectrum::error_image")?;
    Ok(measure(errors, None, width, height))
}

/// [`error_image`] over the pixels where `keep` is true only, for renders whose error some
/// pixels would dominate or hide (those that see an emitter directly: their error is the
/// emitter's edge, not the sampler's). `keep` is row-major like `errors`.
///
/// * `rmse`: the root mean square over the kept pixels;
/// * the blurred RMSEs: a normalized convolution, `G * (e k) / G * k` (the Gaussian `G` of
///   [`error_image`], `k` the mask), at the kept pixels, so a dropped pixel lends no weight;
/// * the periodogram: of the kept errors less their mean, with the dropped pixels at zero,
///   over the kept count (white error over the kept pixels: flat at its variance). Zeroing
///   the holes multiplies the error by the mask, which spreads each frequency of the error by
///   the mask's own spectrum: for a mask that drops a share `q` of the pixels in compact
///   regions, about `q` of the power moves, mostly to frequencies near the original ones.
///
/// With every pixel kept this gives [`error_image`]'s figures (to rounding).
///
/// ```
/// use strata_lab::spectrum::{error_image, error_image_masked};
/// // a smooth error with a block of huge values: masked, the block changes nothing
/// let (w, h) = (32u32, 32u32);
/// let mut e: Vec<f64> = (0..w * h).map(|i| ((i % w) as f64 * 0.7).sin()).collect();
/// let keep: Vec<bool> = (0..w * h).map(|i| i % w >= 8 || i / w >= 8).collect();
/// let a = error_image_masked(&e, &keep, w, h)?;
/// for i in 0..(w * h) as usize {
///     if !keep[i] {
///         e[i] = 1e6;
///     }
/// }
/// let b = error_image_masked(&e, &keep, w, h)?;
/// assert_eq!(a, b);
/// assert!(error_image(&e, w, h)?.rmse > 1e4);
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn error_image_masked(
    errors: &[f64],
    keep: &[bool],
    width: u32,
    height: u32,
) -> Result<ErrorImage> {
    const WHERE: &str = "spectrum::error_image_masked";
    check(errors, width, height, WHERE)?;
    if keep.len() != errors.len() {
        return Err(Error::input(
            WHERE,
            format!(
                "a mask of {} pixels for {} errors; allowed: one flag per pixel",
                keep.len(),
                errors.len()
            ),
        ));
    }
    if !keep.contains(&true) {
        return Err(Error::input(
            WHERE,
            "the mask keeps no pixel; allowed: a mask that keeps at least one",
        ));
    }
    Ok(measure(errors, Some(keep), width, height))
}

/// The checks of [`error_image`]: the size, the sides and finite errors.
fn check(errors: &[f64], width: u32, height: u32, at: &'static str) -> Result<()> {
    let (w, h) = (width as usize, height as usize);
    if w < 2 || h < 2 || w > 1 << 14 || h > 1 << 14 || errors.len() != w * h {
        return Err(Error::input(
            at,
            format!(
                "{} values for a {width} x {height} image; allowed: width x height values, each \
                 side 2 to 16384",
                errors.len()
            ),
        ));
    }
    if let Some(i) = errors.iter().position(|e| !e.is_finite()) {
        return Err(Error::input(
            at,
            format!(
                "pixel {i} has the error {}; errors must be finite",
                errors[i]
            ),
        ));
    }
    Ok(())
}

/// The measures of a checked error image, over the pixels `keep` marks (all without one).
fn measure(errors: &[f64], keep: Option<&[bool]>, width: u32, height: u32) -> ErrorImage {
    let (w, h) = (width as usize, height as usize);
    let kept = |i: usize| keep.is_none_or(|k| k[i]);
    let n = keep.map_or(w * h, |k| k.iter().filter(|&&k| k).count()) as f64;
    let rmse = (errors
        .iter()
        .enumerate()
        .filter(|&(i, _)| kept(i))
        .map(|(_, e)| e * e)
        .sum::<f64>()
        / n)
        .sqrt();
    // with a mask: the kept errors less their mean, the dropped ones at zero
    let mean = match keep {
        None => 0.0,
        Some(_) => {
            (0..w * h)
                .filter(|&i| kept(i))
                .map(|i| errors[i])
                .sum::<f64>()
                / n
        }
    };

    // the periodogram by two passes of 1D FFTs
    let mut planner = FftPlanner::new();
    let (fft_w, fft_h) = (planner.plan_fft_forward(w), planner.plan_fft_forward(h));
    let mut data: Vec<Complex64> = (0..w * h)
        .map(|i| Complex64::new(if kept(i) { errors[i] - mean } else { 0.0 }, 0.0))
        .collect();
    for row in data.chunks_exact_mut(w) {
        fft_w.process(row);
    }
    let mut column = vec![Complex64::new(0.0, 0.0); h];
    for x in 0..w {
        for (y, c) in column.iter_mut().enumerate() {
            *c = data[y * w + x];
        }
        fft_h.process(&mut column);
        for (y, c) in column.iter().enumerate() {
            data[y * w + x] = *c;
        }
    }
    // centre DC and measure
    let mut spectrum = vec![0.0; w * h];
    let (mut low, mut all) = (0.0, 0.0);
    let bins = w.min(h) / 2;
    let mut ring = vec![(0.0f64, 0u32); bins + 1];
    for v in 0..h {
        for u in 0..w {
            let p = data[v * w + u].norm_sqr() / n;
            let (su, sv) = (signed(u, w), signed(v, h));
            spectrum[((sv + (h / 2) as i64) as usize) * w + (su + (w / 2) as i64) as usize] = p;
            if su == 0 && sv == 0 {
                continue;
            }
            let f = ((su as f64 / w as f64).powi(2) + (sv as f64 / h as f64).powi(2)).sqrt();
            all += p;
            if f < LOW_BAND {
                low += p;
            }
            let b = (f * w.min(h) as f64).round() as usize;
            if b >= 1 && b <= bins {
                ring[b].0 += p;
                ring[b].1 += 1;
            }
        }
    }
    let radial = ring
        .iter()
        .enumerate()
        .skip(1)
        .filter(|(_, r)| r.1 > 0)
        .map(|(b, r)| (b as f64 / w.min(h) as f64, r.0 / r.1 as f64))
        .collect();
    ErrorImage {
        width,
        height,
        rmse,
        blur1_rmse: blurred_rmse(errors, keep, w, h, 1.0),
        blur2_rmse: blurred_rmse(errors, keep, w, h, 2.0),
        lowband: if all > 0.0 { low / all } else { 0.0 },
        spectrum,
        radial,
    }
}

/// Frequency index `k` of an `n`-point FFT as a signed frequency, in `[-n/2, n/2)` (`n`
/// even) or `[-(n-1)/2, (n-1)/2]` (odd): `s + n/2` indexes the centred spectrum.
fn signed(k: usize, n: usize) -> i64 {
    if k < n.div_ceil(2) {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// The RMSE of `e` after a separable Gaussian blur of standard deviation `sigma` (cut at 3
/// sigma, renormalized where the kernel leaves the image); with a mask, the normalized
/// convolution `G * (e k) / G * k` at the kept pixels, and the RMSE over them.
fn blurred_rmse(e: &[f64], keep: Option<&[bool]>, w: usize, h: usize, sigma: f64) -> f64 {
    let r = (3.0 * sigma).ceil() as i64;
    let k: Vec<f64> = (-r..=r)
        .map(|d| (-(d * d) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    // one pass along x or y: the kernel's sum over `src` and the weight it found, where
    // `weight` is the mask (or 1 inside the image)
    let pass = |src: &[f64], weight: &[f64], along_x: bool| -> (Vec<f64>, Vec<f64>) {
        let (mut out, mut out_w) = (vec![0.0; w * h], vec![0.0; w * h]);
        for y in 0..h {
            for x in 0..w {
                let (mut sum, mut wsum) = (0.0, 0.0);
                for (j, kv) in k.iter().enumerate() {
                    let d = j as i64 - r;
                    let (sx, sy) = if along_x {
                        (x as i64 + d, y as i64)
                    } else {
                        (x as i64, y as i64 + d)
                    };
                    if sx >= 0 && sy >= 0 && (sx as usize) < w && (sy as usize) < h {
                        let at = sy as usize * w + sx as usize;
                        sum += kv * src[at];
                        wsum += kv * weight[at];
                    }
                }
                out[y * w + x] = sum;
                out_w[y * w + x] = wsum;
            }
        }
        (out, out_w)
    };
    match keep {
        None => {
            // (the weight of a pass is the kernel inside the image: renormalize after each)
            let ones = vec![1.0; w * h];
            let norm = |(s, wt): (Vec<f64>, Vec<f64>)| -> Vec<f64> {
                s.iter().zip(&wt).map(|(s, wt)| s / wt).collect()
            };
            let b = norm(pass(&norm(pass(e, &ones, true)), &ones, false));
            (b.iter().map(|v| v * v).sum::<f64>() / (w * h) as f64).sqrt()
        }
        Some(keep) => {
            let m: Vec<f64> = keep.iter().map(|&k| if k { 1.0 } else { 0.0 }).collect();
            let em: Vec<f64> = e.iter().zip(&m).map(|(e, m)| e * m).collect();
            let (sx, mx) = pass(&em, &m, true);
            let (num, _) = pass(&sx, &mx, false);
            let (den, _) = pass(&mx, &mx, false);
            let (mut sum, mut count) = (0.0, 0usize);
            for i in (0..w * h).filter(|&i| keep[i]) {
                let v = num[i] / den[i];
                sum += v * v;
                count += 1;
            }
            (sum / count as f64).sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_periodogram_matches_a_direct_sum() {
        let (w, h) = (6usize, 5usize);
        let e: Vec<f64> = (0..w * h).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let m = error_image(&e, w as u32, h as u32).unwrap();
        for v in -2i64..=2 {
            for u in -3i64..=2 {
                let (mut re, mut im) = (0.0, 0.0);
                for y in 0..h {
                    for x in 0..w {
                        let a = -2.0
                            * std::f64::consts::PI
                            * (u as f64 * x as f64 / w as f64 + v as f64 * y as f64 / h as f64);
                        re += e[y * w + x] * a.cos();
                        im += e[y * w + x] * a.sin();
                    }
                }
                let direct = (re * re + im * im) / (w * h) as f64;
                let at =
                    m.spectrum[((v + (h / 2) as i64) as usize) * w + (u + (w / 2) as i64) as usize];
                assert!(
                    (at - direct).abs() < 1e-9 * (1.0 + direct),
                    "({u}, {v}): {at} vs {direct}"
                );
            }
        }
        // Parseval: the mean of P is the mean square
        let mean_p = m.spectrum.iter().sum::<f64>() / (w * h) as f64;
        assert!((mean_p - m.rmse * m.rmse).abs() < 1e-9);
    }

    #[test]
    fn smooth_error_sits_in_the_low_band_and_checkerboards_do_not() {
        let (w, h) = (32usize, 32usize);
        let smooth: Vec<f64> = (0..w * h)
            .map(|i| ((i % w) as f64 * std::f64::consts::TAU / w as f64).sin())
            .collect();
        let m = error_image(&smooth, w as u32, h as u32).unwrap();
        assert!(m.lowband > 0.99, "{}", m.lowband);
        assert!(m.blur2_rmse > 0.6 * m.rmse);
        let checker: Vec<f64> = (0..w * h)
            .map(|i| {
                if ((i % w) + i / w) % 2 == 0 {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        let m = error_image(&checker, w as u32, h as u32).unwrap();
        assert!(m.lowband < 1e-12);
        assert!(m.blur1_rmse < 0.05);
        assert!(error_image(&checker, 31, 32).is_err());
        assert!(error_image(&[f64::NAN; 4], 2, 2).is_err());
    }

    /// White noise from a seeded hash, in [-0.5, 0.5).
    fn white(n: usize, seed: u64) -> Vec<f64> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = strata::hash::mix64(x);
                (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    #[test]
    fn a_mask_that_keeps_every_pixel_changes_nothing() {
        let (w, h) = (24usize, 20usize);
        let e = white(w * h, 5);
        let a = error_image(&e, w as u32, h as u32).unwrap();
        let b = error_image_masked(&e, &vec![true; w * h], w as u32, h as u32).unwrap();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs());
        assert!(close(a.rmse, b.rmse) && close(a.blur1_rmse, b.blur1_rmse));
        assert!(close(a.blur2_rmse, b.blur2_rmse) && close(a.lowband, b.lowband));
        // (the masked periodogram takes the mean out; only DC differs)
        for (i, (p, q)) in a.spectrum.iter().zip(&b.spectrum).enumerate() {
            if i != (h / 2) * w + w / 2 {
                assert!(close(*p, *q), "{i}: {p} vs {q}");
            }
        }
    }

    #[test]
    fn dropped_pixels_lend_nothing_to_any_measure() {
        let (w, h) = (32usize, 32usize);
        // a disc of 'emitter' pixels, dropped
        let keep: Vec<bool> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 - 10.5, (i / w) as f64 - 12.5);
                x * x + y * y > 25.0
            })
            .collect();
        let dropped = keep.iter().filter(|&&k| !k).count();
        assert!(dropped > 60 && dropped < 100);
        for seed in 0..8 {
            let mut e = white(w * h, seed + 1);
            let a = error_image_masked(&e, &keep, w as u32, h as u32).unwrap();
            for (e, k) in e.iter_mut().zip(&keep) {
                if !k {
                    *e = 1e3 * (*e + 1.0);
                }
            }
            let b = error_image_masked(&e, &keep, w as u32, h as u32).unwrap();
            assert_eq!(a, b, "seed {seed}");
            // the kept pixels' own figures: the RMSE of the kept values, white in the band
            let kept: Vec<f64> = (0..w * h).filter(|&i| keep[i]).map(|i| e[i]).collect();
            let rms = (kept.iter().map(|v| v * v).sum::<f64>() / kept.len() as f64).sqrt();
            assert!((a.rmse - rms).abs() < 1e-12, "seed {seed}");
            assert!(
                a.lowband > 0.02 && a.lowband < 0.09,
                "seed {seed}: {}",
                a.lowband
            );
            // a blur of white error divides its RMSE by about sqrt(4 pi sigma^2) = 3.5 at 1
            assert!(a.blur1_rmse < 0.45 * a.rmse, "seed {seed}");
            // unmasked, the dropped block dominates every figure
            let u = error_image(&e, w as u32, h as u32).unwrap();
            assert!(u.rmse > 50.0 * a.rmse && u.lowband > 0.3, "seed {seed}");
        }
    }

    #[test]
    fn blue_error_stays_blue_around_a_hole() {
        let (w, h) = (32usize, 32usize);
        let checker: Vec<f64> = (0..w * h)
            .map(|i| {
                if ((i % w) + i / w) % 2 == 0 {
                    1.0
                } else {
                    -1.0
                }
            })
            .collect();
        let keep: Vec<bool> = (0..w * h)
            .map(|i| !((8..14).contains(&(i % w)) && (4..12).contains(&(i / w))))
            .collect();
        let m = error_image_masked(&checker, &keep, w as u32, h as u32).unwrap();
        // the hole's spectrum moves to the checkerboard's frequency, far from the low band
        assert!(m.lowband < 0.01, "{}", m.lowband);
        assert!(m.blur1_rmse < 0.1, "{}", m.blur1_rmse);
        // a bias (the mean error) is left out of the spectrum, hole or not
        let biased: Vec<f64> = checker.iter().map(|e| e + 0.5).collect();
        let b = error_image_masked(&biased, &keep, w as u32, h as u32).unwrap();
        assert!((b.lowband - m.lowband).abs() < 1e-12, "{}", b.lowband);
        assert!(error_image_masked(&checker, &keep[1..], 32, 32).is_err());
        assert!(error_image_masked(&checker, &vec![false; w * h], 32, 32).is_err());
        assert!(error_image_masked(&checker[1..], &keep[1..], 32, 32).is_err());
    }

    #[test]
    fn the_masked_blur_matches_a_direct_sum() {
        let (w, h) = (10usize, 9usize);
        let e = white(w * h, 11);
        let keep: Vec<bool> = white(w * h, 12).iter().map(|v| *v > -0.3).collect();
        let m = error_image_masked(&e, &keep, w as u32, h as u32).unwrap();
        for (sigma, got) in [(1.0f64, m.blur1_rmse), (2.0, m.blur2_rmse)] {
            let r = (3.0 * sigma).ceil() as i64;
            let g = |d: i64| (-(d * d) as f64 / (2.0 * sigma * sigma)).exp();
            let (mut sum, mut count) = (0.0, 0.0);
            for p in (0..w * h).filter(|&p| keep[p]) {
                let (px, py) = ((p % w) as i64, (p / w) as i64);
                let (mut num, mut den) = (0.0, 0.0);
                for q in (0..w * h).filter(|&q| keep[q]) {
                    let (dx, dy) = ((q % w) as i64 - px, (q / w) as i64 - py);
                    if dx.abs() <= r && dy.abs() <= r {
                        num += g(dx) * g(dy) * e[q];
                        den += g(dx) * g(dy);
                    }
                }
                sum += (num / den) * (num / den);
                count += 1.0;
            }
            let direct = (sum / count).sqrt();
            assert!(
                (got - direct).abs() < 1e-12,
                "sigma {sigma}: {got} vs {direct}"
            );
        }
    }
}
