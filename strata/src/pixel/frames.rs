//! Blue noise where the draws of a path meet, a posteriori, for a sequence of frames: pixels
//! exchange their draws within small tiles so that the next frame's error follows a blue-noise
//! mask (Heitz and Belcour, "Distributing Monte Carlo Errors as a Blue Noise in Screen Space by
//! Permuting Pixel Seeds Between Frames", EGSR 2019).
//!
//! A pixel's estimate is a function of the draws it takes (its *seed*: here, the pixel whose
//! keys its [`PixelSampler`](super::PixelSampler) draws are computed for). In a static or
//! slowly changing view, a seed that gave a high estimate in one pixel gives a high one in its
//! neighbour too. [`SeedPermutation::update`] ranks the pixels of each tile by the estimates
//! of the frame just rendered and hands the seed of rank `r` to the pixel where the mask has
//! rank `r`: the next frame's error, rank by rank, follows the mask, whatever the number of
//! dimensions the paths used; every draw of every pixel keeps its own sequence (it is a
//! permutation of whole pixels' draws, so stratification and independence hold as before).
//!
//! What it needs and does not promise: the same seeds must give nearly the same errors in the
//! next frame (the same samples each frame: a static camera redraws, an animation moves a
//! little); with new samples every frame the ranks carry no information and the error stays
//! white. The estimates are of the frame rendered with the current permutation.

use crate::error::{Error, Result};
use crate::prelude::*;

/// The largest side of a [`BlueNoiseMask`].
pub(crate) const MAX_MASK_SIDE: u32 = 256;

/// The largest side of a tile of [`SeedPermutation`].
pub const MAX_TILE: u32 = 64;

/// A blue-noise dither mask: the ranks `0..side^2` on a `side x side` torus, each threshold's
/// set of pixels (rank below `k`) spread as evenly as the void-and-cluster fill makes it
/// (Ulichney, "The void-and-cluster method for dither array generation", SPIE 1993): starting
/// from one pixel, each next rank goes to the pixel of least energy, the energy of a pixel
/// being the sum of a compact bump `(1 - d^2 / R^2)^8` (about a Gaussian of `R / 4`) over the
/// ranked pixels at toroidal distance `d < R`. The bump follows the spacing of the ranked
/// pixels: while `k` pixels are ranked (`2^j <= k < 2^(j+1)`), `R = 2 side / 2^(j/2)`, twice
/// their spacing (at least 2 pixels, at most `side / 2`), and the energy is summed anew when `R`
/// changes. (A radius fixed by the side, too wide for the dense thresholds of a large mask,
/// clumped them 10 to 20 pixels apart; one too narrow leaves the sparse thresholds white.)
/// Ties are broken by a hash of `seed`.
/// Integer and `f32` arithmetic only: the same ranks on every platform.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BlueNoiseMask {
    side: u32,
    /// The rank of each pixel, row-major.
    ranks: Vec<u32>,
}

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

