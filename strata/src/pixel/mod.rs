//! The path-tracer adapter: sample values by (pixel, sample index, dimension).
//!
//! A renderer clones one [`PixelSampler`] per thread, calls
//! [`start_pixel_sample`](PixelSampler::start_pixel_sample) for each (pixel, sample index), then
//! takes dimensions in order: [`get_pixel_2d`](PixelSampler::get_pixel_2d) (dimensions 0-1),
//! then [`get_2d`](PixelSampler::get_2d) and [`get_1d`](PixelSampler::get_1d) for the lens, the
//! light, time, each bounce... [`get_4d`](PixelSampler::get_4d) takes two 2D draws at once
//! (the same values as two `get_2d`, the value scrambles four lanes at a time). Every value is
//! a pure function of (seed, pixel, index, dimension), so the order in which pixels, samples or
//! threads run never changes the image; [`sample_1d`](PixelSampler::sample_1d),
//! [`sample_2d`](PixelSampler::sample_2d) and [`sample_4d`](PixelSampler::sample_4d) are the
//! stateless forms. The adapter is `no_std` (the crate without its `std` feature) and
//! allocation-free.
//!
//! # On a GPU
//!
//! This is the one place that says what runs on a GPU. The draws of every sequence whose row in
//! the [table](#sequences) has a GPU number are 32-bit wrapping integer arithmetic (no 64-bit
//! integers, no per-thread tables; the crate's `kernel` module), and [`WGSL`] is the same kernel
//! as a WGSL module (`shaders/strata.wgsl`): include it in a compute or fragment shader, upload
//! [`PixelSampler::gpu_parameters`] (eight `u32`, [`GpuParameters::words`]) as a uniform, and
//! call `strata_get_2d(params, pixel, index, dim)` for the `f32` pair or `strata_draw` for the
//! 32-bit fixed-point values. The joint sequences (`zjoint`, `zquad` and `zsobol12`, sequence 6;
//! `sobol12`, sequence 7) read more generator columns than a uniform holds: include
//! [`WGSL_ZJOINT`] after [`WGSL`], declare a storage buffer `strata_joint: array<u32>` filled
//! with [`Sequence::gpu_joint_table`], and call `strata_joint_get_2d` instead
//! (`strata_is_joint(sequence)` says which).
//!
//! What is tested, and nothing more: the repository's GPU test (`gpu/`) validates both modules
//! with `naga` and runs them through `wgpu` on the Vulkan adapter present (Mesa's lavapipe CPU
//! driver in CI), comparing `2^22` draws of every GPU sequence (of `zjoint` at groups of 2, 8
//! and 512; `sobol12` and `zsobol12` at 8) bit for bit with [`PixelSampler::sample_2d_u32`]: half a renderer's grid, half
//! hashed over the whole `u32` range of pixel, index and dimension. No hardware GPU and no
//! rust-gpu build have been tested. The shader's domain is sample indices below `2^32` (past
//! them the CPU draws from a fresh key per block of `2^32`); `jittered` and `halton` divide by
//! their block sizes in 64-bit arithmetic and are CPU-only.
//!
//! # Guarantees
//!
//! * **Independent draws.** Each draw (a 1D value or a 2D pair) at dimension `d` of pixel `p`
//!   comes from its own independently randomized copy of a 2D sequence, keyed by
//!   `hash(seed, p, d)`: padding (Kollig and Keller 2002), Cook's uncorrelated jitter
//!   generalized. Within a pixel, the values of different draws are statistically independent,
//!   and so are those of different pixels and seeds; the lab's conformance suite tests it per pixel
//!   and per pair of dimensions. The one exception is by design: `zjoint`'s draws of one
//!   *group* of dimensions are distinct dimensions of one multi-dimensional Sobol' sequence,
//!   stratified jointly rather than independent (its groups are independent of each other),
//!   and so are `zquad`'s groups of four, over the base-4 Faure sequence, and the groups of
//!   `sobol12` and `zsobol12` over the (1,2)-Sobol' sequence.
//!   A scene that never asks for lens or time dimensions never computes them.
//! * **Stratified draws.** Per pixel and draw: `pmj02` and `sobol` are (0,m,2)-nets at every
//!   power-of-two prefix; `lattice` has one point per `1/n` in each coordinate at every power of
//!   two `n`; `zsobol` and `zpmj02` are nets at every power of two up to the samples per pixel
//!   (rounded up to a power of two); `zjoint` has one point per `1/n` in each coordinate of
//!   every draw at those counts, the first draw of each group is a net, and the pairs of draws
//!   of a group are `(t, m, 2)`-nets with the t-values of their Sobol' dimensions; `zquad` as
//!   `zjoint`, and each group's four dimensions a (0,k,4)-net in base 4 at every `4^k` up to
//!   the samples per pixel, its draws at the group's first and third dimension (0,m,2)-nets;
//!   `sobol12` (at every power-of-two prefix) and `zsobol12` (up to the samples per pixel) as
//!   `zjoint`, and their 2D draws at a group's even dimensions `(1,m,2)`-nets (the first a
//!   (0,m,2)-net);
//!   `jittered`
//!   has one point per cell of `s x s` in each block of `spp`; `halton` one per cell of `2^a x 3^b` in each block of `M = 2^a 3^b >= spp` samples. How
//!   each sequence is randomized is in [`sequence`](self#sequences).
//! * **Limits.** Sample indices are `u64`; at `2^32` and beyond, a draw uses the index modulo
//!   `2^32` in a fresh, independently hashed copy (so nothing panics and nothing repeats; the
//!   blocks of `jittered` and `halton` count from each multiple of `2^32`, so the block that
//!   straddles one is not a full set).
//!   Dimensions are any `u32` (the draws of a sample advance with wrapping arithmetic, and
//!   bounce starts saturate at `2^32 - 1`), pixels are any
//!   `(u32, u32)`. Values are `f32` in `[0,1)`, never 1.0. After construction nothing
//!   allocates.
//!
//! # Sequences
//!
//! Every [`Sequence`], from the table [`Sequence::table`] generates (`docs/sequences.md`):
//!
#![doc = include_str!("../../docs/sequences.md")]
//!
//! The progressive sequences give the same values whatever the samples-per-pixel count given
//! to [`PixelSampler::new`], so a renderer may take any number of samples from them and stop at
//! any power of two; the Z-ordered ones need the image's resolution up front.
//!
//! # Padding: how two draws meet
//!
//! A pixel sample's draws (film position, lens, light, direction, ...) are *padded*: each
//! draw is its own 2D sequence, and which sample of one draw goes with which sample of another
//! decides the error of everything the draws do together. Each draw first shuffles its index
//! by a nested scramble, so that every power-of-two prefix of every draw is a (0,m,2)-net. Left
//! there ([`Padding::Nested`]), two draws are paired by a tree automorphism: sibling samples
//! stay together across draws, and pairs of draws cover a grid less evenly than chance would.
//! [`Padding::Shells`] (the default) then reorders each dyadic shell `[2^j, 2^(j+1))` of the
//! index per draw by a random `x -> a x + b` over GF(2^j), a sharply 2-transitive family: two
//! draws meet as under independent uniform permutations inside each shell, and since every
//! power-of-two prefix is a union of whole shells, every prefix still holds the net it held, so
//! a renderer may stop at any power of two. pbrt-v4's padded Sobol' permutes the whole pixel's
//! samples per draw, which pairs the same way but keeps only the whole `spp` a net;
//! [`Padding::Uniform`] does that over each aligned block of `spp` samples (rounded up to a
//! power of two), for the record. The [`WGSL`] shader computes `Nested` and `Shells`
//! ([`PixelSampler::gpu_parameters`] is `None` under `Uniform`). `random`, `jittered` and
//! `halton` already permute whole blocks, and the joint sequences draw several dimensions from
//! one index, so none of them is changed by the padding. `render --padding` compares the three.
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
//! every later dimension of that sample: replace them with mappings of one draw, in `warp` (with
//! the `std` feature: `concentric_disk` for `UnitDisc`, `uniform_sphere` for `UnitSphere`,
//! `normal_pair` for two normals, `pick` for an integer below `n`).
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
//!         sum += light * on_light[0];
//!     }
//!     sum += film[0] + lens[1] + time;
//! }
//! // the same value from the stateless form, in any order
//! assert_eq!(sampler.sample_1d([10, 20], 3, 4), {
//!     sampler.start_pixel_sample([10, 20], 3, 4);
//!     sampler.get_1d()
//! });
//! # let _ = sum;
//! # Ok::<(), strata::Error>(())
//! ```

