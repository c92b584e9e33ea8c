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
//! the [table](#sequences) says "yes" under GPU are 32-bit wrapping integer arithmetic (no
//! 64-bit integers, no per-thread tables; the crate's `kernel` and `padding` modules), and
//! [`WGSL`] is the same draw as a WGSL module (`shaders/strata.wgsl`), one entry point for every
//! such sequence:
//!
//! ```text
//! let gpu = sampler.gpu_parameters()?;     // refuses jittered, halton and Padding::Uniform
//! uniform StrataParameters  <- gpu.words()  // eight u32
//! storage strata_tables     <- gpu.tables() // 128 KiB (and a joint sequence's or sobolbn's table)
//! shader: strata::pixel::WGSL, then @binding(N) var<storage, read> strata_tables: array<u32>;
//! let u = strata_get_2d(params, pixel, index, dim);   // or strata_draw: 32-bit fixed point
//! ```
//!
//! The storage buffer is part of the parameters' contract: the shell padding's table (and, for
//! `zjoint`, `zquad`, `sobol12` and `zsobol12`, their generator columns; for `sobolbn`, its
//! blue-noise table) is read from it by every draw ([`GpuParameters::tables`]).
//!
//! What is tested, and nothing more: the repository's GPU test (`gpu/`) validates the module with
//! `naga` and runs it through `wgpu` on the Vulkan adapter present (Mesa's lavapipe CPU driver in
//! CI), comparing `2^22` draws of every sequence of [`Sequence::NAMES`] that
//! [`PixelSampler::gpu_parameters`] accepts (and of `zjoint` at groups of 2 and 512, `sobol12` at
//! 512), under the nested and the shell padding, bit for bit with
//! [`PixelSampler::sample_2d_u32`]: half a renderer's grid, half hashed over the whole `u32`
//! range of pixel, index and dimension. No hardware GPU and no rust-gpu build have been tested.
//! The shader's domain is sample indices below `2^32` (past them the CPU draws from a fresh key
//! per block of `2^32`); `jittered` and `halton` divide by their block sizes in 64-bit arithmetic
//! and are CPU-only.
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
//!   `sobol12` and `zsobol12` over the (1,2)-Sobol' sequence. Neighbouring pixels of the
//!   Z-ordered sequences and of `sobolbn` are correlated by design (their errors cancel: blue
//!   noise), each pixel's draws still uniform and independent of each other.
//!   A scene that never asks for lens or time dimensions never computes them.
//! * **Stratified draws.** Per pixel and draw: `pmj02`, `sobol` and `sobolbn` are
//!   (0,m,2)-nets at every power-of-two prefix; `lattice` has one point per `1/n` in each coordinate at every power of
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
//! decides the error of everything the draws do together. Under [`Padding::Shells`] (the
//! default) each draw reorders each dyadic shell `[2^j, 2^(j+1))` of the sample index by its own
//! random affine map over GF(2^j), a sharply 2-transitive family (two draws meet as under
//! independent uniform permutations inside each shell), followed by one keyed round of the
//! Owen hash on the shell's positions (without it the two draws' places are related by a
//! binary matrix, whose coarse strata are often tied: the conformance suite sees it). Every
//! power-of-two prefix is a union of whole shells, so it keeps its samples and stays the net it
//! was: a renderer may stop at any power of two. [`Padding::Nested`] shuffles the index by a
//! nested scramble alone (every prefix a net too), which pairs two draws by a tree automorphism:
//! sibling samples stay together across draws. pbrt-v4's padded Sobol' permutes the whole
//! pixel's samples per draw, which pairs as well as the shells but keeps only the whole `spp` a
//! net; [`Padding::Uniform`] does that over each aligned block of `spp` samples (rounded up to a
//! power of two), for the record. The [`WGSL`] shader computes `Nested` and `Shells`
//! ([`PixelSampler::gpu_parameters`] refuses `Uniform`). `random`, `jittered` and `halton`
//! already permute whole blocks and are not changed by the padding; the joint sequences pad each
//! group's index as `sobol` pads each draw's, so every group of theirs changes with the padding,
//! the first one included. `render --padding` compares the three.
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

pub mod bluenoise;
pub mod frames;
mod kernel;
mod padding;
mod rng;
mod sequence;
#[cfg(feature = "std")]
pub mod warp;

pub use bluenoise::BlueNoiseTable;
pub use kernel::DrawKeys;
use kernel::Key;
pub use rng::PixelRng;
pub use sequence::Sequence;
use sequence::{Points, SamplesPerPixel};

use crate::error::{Error, Result};
use crate::prelude::*;
use crate::sampler::Seed;
use crate::scramble::{Lanes, X2, join};
use kernel::{PixelKeys, ZPixel};
use padding::Shell;

/// The WGSL port of the draw kernel (`shaders/strata.wgsl`): a shader module to include, with
/// `strata_get_2d`, `strata_draw` and the parameter struct `StrataParameters`, reading the
/// storage buffer `strata_tables` that the including shader declares (see the
/// [module docs](self#on-a-gpu)).
pub const WGSL: &str = include_str!("../../shaders/strata.wgsl");

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