impl BlueNoiseMask {
    /// The mask of `side x side` pixels (a power of two from 4 to 256) for `seed`.
    /// `O(side^4)` time at worst, about 0.1 s at 256 on one core; `O(side^2)` memory.
    pub fn new(side: u32, seed: u64) -> Result<Self> {
        if !side.is_power_of_two() || !(4..=MAX_MASK_SIDE).contains(&side) {
            return Err(Error::parameter(
                "BlueNoiseMask::new",
                "side",
                side,
                format!("a power of two from 4 to {MAX_MASK_SIDE}"),
            ));
        }
        let n = (side * side) as usize;
        // a tiny hashed energy per pixel breaks the ties of the empty start
        let jitter: Vec<f32> = (0..n as u32)
            .map(|i| {
                let h = crate::hash::hash_u64(seed, i as u64);
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
        Ok(BlueNoiseMask {
            side,
            ranks: fill.ranks,
        })
    }

    /// The rank at `pixel`, the mask repeated over the plane (`0..side^2`).
    #[inline]
    pub fn rank(&self, pixel: [u32; 2]) -> u32 {
        let m = self.side - 1;
        self.ranks[((pixel[1] & m) * self.side + (pixel[0] & m)) as usize]
    }
}

/// Which pixel's draws each pixel of an image takes, permuted within tiles from frame to frame
/// so that the error follows a [`BlueNoiseMask`] (see the [module docs](self)).
///
/// ```
/// use strata::pixel::frames::{BlueNoiseMask, SeedPermutation};
/// let mask = BlueNoiseMask::new(16, 1)?;
/// let mut seeds = SeedPermutation::new(32, 32, 4)?;
/// assert_eq!(seeds.source([5, 7]), [5, 7]); // the first frame: every pixel its own draws
/// // after a frame whose estimates are `frame` (row-major, 32 x 32):
/// let frame: Vec<f32> = (0..32 * 32).map(|i| ((i * 37) % 101) as f32).collect();
/// seeds.update(&frame, &mask)?;
/// let [x, y] = seeds.source([5, 7]); // the pixel whose draws (5, 7) takes next
/// assert!(x / 4 == 5 / 4 && y / 4 == 7 / 4); // from its own tile
/// # Ok::<(), strata::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SeedPermutation {
    width: u32,
    height: u32,
    tile: u32,
    /// The source pixel of each pixel, row-major, as `y * width + x`.
    source: Vec<u32>,
}

impl SeedPermutation {
    /// Every pixel its own draws, for an image of `width x height` (each 1 to 65536, at most
    /// `2^26` pixels) in tiles of `tile x tile` pixels (1 to [`MAX_TILE`]; the tiles at the
    /// right and bottom edges may be smaller). Heitz and Belcour use small tiles (4 to 8): a
    /// larger tile gives the permutation more seeds to choose from, and moves draws farther.
    pub fn new(width: u32, height: u32, tile: u32) -> Result<Self> {
        let context = "SeedPermutation::new";
        for (name, v) in [("width", width), ("height", height)] {
            if v == 0 || v > 1 << 16 {
                return Err(Error::parameter(context, name, v, "1 to 65536 pixels"));
            }
        }
        if width as u64 * height as u64 > 1 << 26 {
            return Err(Error::parameter(
                context,
                "width x height",
                width as u64 * height as u64,
                "at most 2^26 pixels",
            ));
        }
        if tile == 0 || tile > MAX_TILE {
            return Err(Error::parameter(
                context,
                "tile",
                tile,
                format!("1 to {MAX_TILE} pixels"),
            ));
        }
        Ok(SeedPermutation {
            width,
            height,
            tile,
            source: (0..width * height).collect(),
        })
    }

    /// The pixel whose draws `pixel` takes (`pixel` itself outside the image).
    #[inline]
    pub fn source(&self, pixel: [u32; 2]) -> [u32; 2] {
        if pixel[0] >= self.width || pixel[1] >= self.height {
            return pixel;
        }
        let s = self.source[(pixel[1] * self.width + pixel[0]) as usize];
        [s % self.width, s / self.width]
    }

