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

use crate::error::{Error, Result};

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
/// use strata::spectrum::error_image;
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
/// # Ok::<(), strata::Error>(())
/// ```
pub fn error_image(errors: &[f64], width: u32, height: u32) -> Result<ErrorImage> {
    let (w, h) = (width as usize, height as usize);
    if w < 2 || h < 2 || w > 1 << 14 || h > 1 << 14 || errors.len() != w * h {
        return Err(Error::input(
            "spectrum::error_image",
            format!(
                "{} values for a {width} x {height} image; allowed: width x height values, each \
                 side 2 to 16384",
                errors.len()
            ),
        ));
    }
    if let Some(i) = errors.iter().position(|e| !e.is_finite()) {
        return Err(Error::input(
            "spectrum::error_image",
            format!(
                "pixel {i} has the error {}; errors must be finite",
                errors[i]
            ),
        ));
    }
    let n = (w * h) as f64;
    let rmse = (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt();

    // the periodogram by two passes of 1D FFTs
    let mut planner = FftPlanner::new();
    let (fft_w, fft_h) = (planner.plan_fft_forward(w), planner.plan_fft_forward(h));
    let mut data: Vec<Complex64> = errors.iter().map(|&e| Complex64::new(e, 0.0)).collect();
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
    Ok(ErrorImage {
        width,
        height,
        rmse,
        blur1_rmse: blurred_rmse(errors, w, h, 1.0),
        blur2_rmse: blurred_rmse(errors, w, h, 2.0),
        lowband: if all > 0.0 { low / all } else { 0.0 },
        spectrum,
        radial,
    })
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
/// sigma, renormalized where the kernel leaves the image).
fn blurred_rmse(e: &[f64], w: usize, h: usize, sigma: f64) -> f64 {
    let r = (3.0 * sigma).ceil() as i64;
    let k: Vec<f64> = (-r..=r)
        .map(|d| (-(d * d) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let pass = |src: &[f64], along_x: bool| -> Vec<f64> {
        let mut out = vec![0.0; w * h];
        for y in 0..h {
            for x in 0..w {
                let (mut sum, mut weight) = (0.0, 0.0);
                for (j, kv) in k.iter().enumerate() {
                    let d = j as i64 - r;
                    let (sx, sy) = if along_x {
                        (x as i64 + d, y as i64)
                    } else {
                        (x as i64, y as i64 + d)
                    };
                    if sx >= 0 && sy >= 0 && (sx as usize) < w && (sy as usize) < h {
                        sum += kv * src[sy as usize * w + sx as usize];
                        weight += kv;
                    }
                }
                out[y * w + x] = sum / weight;
            }
        }
        out
    };
    let b = pass(&pass(e, true), false);
    (b.iter().map(|v| v * v).sum::<f64>() / (w * h) as f64).sqrt()
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
}