/// What a shader needs to compute the draws of a [`PixelSampler`]: eight `u32` words for
/// [`WGSL`]'s uniform `StrataParameters` ([`words`](Self::words)) and the words of its storage
/// buffer `strata_tables` ([`tables`](Self::tables)). Made by
/// [`PixelSampler::gpu_parameters`], which refuses what the shader cannot draw.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GpuParameters {
    /// The image's key: four words expanded from the seed.
    pub key: [u32; 4],
    /// The image of a Z-ordered sequence (`[0, 0]` for the others).
    pub resolution: [u32; 2],
    /// What the draws read: 0 hashed values (`random`), 1 Sobol' (`sobol`, `zsobol`), 2
    /// pmj02 (`pmj02`, `zpmj02`), 3 the lattice, 4 a joint sequence's matrices (`zjoint`,
    /// `zquad`, `sobol12`, `zsobol12`: [`tables`](Self::tables) holds them), 5 Sobol' through a
    /// blue-noise table (`sobolbn`: [`tables`](Self::tables) holds it).
    pub kernel: u32,
    /// `log2` of the samples per pixel rounded up to a power of two (the Z-ordered sequences'
    /// block of each pixel).
    pub z_bits: u32,
    /// The padding: 0 [`Padding::Nested`], 1 [`Padding::Shells`] (the shader has no other).
    pub padding: u32,
    /// Whether pixels read blocks of one global sequence along a Z curve.
    pub z_ordered: bool,
    /// The joint sequences' matrices or the blue-noise sequences' table (empty for the
    /// others), after the padding's table in [`tables`](Self::tables).
    extra: Vec<u32>,
}

/// Words of the shader's storage buffer before a joint sequence's matrices: the shell
/// padding's table, two 16-bit entries per word.
const GPU_PADDING_WORDS: usize = padding::TABLE_LEN / 2;

impl GpuParameters {
    /// The parameters as the eight words of the shader's uniform (word 6: `kernel`; word 7:
    /// `z_bits` in bits 0-7, `padding` in bit 8, `z_ordered` in bit 9).
    pub fn words(&self) -> [u32; 8] {
        let k = self.key;
        [
            k[0],
            k[1],
            k[2],
            k[3],
            self.resolution[0],
            self.resolution[1],
            self.kernel,
            self.z_bits | self.padding << 8 | (self.z_ordered as u32) << 9,
        ]
    }

    /// The words of the storage buffer `strata_tables` the shader reads, for every sequence:
    /// the shell padding's table (the powers of the primitive element of each GF(2^j),
    /// `j <= 15`, 16 bits each, two per word: 32 768 words, 128 KiB), then, for a joint
    /// sequence, its group size `G` and the 32 generator columns, in the bit-reversed domain,
    /// of each dimension `0..=G` its draws read (`1 + 32 (G + 1)` words: 161 for `zquad`,
    /// 16 417 for groups of 512), or for `sobolbn`, `log2` of its table's side and its
    /// entries, the key and the rank bit-reversed, row-major (`1 + 2 side^2` words: 32 769,
    /// 128 KiB, for the built-in table).
    pub fn tables(&self) -> Vec<u32> {
        let mut words = Vec::with_capacity(GPU_PADDING_WORDS + self.extra.len());
        words.extend(
            padding::EXP
                .chunks(2)
                .map(|p| p[0] as u32 | (p[1] as u32) << 16),
        );
        words.extend_from_slice(&self.extra);
        words
    }
}

/// How the samples of two draws of a pixel meet (which sample of one draw is paired with which
/// sample of another), for the sequences that read a padded index (`sobol`, `pmj02`, the
/// lattice, the Z-ordered and the joint sequences, `sobolbn`); `random`, `jittered` and
/// `halton` are unchanged by it. `sobolbn` keeps the sets its table arranged at every power of
/// two under `Shells` and `Nested`, and only at multiples of the samples per pixel (rounded up
/// to a power of two) under `Uniform`.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Padding {
    /// Each draw shuffles the sample index by a nested (tree-preserving) scramble: every
    /// power-of-two prefix of every draw is a (0,m,2)-net, so a renderer may stop at any power
    /// of two; two draws' strata are then paired by a tree automorphism rather than by chance.
    Nested,
    /// Each draw maps the sample's position inside each aligned block of `B` samples (`B` =
    /// samples per pixel rounded up to a power of two, at most `2^15`) by a random
    /// `x -> a x + b` over GF(B), a sharply 2-transitive family: two draws are paired as by
    /// independent uniform permutations, and each whole block is still the net it was; its
    /// prefixes are not. For renderers that take all `spp` samples (a power of two).
    Uniform,
    /// Each draw maps the sample's position inside its dyadic shell `[2^j, 2^(j+1))` (samples
    /// 0 and 1 stay) by a random `x -> a x + b` over GF(2^j), keyed by the pixel, the draw and
    /// the shell (from `2^16` samples on, a nested scramble of the shell instead). Every
    /// power-of-two prefix is a union of whole shells, so it holds the same samples as under
    /// `Nested` and stays the (0,m,2)-net it was, at every count and without knowing the count;
    /// inside each shell two draws meet as under independent uniform permutations (the family
    /// is sharply 2-transitive), not tied by a nested scramble's tree. pbrt-v4's padded Sobol'
    /// permutes the whole pixel's samples at random per draw, which pairs as well but keeps
    /// only the whole `spp` a net. One hash and one lookup in a 128 KiB table per draw (the
    /// pixel bench times it: the repository's `docs/results.md`). The default.
    #[default]
    Shells,
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
}

impl PixelState {
    /// Whether this is the state of `pixel` in `epoch` (one branch-free comparison: it runs
    /// once per pixel sample).
    #[inline(always)]
    fn is(&self, pixel: [u32; 2], epoch: u32) -> bool {
        (pixel[0] ^ self.pixel[0]) | (pixel[1] ^ self.pixel[1]) | (epoch ^ self.epoch) == 0
    }
}

