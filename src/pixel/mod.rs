//! The path-tracer adapter: sample values by (pixel, sample index, dimension).
//!
//! A renderer clones one [`PixelSampler`] per thread, calls
//! [`start_pixel_sample`](PixelSampler::start_pixel_sample) for each (pixel, sample index), then
//! takes dimensions in order: [`get_pixel_2d`](PixelSampler::get_pixel_2d) (dimensions 0-1),
//! then [`get_2d`](PixelSampler::get_2d) and [`get_1d`](PixelSampler::get_1d) for the lens, the
//! light, time, each bounce... [`get_4d`](PixelSampler::get_4d) takes two 2D draws at once
//! (the same values as two `get_2d`, with the hashing of both in SIMD lanes: about 25% less
//! time per value for Sobol' and pmj02). Every value is a pure function of (seed, pixel, index,
//! dimension), so the order in which pixels, samples or threads run never changes the image;
//! [`sample`](PixelSampler::sample), [`sample_2d`](PixelSampler::sample_2d) and
//! [`sample_4d`](PixelSampler::sample_4d) are the stateless forms. The adapter is `no_std`
//! (the crate without its `std` feature).
//!
//! # Guarantees
//!
//! * **Independent draws.** Each draw (a 1D value or a 2D pair) at dimension `d` of pixel `p`
//!   comes from its own independently randomized copy of a 2D sequence, keyed by
//!   `hash(seed, p, d)`: padding (Kollig and Keller 2002), Cook's uncorrelated jitter
//!   generalized. Within a pixel, the values of different draws are statistically independent,
//!   and so are those of different pixels and seeds; [`crate::conformance`] tests it per pixel
//!   and per pair of dimensions. A scene that never asks for lens or time dimensions never
//!   computes them.
//! * **Stratified draws.** Per pixel and draw: `pmj02` and `sobol` are (0,m,2)-nets at every
//!   power-of-two prefix; `jittered` has one point per cell of `s x s` in each block of `spp`;
//!   `halton` one per cell of `2^a x 3^b` in each block of `M = 2^a 3^b >= spp` samples. How
//!   each sequence is randomized is in [`sequence`](self#sequences).
//! * **Limits.** Sample indices are `u64`; at `2^32` and beyond, a draw uses the index modulo
//!   `2^32` in a fresh, independently hashed copy (so nothing panics and nothing repeats; the
//!   blocks of `jittered` and `halton` count from each multiple of `2^32`, so the block that
//!   straddles one is not a full set).
//!   pmj02 reads a shared table of `2^16` points and computes later points of the same sequence
//!   on demand, with the same guarantees. Dimensions are unlimited (`u32`), pixels are any
//!   `(u32, u32)`. Values are `f32` in `[0,1)`, never 1.0. After construction nothing
//!   allocates.
//!
//! # Sequences
//!
//! [`Sequence`]: `random` (hashed uniform), `jittered` (`spp` must be a square), `pmj02` (a stochastic pmj02
//! table built once and shared), `sobol` (Owen-scrambled Sobol', Burley 2020), `halton`
//! (scrambled bases 2 and 3). The samples-per-pixel count given to [`PixelSampler::new`] is
//! used only by `jittered` (the size of its sets) and `halton` (the size of its blocks); the
//! progressive `random`, `pmj02` and `sobol` give the same values whatever it is, so a renderer
//! may take any number of samples from them and stop at any power of two.
//!
//! # Dimensions in a renderer that bounces
//!
//! A path that bounces asks for a varying number of values: it may pick a light, sample a
//! BSDF lobe, play Russian roulette, or stop. If each bounce simply took the next dimensions,
//! the same dimension would mean the light at one sample and the BSDF at another, and the
//! stratification of every later draw would be lost. Give each bounce a fixed budget instead:
//! [`start_bounce(k)`](PixelSampler::start_bounce) moves to the first dimension of bounce `k`
//! in a [`DimensionLayout`] (by default dimensions 0-7 for the camera, then 8 per bounce);
//! [`dimension`](PixelSampler::dimension) and [`set_dimension`](PixelSampler::set_dimension)
//! read and set the position directly.
//!
//! A 1D draw at `d` is the first coordinate of the 2D draw at `d`; a renderer that asks for
//! both at one dimension gets the same value twice.
//!
//! **Discrete choices** (which light, which lobe of a mixture, Russian roulette): take the
//! choice from its own [`get_1d`](PixelSampler::get_1d), and the continuous sample that
//! follows from the next [`get_2d`](PixelSampler::get_2d). Every draw is then stratified on
//! its own. (Reusing the choice's value, rescaled, for the continuous sample saves a dimension
//! but ties the two together.)
//!
//! **Code written against `rand`**: [`PixelSampler::rng`] lends a [`PixelRng`], which
//! implements `rand::Rng` and hands out successive dimensions of the current pixel sample. Calls
//! that consume exactly one value per call keep their dimension: `random::<f32>()`,
//! `random::<f64>()`, `random_bool(p)`, `random_range` over floats. Calls that consume a
//! variable number (rejection sampling: `rand_distr`'s `UnitDisc`, `UnitSphere`, `UnitCircle`,
//! `Normal`, `Exp`, `Gamma`; integer `random_range`, which draws again in rare cases) shift
//! every later dimension of that sample: replace them with mappings of one draw, in [`warp`]
//! ([`concentric_disk`](warp::concentric_disk) for `UnitDisc`,
//! [`uniform_sphere`](warp::uniform_sphere) for `UnitSphere`,
//! [`normal_pair`](warp::normal_pair) for two normals, [`pick`](warp::pick) for an integer
//! below `n`).
//!
//! ```
//! use strata::{PixelSampler, Seed, Sequence};
//! // 16 samples per pixel of padded, scrambled Sobol'
//! let mut sampler = PixelSampler::new(Sequence::sobol(), 16, Seed(7))?;
//! let mut sum = 0.0;
//! for index in 0..16 {
//!     sampler.start_pixel_sample([10, 20], index, 0);
//!     let film = sampler.get_pixel_2d(); // position inside the pixel
//!     let lens = sampler.get_2d(); // dimensions 2-3
//!     let time = sampler.get_1d(); // dimension 4
//!     for bounce in 0..3 {
//!         sampler.start_bounce(bounce); // dimension 8 + 8 * bounce
//!         let light = sampler.get_1d(); // which light
//!         let on_light = sampler.get_2d(); // where on it
//!         sum += light * on_light.x;
//!     }
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

