//! Blue-noise dither masks by void and cluster (Ulichney, "The void-and-cluster method for
//! dither array generation", SPIE 1993): the ranks `0..side^2` on a `side x side` torus, each
//! threshold's set of pixels (rank below `k`) spread as evenly as the fill makes it. The
//! renderer crate's frame permutation ([`strata::pixel::frames`]) reads such a mask as data
//! ([`BlueNoiseMask`]); its built-in mask is [`void_and_cluster`]`(64, `[`BUILTIN_SEED`]`)`,
//! written into `strata/src/pixel/frames/blue_noise_64.rs` by the `mask` program and checked against
//! this function by the lab's tests.
//!
//! The fill: starting from one pixel, each next rank goes to the pixel of least energy, the
//! energy of a pixel being the sum of a compact bump `(1 - d^2 / R^2)^8` (about a Gaussian of
//! `R / 4`) over the ranked pixels at toroidal distance `d < R`. The bump follows the spacing of
//! the ranked pixels: while `k` pixels are ranked (`2^j <= k < 2^(j+1)`), `R = 2 side /
//! 2^(j/2)`, twice their spacing (at least 2 pixels, at most `side / 2`), and the energy is
//! summed anew when `R` changes. (A radius fixed by the side, too wide for the dense thresholds
//! of a large mask, clumped them 10 to 20 pixels apart; one too narrow leaves the sparse
//! thresholds white.) Ties are broken by a hash of the seed. Integer and `f32` arithmetic
//! only: the same ranks on every platform.

use std::fmt::Write as _;

use strata::Seed;
use strata::pixel::frames::{BlueNoiseMask, MAX_MASK_SIDE};

use crate::{Error, Result};

/// The seed of the renderer crate's built-in mask ([`BlueNoiseMask::builtin`]), side
/// [`BUILTIN_SIDE`].
pub const BUILTIN_SEED: Seed = Seed(0x6d61_736b);

/// The side of the renderer crate's built-in mask.
pub const BUILTIN_SIDE: u32 = 64;

/// The bump `(1 - d^2 / R^2)^8` of radius `radius` as a table over the offsets `(dx, dy)` in `[-R, R]^2`.
fn bump(radius: i32) -> Vec<f32> {
    let width = (2 * radius + 1) as usize;
    let r2 = (radius * radius) as f32;
    (0..width * width)
        .map(|k| {
            let (dx, dy) = ((k % width) as i32 - radius, (k / width) as i32 - radius);
            let d2 = (dx * dx + dy * dy) as f32;
            if d2 < r2 {
                let u = 1.0 - d2 / r2;
                let u2 = u * u;
                u2 * u2 * (u2 * u2)
            } else {
                0.0
            }
        })
        .collect()
}

/// The void-and-cluster fill's state: the energy of every pixel and, per row, the unranked
/// pixel of least energy (recomputed when the row's energies change).
struct Fill {
    side: u32,
    energy: Vec<f32>,
    ranks: Vec<u32>,
    row_best: Vec<(f32, u32)>,
    row_dirty: Vec<bool>,
}

impl Fill {
    /// Adds the bump `b` of radius `radius` around pixel `i`.
    fn add(&mut self, i: usize, b: &[f32], radius: i32) {
        let side = self.side as i32;
        let (m, width) = (side - 1, 2 * radius + 1);
        let (x, y) = (i as i32 % side, i as i32 / side);
        for dy in -radius..=radius {
            let py = (y + dy) & m;
            self.row_dirty[py as usize] = true;
            let row = &b[((dy + radius) * width) as usize..][..width as usize];
            for (k, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    let px = (x + k as i32 - radius) & m;
                    self.energy[(py * side + px) as usize] += v;
                }
            }
        }
    }

    /// The unranked pixel of least energy (the first on a tie).
    fn least(&mut self) -> usize {
        let side = self.side as usize;
        let mut best = (f32::INFINITY, u32::MAX);
        for y in 0..side {
            if self.row_dirty[y] {
                let mut r = (f32::INFINITY, u32::MAX);
                for x in 0..side {
                    let i = y * side + x;
                    if self.ranks[i] == u32::MAX && self.energy[i] < r.0 {
                        r = (self.energy[i], i as u32);
                    }
                }
                self.row_best[y] = r;
                self.row_dirty[y] = false;
            }
            let r = self.row_best[y];
            if r.1 != u32::MAX && (r.0 < best.0 || (r.0 == best.0 && r.1 < best.1)) {
                best = r;
            }
        }
        best.1 as usize
    }
}

