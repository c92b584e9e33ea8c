//! The path-tracer adapter: sample values by (pixel, sample index, dimension).
//!
//! A renderer clones one [`PixelSampler`] per thread, calls
//! [`start_pixel_sample`](PixelSampler::start_pixel_sample) for each (pixel, sample index), then
//! takes dimensions in order: [`get_pixel_2d`](PixelSampler::get_pixel_2d) (dimensions 0-1),
//! then [`get_2d`](PixelSampler::get_2d) and [`get_1d`](PixelSampler::get_1d) for the lens, the
//! light, time, ... Every value is a pure function of (seed, pixel, index, dimension), so the
//! order in which pixels, samples or threads run never changes the image;
//! [`sample`](PixelSampler::sample) and [`sample_2d`](PixelSampler::sample_2d) are the stateless
//! forms.
//!
//! **Padding.** Each draw (a 1D value or a 2D pair) at dimension `d` of pixel `p` comes from its
//! own independently scrambled copy of a 2D sequence, keyed by `hash(seed, p, d)`: Cook's
//! uncorrelated jitter generalized. A scene that never asks for lens or time dimensions never
//! computes them. Decorrelation uses index shuffling and Owen scrambling, which keep every
//! (0,m,2)-net of the nets-based sequences; there is no Cranley-Patterson rotation (which would
//! break nets).
//!
//! **Sequences** ([`PixelSequence`]): `random` (hashed uniform), `jittered` (a jittered
//! `s x s` set per pixel and dimension, the stratum chosen by a hashed permutation of the sample
//! index; `spp` must be a square), `pmj02` (a stochastic pmj02 table built once and shared,
//! index-shuffled by XOR and digitally shifted per draw), `sobol` (Owen-scrambled Sobol' dimensions 0-1
//! with a shuffled index, Burley 2020), `halton` (scrambled bases 2 and 3).
//!
//! **Limits.** Sample indices are `u64`; at `2^32` and beyond, a draw uses the index modulo
//! `2^32` in a fresh, independently hashed copy (so nothing panics and nothing repeats).
//! Dimensions are unlimited (`u32`), pixels are any `(u32, u32)`. Values are `f32` in `[0,1)`,
//! never 1.0. After construction nothing allocates.
//!
//! ```
//! use strata::pixel::{PixelSampler, Sequence};
//! // 16 samples per pixel of padded, scrambled Sobol'
//! let mut sampler = PixelSampler::new(Sequence::sobol(), 16, 7)?;
//! let mut sum = 0.0;
//! for index in 0..16 {
//!     sampler.start_pixel_sample([10, 20], index, 0);
//!     let film = sampler.get_pixel_2d(); // position inside the pixel
//!     let lens = sampler.get_2d(); // dimensions 2-3
//!     let time = sampler.get_1d(); // dimension 4
//!     sum += film.x + lens.y + time;
//! }
//! // the same value from the stateless form, in any order
//! assert_eq!(sampler.sample([10, 20], 3, 4), {
//!     sampler.start_pixel_sample([10, 20], 3, 4);
//!     sampler.get_1d()
//! });
//! # let _ = sum;
//! # Ok::<(), strata::Error>(())
//! ```

use std::sync::{Arc, OnceLock};

use glam::Vec2;

use crate::error::{Error, Result};
use crate::hash::{DivMod, GOLDEN_GAMMA, Permutation, hash_u64, mix64, stream_seed};
use crate::sampler::{Strata, unit_f32_from_u32};
use crate::samplers::{Pmj02Stochastic, halton, sobol};

/// Points in the shared pmj02 table (`2^16`, 512 KB: lookups stay in cache); later indices
/// are computed on demand from the same sequence.
pub const PMJ02_TABLE_LEN: usize = 1 << 16;

/// The seed of the shared pmj02 sequence.
const PMJ02_SEED: u64 = 0x706d_6a30_3200;