/// What the draws of one pixel sample share.
#[derive(Clone, Copy, Debug)]
struct SampleState {
    /// The pixel.
    pixel: [u32; 2],
    /// The pixel's own keys.
    own: PixelKeys,
    /// The sample index (below `2^32`: the index modulo `2^32` in its epoch).
    index: u32,
    /// The index's shell ([`Padding::Shells`]).
    shell: Shell,
    /// The Z-ordered sequences' view of the pixel, when the sample is inside the pixel's block
    /// of the global sequence (epoch 0, inside the image, below the block's size).
    z: Option<ZPixel>,
}

/// How [`PixelSampler::get_4d`] (and [`get_2d`](PixelSampler::get_2d), two draws at a time)
/// reaches a sequence's draws: the default padding's kernel sequences by paths of their own,
/// chosen when the sampler is made, the rest through [`Points`] (the same values).
#[derive(Clone, Copy, Debug)]
enum Route {
    /// A digital sequence that is not Z-ordered.
    Digital(&'static crate::digital::PairTables),
    /// A Z-ordered digital sequence (inside a pixel's block; the generic path elsewhere).
    DigitalZ(&'static crate::digital::PairTables),
    /// A joint sequence.
    Joint,
    /// Every other sequence and padding.
    Generic,
}

/// A word per draw for dimensions below 64, computed on first use and kept until
/// [`clear`](Self::clear) (what a pixel's samples, or a shell's, share).
#[derive(Clone, Debug)]
struct PerDraw {
    words: [u32; 64],
    /// The dimensions whose word is valid, a bit each.
    valid: u64,
}

impl PerDraw {
    /// Nothing kept yet.
    fn new() -> Self {
        PerDraw {
            words: [0; 64],
            valid: 0,
        }
    }

    /// The word of `dim`: kept below 64, else `f()` each time.
    #[inline(always)]
    fn get(&mut self, dim: u32, f: impl FnOnce() -> u32) -> u32 {
        if dim >= 64 {
            return f();
        }
        let bit = 1u64 << dim;
        if self.valid & bit == 0 {
            self.words[dim as usize] = f();
            self.valid |= bit;
        }
        self.words[dim as usize]
    }

    /// Forgets every word.
    #[inline(always)]
    fn clear(&mut self) {
        self.valid = 0;
    }
}

/// `z 2^bits` (modulo `2^32`), bit-reversed, for the place `z` of pixel `zp` in the draw whose
/// group starts at `g`.
#[inline(always)]
fn z_base_of(zp: &ZPixel, g: u32, bits: u32) -> u32 {
    kernel::z_place(zp, g).reverse_bits() >> bits
}

/// The paddings as numbers, the const parameter of the draws (each compiled on its own).
const SHELLS: u8 = 0;
/// See [`SHELLS`].
const NESTED: u8 = 1;
/// See [`SHELLS`].
const UNIFORM: u8 = 2;
/// [`SHELLS`] below `2^16`, each draw's [`Shell::keys`] from the sampler's cache (the stateful
/// draws' paths; the same values).
const SHELLS_CACHED: u8 = 3;

/// The tag of a pending pair in [`PixelSampler`]'s `next`.
const PENDING: u64 = 1 << 32;

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
    /// Whether a pixel's place can reach past the first tile (`2^32` global indices).
    z_tiles: bool,
    /// How the draws' samples are paired ([`Padding`]).
    padding: Padding,
    /// Whether [`get_2d`](Self::get_2d) computes two draws at once
    /// ([`Points::pairs_draws`]).
    pairs: bool,
    /// The default padding's sequences take paths of their own ([`Route`]).
    route: Route,
    /// The current pixel's place per draw for dimensions below 64 (a pixel's samples share
    /// them), as the start of its block of global indices (`z 2^bits`), bit-reversed.
    z_bases: PerDraw,
    /// The current shell's [`Shell::keys`] per draw for dimensions below 64 (the samples of one
    /// shell of a pixel share them).
    shell_keys: PerDraw,
    /// The row part of the last pixel's keys ([`kernel::row_keys`]): the row `y`, the epoch
    /// and the words (a renderer's next pixel is mostly in the same row).
    row: (u32, u32, [u32; 4]),
    /// The draw at dimension `next - 2^32` of the current sample, computed beside the
    /// previous one by [`get_2d`](Self::get_2d) (`next` is 0 when there is none: one
    /// comparison per call).
    next_pair: [f32; 2],
    next: u64,
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
        let spp = SamplesPerPixel::new(samples_per_pixel);
        let z_tiles = match sequence.resolution() {
            Some(r) => {
                let bits = spp.z_bits();
                bits > 0 && kernel::z_mask(r) >> (32 - bits) != 0
            }
            None => false,
        };
        let own = kernel::pixel_keys(&key, [0, 0]);
        let pairs = sequence.points().pairs_draws();
        let mut s = PixelSampler {
            sequence,
            spp,
            key,
            layout: DimensionLayout::default(),
            pixel: PixelState {
                pixel: [0, 0],
                epoch: 0,
                own,
                z: None,
            },
            current: SampleState {
                pixel: [0, 0],
                own,
                index: 0,
                shell: Shell::new(0, 0),
                z: None,
            },
            z_tile0: kernel::tile_keys(&key, 0),
            z_tiles,
            padding: Padding::Shells,
            pairs,
            route: Route::Generic,
            z_bases: PerDraw::new(),
            shell_keys: PerDraw::new(),
            row: (0, 0, kernel::row_keys(&key, 0)),
            next_pair: [0.0; 2],
            next: 0,
            dim: 0,
            limit: None,
        };
        s.pixel = s.pixel_state([0, 0], 0);
        s.start_pixel_sample([0, 0], 0, 0);
        Ok(s.with_padding(Padding::Shells))
    }