pub mod frames;
mod kernel;
mod rng;
mod sequence;
#[cfg(feature = "std")]
pub mod warp;

pub use kernel::DrawKeys;
use kernel::Key;
pub use rng::PixelRng;
use sequence::SamplesPerPixel;
pub use sequence::Sequence;

use crate::error::Result;
use crate::prelude::*;
use crate::sampler::Seed;
use kernel::{PixelKeys, ZPixel};

/// The WGSL port of the draw kernel (`shaders/strata.wgsl`): a shader module to include, with
/// `strata_get_2d`, `strata_draw` and the parameter struct `StrataParameters` (see the
/// [module docs](self#on-a-gpu)).
pub const WGSL: &str = include_str!("../../shaders/strata.wgsl");

/// The WGSL draws of the joint sequences, `zjoint`, `zquad`, `zsobol12` and `sobol12`
/// (`shaders/strata_zjoint.wgsl`): `strata_joint_draw` and
/// `strata_joint_get_2d`, with the arguments of [`WGSL`]'s `strata_draw` and `strata_get_2d`.
/// Include it after [`WGSL`], and declare the storage buffer it reads, at a binding of your
/// choice, filled with [`Sequence::gpu_joint_table`]:
///
/// ```wgsl
/// @group(0) @binding(3) var<storage, read> strata_joint: array<u32>;
/// ```
pub const WGSL_ZJOINT: &str = include_str!("../../shaders/strata_zjoint.wgsl");