mod rng;
mod sequence;
#[cfg(feature = "std")]
pub mod warp;

use glam::{Vec2, Vec4};

pub use rng::PixelRng;
pub use sequence::{DEFAULT_Z_RESOLUTION, MAX_Z_RESOLUTION, PMJ02_TABLE_LEN, Sequence};
use sequence::{NO_Z, SampleIndex, SamplesPerPixel};

use crate::error::Result;
use crate::hash::{GOLDEN_GAMMA, Stream, mix64, stream_seed};
use crate::prelude::*;
use crate::sampler::Seed;

/// Where each bounce of a path starts in the dimensions of a pixel sample: the camera takes
/// dimensions `0..camera`, bounce `k` the `per_bounce` dimensions from `camera + k per_bounce`.
///
/// A fixed budget per bounce keeps each draw at the same dimension for every sample of a
/// pixel, whatever the path did before it (how many lights it sampled, whether it took a
/// discrete choice), so that each draw stays stratified across the samples. Budgets too
/// generous cost nothing: dimensions that are never asked for are never computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DimensionLayout {
    /// Dimensions of the camera sample (film 0-1, then lens, time, wavelength...).
    pub camera: u32,
    /// Dimensions of each bounce (light choice, light point, lobe choice, direction,
    /// Russian roulette...).
    pub per_bounce: u32,
}