fn pmj02_table() -> &'static Arc<Vec<[u32; 2]>> {
    static TABLE: OnceLock<Arc<Vec<[u32; 2]>>> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut s = Pmj02Stochastic::new(PMJ02_SEED);
        s.reserve(PMJ02_TABLE_LEN as u64);
        Arc::new(s.generated().to_vec())
    })
}

/// A samples-per-pixel count with what the sequences derive from it, computed once when the
/// sampler is built rather than on every draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplesPerPixel {
    spp: u32,
    /// Jittered: the `s^2 <= spp` cells of a set, and the side `s`.
    cells: DivMod,
    side: DivMod,
    strata: Strata,
}

impl SamplesPerPixel {
    /// The derived values of `spp` (0 is treated as 1).
    pub fn new(spp: u32) -> Self {
        let s = spp.isqrt().max(1);
        SamplesPerPixel {
            spp,
            cells: DivMod::new(s * s).expect("s >= 1"),
            side: DivMod::new(s).expect("s >= 1"),
            strata: Strata::new(s as u64),
        }
    }

    /// The count.
    pub fn get(&self) -> u32 {
        self.spp
    }
}

/// A 2D sequence the adapter draws from: point `index` of the independently scrambled copy
/// selected by `stream` (a well-mixed 64-bit value).
pub trait PixelSequence: Clone + Send + Sync {
    /// The registered name of the underlying sampler.
    fn name(&self) -> &'static str;

    /// The 2D point `index` of copy `stream` (`index < 2^32`; `spp` is the samples per pixel).
    fn sample_2d(&self, stream: u64, index: u32, spp: &SamplesPerPixel) -> [f32; 2];

    /// A 1D value: the first coordinate of [`sample_2d`](PixelSequence::sample_2d).
    fn sample_1d(&self, stream: u64, index: u32, spp: &SamplesPerPixel) -> f32 {
        self.sample_2d(stream, index, spp)[0]
    }

    /// The sample count nearest above `n` at which the sequence is best stratified.
    fn round_count(&self, n: u32) -> u32;

    /// Checks a samples-per-pixel count.
    fn check_spp(&self, spp: u32) -> Result<()> {
        if spp == 0 {
            return Err(Error::count(self.name(), 0, "at least 1 sample per pixel"));
        }
        Ok(())
    }
}

/// The sequences of the adapter, chosen at run time.
#[derive(Clone, Debug)]
pub enum Sequence {
    /// Hashed independent uniform values.
    Random,
    /// A jittered `s x s` set per pixel and draw (`spp = s^2`).
    Jittered,
    /// A shared stochastic pmj02 table, XOR-shuffled and digitally shifted per draw.
    Pmj02(Arc<Vec<[u32; 2]>>),
    /// Owen-scrambled Sobol' (dimensions 0-1) with a shuffled index.
    Sobol,
    /// Scrambled Halton (bases 2 and 3).
    Halton,
}

impl Sequence {
    /// Independent uniform values.
    pub fn random() -> Self {
        Sequence::Random
    }
    /// Jittered sets (the samples per pixel must be a square).
    pub fn jittered() -> Self {
        Sequence::Jittered
    }
    /// pmj02 (builds the shared table on first use: 65536 points, 512 KB).
    pub fn pmj02() -> Self {
        Sequence::Pmj02(pmj02_table().clone())
    }
    /// Sobol'.
    pub fn sobol() -> Self {
        Sequence::Sobol
    }
    /// Halton.
    pub fn halton() -> Self {
        Sequence::Halton
    }