/// A sample index below `2^32` with its bit reversal, which the nets-based sequences need
/// and which is the same for every draw of a pixel sample: computed once per sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SampleIndex {
    index: u32,
    reversed: u32,
}

impl SampleIndex {
    /// The index `index`.
    #[inline]
    pub(crate) fn new(index: u32) -> Self {
        SampleIndex {
            index,
            reversed: index.reverse_bits(),
        }
    }

    /// The index.
    #[inline]
    pub(crate) fn get(&self) -> u32 {
        self.index
    }

    /// The index with its 32 bits reversed.
    #[inline]
    pub(crate) fn reversed(&self) -> u32 {
        self.reversed
    }
}

/// Where each bounce of a path starts in the dimensions of a pixel sample: the camera takes
/// dimensions `0..camera`, bounce `k` the `per_bounce` dimensions from `camera + k per_bounce`.
///
/// A fixed budget per bounce keeps each draw at the same dimension for every sample of a
/// pixel, whatever the path did before it (how many lights it sampled, whether it took a
/// discrete choice), so that each draw stays stratified across the samples. Budgets too
/// generous cost nothing: dimensions that are never asked for are never computed (but for
/// the pair [`PixelSampler::get_2d`] computes ahead at a multiple of 4).
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

/// What a shader needs to compute the draws of a [`PixelSampler`] ([`WGSL`]'s
/// `StrataParameters`, in this field order, eight `u32` words: [`words`](Self::words)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GpuParameters {
    /// The image's key: four words expanded from the seed.
    pub key: [u32; 4],
    /// The image of a Z-ordered sequence (`[0, 0]` for the others).
    pub resolution: [u32; 2],
    /// The sequence: 0 `random`, 1 `sobol`, 2 `pmj02`, 3 `lattice`, 4 `zsobol`, 5 `zpmj02`, 6
    /// `zjoint`, `zquad` and `zsobol12`, 7 `sobol12` (6 and 7: [`WGSL_ZJOINT`], with the
    /// sequence's own table).
    pub sequence: u32,
    /// `log2` of the samples per pixel rounded up to a power of two (the Z-ordered sequences'
    /// block of each pixel).
    pub z_bits: u32,
    /// The padding: 0 [`Padding::Nested`], 1 [`Padding::Shells`] (the shader has no other).
    pub padding: u32,
}

impl GpuParameters {
    /// The parameters as the eight words of the shader's uniform (word 7: `z_bits` in bits
    /// 0-7, `padding` in bit 8).
    pub fn words(&self) -> [u32; 8] {
        let k = self.key;
        [
            k[0],
            k[1],
            k[2],
            k[3],
            self.resolution[0],
            self.resolution[1],
            self.sequence,
            self.z_bits | self.padding << 8,
        ]
    }
}