impl Default for DimensionLayout {
    /// Eight dimensions for the camera and eight per bounce.
    fn default() -> Self {
        DimensionLayout {
            camera: 8,
            per_bounce: 8,
        }
    }
}

impl DimensionLayout {
    /// The first dimension of bounce `k` (saturating at `u32::MAX`).
    pub fn bounce_start(&self, k: u32) -> u32 {
        self.camera
            .saturating_add(k.saturating_mul(self.per_bounce))
    }
}

/// The per-thread sampler state of a path tracer.
#[derive(Clone, Debug)]
pub struct PixelSampler {
    sequence: Sequence,
    spp: SamplesPerPixel,
    seed: u64,
    layout: DimensionLayout,
    pixel: PixelKeys,
    /// The key of the global sequence of the Z-ordered sequences.
    z_key: u64,
    /// The current sample: its index modulo `2^32` and which `2^32` block it is in.
    sample: SampleIndex,
    epoch: u32,
    dim: u32,
    /// The end of the current bounce's dimensions (checked in debug builds).
    limit: u32,
}

impl PixelSampler {
    /// A sampler over `sequence` with `samples_per_pixel` samples per pixel, seeded by `seed`.
    ///
    /// Only `jittered` (whose sets are `s x s = samples_per_pixel`) and `halton` (whose blocks
    /// are the smallest `2^a 3^b >= samples_per_pixel`) use the count; the other sequences are
    /// progressive and give the same values for any count.
    pub fn new(sequence: Sequence, samples_per_pixel: u32, seed: Seed) -> Result<Self> {
        sequence.check_spp(samples_per_pixel)?;
        let seed = seed.0;
        Ok(PixelSampler {
            sequence,
            spp: SamplesPerPixel::new(samples_per_pixel),
            seed,
            layout: DimensionLayout::default(),
            pixel: PixelKeys {
                key: pixel_key(seed, [0, 0]),
                z: NO_Z,
                z_tile_key: 0,
            },
            z_key: stream_seed(seed, Stream::ZOrderedDraws.id()),
            sample: SampleIndex::new(0),
            epoch: 0,
            dim: 0,
            limit: u32::MAX,
        })
    }

    /// The same sampler with another [`DimensionLayout`] for
    /// [`start_bounce`](Self::start_bounce).
    pub fn with_layout(mut self, layout: DimensionLayout) -> Self {
        self.layout = layout;
        self
    }

    /// Samples per pixel.
    pub fn samples_per_pixel(&self) -> u32 {
        self.spp.get()
    }

    /// The sample count nearest above `n` at which the sequence is best stratified (a square
    /// for jittered, a power of two for pmj02 and Sobol', `2^a 3^b` for Halton).
    pub fn round_count(&self, n: u32) -> u32 {
        self.sequence.round_count(n)
    }

    /// The underlying sequence.
    pub fn sequence(&self) -> &Sequence {
        &self.sequence
    }

    /// The dimension layout of [`start_bounce`](Self::start_bounce).
    pub fn layout(&self) -> DimensionLayout {
        self.layout
    }

    /// The grids on which the first `n` samples of each draw lie, each cell holding the same
    /// number of points (empty where the sequence promises none at `n`).
    pub fn promised_strata(&self, n: u64) -> Vec<crate::StrataGrid> {
        self.sequence.promised_strata(&self.spp, n)
    }

