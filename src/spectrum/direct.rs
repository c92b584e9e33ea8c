//! The reference periodogram: every term `exp(-2 pi i w . x_k)` evaluated on its own.
//!
//! The phase is reduced exactly before the trigonometric functions: `u x + v y` with `f32`
//! coordinates (24-bit mantissas) and `|u|, |v| <= 2^11` is exact in `f64`, and so is its
//! fractional part, so every term is accurate to a few ulps whatever the frequency.

use std::f64::consts::TAU;

use rayon::prelude::*;

use strata::Point2;

/// `P(u, v)` on the `(K+1)^2` grid, row-major with `v` then `u` ascending from `-K/2`.
pub(crate) fn periodogram(points: &[Point2], k: usize) -> Vec<f64> {
    let side = k + 1;
    let half = (k / 2) as i64;
    let n = points.len() as f64;
    let coords: Vec<(f64, f64)> = points.iter().map(|p| (p[0] as f64, p[1] as f64)).collect();
    let mut out = vec![0.0f64; side * side];
    out.par_chunks_mut(side).enumerate().for_each(|(row, dst)| {
        let v = row as i64 - half;
        for (col, d) in dst.iter_mut().enumerate() {
            let u = col as i64 - half;
            let (mut re, mut im) = (0.0f64, 0.0f64);
            for &(x, y) in &coords {
                let phase = u as f64 * x + v as f64 * y;
                let (s, c) = (TAU * (phase - phase.floor())).sin_cos();
                re += c;
                im -= s;
            }
            *d = (re * re + im * im) / n;
        }
    });
    out
}