/// How the samples of two draws of a pixel meet (which sample of one draw is paired with which
/// sample of another), for the digital sequences (`sobol`, `pmj02`, `zsobol`, `zpmj02`) and
/// `lattice`; `random`, `jittered` and `halton` are unchanged by it.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Padding {
    /// Each draw shuffles the sample index by a nested (tree-preserving) scramble: every
    /// power-of-two prefix of every draw is a (0,m,2)-net, so a renderer may stop at any power
    /// of two; two draws' strata are then paired by a tree automorphism rather than by chance.
    Nested,
    /// As `Nested`, then each draw maps the sample's position inside each aligned block of
    /// `B` samples (`B` = samples per pixel rounded up to a power of two, at most `2^16`) by a
    /// random `x -> a x + b` over GF(B), a sharply 2-transitive family: two draws are paired as
    /// by independent uniform permutations, and each whole block is still the net it was; its
    /// prefixes are not. For renderers that take all `spp` samples (a power of two).
    Uniform,
    /// As `Nested`, then each draw maps the sample's position inside its dyadic shell
    /// `[2^j, 2^(j+1))` (samples 0 and 1 stay) by a random `x -> a x + b` over GF(2^j), keyed by
    /// the pixel and the draw (for `j <= 16`: samples from `2^17` on keep the nested order).
    /// It costs three hashes, a division and a GF(2^j) product per draw (the pixel bench times
    /// it beside `Nested`: the repository's `docs/results.md`, `bench-pixel`). Every
    /// power-of-two prefix is a union of whole shells, so it holds the same samples as under
    /// `Nested` and stays the (0,m,2)-net it was, at every count and
    /// without knowing the count; inside each shell two draws meet as under independent
    /// uniform permutations (the family is sharply 2-transitive), not tied by the nested
    /// scramble's tree. pbrt-v4's padded Sobol' permutes the whole pixel's samples at random
    /// per draw, which pairs as well but keeps only the whole `spp` a net. The default.
    #[default]
    Shells,
}

/// The `bits` of a [`SampleState::pad`] that mean [`Padding::Shells`].
const SHELLS: u32 = u32::MAX;

/// The keys and the index the draws of one pixel sample read: the pixel's own copy, or, for
/// the Z-ordered sequences inside the pixel's block, the keys of the global sequence's first
/// tile, the sample's index inside the pixel's block and the pixel's place, which each draw
/// turns into its own global index ([`SampleState::at`]).
#[derive(Clone, Copy, Debug)]
struct SampleState {
    keys: PixelKeys,
    index: SampleIndex,
    z: Option<ZPixel>,
    /// With [`Padding::Uniform`]: the pixel's padding key and `log2` of the block.
    pad: Option<(u32, u32)>,
}

impl SampleState {
    /// The keys and the index of the draw at `dim`: for the Z-ordered sequences, sample `i`
    /// of the pixel at place `z` (this draw's place) is sample `z B + i` of the global sequence
    /// (`B` = samples per pixel rounded up to a power of two), in tiles of `2^32` samples with
    /// keys of their own.
    #[inline(always)]
    fn at(&self, key: &Key, z_bits: u32, dim: u32) -> (PixelKeys, SampleIndex) {
        match &self.z {
            None => (self.keys, self.padded(dim)),
            Some(zp) => self.at_place(key, z_bits, kernel::z_place(zp, dim), dim),
        }
    }

    /// The pixel's sample index for the draw at `dim`: itself, or with [`Padding::Uniform`]
    /// its position inside its block mapped anew for the draw, with [`Padding::Shells`] its
    /// position inside its dyadic shell ([`kernel::uniform_block`], [`kernel::shell_block`]).
    #[inline(always)]
    fn padded(&self, dim: u32) -> SampleIndex {
        match self.pad {
            None => self.index,
            Some((key, SHELLS)) => {
                SampleIndex::new(kernel::shell_block(self.index.get(), key, dim))
            }
            Some((key, bits)) => {
                SampleIndex::new(kernel::uniform_block(self.index.get(), bits, key, dim))
            }
        }
    }

    /// [`at`](Self::at) for a Z-ordered sample whose pixel has place `z` in this draw.
    #[inline(always)]
    fn at_place(&self, key: &Key, z_bits: u32, z: u32, dim: u32) -> (PixelKeys, SampleIndex) {
        match kernel::z_global(z, z_bits, self.padded(dim).get()) {
            Some((0, g)) => (self.keys, SampleIndex::new(g)),
            Some((tile, g)) => (kernel::tile_keys(key, tile), SampleIndex::new(g)),
            // (not reached: a state with a place is made only inside the pixel's block)
            None => (self.keys, self.index),
        }
    }
}

/// What a pixel sample needs of its pixel, kept while the pixel stays the same.
#[derive(Clone, Copy, Debug)]
struct PixelState {
    pixel: [u32; 2],
    epoch: u32,
    /// The pixel's own keys (of the key of its epoch, `2^32` samples).
    own: PixelKeys,
    /// The Z-ordered sequences' view of the pixel (epoch 0, inside the image).
    z: Option<ZPixel>,
    /// With [`Padding::Uniform`], for the sequences it changes: the pixel's padding key and
    /// `log2` of the block.
    pad: Option<(u32, u32)>,
}

