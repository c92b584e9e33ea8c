//! The fast periodogram: a type-1 non-uniform FFT with Gaussian gridding.
//!
//! Greengard and Lee, "Accelerating the Nonuniform Fast Fourier Transform" (SIAM Review 2004).
//! For points `x_j` on the unit torus and integer frequencies `|u|, |v| <= K/2` we want
//! `F(u, v) = sum_j exp(-2 pi i (u x_j + v y_j))`.
//!
//! 1. **Spread.** Convolve the point masses with the periodic Gaussian
//!    `g(x) = sum_n exp(-(x - n)^2 / (4 tau))` and sample the result `h` on an `M x M` grid
//!    (`M >= 2 (K + 1)`). The Gaussian is truncated to the `2q` nearest grid points per axis, and
//!    it is separable, so each point costs `4q` exponentials' worth of recurrences and `(2q)^2`
//!    multiply-adds.
//! 2. **FFT.** The grid's DFT gives `h^(u, v) = g^(u) g^(v) F(u, v)` up to aliasing.
//! 3. **Deconvolve.** Divide by `g^(k) = sqrt(4 pi tau) exp(-4 pi^2 k^2 tau)`.
//!
//! Errors: truncation (`~exp(-(q/M)^2 / (4 tau) + pi^2 K^2 tau)`, relative to `g^` at the band
//! edge) and aliasing (`~exp(-4 pi^2 tau M (M - K))`) balance at `tau = q / (2 pi M (2M - K))`,
//! where both are `exp(-2 pi q (M - K) / (2M - K))`, about `exp(-2.1 q)` at `M = 2K`; this is
//! Greengard and Lee's choice. The error of `F` is that times `sum |c_j| = N`, and the
//! periodogram `|F|^2 / N` at a peak (`|F| = N`) inherits twice the error of `F`. We pick `q` so
//! that the absolute error of the periodogram stays below `1e-7` for any pattern:
//! `exp(-2.1 q) N <= 5e-8`.

use std::f64::consts::PI;
use std::sync::Arc;

use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

use strata::Point2;

/// Largest spreading half-width (beyond it double precision is the limit anyway).
const MAX_HALF_WIDTH: usize = 18;

/// A planned transform for one resolution and point count.
pub(crate) struct Plan {
    /// Output frequencies per axis: `K + 1`.
    modes: usize,
    /// Fine grid size per axis.
    m: usize,
    /// Spreading half-width: grid offsets `-q+1 ..= q` around the point's cell.
    q: usize,
    tau: f64,
    /// `exp(-(j/M)^2 / (4 tau))` for `j = -q+1 ..= q`.
    e3: Vec<f64>,
    /// `1 / (M g^(k))` for `k = -K/2 ..= K/2`.
    deconvolve: Vec<f64>,
    /// The DFT index of each wanted frequency `-K/2 ..= K/2` (`f mod M`), and of its negative.
    wanted: Vec<(usize, usize)>,
    fft: Arc<dyn Fft<f64>>,
}

/// The smallest `2^a 3^b 5^c >= n` (sizes whose FFTs are fast).
fn smooth_size(n: usize) -> usize {
    (n..)
        .find(|&k| {
            let mut k = k;
            for p in [2, 3, 5] {
                while k % p == 0 {
                    k /= p;
                }
            }
            k == 1
        })
        .expect("smooth numbers are unbounded")
}

impl Plan {
    /// A plan for resolution `k` (even, >= 2) and `n >= 1` points.
    pub(crate) fn new(k: usize, n: usize) -> Self {
        let modes = k + 1;
        let m = smooth_size(2 * modes).max(8);
        let (mf, kf) = (m as f64, k as f64);
        // Error exponent per unit of q, and the exponent needed for 5e-8 / N.
        let rate = 2.0 * PI * (mf - kf) / (2.0 * mf - kf);
        let needed = (n as f64).ln() + (1.0 / 5e-8f64).ln();
        let q = ((needed / rate).ceil() as usize + 1).clamp(4, MAX_HALF_WIDTH);
        let tau = q as f64 / (2.0 * PI * mf * (2.0 * mf - kf));
        let e3 = (-(q as i64) + 1..=q as i64)
            .map(|j| {
                let d = j as f64 / mf;
                (-d * d / (4.0 * tau)).exp()
            })
            .collect();
        let half = (k / 2) as i64;
        let deconvolve = (-half..=half)
            .map(|f| {
                let g_hat = (4.0 * PI * tau).sqrt() * (-4.0 * PI * PI * (f * f) as f64 * tau).exp();
                1.0 / (mf * g_hat)
            })
            .collect();
        let wanted = (0..modes)
            .map(|f| {
                let at = (f + m - k / 2) % m;
                (at, (m - at) % m)
            })
            .collect();
        let fft = FftPlanner::new().plan_fft_forward(m);
        Plan {
            modes,
            m,
            q,
            tau,
            e3,
            deconvolve,
            wanted,
            fft,
        }
    }

    /// The periodogram `|F(u, v)|^2 / n` on the `(K+1)^2` grid, row-major with `v` (then `u`)
    /// ascending from `-K/2`.
    pub(crate) fn periodogram(&self, points: &[Point2]) -> Vec<f64> {
        let f = self.transform(points);
        let n = points.len() as f64;
        f.iter().map(|c| c.norm_sqr() / n).collect()
    }