    /// The same sampler with another [`DimensionLayout`] for
    /// [`start_bounce`](Self::start_bounce); an error for `per_bounce == 0` (every bounce
    /// would start at the same dimension and reuse the previous bounce's draws).
    pub fn with_layout(mut self, layout: DimensionLayout) -> Result<Self> {
        if layout.per_bounce == 0 {
            return Err(Error::input(
                "PixelSampler::with_layout",
                "per_bounce 0: each bounce needs at least one dimension of its own",
            ));
        }
        self.layout = layout;
        Ok(self)
    }

    /// The same sampler with another [`Padding`] (how the samples of two draws meet).
    pub fn with_padding(mut self, padding: Padding) -> Self {
        self.padding = padding;
        self.next = 0;
        self.route = match self.sequence.points() {
            Points::Digital(p) if self.sequence.z_ordered() => Route::DigitalZ(p.tables()),
            Points::Digital(p) => Route::Digital(p.tables()),
            Points::Joint(_) => Route::Joint,
            _ => Route::Generic,
        };
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
            && self.sequence.points().padded()
            && bits <= padding::MAX_FIELD_BITS
            && !n.is_multiple_of(1u64 << bits)
        {
            return Vec::new();
        }
        let mut grids = self.sequence.promised_strata(&self.spp, n);
        grids.retain(crate::StrataGrid::resolvable);
        grids
    }

    /// What the [`WGSL`] shader needs to compute this sampler's draws: its uniform's words and
    /// its storage buffer's. Refused for `jittered` and `halton`, which run on the CPU only,
    /// and under [`Padding::Uniform`] (the shader has the nested and the shell padding).
    pub fn gpu_parameters(&self) -> Result<GpuParameters> {
        let context = "PixelSampler::gpu_parameters";
        let Some(kernel) = self.sequence.points().kernel() else {
            let gpu: Vec<&str> = Sequence::NAMES
                .iter()
                .filter(|n| Sequence::by_name(n, [1, 1]).is_ok_and(|s| s.runs_on_gpu()))
                .copied()
                .collect();
            return Err(Error::input(
                context,
                format!(
                    "{} runs on the CPU only (it divides by its block size in 64-bit \
                     arithmetic); the GPU draws {}",
                    self.sequence.name(),
                    gpu.join(", ")
                ),
            ));
        };
        let padding = match self.padding {
            Padding::Nested => 0,
            Padding::Shells => 1,
            Padding::Uniform => {
                return Err(Error::input(
                    context,
                    "the shader has the nested and the shell padding, not Padding::Uniform",
                ));
            }
        };
        Ok(GpuParameters {
            key: self.key.words(),
            resolution: self.sequence.resolution().unwrap_or([0, 0]),
            kernel,
            z_bits: self.spp.z_bits(),
            padding,
            z_ordered: self.sequence.z_ordered(),
            extra: self.sequence.gpu_words(),
        })
    }