/// The void-and-cluster mask of `side x side` pixels (a power of two from 4 to
/// [`MAX_MASK_SIDE`]) for `seed`: the rank of each pixel, row-major, a permutation of
/// `0..side^2` that [`BlueNoiseMask::new`] takes. `O(side^4)` time at worst, about 0.1 s at 256
/// on one core; `O(side^2)` memory.
pub fn void_and_cluster(side: u32, seed: Seed) -> Result<Vec<u16>> {
    if !side.is_power_of_two() || !(4..=MAX_MASK_SIDE).contains(&side) {
        return Err(Error::parameter(
            "mask::void_and_cluster",
            "side",
            side,
            format!("a power of two from 4 to {MAX_MASK_SIDE}"),
        ));
    }
    let n = (side * side) as usize;
    // a tiny hashed energy per pixel breaks the ties of the empty start
    let jitter: Vec<f32> = (0..n as u32)
        .map(|i| {
            let h = strata::hash::hash_u64(i as u64, seed.0);
            (h >> 40) as f32 * (1e-6 / (1u64 << 24) as f32)
        })
        .collect();
    let mut fill = Fill {
        side,
        energy: jitter.clone(),
        ranks: vec![u32::MAX; n],
        row_best: vec![(f32::INFINITY, u32::MAX); side as usize],
        row_dirty: vec![true; side as usize],
    };
    let mut order = Vec::with_capacity(n);
    let (mut radius, mut b) = (0, Vec::new());
    for rank in 0..n as u32 {
        // the radius of the stage 2^j <= max(rank, 1) < 2^(j+1): 2 side / 2^(j/2)
        let j = rank.max(1).ilog2();
        // (floor of sqrt(4 side^2 / 2^j), exact in integers: no `sqrt` without `std`)
        let r = ((((4 * side as u64 * side as u64) << 16) >> j).isqrt() >> 8) as i32;
        let r = r.clamp(2, side as i32 / 2);
        if r != radius {
            radius = r;
            b = bump(radius);
            fill.energy.copy_from_slice(&jitter);
            fill.row_dirty.fill(true);
            for &i in &order {
                fill.add(i, &b, radius);
            }
        }
        let best = fill.least();
        fill.ranks[best] = rank;
        order.push(best);
        fill.row_dirty[best / side as usize] = true;
        fill.add(best, &b, radius);
    }
    Ok(fill.ranks.iter().map(|&r| r as u16).collect())
}