    /// `F(u, v)` on the `(K+1)^2` grid, same layout as [`periodogram`](Plan::periodogram).
    pub(crate) fn transform(&self, points: &[Point2]) -> Vec<Complex64> {
        let grid = self.spread(points);
        self.fft_and_deconvolve(grid)
    }

    /// Step 1: the Gaussian-smoothed point masses on the periodic `M x M` grid (row = y).
    fn spread(&self, points: &[Point2]) -> Vec<f64> {
        let (m, q) = (self.m, self.q);
        let width = 2 * q;
        // A padded grid (offsets never wrap inside the hot loop); folded back afterwards.
        let pw = m + width;
        let mut padded = vec![0.0f64; pw * pw];
        let (mut gx, mut gy) = (vec![0.0f64; width], vec![0.0f64; width]);
        for p in points {
            let cx = self.kernel(p[0] as f64, &mut gx);
            let cy = self.kernel(p[1] as f64, &mut gy);
            // Padded index of offset j (from -q+1) around cell c is c + j + q - 1 = c + (index).
            for (jy, &wy) in gy.iter().enumerate() {
                let row = (cy + jy) * pw + cx;
                let dst = &mut padded[row..row + width];
                for (d, &wx) in dst.iter_mut().zip(&gx) {
                    *d += wx * wy;
                }
            }
        }
        // Fold the padding: padded index i is grid index (i - (q - 1)) mod m.
        let shift = m - (q - 1); // adding this (mod m) subtracts q - 1
        let mut grid = vec![0.0f64; m * m];
        for (i, prow) in padded.chunks_exact(pw).enumerate() {
            let gy_row = (i + shift) % m;
            let grow = &mut grid[gy_row * m..(gy_row + 1) * m];
            // contiguous runs of the padded row onto the grid row (same order of additions)
            let mut j = 0;
            while j < pw {
                let t = (j + shift) % m;
                let len = (m - t).min(pw - j);
                for (g, &v) in grow[t..t + len].iter_mut().zip(&prow[j..j + len]) {
                    *g += v;
                }
                j += len;
            }
        }
        grid
    }

    /// The `2q` kernel weights of a coordinate and the index of its cell on the fine grid.
    #[inline]
    fn kernel(&self, x: f64, out: &mut [f64]) -> usize {
        let mf = self.m as f64;
        let c = ((x * mf) as usize).min(self.m - 1);
        let xi = x - c as f64 / mf; // in [0, 1/M)
        // exp(-(xi - j/M)^2 / 4tau) = exp(-xi^2/4tau) * exp(xi j / (2 tau M))^j... * e3[j]
        let e1 = (-xi * xi / (4.0 * self.tau)).exp();
        let e2 = (xi / (2.0 * self.tau * mf)).exp();
        let mut pow = e1 * e2.powi(-(self.q as i32) + 1);
        for (o, &e) in out.iter_mut().zip(&self.e3) {
            *o = pow * e;
            pow *= e2;
        }
        c
    }

    /// Steps 2 and 3: DFT of the grid at the `K + 1` wanted frequencies per axis, divided by the
    /// kernel's transform.
    fn fft_and_deconvolve(&self, grid: Vec<f64>) -> Vec<Complex64> {
        let (m, modes) = (self.m, self.modes);
        let mut scratch = vec![Complex64::new(0.0, 0.0); self.fft.get_inplace_scratch_len()];

        // Pass 1 along x: two real rows per complex FFT (z = a + i b gives A and B by symmetry).
        // rows[y][f] for the wanted x frequencies f.
        let mut rows = vec![Complex64::new(0.0, 0.0); m * modes];
        let mut buf = vec![Complex64::new(0.0, 0.0); m];
        let mut y = 0;
        while y < m {
            let two = y + 1 < m;
            for (x, b) in buf.iter_mut().enumerate() {
                let im = if two { grid[(y + 1) * m + x] } else { 0.0 };
                *b = Complex64::new(grid[y * m + x], im);
            }
            self.fft.process_with_scratch(&mut buf, &mut scratch);
            for (f, &(k, minus_k)) in self.wanted.iter().enumerate() {
                let z = buf[k];
                let zc = buf[minus_k].conj();
                rows[y * modes + f] = (z + zc) * 0.5;
                if two {
                    // (z - conj z(-k)) / 2i
                    let d = (z - zc) * 0.5;
                    rows[(y + 1) * modes + f] = Complex64::new(d.im, -d.re);
                }
            }
            y += 2;
        }

        // Pass 2 along y, one column per wanted x frequency.
        let mut out = vec![Complex64::new(0.0, 0.0); modes * modes];
        for fx in 0..modes {
            for (yy, b) in buf.iter_mut().enumerate() {
                *b = rows[yy * modes + fx];
            }
            self.fft.process_with_scratch(&mut buf, &mut scratch);
            for (fy, &(k, _)) in self.wanted.iter().enumerate() {
                out[fy * modes + fx] = buf[k] * (self.deconvolve[fx] * self.deconvolve[fy]);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smooth_sizes() {
        assert_eq!(smooth_size(258), 270);
        assert_eq!(smooth_size(1026), 1080);
        assert_eq!(smooth_size(7), 8);
    }

    #[test]
    fn single_point_has_unit_magnitude_everywhere() {
        let plan = Plan::new(16, 1);
        let f = plan.transform(&[[0.3, 0.71]]);
        for c in f {
            // |F| = 1; the plan targets 5e-8 / N absolute error in F.
            assert!((c.norm() - 1.0).abs() < 5e-8, "{c}");
        }
    }
}