    /// Permutes the draws after a frame rendered with this permutation, whose per-pixel
    /// estimates (luminance, or any scalar the error should follow) are `estimates`
    /// (row-major, `width x height`): in each tile, the draws of the pixel of the `r`-th
    /// smallest estimate go to the pixel of the `r`-th smallest rank of `mask` (ties in the
    /// order of the pixels). Refuses estimates of the wrong length or with a NaN or infinite
    /// value (naming the first), leaving the permutation as it was.
    pub fn update(&mut self, estimates: &[f32], mask: &BlueNoiseMask) -> Result<()> {
        let context = "SeedPermutation::update";
        let n = (self.width * self.height) as usize;
        if estimates.len() != n {
            return Err(Error::input(
                context,
                format!(
                    "{} estimates for an image of {} x {} = {n} pixels; one per pixel is needed",
                    estimates.len(),
                    self.width,
                    self.height
                ),
            ));
        }
        if let Some(i) = estimates.iter().position(|v| !v.is_finite()) {
            return Err(Error::input(
                context,
                format!(
                    "the estimate of pixel ({}, {}) is {}; finite values are needed (a renderer \
                     that cannot stop keeps the permutation it has)",
                    i as u32 % self.width,
                    i as u32 / self.width,
                    estimates[i]
                ),
            ));
        }
        let t = self.tile;
        let mut by_value: Vec<u32> = Vec::with_capacity((t * t) as usize);
        let mut by_rank: Vec<u32> = Vec::with_capacity((t * t) as usize);
        let old = self.source.clone();
        for ty in (0..self.height).step_by(t as usize) {
            for tx in (0..self.width).step_by(t as usize) {
                by_value.clear();
                for y in ty..(ty + t).min(self.height) {
                    for x in tx..(tx + t).min(self.width) {
                        by_value.push(y * self.width + x);
                    }
                }
                by_rank.clear();
                by_rank.extend_from_slice(&by_value);
                by_value.sort_by(|&a, &b| estimates[a as usize].total_cmp(&estimates[b as usize]));
                by_rank.sort_by_key(|&p| mask.rank([p % self.width, p / self.width]));
                for (&to, &from) in by_rank.iter().zip(&by_value) {
                    self.source[to as usize] = old[from as usize];
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mask_is_a_permutation_of_its_ranks() {
        for side in [4u32, 8, 32] {
            let m = BlueNoiseMask::new(side, 7).unwrap();
            let mut seen = vec![false; (side * side) as usize];
            for y in 0..side {
                for x in 0..side {
                    let r = m.rank([x, y]) as usize;
                    assert!(!seen[r], "rank {r} twice");
                    seen[r] = true;
                }
            }
            assert_eq!(m.rank([side + 1, 2 * side]), m.rank([1, 0]));
        }
        assert!(BlueNoiseMask::new(12, 1).is_err());
        assert!(BlueNoiseMask::new(512, 1).is_err());
        assert_ne!(BlueNoiseMask::new(16, 1), BlueNoiseMask::new(16, 2));
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
            let m = BlueNoiseMask::new(side, 11).unwrap();
            let key = |i: u32| crate::hash::hash_u64(5, i as u64);
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
                let blue = low_band(|x, y| m.rank([x, y]), side, k, band);
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

    #[test]
    fn the_permutation_moves_draws_within_tiles_and_follows_the_mask() {
        let mask = BlueNoiseMask::new(8, 3).unwrap();
        let (w, h, t) = (21u32, 10u32, 4u32);
        let mut p = SeedPermutation::new(w, h, t).unwrap();
        let values: Vec<f32> = (0..w * h).map(|i| ((i * 7919) % 211) as f32).collect();
        p.update(&values, &mask).unwrap();
        // a permutation, within tiles
        let mut seen = vec![false; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let [sx, sy] = p.source([x, y]);
                assert_eq!((sx / t, sy / t), (x / t, y / t));
                assert!(!seen[(sy * w + sx) as usize]);
                seen[(sy * w + sx) as usize] = true;
            }
        }
        // in every tile, the order of the estimates moved to the pixels is the mask's order
        for ty in (0..h).step_by(t as usize) {
            for tx in (0..w).step_by(t as usize) {
                let mut pixels: Vec<[u32; 2]> = (ty..(ty + t).min(h))
                    .flat_map(|y| (tx..(tx + t).min(w)).map(move |x| [x, y]))
                    .collect();
                pixels.sort_by_key(|&q| mask.rank(q));
                let moved: Vec<f32> = pixels
                    .iter()
                    .map(|&q| {
                        let [sx, sy] = p.source(q);
                        values[(sy * w + sx) as usize]
                    })
                    .collect();
                assert!(moved.windows(2).all(|v| v[0] <= v[1]), "{moved:?}");
            }
        }
        // bad input leaves it as it was
        let before = p.clone();
        let mut bad = values.clone();
        bad[37] = f32::NAN;
        let e = p.update(&bad, &mask).unwrap_err().to_string();
        assert!(e.contains("(16, 1)") && e.contains("NaN"), "{e}");
        assert!(p.update(&values[1..], &mask).is_err());
        assert_eq!(p, before);
        assert!(SeedPermutation::new(0, 4, 4).is_err());
        assert!(SeedPermutation::new(4, 4, 65).is_err());
        assert_eq!(p.source([w, 0]), [w, 0]);
    }
}