impl PixelState {
    /// Whether this is the state of `pixel` in `epoch` (one branch-free comparison: it runs
    /// once per pixel sample).
    #[inline(always)]
    fn is(&self, pixel: [u32; 2], epoch: u32) -> bool {
        (pixel[0] ^ self.pixel[0]) | (pixel[1] ^ self.pixel[1]) | (epoch ^ self.epoch) == 0
    }
}

/// The per-thread sampler state of a path tracer.
#[derive(Clone, Debug)]
pub struct PixelSampler {
    sequence: Sequence,
    spp: SamplesPerPixel,
    key: Key,
    layout: DimensionLayout,
    pixel: PixelState,
    current: SampleState,
    /// The keys of the first tile of the Z-ordered sequences' global sequence.
    z_tile0: PixelKeys,
    /// How the draws' samples are paired ([`Padding`]).
    padding: Padding,
    /// The current pixel's place per draw for dimensions below 64 (a pixel's samples share
    /// them), valid where `z_valid` has the dimension's bit.
    z_places: [u32; 64],
    z_valid: u64,
    /// The draw at `next_dim` of the current sample, computed beside the previous one by
    /// [`get_2d`](Self::get_2d) (`next_dim` is `None` when there is none).
    next_pair: [f32; 2],
    next_dim: Option<u32>,
    dim: u32,
    /// The end of the current bounce's dimensions (checked in debug builds); `None` when no
    /// bounce is open.
    limit: Option<u32>,
}

impl PixelSampler {
    /// A sampler over `sequence` with `samples_per_pixel` samples per pixel, seeded by `seed`.
    ///
    /// Only `jittered` (whose sets are `s x s = samples_per_pixel`), `halton` (whose blocks
    /// are the smallest `2^a 3^b >= samples_per_pixel`) and the Z-ordered sequences (whose
    /// pixels take blocks of the count rounded up to a power of two) use the count; the other
    /// sequences are progressive and give the same values for any count.
    pub fn new(sequence: Sequence, samples_per_pixel: u32, seed: Seed) -> Result<Self> {
        sequence.check_spp(samples_per_pixel)?;
        let key = Key::new(seed);
        let mut s = PixelSampler {
            sequence,
            spp: SamplesPerPixel::new(samples_per_pixel),
            key,
            layout: DimensionLayout::default(),
            pixel: PixelState {
                pixel: [0, 0],
                epoch: 0,
                own: kernel::pixel_keys(&key, [0, 0]),
                z: None,
                pad: None,
            },
            current: SampleState {
                keys: kernel::pixel_keys(&key, [0, 0]),
                index: SampleIndex::new(0),
                z: None,
                pad: None,
            },
            padding: Padding::Shells,
            z_tile0: kernel::tile_keys(&key, 0),
            z_places: [0; 64],
            z_valid: 0,
            next_pair: [0.0; 2],
            next_dim: None,
            dim: 0,
            limit: None,
        };
        s.pixel = s.pixel_state([0, 0], 0);
        s.start_pixel_sample([0, 0], 0, 0);
        Ok(s)
    }

    /// The same sampler with another [`DimensionLayout`] for
    /// [`start_bounce`](Self::start_bounce).
    pub fn with_layout(mut self, layout: DimensionLayout) -> Self {
        self.layout = layout;
        self
    }

    /// The same sampler with another [`Padding`] (how the samples of two draws meet).
    pub fn with_padding(mut self, padding: Padding) -> Self {
        self.padding = padding;
        let (pixel, index) = (self.pixel.pixel, self.current.index.get());
        self.pixel = self.pixel_state(pixel, self.pixel.epoch);
        self.z_valid = 0;
        self.next_dim = None;
        self.current = self.sample_state(&self.pixel, index);
        self
    }

    /// The padding in use.
    pub fn padding(&self) -> Padding {
        self.padding
    }

    /// Samples per pixel.
    pub fn samples_per_pixel(&self) -> u32 {
        self.spp.get()
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
        // uniform padding reorders each block: only whole blocks keep the promises
        let bits = self.spp.z_bits();
        if self.padding == Padding::Uniform
            && self.current_pads()
            && bits <= 16
            && !n.is_multiple_of(1u64 << bits)
        {
            return Vec::new();
        }
        self.sequence.promised_strata(&self.spp, n)
    }

    /// Whether [`Padding::Uniform`] is in use and changes this sequence.
    fn current_pads(&self) -> bool {
        self.padding != Padding::Nested && self.sequence.pads_uniformly()
    }

