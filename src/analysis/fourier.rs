//! The Fourier view made operational: the variance of a Monte Carlo estimate predicted from the
//! integrand's Fourier coefficients and the pattern's expected power spectrum.
//!
//! For a pattern whose expected spectrum is shift-invariant (Subr and Kautz 2013; Pilleboue et
//! al. 2015), the estimator `(1/N) sum f(x_k)` on the unit torus has
//!
//! ```text
//! Var = (1/N) sum_{w != 0} |f^(w)|^2 E[P(w)]
//! ```
//!
//! with `P` the periodogram (white noise: 1). Inside the computed grid `|u|, |v| <= K/2` we use
//! the measured expected spectrum; beyond it, white noise (`P = 1`), which makes the formula
//! `(1/N) (sigma^2 + sum_{grid, w != 0} |f^(w)|^2 (E[P(w)] - 1))` with `sigma^2 = int f^2 -
//! (int f)^2`. It is **exact for random sampling** (`E[P] = 1` everywhere) and an
//! **approximation** for stratified patterns, whose sets are not shift-invariant (a jittered set
//! shifted is no longer aligned to its grid): there it neglects the cross terms between
//! frequencies, and the truncation at `K/2` assumes white noise beyond.
//!
//! The integrand's coefficients are computed numerically: cell averages on an `M x M` grid
//! (`M = 8K` between 512 and 2048, `4 x 4` sub-samples per cell), a 2D FFT, and the division
//! by the cell's box filter `sinc(u/M) sinc(v/M)` (within 1% of closed forms at low
//! frequencies, a few % higher up, where the discontinuities of the periodized integrands
//! alias).

use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

use super::Integrand;
use crate::spectrum::Spectrum;

/// `|f^(w)|^2` on the `(K+1)^2` grid `|u|, |v| <= K/2` (row-major, `v` then `u` ascending) of a
/// 2D integrand.
pub fn integrand_power(f: Integrand, resolution: u32) -> Vec<f64> {
    let k = resolution as usize;
    let m = (8 * k).clamp(512, 2048).next_power_of_two();
    let sub = 4;
    let mut grid = vec![Complex64::new(0.0, 0.0); m * m];
    for row in 0..m {
        for col in 0..m {
            let mut sum = 0.0;
            for a in 0..sub {
                for b in 0..sub {
                    let x = ((col * sub + b) as f64 + 0.5) / (m * sub) as f64;
                    let y = ((row * sub + a) as f64 + 0.5) / (m * sub) as f64;
                    sum += f.eval(&[x as f32, y as f32]);
                }
            }
            grid[row * m + col] = Complex64::new(sum / (sub * sub) as f64, 0.0);
        }
    }
    let fft = FftPlanner::new().plan_fft_forward(m);
    for r in grid.chunks_exact_mut(m) {
        fft.process(r);
    }
    let mut column = vec![Complex64::new(0.0, 0.0); m];
    for c in 0..m {
        for r in 0..m {
            column[r] = grid[r * m + c];
        }
        fft.process(&mut column);
        for r in 0..m {
            grid[r * m + c] = column[r];
        }
    }
    let half = (k / 2) as i64;
    let sinc = |t: f64| {
        if t == 0.0 {
            1.0
        } else {
            (std::f64::consts::PI * t).sin() / (std::f64::consts::PI * t)
        }
    };
    let mut out = Vec::with_capacity((k + 1) * (k + 1));
    for v in -half..=half {
        for u in -half..=half {
            let idx = |f: i64| f.rem_euclid(m as i64) as usize;
            let c = grid[idx(v) * m + idx(u)] / (m * m) as f64;
            let filter = sinc(u as f64 / m as f64) * sinc(v as f64 / m as f64);
            out.push(c.norm_sqr() / (filter * filter));
        }
    }
    out
}

/// The variance predicted for `n`-point estimates of `f` by a pattern with expected spectrum
/// `spectrum` (see the module docs; `power` from [`integrand_power`] at the same resolution).
pub fn predicted_variance(f: Integrand, power: &[f64], spectrum: &Spectrum, n: usize) -> f64 {
    let centre = power.len() / 2;
    let excess: f64 = power
        .iter()
        .zip(spectrum.values())
        .enumerate()
        .filter(|&(i, _)| i != centre)
        .map(|(_, (p, s))| p * (s - 1.0))
        .sum();
    (f.variance() + excess).max(0.0) / n as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coefficients_match_closed_forms() {
        // x y on the torus: f^(u, v) = a(u) a(v), a(0) = 1/2, a(u) = i / (2 pi u)
        let k = 64usize;
        let p = integrand_power(Integrand::Bilinear, k as u32);
        let a2 = |u: i64| {
            if u == 0 {
                0.25
            } else {
                1.0 / (2.0 * std::f64::consts::PI * u as f64).powi(2)
            }
        };
        let h = (k / 2) as i64;
        for (u, v) in [
            (0i64, 0i64),
            (1, 0),
            (0, 3),
            (2, 5),
            (-7, 11),
            (16, -16),
            (24, 3),
        ] {
            let got = p[((v + h) * (k as i64 + 1) + u + h) as usize];
            let want = a2(u) * a2(v);
            // cell averaging and aliasing: well under 1% inside, a few % at the grid's edge
            let tol = if u.abs().max(v.abs()) < 10 {
                1e-2
            } else {
                5e-2
            };
            assert!(
                (got - want).abs() < tol * want,
                "({u}, {v}): {got} vs {want}"
            );
        }
        // DC terms are the integrals squared
        for f in [Integrand::Disk, Integrand::Gaussian, Integrand::Step] {
            let p = integrand_power(f, 32);
            let dc = p[p.len() / 2];
            assert!((dc - f.exact().powi(2)).abs() < 1e-3, "{}: {dc}", f.name());
        }
    }
}