    /// The names the adapter knows.
    pub const NAMES: [&'static str; 5] = ["random", "jittered", "pmj02", "sobol", "halton"];

    /// The sequence registered under `name` (one of [`Sequence::NAMES`]).
    pub fn by_name(name: &str) -> Result<Self> {
        Ok(match name {
            "random" => Self::random(),
            "jittered" => Self::jittered(),
            "pmj02" => Self::pmj02(),
            "sobol" => Self::sobol(),
            "halton" => Self::halton(),
            other => {
                return Err(Error::input(
                    "pixel",
                    format!(
                        "no path-tracer adapter for '{other}'; samplers with one: {}",
                        Self::NAMES.join(", ")
                    ),
                ));
            }
        })
    }
}

impl PixelSequence for Sequence {
    fn name(&self) -> &'static str {
        match self {
            Sequence::Random => "random",
            Sequence::Jittered => "jittered",
            Sequence::Pmj02(_) => "pmj02",
            Sequence::Sobol => "sobol",
            Sequence::Halton => "halton",
        }
    }

    #[inline]
    fn sample_2d(&self, stream: u64, index: u32, spp: &SamplesPerPixel) -> [f32; 2] {
        match self {
            Sequence::Random => {
                let h = hash_u64(stream, index as u64);
                [
                    unit_f32_from_u32(h as u32),
                    unit_f32_from_u32((h >> 32) as u32),
                ]
            }
            Sequence::Jittered => {
                // Set number `index / spp` of this stream; its stratum by a hashed permutation.
                let (block, i) = spp.cells.div_rem(index);
                let key = mix64(stream ^ (block as u64).wrapping_mul(GOLDEN_GAMMA));
                let k = Permutation::with_divider(&spp.cells, key as u32).apply(i);
                let (row, col) = spp.side.div_rem(k);
                let h = hash_u64(key, i as u64);
                spp.strata
                    .place2([col, row], [h as u32, (h >> 32) as u32])
                    .to_array()
            }
            Sequence::Pmj02(table) => {
                // XOR shuffle of the index (an aligned block of the table per pixel and draw:
                // still a net) and a random digital shift of the values (XOR: maps elementary
                // intervals onto elementary intervals, so nets stay nets; uniform, unbiased).
                let i = index ^ (stream as u32 & (PMJ02_TABLE_LEN as u32 - 1));
                let p = match table.get(i as usize) {
                    Some(p) => *p,
                    None => Pmj02Stochastic::point_at_fixed(PMJ02_SEED, i),
                };
                let shift = mix64(stream);
                [
                    unit_f32_from_u32(p[0] ^ shift as u32),
                    unit_f32_from_u32(p[1] ^ (shift >> 32) as u32),
                ]
            }
            Sequence::Sobol => {
                let [x, y] = sobol::Scramble::from_mixed(stream).sample01_u32(index);
                [unit_f32_from_u32(x), unit_f32_from_u32(y)]
            }
            Sequence::Halton => [
                halton::scrambled_radical_inverse(0, index as u64, stream),
                halton::scrambled_radical_inverse(1, index as u64, stream),
            ],
        }
    }

    #[inline]
    fn sample_1d(&self, stream: u64, index: u32, spp: &SamplesPerPixel) -> f32 {
        match self {
            // the second coordinate (base 3) is most of the cost: skip it
            Sequence::Halton => halton::scrambled_radical_inverse(0, index as u64, stream),
            _ => self.sample_2d(stream, index, spp)[0],
        }
    }

    fn round_count(&self, n: u32) -> u32 {
        let n = n.max(1);
        match self {
            Sequence::Random | Sequence::Halton => n,
            Sequence::Jittered => {
                let s = n.isqrt();
                if s * s == n { n } else { (s + 1) * (s + 1) }
            }
            Sequence::Pmj02(_) | Sequence::Sobol => {
                n.checked_next_power_of_two().unwrap_or(1 << 31)
            }
        }
    }