    /// What the [`WGSL`] shader needs to compute this sampler's draws; `None` for `jittered`
    /// and `halton`, which run on the CPU only, and under [`Padding::Uniform`] (the shader has
    /// the nested and the shell padding). The joint sequences (6 and 7) also need [`WGSL_ZJOINT`] and their table
    /// ([`Sequence::gpu_joint_table`]).
    pub fn gpu_parameters(&self) -> Option<GpuParameters> {
        let padding = match self.padding {
            Padding::Uniform if self.current_pads() => return None,
            Padding::Shells if self.current_pads() => 1,
            _ => 0,
        };
        Some(GpuParameters {
            key: self.key.words(),
            resolution: self.sequence.resolution().unwrap_or([0, 0]),
            sequence: self.sequence.kind().row().shader?,
            z_bits: self.spp.z_bits(),
            padding,
        })
    }

    /// Starts sample `index` of `pixel`, at dimension `dim` (usually 0).
    #[inline]
    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u64, dim: u32) {
        let epoch = (index >> 32) as u32;
        if !self.pixel.is(pixel, epoch) {
            self.pixel = self.pixel_state(pixel, epoch);
            self.current.keys = self.pixel.own;
            self.z_valid = 0;
        }
        if self.pixel.z.is_none() {
            // the pixel's own copy: its keys are already in place
            self.current.index = SampleIndex::new(index as u32);
            self.current.z = None;
            self.current.pad = self.pixel.pad;
        } else {
            self.current = self.sample_state(&self.pixel, index as u32);
        }
        self.next_dim = None;
        self.dim = dim;
        self.limit = None;
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
    /// took more would reuse the next bounce's dimensions, tying the two together). Dimensions
    /// are `u32`: a bounce that starts past the last dimension (`2^32 - 1`, bounce `2^29` of the
    /// default layout) starts at it, its budget unchecked.
    #[inline]
    pub fn start_bounce(&mut self, k: u32) {
        self.dim = self.layout.bounce_start(k);
        let end = self.layout.bounce_start(k.saturating_add(1));
        self.limit = (end < u32::MAX).then_some(end);
    }

    /// Debug builds: the next `width` dimensions stay inside the current bounce's budget.
    #[inline]
    fn check_budget(&self, width: u64) {
        if let Some(limit) = self.limit {
            debug_assert!(
                self.dim as u64 + width <= limit as u64,
                "dimension {} is past the budget of this bounce (it ends at {limit}): raise \
                 DimensionLayout::per_bounce",
                self.dim,
            );
        }
    }

    /// The next dimension as a 1D value.
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        self.check_budget(1);
        let v = if self.next_dim == Some(self.dim) {
            self.next_pair[0]
        } else {
            let (keys, index) = self.draw_at(self.dim);
            self.sequence.sample_1d(&keys, index, self.dim, &self.spp)
        };
        self.dim = self.dim.wrapping_add(1);
        v
    }

    /// The next two dimensions as a 2D value.
    ///
    /// At a dimension that is a multiple of 4, the sequences whose kernel computes two draws
    /// in one pass of four lanes (all but `jittered` and `halton`) compute the draw at the
    /// next two dimensions too and keep it for the next call, as [`get_4d`](Self::get_4d)
    /// does: the same values, for little more than the cost of one draw.
    #[inline(always)]
    pub fn get_2d(&mut self) -> [f32; 2] {
        self.check_budget(2);
        let dim = self.dim;
        let v = if self.next_dim == Some(dim) {
            self.next_pair
        } else if dim.is_multiple_of(4) && self.sequence.pairs_draws() {
            let [x, y, z, w] = self.draw_4(dim);
            self.next_pair = [z, w];
            self.next_dim = Some(dim + 2);
            [x, y]
        } else {
            let (keys, index) = self.draw_at(dim);
            self.sequence.sample_2d(&keys, index, dim, &self.spp)
        };
        self.dim = dim.wrapping_add(2);
        v
    }

    /// The next four dimensions as two 2D draws `(x0, y0, x1, y1)`: the same values as two
    /// calls of [`get_2d`](Self::get_2d), computed together (the value scrambles of the kernel
    /// sequences run four lanes at a time), for renderers that draw a light sample and a
    /// direction at once.
    #[inline]
    pub fn get_4d(&mut self) -> [f32; 4] {
        self.check_budget(4);
        let v = self.draw_4(self.dim);
        self.dim = self.dim.wrapping_add(4);
        v
    }

    /// The draws at `dim` and `dim + 2` of the current sample.
    #[inline(always)]
    fn draw_4(&mut self, dim: u32) -> [f32; 4] {
        if self.current.z.is_none() && self.current.pad.is_none() {
            let c = &self.current;
            self.sequence.sample_4d(&c.keys, c.index, dim, &self.spp)
        } else {
            let (ka, ia) = self.draw_at(dim);
            let (kb, ib) = self.draw_at(dim.wrapping_add(2));
            self.two_2d(ka, ia, kb, ib, dim)
        }
    }

    /// The position inside the pixel: a 2D draw meant for dimensions 0-1 (call it first).
    #[inline]
    pub fn get_pixel_2d(&mut self) -> [f32; 2] {
        self.get_2d()
    }

    /// Starts sample `index` of `pixel` at dimension `dim` and fills `out` with its dimensions
    /// `dim..dim + out.len()`, as `points --pixel X,Y --dims D` prints them (with `dim` 0): one
    /// [`get_2d`](Self::get_2d) per pair of values, and a last [`get_1d`](Self::get_1d) when
    /// `out` has an odd length. Value `k` is therefore coordinate `k & 1` of the stateless
    /// [`sample_2d`](Self::sample_2d)`(pixel, index, dim + (k & !1))` (a 1D draw is the first
    /// coordinate of the 2D draw at its dimension), and the next draw is at dimension
    /// `dim + out.len()`.
    ///
    /// ```
    /// use strata::{PixelSampler, Seed, Sequence};
    /// let mut s = PixelSampler::new(Sequence::pmj02(), 16, Seed(3))?;
    /// let mut row = [0.0f32; 5];
    /// s.fill_sample([4, 2], 7, 0, &mut row);
    /// assert_eq!(row[2..4], s.sample_2d([4, 2], 7, 2));
    /// assert_eq!(row[4], s.sample_1d([4, 2], 7, 4));
    /// # Ok::<(), strata::Error>(())
    /// ```
    #[inline]
    pub fn fill_sample(&mut self, pixel: [u32; 2], index: u64, dim: u32, out: &mut [f32]) {
        self.start_pixel_sample(pixel, index, dim);
        let mut pairs = out.chunks_exact_mut(2);
        for pair in &mut pairs {
            pair.copy_from_slice(&self.get_2d());
        }
        if let [last] = pairs.into_remainder() {
            *last = self.get_1d();
        }
    }

    /// A `rand::Rng` over the current pixel sample: each `next_u32` / `next_u64` is the next
    /// dimension (see the [module docs](self#dimensions-in-a-renderer-that-bounces) for which
    /// `rand` calls keep their dimension).
    pub fn rng(&mut self) -> PixelRng<'_> {
        PixelRng::new(self)
    }

    /// Stateless: the 1D value [`get_1d`](Self::get_1d) gives at `dim` for `(pixel, index)`.
    pub fn sample_1d(&self, pixel: [u32; 2], index: u64, dim: u32) -> f32 {
        let c = self.stateless(pixel, index);
        let (keys, index) = self.at(&c, dim);
        self.sequence.sample_1d(&keys, index, dim, &self.spp)
    }

    /// Stateless: the 2D value [`get_2d`](Self::get_2d) gives at `dim` for `(pixel, index)`.
    pub fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> [f32; 2] {
        let c = self.stateless(pixel, index);
        let (keys, index) = self.at(&c, dim);
        self.sequence.sample_2d(&keys, index, dim, &self.spp)
    }

    /// Stateless: the 4D value [`get_4d`](Self::get_4d) gives at `dim` for `(pixel, index)`.
    pub fn sample_4d(&self, pixel: [u32; 2], index: u64, dim: u32) -> [f32; 4] {
        let c = self.stateless(pixel, index);
        self.four(&c, dim)
    }

    /// Stateless: the 2D draw at `dim` for `(pixel, index)` as the kernel's 32-bit
    /// fixed-point values (`value / 2^32`; [`get_2d`](Self::get_2d) is their top 24 bits), the
    /// values the [`WGSL`] shader computes; `None` for `jittered` and `halton`.
    pub fn sample_2d_u32(&self, pixel: [u32; 2], index: u64, dim: u32) -> Option<[u32; 2]> {
        let c = self.stateless(pixel, index);
        let (keys, index) = self.at(&c, dim);
        self.sequence.sample_2d_u32(&keys, index, dim)
    }

    /// The state of `pixel` in `epoch`.
    fn pixel_state(&self, pixel: [u32; 2], epoch: u32) -> PixelState {
        let key = self.key.epoch(epoch);
        let z = match self.sequence.resolution() {
            Some(res) if epoch == 0 => kernel::z_pixel(&self.key, res, pixel),
            _ => None,
        };
        let own = kernel::pixel_keys(&key, pixel);
        PixelState {
            pixel,
            epoch,
            own,
            z,
            pad: self.current_pads().then(|| {
                let bits = match self.padding {
                    Padding::Shells => SHELLS,
                    _ => self.spp.z_bits(),
                };
                (own.0[0], bits)
            }),
        }
    }

    /// The state of sample `index` (below `2^32`) of `pixel`: for the Z-ordered sequences
    /// inside the pixel's block of `B` samples (`B` = samples per pixel rounded up to a power of
    /// two), a place along the global sequence per draw ([`SampleState::at`]); past the pixel's
    /// block, outside the image and past the first `2^32` samples a draw reads the pixel's own
    /// independent copy.
    #[inline]
    fn sample_state(&self, pixel: &PixelState, index: u32) -> SampleState {
        let bits = self.spp.z_bits();
        let pad = pixel.pad;
        match pixel.z {
            Some(z) if bits < 32 && index >> bits == 0 => SampleState {
                keys: self.z_tile0,
                index: SampleIndex::new(index),
                z: Some(z),
                pad,
            },
            _ => SampleState {
                keys: pixel.own,
                index: SampleIndex::new(index),
                z: None,
                pad,
            },
        }
    }

    /// The four values of [`get_4d`](Self::get_4d) at `dim`: the Z-ordered sequences place the
    /// pixel per draw, so their two draws are two [`SampleState::at`]; the others share one
    /// index and compute the pair together.
    #[inline(always)]
    fn four(&self, c: &SampleState, dim: u32) -> [f32; 4] {
        if c.z.is_none() && c.pad.is_none() {
            return self.sequence.sample_4d(&c.keys, c.index, dim, &self.spp);
        }
        let (ka, ia) = self.at(c, dim);
        let (kb, ib) = self.at(c, dim.wrapping_add(2));
        self.two_2d(ka, ia, kb, ib, dim)
    }

    /// Two 2D draws at `dim` and `dim + 2`, each with its own keys and index.
    #[inline(always)]
    fn two_2d(
        &self,
        ka: PixelKeys,
        ia: SampleIndex,
        kb: PixelKeys,
        ib: SampleIndex,
        dim: u32,
    ) -> [f32; 4] {
        self.sequence
            .sample_2x2d([(&ka, ia), (&kb, ib)], dim, &self.spp)
    }

    /// The keys and the index of the current sample's draw at `dim`; for the Z-ordered
    /// sequences the pixel's place in this draw comes from the per-pixel cache.
    #[inline(always)]
    fn draw_at(&mut self, dim: u32) -> (PixelKeys, SampleIndex) {
        let dim = self.sequence.group_start(dim);
        let Some(zp) = self.current.z else {
            return (self.current.keys, self.current.padded(dim));
        };
        let z = if dim < 64 {
            let bit = 1u64 << dim;
            if self.z_valid & bit == 0 {
                self.z_places[dim as usize] = kernel::z_place(&zp, dim);
                self.z_valid |= bit;
            }
            self.z_places[dim as usize]
        } else {
            kernel::z_place(&zp, dim)
        };
        self.current.at_place(&self.key, self.spp.z_bits(), z, dim)
    }

    /// The keys and the index of the draw at `dim` of sample state `c` (the index of
    /// `dim`'s group: [`Sequence::group_start`]).
    #[inline(always)]
    fn at(&self, c: &SampleState, dim: u32) -> (PixelKeys, SampleIndex) {
        c.at(&self.key, self.spp.z_bits(), self.sequence.group_start(dim))
    }

    /// The state of sample `index` of `pixel`, without changing `self`.
    fn stateless(&self, pixel: [u32; 2], index: u64) -> SampleState {
        let epoch = (index >> 32) as u32;
        let p = if self.pixel.is(pixel, epoch) {
            self.pixel
        } else {
            self.pixel_state(pixel, epoch)
        };
        self.sample_state(&p, index as u32)
    }

    /// 40 random bits for the low end of [`PixelRng`]'s words, beyond the sequence's 24.
    #[inline]
    fn low_bits(&self) -> u64 {
        let (keys, index) = self.at(&self.current, self.dim);
        let k = kernel::DrawKeys::new(&keys, self.dim);
        crate::hash::hash_u64(!k.stream(), index.get() as u64)
    }
}