/// The Rust source of a mask's table as the renderer's crate includes it
/// (`strata/src/pixel/frames/blue_noise_64.rs` for the built-in): a `const` array of the ranks,
/// row-major, 16 to a line, under a header that names the program and options that wrote it.
pub fn rust_table(side: u32, seed: Seed) -> Result<String> {
    let ranks = void_and_cluster(side, seed)?;
    // the table must be one the renderer's crate accepts
    BlueNoiseMask::new(side, &ranks)?;
    let mut s = format!(
        "// A {side} x {side} blue-noise dither mask: void and cluster (Ulichney 1993) as\n\
         // `strata_lab::samplers::mask::void_and_cluster({side}, Seed({:#x}))`, the rank\n\
         // of each pixel, row-major. Written by the lab's `mask` program (`cargo run --release\n\
         // --example mask -- --side {side} --seed {}`); the lab's tests check it against\n\
         // that function. Do not edit.\n\n\
         /// The ranks of the built-in mask, row-major.\n\
         #[rustfmt::skip]\n\
         pub(crate) const RANKS: [u16; {}] = [\n",
        seed.0,
        seed.0,
        side * side
    );
    for line in ranks.chunks(16) {
        s.push_str("   ");
        for r in line {
            write!(s, " {r},").expect("a String takes every write");
        }
        s.push('\n');
    }
    s.push_str("];\n");
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mask_is_a_permutation_of_its_ranks() {
        for side in [4u32, 8, 32] {
            let m = void_and_cluster(side, strata::Seed(7)).unwrap();
            assert!(BlueNoiseMask::new(side, &m).is_ok());
        }
        assert!(void_and_cluster(12, strata::Seed(1)).is_err());
        assert!(void_and_cluster(512, strata::Seed(1)).is_err());
        assert_ne!(
            void_and_cluster(16, strata::Seed(1)),
            void_and_cluster(16, strata::Seed(2))
        );
    }

    /// The mean periodogram of the pixels of rank below `k` over the frequencies
    /// `0 < |f| <= band` (cycles per mask), normalised so that `k` pixels drawn at random
    /// without replacement give `1 - k / n` in expectation. A DFT by rows, then by columns.
    fn low_band(rank: impl Fn(u32, u32) -> u32, side: u32, k: u32, band: f64) -> f64 {
        let s = side as usize;
        let b = band.floor() as i64;
        let tau = 2.0 * core::f64::consts::PI / side as f64;
        let (cos, sin): (Vec<f64>, Vec<f64>) = (0..s)
            .map(|t| ((tau * t as f64).cos(), (tau * t as f64).sin()))
            .unzip();
        let at = |u: i64, t: usize| (u.rem_euclid(side as i64) as usize * t) % s;
        // rows[y][u + b]: the row's transform at frequency u
        let rows: Vec<Vec<(f64, f64)>> = (0..side)
            .map(|y| {
                (-b..=b)
                    .map(|u| {
                        let (mut re, mut im) = (0.0, 0.0);
                        for x in 0..side {
                            if rank(x, y) < k {
                                re += cos[at(u, x as usize)];
                                im -= sin[at(u, x as usize)];
                            }
                        }
                        (re, im)
                    })
                    .collect()
            })
            .collect();
        let (mut sum, mut count) = (0.0, 0);
        for v in -b..=b {
            for u in -b..=b {
                if (u, v) == (0, 0) || ((u * u + v * v) as f64) > band * band {
                    continue;
                }
                let (mut re, mut im) = (0.0, 0.0);
                for (y, row) in rows.iter().enumerate() {
                    let (r, i) = row[(u + b) as usize];
                    let (c, sn) = (cos[at(v, y)], sin[at(v, y)]);
                    re += r * c + i * sn;
                    im += i * c - r * sn;
                }
                sum += (re * re + im * im) / k as f64;
                count += 1;
            }
        }
        sum / count as f64
    }

    #[test]
    fn the_mask_s_thresholds_are_blue_at_every_side() {
        // The pixels of rank below k, for k from 1/64 to 3/4 of the mask, at every side allowed:
        // their power below half their own spacing's frequency (0 < |f| <= sqrt(k / n) side / 2
        // cycles per mask, with n - k for k past half) under a fifth of a random set's (white:
        // 1 - k/n; measured at most 0.125); a random ranking fails the same bound. (The former
        // bump radius, fixed by the side, gave 0.24-0.49 at sides 16-64 and 1.3-28 at 128-256.)
        for side in [4u32, 8, 16, 32, 64, 128, 256] {
            let n = side * side;
            let m = void_and_cluster(side, strata::Seed(11)).unwrap();
            let rank = |x: u32, y: u32| m[(y * side + x) as usize] as u32;
            let key = |i: u32| strata::hash::hash_u64(i as u64, 5);
            let mut order: Vec<u32> = (0..n).collect();
            order.sort_by_key(|&i| key(i));
            let mut random = vec![0u32; n as usize];
            for (r, &i) in order.iter().enumerate() {
                random[i as usize] = r as u32;
            }
            for k in [n / 64, n / 16, n / 4, n / 2, 3 * n / 4] {
                // half the frequency of the spacing of the k pixels (or of the n - k others)
                let band = (k.min(n - k) as f64 / n as f64).sqrt() * side as f64 / 2.0;
                if band < 1.0 {
                    continue;
                }
                let white = 1.0 - k as f64 / n as f64;
                let blue = low_band(rank, side, k, band);
                assert!(
                    blue < 0.2 * white,
                    "side {side} k {k}: {blue:.4} against white {white:.4}"
                );
                let r = low_band(|x, y| random[(y * side + x) as usize], side, k, band);
                assert!(
                    r > 0.3 * white,
                    "side {side} k {k}: the random ranking gives {r}"
                );
            }
        }
    }
}