    /// Starts sample `index` of `pixel`, at dimension `dim` (usually 0).
    #[inline(always)]
    pub fn start_pixel_sample(&mut self, pixel: [u32; 2], index: u64, dim: u32) {
        let epoch = (index >> 32) as u32;
        if !self.pixel.is(pixel, epoch) {
            if (self.row.0, self.row.1) != (pixel[1], epoch) {
                self.row = (
                    pixel[1],
                    epoch,
                    kernel::row_keys(&self.key.epoch(epoch), pixel[1]),
                );
            }
            let own = kernel::pixel_keys_in_row(&self.row.2, pixel[0]);
            self.pixel = self.pixel_state_with(pixel, epoch, own);
            self.z_bases.clear();
            self.shell_keys.clear();
        }
        let sample = self.sample_state(&self.pixel, index as u32);
        if !sample.shell.same_size(&self.current.shell) {
            self.shell_keys.clear();
        }
        self.current = sample;
        self.next = 0;
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
    #[inline(always)]
    pub fn get_1d(&mut self) -> f32 {
        self.check_budget(1);
        let dim = self.dim;
        let v = if self.next == PENDING | dim as u64 {
            self.next_pair[0]
        } else {
            let z = self.z_base_cached(dim);
            self.one_1d(&self.current, dim, z)
        };
        self.dim = dim.wrapping_add(1);
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
        let v = if self.next == PENDING | dim as u64 {
            self.next_pair
        } else if dim.is_multiple_of(4) && self.pairs {
            let [x, y, z, w] = self.draw_4(dim);
            self.next_pair = [z, w];
            self.next = PENDING | dim.wrapping_add(2) as u64;
            [x, y]
        } else {
            let z = self.z_base_cached(dim);
            self.one(&self.current, dim, z)
        };
        self.dim = dim.wrapping_add(2);
        v
    }

    /// The next four dimensions as two 2D draws `(x0, y0, x1, y1)`: the same values as two
    /// calls of [`get_2d`](Self::get_2d), computed together (the value scrambles of the kernel
    /// sequences run four lanes at a time), for renderers that draw a light sample and a
    /// direction at once.
    #[inline(always)]
    pub fn get_4d(&mut self) -> [f32; 4] {
        self.check_budget(4);
        let v = self.draw_4(self.dim);
        self.dim = self.dim.wrapping_add(4);
        v
    }

    /// The draws at `dim` and `dim + 2` of the current sample. Inlined into every caller where
    /// speed is measured (about 15% of a draw's time in the pixel bench); with debug assertions
    /// on (tests) merely inline: its six routes inlined at every call site of a test crate took
    /// minutes to compile at `opt-level = 1`. The values are the same either way.
    #[cfg_attr(not(debug_assertions), inline(always))]
    #[cfg_attr(debug_assertions, inline)]
    fn draw_4(&mut self, dim: u32) -> [f32; 4] {
        let z = self.current.z.is_some();
        match (self.route, self.padding) {
            // the shells below 2^16 (nearly every sample a renderer takes): the cached keys
            (Route::Digital(t), Padding::Shells) if !self.current.shell.nested() => {
                return self.digital_4::<SHELLS_CACHED>(t, dim);
            }
            (Route::Digital(t), Padding::Shells) => return self.digital_4::<SHELLS>(t, dim),
            (Route::Digital(t), Padding::Nested) => return self.digital_4::<NESTED>(t, dim),
            (Route::DigitalZ(t), Padding::Shells) if z && !self.current.shell.nested() => {
                return self.digital_z_4::<SHELLS_CACHED>(t, dim);
            }
            (Route::DigitalZ(t), Padding::Shells) if z => {
                return self.digital_z_4::<SHELLS>(t, dim);
            }
            (Route::DigitalZ(t), Padding::Nested) if z => {
                return self.digital_z_4::<NESTED>(t, dim);
            }
            (Route::Joint, Padding::Shells) if !self.current.shell.nested() => {
                return self.joint_4::<SHELLS_CACHED>(dim);
            }
            (Route::Joint, Padding::Shells) => return self.joint_4::<SHELLS>(dim),
            (Route::Joint, Padding::Nested) => return self.joint_4::<NESTED>(dim),
            (Route::Digital(_) | Route::DigitalZ(_) | Route::Joint, Padding::Uniform)
            | (Route::DigitalZ(_) | Route::Generic, _) => {}
        }
        let za = self.z_base_cached(dim);
        let zb = self.z_base_cached(dim.wrapping_add(2));
        self.two(&self.current, dim, [za, zb])
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
        self.one_1d(&c, dim, self.z_base(&c, dim))
    }

    /// Stateless: the 2D value [`get_2d`](Self::get_2d) gives at `dim` for `(pixel, index)`.
    pub fn sample_2d(&self, pixel: [u32; 2], index: u64, dim: u32) -> [f32; 2] {
        let c = self.stateless(pixel, index);
        self.one(&c, dim, self.z_base(&c, dim))
    }

    /// Stateless: the 4D value [`get_4d`](Self::get_4d) gives at `dim` for `(pixel, index)`.
    pub fn sample_4d(&self, pixel: [u32; 2], index: u64, dim: u32) -> [f32; 4] {
        let c = self.stateless(pixel, index);
        let z = [self.z_base(&c, dim), self.z_base(&c, dim.wrapping_add(2))];
        self.two(&c, dim, z)
    }

    /// Stateless: the 2D draw at `dim` for `(pixel, index)` as the kernel's 32-bit
    /// fixed-point values (`value / 2^32`; [`get_2d`](Self::get_2d) is their top 24 bits), the
    /// values the [`WGSL`] shader computes; `None` for `jittered` and `halton`.
    pub fn sample_2d_u32(&self, pixel: [u32; 2], index: u64, dim: u32) -> Option<[u32; 2]> {
        let c = self.stateless(pixel, index);
        let z = self.z_base(&c, dim);
        match self.padding {
            Padding::Shells => self.one_u32::<SHELLS>(&c, dim, z),
            Padding::Nested => self.one_u32::<NESTED>(&c, dim, z),
            Padding::Uniform => self.one_u32::<UNIFORM>(&c, dim, z),
        }
    }

    /// The state of `pixel` in `epoch`.
    fn pixel_state(&self, pixel: [u32; 2], epoch: u32) -> PixelState {
        let own = kernel::pixel_keys(&self.key.epoch(epoch), pixel);
        self.pixel_state_with(pixel, epoch, own)
    }

    /// The state of `pixel` in `epoch`, whose keys are `own`.
    #[inline(always)]
    fn pixel_state_with(&self, pixel: [u32; 2], epoch: u32, own: PixelKeys) -> PixelState {
        let z = match self.sequence.resolution() {
            Some(res) if epoch == 0 => kernel::z_pixel(&self.key, res, pixel),
            _ => None,
        };
        PixelState {
            pixel,
            epoch,
            own,
            z,
        }
    }

    /// The state of sample `index` (below `2^32`) of `pixel`: for the Z-ordered sequences
    /// inside the pixel's block of `B` samples (`B` = samples per pixel rounded up to a power of
    /// two), a place along the global sequence per draw; past the pixel's block, outside the
    /// image and past the first `2^32` samples a draw reads the pixel's own independent copy.
    #[inline(always)]
    fn sample_state(&self, pixel: &PixelState, index: u32) -> SampleState {
        let bits = self.spp.z_bits();
        SampleState {
            pixel: pixel.pixel,
            own: pixel.own,
            index,
            shell: Shell::new(index, pixel.own.0[2]),
            z: pixel.z.filter(|_| index >> bits == 0),
        }
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

    /// Where the current sample's pixel reads along the global sequence of a Z-ordered
    /// sequence for the draw at `dim` (its group's): the start of its block of global indices,
    /// `z 2^bits` modulo `2^32`, bit-reversed, from the per-pixel cache; `None` outside a Z
    /// block.
    #[inline(always)]
    fn z_base_cached(&mut self, dim: u32) -> Option<u32> {
        self.z_base_of_group(self.sequence.group_start(dim))
    }

    /// [`z_base_cached`](Self::z_base_cached) for the draw whose group starts at `g`.
    #[inline(always)]
    fn z_base_of_group(&mut self, g: u32) -> Option<u32> {
        let zp = self.current.z?;
        let bits = self.spp.z_bits();
        Some(self.z_bases.get(g, || z_base_of(&zp, g, bits)))
    }

    /// [`z_base_cached`](Self::z_base_cached) without the cache.
    #[inline(always)]
    fn z_base(&self, c: &SampleState, dim: u32) -> Option<u32> {
        let zp = c.z?;
        Some(z_base_of(
            &zp,
            self.sequence.group_start(dim),
            self.spp.z_bits(),
        ))
    }

    /// The keys of the tile of the Z-ordered sequences' global sequence where the current
    /// sample's pixel reads in the draw whose group starts at `g` (the first tile's, unless the
    /// image and the samples per pixel reach past `2^32` global indices).
    #[inline(always)]
    fn tile_keys(&self, c: &SampleState, g: u32) -> PixelKeys {
        match c.z {
            Some(zp) if self.z_tiles => self.tile_keys_of(&zp, g),
            _ => self.z_tile0,
        }
    }

    /// [`tile_keys`](Self::tile_keys) past the first tile.
    #[cold]
    fn tile_keys_of(&self, zp: &ZPixel, g: u32) -> PixelKeys {
        let z = kernel::z_place(zp, g);
        let bits = self.spp.z_bits();
        let tile = if bits == 0 { 0 } else { z >> (32 - bits) };
        if tile == 0 {
            self.z_tile0
        } else {
            kernel::tile_keys(&self.key, tile)
        }
    }

    /// Where the draw at `dim`, whose group starts at `g`, reads, given its pixel's place `z`
    /// (reversed; `None` outside a Z block), under the padding `P` (one of [`SHELLS`],
    /// [`NESTED`], [`UNIFORM`]: each padding's draws are compiled on their own): the padded
    /// index of the pixel's sample (placed along the global sequence for the Z-ordered
    /// sequences, shuffled under [`Padding::Nested`]), bit-reversed, and the draw's value keys.
    #[inline(always)]
    fn at<const P: u8>(
        &self,
        c: &SampleState,
        g: u32,
        dim: u32,
        z: Option<u32>,
    ) -> (u32, [u32; 2]) {
        self.at_keyed::<P>(c, g, dim, z, 0)
    }

    /// [`at`](Self::at), and under [`SHELLS_CACHED`] (below `2^16`) with the shell's
    /// [`Shell::keys`] for the group at `g` given (`shell`; unread under the other paddings).
    #[inline(always)]
    fn at_keyed<const P: u8>(
        &self,
        c: &SampleState,
        g: u32,
        dim: u32,
        z: Option<u32>,
        shell: u32,
    ) -> (u32, [u32; 2]) {
        let Some(z) = z else {
            // the pixel's own copy: padded (the shells and the uniform blocks mix their
            // positions themselves) or shuffled
            let keys = c.own;
            let index = match P {
                SHELLS => c.shell.map_rev(g, DrawKeys::hash(&keys, g)),
                SHELLS_CACHED => c.shell.mixed(shell, DrawKeys::hash(&keys, g)),
                NESTED => kernel::shuffled(&DrawKeys::new(&keys, g), c.index.reverse_bits()),
                _ => padding::uniform_rev(
                    c.index,
                    self.spp.z_bits(),
                    keys.0[2],
                    g,
                    DrawKeys::hash(&keys, g),
                ),
            };
            return (index, DrawKeys::values(&keys, dim));
        };
        // a Z-ordered sequence inside the pixel's block: the pixel's index padded (without the
        // mix), placed along the global sequence, and the global index shuffled under the
        // tile's keys (see `Shell::affine_rev`)
        let keys = self.tile_keys(c, g);
        let a = match P {
            SHELLS => c.shell.affine_rev(g),
            SHELLS_CACHED => c.shell.affine_keyed(shell),
            NESTED => c.index.reverse_bits(),
            _ => padding::uniform_rev(c.index, self.spp.z_bits(), c.own.0[2], g, 0),
        };
        let index = kernel::shuffled(&DrawKeys::new(&keys, g), z | a);
        (index, DrawKeys::values(&keys, dim))
    }

    /// [`two`](Self::two) for a digital sequence that is not Z-ordered, under the padding `P`:
    /// the same values, by the shortest path.
    #[inline(always)]
    fn digital_4<const P: u8>(&mut self, t: &crate::digital::PairTables, dim: u32) -> [f32; 4] {
        let d2 = dim.wrapping_add(2);
        let (sa, sb) = (self.shell_keys_of::<P>(dim), self.shell_keys_of::<P>(d2));
        let c = &self.current;
        let ((ia, va), (ib, vb)) = (
            self.at_keyed::<P>(c, dim, dim, None, sa),
            self.at_keyed::<P>(c, d2, d2, None, sb),
        );
        kernel::scrambled_pair(t.point_rev(ia), va, t.point_rev(ib), vb)
    }

    /// The current shell's [`Shell::keys`] for the group at `g` under [`SHELLS_CACHED`] (0
    /// under the other paddings, which do not read them), from the cache for groups below 64.
    #[inline(always)]
    fn shell_keys_of<const P: u8>(&mut self, g: u32) -> u32 {
        if P != SHELLS_CACHED {
            return 0;
        }
        let shell = self.current.shell;
        self.shell_keys.get(g, || shell.keys(g))
    }

    /// [`two`](Self::two) for a Z-ordered digital sequence under the padding `P`, inside the
    /// pixel's block (every draw its own group).
    #[inline(always)]
    fn digital_z_4<const P: u8>(&mut self, t: &crate::digital::PairTables, dim: u32) -> [f32; 4] {
        let d2 = dim.wrapping_add(2);
        let (za, zb) = (self.z_base_of_group(dim), self.z_base_of_group(d2));
        let (sa, sb) = (self.shell_keys_of::<P>(dim), self.shell_keys_of::<P>(d2));
        let c = &self.current;
        let ((ia, va), (ib, vb)) = (
            self.at_keyed::<P>(c, dim, dim, za, sa),
            self.at_keyed::<P>(c, d2, d2, zb, sb),
        );
        kernel::scrambled_pair(t.point_rev(ia), va, t.point_rev(ib), vb)
    }

    /// [`two`](Self::two) for a joint sequence under the padding `P`.
    #[inline(always)]
    fn joint_4<const P: u8>(&mut self, dim: u32) -> [f32; 4] {
        let d2 = dim.wrapping_add(2);
        let (ga, gb) = (
            self.sequence.group_start(dim),
            self.sequence.group_start(d2),
        );
        let (za, zb) = (self.z_base_of_group(ga), self.z_base_of_group(gb));
        let (sa, sb) = (self.shell_keys_of::<P>(ga), self.shell_keys_of::<P>(gb));
        let c = &self.current;
        let Points::Joint(tables) = self.sequence.points() else {
            return self.two(c, dim, [za, zb]);
        };
        let (ia, va) = self.at_keyed::<P>(c, ga, dim, za, sa);
        let (ib, vb) = if ga == gb {
            // the group's index, the keys of `at` (the pixel's own or the tile's)
            let keys = match zb {
                None => c.own,
                Some(_) => self.tile_keys(c, gb),
            };
            (ia, DrawKeys::values(&keys, d2))
        } else {
            self.at_keyed::<P>(c, gb, d2, zb, sb)
        };
        let (oa, ob) = ((dim - ga) as usize, (d2 - gb) as usize);
        let lookup = crate::digital::lookup;
        kernel::scrambled_pair(
            [lookup(&tables[oa], ia), lookup(&tables[oa + 1], ia)],
            va,
            [lookup(&tables[ob], ib), lookup(&tables[ob + 1], ib)],
            vb,
        )
    }

    /// The 2D draw at `dim` of sample `c` (`z` the place of its group, reversed).
    #[inline(always)]
    fn one(&self, c: &SampleState, dim: u32, z: Option<u32>) -> [f32; 2] {
        match self.padding {
            Padding::Shells => self.one_with::<SHELLS>(c, dim, z),
            Padding::Nested => self.one_with::<NESTED>(c, dim, z),
            Padding::Uniform => self.one_with::<UNIFORM>(c, dim, z),
        }
    }

    /// [`one`](Self::one) under the padding `P`.
    #[inline(always)]
    fn one_with<const P: u8>(&self, c: &SampleState, dim: u32, z: Option<u32>) -> [f32; 2] {
        match self.sequence.points() {
            Points::Hashed => kernel::random::<X2>(&DrawKeys::new(&c.own, dim), c.index).unit_f32(),
            Points::Digital(p) => {
                let (i, v) = self.at::<P>(c, dim, dim, z);
                kernel::digital::<X2>(p.tables(), v, i).unit_f32()
            }
            Points::Lattice => {
                let (i, v) = self.at::<P>(c, dim, dim, z);
                kernel::lattice::<X2>(v, i).unit_f32()
            }
            Points::Joint(tables) => {
                let g = self.sequence.group_start(dim);
                let (i, v) = self.at::<P>(c, g, dim, z);
                kernel::joint::<X2>(tables, v, dim - g, i).unit_f32()
            }
            Points::Jittered => {
                sequence::jittered_draw(&DrawKeys::new(&c.own, dim), c.index, &self.spp)
            }
            Points::Halton => {
                sequence::halton_draw(&DrawKeys::new(&c.own, dim), c.index, &self.spp)
            }
            Points::BlueNoise(t) => {
                let (i, key, shift) = self.blue_noise_at::<P>(t, c, dim);
                bluenoise::point_rev_x2(key, i)
                    .xor(X2::new(shift))
                    .reverse_bits()
                    .unit_f32()
            }
        }
    }

    /// The draw at `dim` as the kernel's 32-bit values (`None` for the CPU-only sequences).
    #[inline(always)]
    fn one_u32<const P: u8>(&self, c: &SampleState, dim: u32, z: Option<u32>) -> Option<[u32; 2]> {
        Some(match self.sequence.points() {
            Points::Hashed => kernel::random::<[u32; 2]>(&DrawKeys::new(&c.own, dim), c.index),
            Points::Digital(p) => {
                let (i, v) = self.at::<P>(c, dim, dim, z);
                kernel::digital::<[u32; 2]>(p.tables(), v, i)
            }
            Points::Lattice => {
                let (i, v) = self.at::<P>(c, dim, dim, z);
                kernel::lattice::<[u32; 2]>(v, i)
            }
            Points::Joint(tables) => {
                let g = self.sequence.group_start(dim);
                let (i, v) = self.at::<P>(c, g, dim, z);
                kernel::joint::<[u32; 2]>(tables, v, dim - g, i)
            }
            Points::BlueNoise(t) => {
                let (i, key, shift) = self.blue_noise_at::<P>(t, c, dim);
                bluenoise::point_rev::<[u32; 2]>(key, i)
                    .xor(shift)
                    .reverse_bits()
            }
            Points::Jittered | Points::Halton => return None,
        })
    }

    /// A 1D draw: the first coordinate of [`one`](Self::one).
    #[inline(always)]
    fn one_1d(&self, c: &SampleState, dim: u32, z: Option<u32>) -> f32 {
        match self.sequence.points() {
            // the second coordinate (base 3) is most of the cost: skip it
            Points::Halton => {
                sequence::halton_draw_1d(&DrawKeys::new(&c.own, dim), c.index, &self.spp)
            }
            Points::Hashed
            | Points::Digital(_)
            | Points::Lattice
            | Points::Joint(_)
            | Points::BlueNoise(_)
            | Points::Jittered => self.one(c, dim, z)[0],
        }
    }

    /// The draws at `dim` and `dim + 2` of sample `c` (`z` the places of their groups,
    /// reversed): the kernel sequences' value scrambles and conversions four lanes at a time.
    #[inline(always)]
    fn two(&self, c: &SampleState, dim: u32, z: [Option<u32>; 2]) -> [f32; 4] {
        match self.padding {
            Padding::Shells => self.two_with::<SHELLS>(c, dim, z),
            Padding::Nested => self.two_with::<NESTED>(c, dim, z),
            Padding::Uniform => self.two_with::<UNIFORM>(c, dim, z),
        }
    }

    /// [`two`](Self::two) under the padding `P`.
    #[inline(always)]
    fn two_with<const P: u8>(&self, c: &SampleState, dim: u32, z: [Option<u32>; 2]) -> [f32; 4] {
        let d2 = dim.wrapping_add(2);
        match self.sequence.points() {
            Points::Hashed => join(
                kernel::random::<X2>(&DrawKeys::new(&c.own, dim), c.index),
                kernel::random::<X2>(&DrawKeys::new(&c.own, d2), c.index),
            )
            .unit_f32(),
            Points::Digital(p) => {
                let t = p.tables();
                let ((ia, va), (ib, vb)) = (
                    self.at::<P>(c, dim, dim, z[0]),
                    self.at::<P>(c, d2, d2, z[1]),
                );
                kernel::scrambled_pair(t.point_rev(ia), va, t.point_rev(ib), vb)
            }
            Points::Lattice => {
                let ((ia, va), (ib, vb)) = (
                    self.at::<P>(c, dim, dim, z[0]),
                    self.at::<P>(c, d2, d2, z[1]),
                );
                join(kernel::lattice::<X2>(va, ia), kernel::lattice::<X2>(vb, ib)).unit_f32()
            }
            Points::Joint(tables) => {
                let (ga, gb) = (
                    self.sequence.group_start(dim),
                    self.sequence.group_start(d2),
                );
                let (ia, va) = self.at::<P>(c, ga, dim, z[0]);
                let (ib, vb) = if gb == ga {
                    // the same group: its index and keys, the next dimensions' value keys
                    let keys = match z[0] {
                        None => c.own,
                        Some(_) => self.tile_keys(c, ga),
                    };
                    (ia, DrawKeys::values(&keys, d2))
                } else {
                    self.at::<P>(c, gb, d2, z[1])
                };
                let (oa, ob) = ((dim - ga) as usize, (d2 - gb) as usize);
                let lookup = crate::digital::lookup;
                kernel::scrambled_pair(
                    [lookup(&tables[oa], ia), lookup(&tables[oa + 1], ia)],
                    va,
                    [lookup(&tables[ob], ib), lookup(&tables[ob + 1], ib)],
                    vb,
                )
            }
            Points::BlueNoise(t) => {
                let ((ia, ka, sa), (ib, kb, sb)) = (
                    self.blue_noise_at::<P>(t, c, dim),
                    self.blue_noise_at::<P>(t, c, d2),
                );
                join(
                    bluenoise::point_rev_x2(ka, ia).xor(X2::new(sa)),
                    bluenoise::point_rev_x2(kb, ib).xor(X2::new(sb)),
                )
                .reverse_bits()
                .unit_f32()
            }
            Points::Jittered | Points::Halton => {
                let [x, y] = self.one_with::<P>(c, dim, z[0]);
                let [u, w] = self.one_with::<P>(c, d2, z[1]);
                [x, y, u, w]
            }
        }
    }

    /// Where the draw at `dim` of a blue-noise sequence reads: the pixel's padded index
    /// XOR-ed with the rank of its entry in the table `t` shifted by the draw (bit-reversed),
    /// the entry's key, and the draw's digital shift of the values (in the reversed domain).
    /// Under [`Padding::Nested`] the shuffled index is XOR-ed with the shuffle of index 0, so
    /// that the first `2^m` samples stay the first `2^m` (the sets the table arranged). The
    /// shift of the table and the two coordinates' digital shifts come from the image's keys
    /// (`z_tile0`, a hash of the seed alone) and the dimension, each from its own word of
    /// them.
    #[inline(always)]
    fn blue_noise_at<const P: u8>(
        &self,
        t: &BlueNoiseTable,
        c: &SampleState,
        dim: u32,
    ) -> (u32, u32, [u32; 2]) {
        let (mut index, _) = self.at::<P>(c, dim, dim, None);
        if P == NESTED {
            index ^= kernel::shuffled(&DrawKeys::new(&c.own, dim), 0);
        }
        let image = DrawKeys::new(&self.z_tile0, dim);
        let [key, rank_rev] = t.entry_rev([
            c.pixel[0].wrapping_add(image.e >> 22),
            c.pixel[1].wrapping_add(image.e >> 12),
        ]);
        let shift = [image.v[0], crate::hash::hash32(dim, self.z_tile0.0[3])];
        (index ^ rank_rev, key, shift)
    }

    /// 40 random bits for the low end of [`PixelRng`]'s words, beyond the sequence's 24.
    #[inline]
    fn low_bits(&self) -> u64 {
        let k = DrawKeys::new(&self.current.own, self.dim);
        crate::hash::hash_u64(self.current.index as u64, !k.stream())
    }
}