    fn check_spp(&self, spp: u32) -> Result<()> {
        if spp == 0 {
            return Err(Error::count(self.name(), 0, "at least 1 sample per pixel"));
        }
        if let Sequence::Jittered = self {
            let s = spp.isqrt();
            if s * s != spp {
                return Err(Error::count(
                    "jittered",
                    spp as u64,
                    format!(
                        "jittered needs a square number of samples per pixel (nearest allowed: {})",
                        crate::error::nearest_squares(spp as u64)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The per-thread sampler state of a path tracer.
#[derive(Clone, Debug)]
pub struct PixelSampler<S: PixelSequence = Sequence> {
    sequence: S,
    spp: SamplesPerPixel,
    seed: u64,
    pixel_key: u64,
    index: u64,
    dim: u32,
}

impl<S: PixelSequence> PixelSampler<S> {
    /// A sampler over `sequence` with `samples_per_pixel` samples per pixel, seeded by `seed`.
    pub fn new(sequence: S, samples_per_pixel: u32, seed: u64) -> Result<Self> {
        sequence.check_spp(samples_per_pixel)?;
        Ok(PixelSampler {
            sequence,
            spp: SamplesPerPixel::new(samples_per_pixel),
            seed,
            pixel_key: pixel_key(seed, [0, 0]),
            index: 0,
            dim: 0,
        })
    }

    /// Samples per pixel.
    pub fn samples_per_pixel(&self) -> u32 {
        self.spp.get()
    }

    /// The sample count nearest above `n` at which the sequence is best stratified (a square
    /// for jittered, a power of two for pmj02 and Sobol').
    pub fn round_count(&self, n: u32) -> u32 {
        self.sequence.round_count(n)
    }

    /// The underlying sequence.
    pub fn sequence(&self) -> &S {
        &self.sequence
    }

    /// Starts sample `index` of `pixel`, at dimension `dim` (usually 0).
    #[inline]
    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u64, dim: u32) {
        self.pixel_key = pixel_key(self.seed, pixel);
        self.index = index;
        self.dim = dim;
    }

    /// The next dimension as a 1D value.
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        let v = self.value_1d(self.pixel_key, self.index, self.dim);
        self.dim = self.dim.wrapping_add(1);
        v
    }

    /// The next two dimensions as a 2D value.
    #[inline]
    pub fn get_2d(&mut self) -> Vec2 {
        let v = self.value_2d(self.pixel_key, self.index, self.dim);
        self.dim = self.dim.wrapping_add(2);
        v
    }

    /// The position inside the pixel: a 2D draw meant for dimensions 0-1 (call it first).
    #[inline]
    pub fn get_pixel_2d(&mut self) -> Vec2 {
        self.get_2d()
    }

    /// Stateless: the 1D value [`get_1d`](Self::get_1d) gives at `dim` for `(pixel, index)`.
    pub fn sample(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        self.value_1d(pixel_key(self.seed, pixel), index, dim)
    }

    /// Stateless: the 2D value [`get_2d`](Self::get_2d) gives at `dim` for `(pixel, index)`.
    pub fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2 {
        self.value_2d(pixel_key(self.seed, pixel), index, dim)
    }

    #[inline]
    fn stream(&self, pixel_key: u64, index: u64, dim: u32) -> (u64, u32) {
        let mut s = mix64(pixel_key ^ (dim as u64).wrapping_mul(GOLDEN_GAMMA));
        if index >= 1 << 32 {
            s = stream_seed(s, index >> 32); // a fresh copy per 2^32 samples
        }
        (s, index as u32)
    }

    #[inline]
    fn value_1d(&self, pixel_key: u64, index: u64, dim: u32) -> f32 {
        let (s, i) = self.stream(pixel_key, index, dim);
        self.sequence.sample_1d(s, i, &self.spp)
    }

    #[inline]
    fn value_2d(&self, pixel_key: u64, index: u64, dim: u32) -> Vec2 {
        let (s, i) = self.stream(pixel_key, index, dim);
        let [x, y] = self.sequence.sample_2d(s, i, &self.spp);
        Vec2::new(x, y)
    }
}

#[inline]
fn pixel_key(seed: u64, pixel: [u32; 2]) -> u64 {
    stream_seed(seed, (pixel[0] as u64) << 32 | pixel[1] as u64)
}
