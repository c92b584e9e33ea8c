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

/// The largest side of a [`BlueNoiseMask`] (its ranks fit `u16`).
pub const MAX_MASK_SIDE: u32 = 256;

/// The largest side of a tile of [`SeedPermutation`].
pub const MAX_TILE: u32 = 64;

/// The table of the built-in mask ([`BlueNoiseMask::builtin`]).
mod blue_noise_64;

/// A blue-noise dither mask: the ranks `0..side^2` on a `side x side` torus (repeated over the
/// plane), each threshold's set of pixels (rank below `k`) spread evenly, as a void-and-cluster
/// fill makes it (Ulichney, "The void-and-cluster method for dither array generation", SPIE
/// 1993). The mask is data: [`builtin`](BlueNoiseMask::builtin) is a 64 x 64 table made
/// offline by the lab (`strata_lab::samplers::mask`, with a fixed seed; the table's file names
/// the command), and [`new`](BlueNoiseMask::new) takes any other, checked to be a permutation
/// of its ranks. Nothing is computed at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlueNoiseMask<'a> {
    side: u32,
    /// The rank of each pixel, row-major.
    ranks: &'a [u16],
}

impl BlueNoiseMask<'static> {
    /// The built-in 64 x 64 mask (8 KiB of `const` data).
    pub fn builtin() -> Self {
        BlueNoiseMask {
            side: 64,
            ranks: &blue_noise_64::RANKS,
        }
    }
}

impl<'a> BlueNoiseMask<'a> {
    /// The mask of `side x side` pixels (a power of two from 4 to [`MAX_MASK_SIDE`]) whose
    /// ranks, row-major, are `ranks`: a permutation of `0..side^2`, or an error saying what is
    /// wrong. (Whether it is blue is the maker's promise: the lab's `void_and_cluster` makes
    /// one and measures it.)
    pub fn new(side: u32, ranks: &'a [u16]) -> Result<Self> {
        let context = "BlueNoiseMask::new";
        if !side.is_power_of_two() || !(4..=MAX_MASK_SIDE).contains(&side) {
            return Err(Error::parameter(
                context,
                "side",
                side,
                format!("a power of two from 4 to {MAX_MASK_SIDE}"),
            ));
        }
        let n = (side * side) as usize;
        if ranks.len() != n {
            return Err(Error::input(
                context,
                format!(
                    "{} ranks for a side of {side}; side^2 = {n} are needed",
                    ranks.len()
                ),
            ));
        }
        let mut seen = vec![0u64; n.div_ceil(64)];
        for (i, &r) in ranks.iter().enumerate() {
            let r = r as usize;
            if r >= n || seen[r / 64] >> (r % 64) & 1 == 1 {
                return Err(Error::input(
                    context,
                    format!(
                        "the rank {r} of pixel ({}, {}) is {}; each of 0 to {} once is needed",
                        i % side as usize,
                        i / side as usize,
                        if r >= n { "too large" } else { "repeated" },
                        n - 1
                    ),
                ));
            }
            seen[r / 64] |= 1 << (r % 64);
        }
        Ok(BlueNoiseMask { side, ranks })
    }

    /// The side of the mask.
    pub fn side(&self) -> u32 {
        self.side
    }

    /// The rank at `pixel`, the mask repeated over the plane (`0..side^2`).
    #[inline]
    pub fn rank(&self, pixel: [u32; 2]) -> u32 {
        let m = self.side - 1;
        self.ranks[((pixel[1] & m) * self.side + (pixel[0] & m)) as usize] as u32
    }
}

/// Which pixel's draws each pixel of an image takes, permuted within tiles from frame to frame
/// so that the error follows a [`BlueNoiseMask`] (see the [module docs](self)).
///
/// ```
/// use strata::pixel::frames::{BlueNoiseMask, SeedPermutation};
/// let mask = BlueNoiseMask::builtin();
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
    pub fn update(&mut self, estimates: &[f32], mask: &BlueNoiseMask<'_>) -> Result<()> {
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
        let m = BlueNoiseMask::builtin();
        assert_eq!(BlueNoiseMask::new(64, &blue_noise_64::RANKS), Ok(m));
        assert_eq!(m.rank([65, 128]), m.rank([1, 0]));
        // a table that is not a permutation, or of the wrong size, is refused and named
        let mut bad = blue_noise_64::RANKS;
        bad[70] = bad[3];
        let e = BlueNoiseMask::new(64, &bad).unwrap_err().to_string();
        assert!(e.contains("pixel (6, 1)") && e.contains("repeated"), "{e}");
        bad[70] = 4096;
        let e = BlueNoiseMask::new(64, &bad).unwrap_err().to_string();
        assert!(e.contains("too large"), "{e}");
        assert!(BlueNoiseMask::new(32, &blue_noise_64::RANKS).is_err());
        assert!(BlueNoiseMask::new(12, &[0; 144]).is_err());
        let sixteen: Vec<u16> = (0..16).rev().collect();
        assert_eq!(BlueNoiseMask::new(4, &sixteen).unwrap().rank([0, 0]), 15);
    }

    #[test]
    fn the_permutation_moves_draws_within_tiles_and_follows_the_mask() {
        let ranks: Vec<u16> = (0..64u16).map(|i| (i * 37) % 64).collect();
        let mask = BlueNoiseMask::new(8, &ranks).unwrap();
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