    /// Starts sample `index` of `pixel`, at dimension `dim` (usually 0).
    #[inline]
    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u64, dim: u32) {
        self.pixel = self.keys(pixel);
        self.sample = SampleIndex::new(index as u32);
        self.epoch = (index >> 32) as u32;
        self.dim = dim;
        self.limit = u32::MAX;
    }

    /// The dimension the next draw will use.
    #[inline]
    pub fn dimension(&self) -> u32 {
        self.dim
    }

    /// Moves the next draw to dimension `dim`.
    #[inline]
    pub fn set_dimension(&mut self, dim: u32) {
        self.dim = dim;
    }

    /// Moves the next draw to the first dimension of bounce `k` (see [`DimensionLayout`]).
    /// Debug builds then check that the bounce's draws stay inside its budget (a bounce that
    /// took more would reuse the next bounce's dimensions, tying the two together).
    #[inline]
    pub fn start_bounce(&mut self, k: u32) {
        self.dim = self.layout.bounce_start(k);
        self.limit = self.layout.bounce_start(k.saturating_add(1));
    }

    /// Debug builds: the next `width` dimensions stay inside the current bounce's budget.
    #[inline]
    fn check_budget(&self, width: u64) {
        debug_assert!(
            self.dim as u64 + width <= self.limit as u64,
            "dimension {} is past the budget of this bounce (it ends at {}): raise \
             DimensionLayout::per_bounce",
            self.dim,
            self.limit
        );
    }

    /// The next dimension as a 1D value.
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        self.check_budget(1);
        let v = self.value_1d(&self.pixel, self.sample, self.epoch, self.dim);
        self.dim = self.dim.wrapping_add(1);
        v
    }

    /// The next two dimensions as a 2D value.
    #[inline]
    pub fn get_2d(&mut self) -> Vec2 {
        self.check_budget(2);
        let v = self.value_2d(&self.pixel, self.sample, self.epoch, self.dim);
        self.dim = self.dim.wrapping_add(2);
        v
    }

    /// The next four dimensions as two 2D draws `(x0, y0, x1, y1)`: the same values as two
    /// calls of [`get_2d`](Self::get_2d), computed together (the hashing of the Owen-scrambled
    /// sequences runs lane-parallel), for renderers that draw a light sample and a direction
    /// at once.
    #[inline]
    pub fn get_4d(&mut self) -> Vec4 {
        self.check_budget(4);
        let v = self.value_4d(&self.pixel, self.sample, self.epoch, self.dim);
        self.dim = self.dim.wrapping_add(4);
        v
    }

    /// The position inside the pixel: a 2D draw meant for dimensions 0-1 (call it first).
    #[inline]
    pub fn get_pixel_2d(&mut self) -> Vec2 {
        self.get_2d()
    }

    /// A `rand::Rng` over the current pixel sample: each `next_u32` / `next_u64` is the next
    /// dimension (see the [module docs](self#dimensions-in-a-renderer-that-bounces) for which
    /// `rand` calls keep their dimension).
    pub fn rng(&mut self) -> PixelRng<'_> {
        PixelRng::new(self)
    }

    /// Stateless: the 1D value [`get_1d`](Self::get_1d) gives at `dim` for `(pixel, index)`.
    pub fn sample(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        let (sample, epoch) = split(index);
        self.value_1d(&self.keys(pixel), sample, epoch, dim)
    }

    /// Stateless: the 2D value [`get_2d`](Self::get_2d) gives at `dim` for `(pixel, index)`.
    pub fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec2 {
        let (sample, epoch) = split(index);
        self.value_2d(&self.keys(pixel), sample, epoch, dim)
    }

    /// Stateless: the 4D value [`get_4d`](Self::get_4d) gives at `dim` for `(pixel, index)`.
    pub fn sample_4d(&self, pixel: [u32; 2], index: u64, dim: u32) -> Vec4 {
        let (sample, epoch) = split(index);
        self.value_4d(&self.keys(pixel), sample, epoch, dim)
    }

    /// The copy of the sequence that a draw at `dim` reads: one per pixel, dimension and block
    /// of `2^32` samples (`epoch`).
    #[inline(always)]
    fn stream(&self, pixel_key: u64, epoch: u32, dim: u32) -> u64 {
        let s = mix64(pixel_key ^ (dim as u64).wrapping_mul(GOLDEN_GAMMA));
        if epoch == 0 {
            s
        } else {
            stream_seed(s, epoch as u64) // a fresh copy per 2^32 samples
        }
    }

    /// The keys of `pixel`: its own (for the per-pixel sequences) and, for the Z-ordered ones,
    /// its place along the global sequence.
    #[inline(always)]
    fn keys(&self, pixel: [u32; 2]) -> PixelKeys {
        let z = self.sequence.z_index(pixel, self.seed);
        // the global index z B + i may pass 2^32: each tile of 2^32 indices reads its own copy
        let tile = if z == NO_Z {
            0
        } else {
            (z << self.spp.z_bits()) >> 32
        };
        PixelKeys {
            key: pixel_key(self.seed, pixel),
            z,
            z_tile_key: if tile == 0 {
                self.z_key
            } else {
                stream_seed(self.z_key, tile)
            },
        }
    }

    /// The copy of the sequence a draw reads and the index inside it. For the Z-ordered
    /// sequences, sample `i < B` (`B` = samples per pixel rounded up to a power of two) of the
    /// pixel at place `z` is sample `z B + i` of one global sequence per dimension (and per
    /// `2^32` samples of it); past the pixel's block, or outside the resolution, a draw falls
    /// back to the pixel's own independent copy.
    #[inline(always)]
    fn draw(
        &self,
        keys: &PixelKeys,
        sample: SampleIndex,
        epoch: u32,
        dim: u32,
    ) -> (u64, SampleIndex) {
        if keys.z != NO_Z && epoch == 0 && sample.get() < self.spp.z_block() {
            let g = (keys.z << self.spp.z_bits()) | sample.get() as u64;
            let s = mix64(keys.z_tile_key ^ (dim as u64).wrapping_mul(GOLDEN_GAMMA));
            return (s, SampleIndex::new(g as u32));
        }
        (self.stream(keys.key, epoch, dim), sample)
    }

    #[inline(always)]
    fn value_1d(&self, keys: &PixelKeys, sample: SampleIndex, epoch: u32, dim: u32) -> f32 {
        let (s, i) = self.draw(keys, sample, epoch, dim);
        self.sequence.sample_1d(s, i, &self.spp)
    }

    #[inline(always)]
    fn value_2d(&self, keys: &PixelKeys, sample: SampleIndex, epoch: u32, dim: u32) -> Vec2 {
        let (s, i) = self.draw(keys, sample, epoch, dim);
        let [x, y] = self.sequence.sample_2d(s, i, &self.spp);
        Vec2::new(x, y)
    }

    #[inline(always)]
    fn value_4d(&self, keys: &PixelKeys, sample: SampleIndex, epoch: u32, dim: u32) -> Vec4 {
        let (s0, i) = self.draw(keys, sample, epoch, dim);
        let (s1, _) = self.draw(keys, sample, epoch, dim.wrapping_add(2)); // the same index
        Vec4::from_array(self.sequence.sample_4d([s0, s1], i, &self.spp))
    }

    /// 40 random bits for the low end of [`PixelRng`]'s words, beyond the sequence's 24.
    #[inline]
    fn low_bits(&self) -> u64 {
        let s = self.stream(self.pixel.key, self.epoch, self.dim);
        crate::hash::hash_u64(!s, self.sample.get() as u64)
    }
}

/// A sample index as its value modulo `2^32` and its block of `2^32`.
#[inline]
fn split(index: u64) -> (SampleIndex, u32) {
    (SampleIndex::new(index as u32), (index >> 32) as u32)
}

/// A pixel's keys (see [`PixelSampler::keys`]).
#[derive(Clone, Copy, Debug)]
struct PixelKeys {
    key: u64,
    z: u64,
    /// The Z-ordered sequences' key of the pixel's tile of `2^32` global indices.
    z_tile_key: u64,
}

#[inline]
fn pixel_key(seed: u64, pixel: [u32; 2]) -> u64 {
    stream_seed(seed, (pixel[0] as u64) << 32 | pixel[1] as u64)
}
