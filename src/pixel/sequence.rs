//! The sequences the adapter draws from, and how one draw is randomized.
//!
//! A *draw* is one call of `get_1d` / `get_2d` at a dimension `d` of a pixel sample. Every
//! draw of every pixel (and seed, and block of `2^32` samples) reads its own copy of a 2D
//! sequence, selected by a well-mixed 64-bit `stream`. What makes two copies independent is
//! different per sequence, and it matters: within one pixel sample, the values of different
//! draws meet in one integrand (the lens, the light, the next bounce), so the *pairing* of
//! sample `i` of one draw with sample `i` of another must be random. An XOR of the index or a
//! digital shift of the values is not enough for a (0,2)-sequence: both keep sample `i` of
//! every copy in corresponding strata, so the copies stay tied together (correlations near 1)
//! and a pixel's estimate converges to a wrong value.
//!
//! * `sobol`, `pmj02`: the index goes through a nested uniform shuffle (each bit flipped by a
//!   hash of the bits above it: aligned blocks of `2^m` indices map to aligned blocks, so every
//!   power-of-two prefix is still a (0,m,2)-net, while the order inside is scrambled; two
//!   rounds of Burley's hash, see [`owen_scrambled`]), then each coordinate is Owen-scrambled (Burley, "Practical Hash-based Owen Scrambling",
//!   JCGT 2020; Helmer, Christensen, Kensler, "Stochastic Generation of (t, s) Sample
//!   Sequences", EGSR 2021, for pmj02).
//! * `halton`: scrambled Halton in bases 2 and 3 for every draw, padded as Kollig and Keller
//!   ("Efficient Multidimensional Sampling", Eurographics 2002) pad 2D sets: the index is
//!   permuted at random inside aligned blocks of `M = 2^a 3^b` samples (the smallest such
//!   number at least the samples per pixel), so each block is the stratified set of `M` Halton
//!   points (one per cell of `2^a x 3^b`) in an order of its own per draw. Halton's digits tie
//!   every index permutation that keeps its prefixes to the same strata, so the prefix property
//!   is kept per block, not at every `2^a 3^b` below `M`.
//! * `jittered`: a jittered `s x s` set per block of `spp = s^2` samples, its cells visited in
//!   a hashed random order per draw.
//! * `random`: hashed independent uniform values.

use alloc::sync::Arc;

use crate::error::{Error, Result};
use crate::float::{Strata, unit_f32_from_u32};
use crate::hash::{
    DivMod, GOLDEN_GAMMA, Permutation, Stream, hash_u64, mix64, owen_scramble_base4_rev,
    owen_scramble_rev, owen_scramble_rev_lanes, owen_scrambled_unit_f32x4, stream_seed,
};
use crate::morton::morton;
use crate::prelude::*;
use crate::sampler::{Seed, StrataGrid};
use crate::samplers::pmj::stochastic;
use crate::samplers::{Pmj02Stochastic, halton, lattice, pmj, sobol};

/// Bits of the shared pmj02 table's index: `2^16` points (512 KB, lookups stay in cache).
const PMJ02_TABLE_BITS: u32 = 16;

/// Points in the shared pmj02 table; later indices are computed on demand from the same
/// sequence (`O(log i)` each).
pub const PMJ02_TABLE_LEN: usize = 1 << PMJ02_TABLE_BITS;

/// The seed of the shared pmj02 sequence.
const PMJ02_SEED: Seed = Seed(0x706d_6a30_3200);

/// The first [`PMJ02_TABLE_LEN`] points of the shared pmj02 sequence, in index order (a
/// pixel's draw reads an aligned block of it: a few cache lines), both coordinates
/// bit-reversed (the domain of the Owen scramble that follows the lookup). Built once per
/// process with `std`; without it, once per [`Sequence::pmj02`] call (about 0.3 ms; clones share
/// it).
fn pmj02_table() -> Arc<Vec<[u32; 2]>> {
    let build = || {
        let mut s = Pmj02Stochastic::new(PMJ02_SEED);
        s.reserve(PMJ02_TABLE_LEN as u64);
        let table = s
            .generated()
            .iter()
            .map(|p| [p[0].reverse_bits(), p[1].reverse_bits()])
            .collect();
        Arc::new(table)
    };
    #[cfg(feature = "std")]
    {
        static TABLE: std::sync::OnceLock<Arc<Vec<[u32; 2]>>> = std::sync::OnceLock::new();
        TABLE.get_or_init(build).clone()
    }
    #[cfg(not(feature = "std"))]
    build()
}

/// The largest block of [`Sequence::halton`]: `2^31`.
const MAX_HALTON_BLOCK: u64 = 1 << 31;

/// The smallest `2^a 3^b >= n` (at most `2^31`), with its exponents.
fn halton_block(n: u32) -> (u32, u32, u32) {
    let n = (n.max(1) as u64).min(MAX_HALTON_BLOCK);
    let mut best = (MAX_HALTON_BLOCK, 31, 0);
    let mut three = 1u64;
    for b in 0..20 {
        if three > MAX_HALTON_BLOCK {
            break;
        }
        // the smallest 2^a with 2^a 3^b >= n
        let a = n.div_ceil(three).next_power_of_two().trailing_zeros();
        let m = three << a;
        if m <= MAX_HALTON_BLOCK && m < best.0 {
            best = (m, a, b);
        }
        three *= 3;
    }
    (best.0 as u32, best.1, best.2)
}

/// A samples-per-pixel count with what the sequences derive from it, computed once when the
/// sampler is built rather than on every draw. Only `jittered` (its `s x s` sets), `halton`
/// (its blocks) and the Z-ordered sequences (the block of each pixel) use it; `random`,
/// `pmj02`, `sobol` and `lattice` are progressive and ignore it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SamplesPerPixel {
    spp: u32,
    /// Jittered: the `s^2 <= spp` cells of a set, and the side `s`.
    cells: DivMod,
    side: DivMod,
    strata: Strata,
    /// Halton: the block `M = 2^a 3^b >= spp`, and `(a, b)`.
    block: DivMod,
    block_exponents: (u32, u32),
    /// The Z-ordered sequences: `log2 B`, `B` the samples per pixel rounded up to a power of
    /// two (at most `2^31`).
    z_bits: u32,
}

impl SamplesPerPixel {
    /// The derived values of `spp` (0 is treated as 1).
    pub(crate) fn new(spp: u32) -> Self {
        let s = spp.isqrt().max(1);
        let (m, a, b) = halton_block(spp);
        SamplesPerPixel {
            spp,
            cells: DivMod::new(s * s).expect("s >= 1"),
            side: DivMod::new(s).expect("s >= 1"),
            strata: Strata::new(s as u64),
            block: DivMod::new(m).expect("m >= 1"),
            block_exponents: (a, b),
            z_bits: spp.max(1).next_power_of_two().trailing_zeros().min(31),
        }
    }

    /// `log2 B` of the Z-ordered sequences.
    #[inline]
    pub(crate) fn z_bits(&self) -> u32 {
        self.z_bits
    }

    /// `B`: the samples of a pixel's block along a Z-ordered sequence.
    #[inline]
    pub(crate) fn z_block(&self) -> u32 {
        1 << self.z_bits
    }

    /// The count.
    pub(crate) fn get(&self) -> u32 {
        self.spp
    }
}

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

/// The sequences of the adapter, chosen at run time.
#[derive(Clone, Debug)]
pub enum Sequence {
    /// Hashed independent uniform values.
    Random,
    /// A jittered `s x s` set per pixel and draw (`spp = s^2`), cells in a random order.
    Jittered,
    /// A shared stochastic pmj02 table; per draw a nested uniform shuffle of the index and an
    /// Owen scramble of the values.
    Pmj02(Arc<Vec<[u32; 2]>>),
    /// Sobol' dimensions 0-1; per draw a nested uniform shuffle of the index and an Owen
    /// scramble of the values.
    Sobol,
    /// Scrambled Halton (bases 2 and 3); per draw a random order inside blocks of `2^a 3^b`.
    Halton,
    /// Z-ordered Sobol' for an image of `[width, height]` pixels (screen-space blue-noise
    /// error): pixels take consecutive blocks of one global sequence along a scrambled Morton
    /// curve.
    ZSobol([u32; 2]),
    /// Z-ordered pmj02 (the digital form of pmj02), as [`Sequence::ZSobol`].
    ZPmj02([u32; 2]),
    /// An extensible rank-1 lattice (Cools, Kuo, Nuyens 2006, dimensions 0-1); per draw a
    /// nested uniform shuffle of the index and a toroidal shift.
    Lattice,
}

/// The largest side of the image of a Z-ordered sequence (the Morton code of a pixel has 32
/// bits).
pub const MAX_Z_RESOLUTION: u32 = 1 << 16;

/// The resolution the Z-ordered sequences take by name, without one given.
pub const DEFAULT_Z_RESOLUTION: [u32; 2] = [256, 256];

/// No place along a global sequence: the pixel draws from its own copies.
pub(crate) const NO_Z: u64 = u64::MAX;

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
        Sequence::Pmj02(pmj02_table())
    }
    /// Sobol'.
    pub fn sobol() -> Self {
        Sequence::Sobol
    }
    /// Halton.
    pub fn halton() -> Self {
        Sequence::Halton
    }
    /// The extensible rank-1 lattice.
    pub fn lattice() -> Self {
        Sequence::Lattice
    }
    /// Z-ordered Sobol' for an image of `width x height` pixels (each 1 to
    /// [`MAX_Z_RESOLUTION`]): the image must be known up front, since neighbouring pixels take
    /// neighbouring blocks of one sequence. Pixels outside it get independent values.
    pub fn zsobol(width: u32, height: u32) -> Result<Self> {
        Ok(Sequence::ZSobol(check_resolution(
            "Sequence::zsobol",
            width,
            height,
        )?))
    }
    /// Z-ordered pmj02 for an image of `width x height` pixels (see [`Sequence::zsobol`]).
    pub fn zpmj02(width: u32, height: u32) -> Result<Self> {
        Ok(Sequence::ZPmj02(check_resolution(
            "Sequence::zpmj02",
            width,
            height,
        )?))
    }

    /// The names the adapter knows.
    pub const NAMES: [&'static str; 8] = [
        "random", "jittered", "pmj02", "sobol", "halton", "lattice", "zsobol", "zpmj02",
    ];

    /// The sequence registered under `name` (one of [`Sequence::NAMES`]); the Z-ordered ones
    /// for an image of [`DEFAULT_Z_RESOLUTION`] (see [`Sequence::by_name_at`]).
    pub fn by_name(name: &str) -> Result<Self> {
        Self::by_name_at(name, DEFAULT_Z_RESOLUTION)
    }

    /// The sequence registered under `name`, the Z-ordered ones for an image of `resolution`
    /// (`[width, height]`; the others ignore it).
    pub fn by_name_at(name: &str, resolution: [u32; 2]) -> Result<Self> {
        Ok(match name {
            "random" => Self::random(),
            "jittered" => Self::jittered(),
            "pmj02" => Self::pmj02(),
            "sobol" => Self::sobol(),
            "halton" => Self::halton(),
            "lattice" => Self::lattice(),
            "zsobol" => Self::zsobol(resolution[0], resolution[1])?,
            "zpmj02" => Self::zpmj02(resolution[0], resolution[1])?,
            other => {
                return Err(Error::input(
                    "Sequence::by_name_at",
                    format!(
                        "no path-tracer adapter for '{other}'; samplers with one: {}",
                        Self::NAMES.join(", ")
                    ),
                ));
            }
        })
    }
}

impl Sequence {
    /// The place of `pixel` along the global sequence of a Z-ordered sequence: its Morton
    /// code under a nested base-4 scramble keyed by `seed` (which turns the Z curve's fixed
    /// pattern into a random one while keeping every aligned `2^k x 2^k` tile of pixels on
    /// consecutive blocks); [`NO_Z`] for the other sequences and outside the image.
    #[inline(always)]
    pub(crate) fn z_index(&self, pixel: [u32; 2], seed: u64) -> u64 {
        match self {
            Sequence::ZSobol(res) | Sequence::ZPmj02(res) => {
                if pixel[0] >= res[0] || pixel[1] >= res[1] {
                    return NO_Z;
                }
                let key = stream_seed(seed, Stream::ZOrderedPixels.id()) as u32;
                let m = morton(pixel[0], pixel[1]).reverse_bits();
                owen_scramble_base4_rev(m, key).reverse_bits() as u64
            }
            _ => NO_Z,
        }
    }
}

/// Checks the resolution of a Z-ordered sequence.
fn check_resolution(context: &'static str, width: u32, height: u32) -> Result<[u32; 2]> {
    for (name, v) in [("width", width), ("height", height)] {
        if v == 0 || v > MAX_Z_RESOLUTION {
            return Err(Error::parameter(
                context,
                name,
                v,
                format!("1 to {MAX_Z_RESOLUTION} pixels"),
            ));
        }
    }
    Ok([width, height])
}

/// Point `index` of a scrambled copy of a base-2 (0,2)-sequence. The index goes through a
/// nested uniform shuffle (an Owen scramble in the bit-reversed domain, Burley 2020);
/// `point_rev(r)` returns the unscrambled sequence's point at the shuffled index `r`, index and
/// coordinates bit-reversed; each coordinate is then Owen-scrambled with its own seed.
///
/// The shuffle is two rounds of the hash-based scramble with independent seeds (the lower and
/// upper halves of `stream`; a composition of nested scrambles is nested). One round, as in
/// Burley's paper, leaves about one pair of draws in 10^4 tied together: the hash's flips
/// depend on a few bits of its seed, so two streams can get nearly the same shuffle, and
/// their draws then differ by little more than an XOR. Measured on 196,608 pairs of draws at
/// 4096 samples (chi-square on 31 x 31 cells), one round gave chi2 up to 1363 (p ~ 1e-25),
/// two rounds at most 1239, the same as an ideal random nested shuffle (a hash per bit; 1232).
/// The value seeds are the two halves of `stream` XOR-ed (and that rotated for `y`).
#[inline]
fn owen_scrambled(
    stream: u64,
    index_rev: u32,
    point_rev: impl FnOnce(u32) -> [u32; 2],
) -> [f32; 2] {
    let p = point_rev(shuffle_rev(stream, index_rev));
    let seed = value_seed(stream);
    let x = owen_scramble_rev(p[0], seed);
    let y = owen_scramble_rev(p[1], seed.rotate_left(16) ^ 0x9e37_79b9);
    // one 64-bit reversal brings both coordinates back: reverse(x:y) = reverse(y):reverse(x)
    let both = (((x as u64) << 32) | y as u64).reverse_bits();
    [
        unit_f32_from_u32(both as u32),
        unit_f32_from_u32((both >> 32) as u32),
    ]
}

/// The value-scramble seed of `x` in [`owen_scrambled`] (`y`'s is it rotated, XOR a constant).
#[inline(always)]
fn value_seed(stream: u64) -> u32 {
    (stream as u32) ^ (stream >> 32) as u32
}

/// Two draws of [`owen_scrambled`] at once (two streams, one index), lane-parallel: the two
/// shuffles in two lanes, the four value scrambles and bit reversals in four. The same bits
/// as two calls of [`owen_scrambled`].
#[inline(always)]
fn owen_scrambled_pair(
    streams: [u64; 2],
    index_rev: u32,
    point_rev: impl Fn(u32, u64) -> [u32; 2],
) -> [f32; 4] {
    let r = owen_scramble_rev_lanes(
        owen_scramble_rev_lanes([index_rev; 2], streams.map(|s| s as u32)),
        streams.map(|s| (s >> 32) as u32),
    );
    let (p, q) = (point_rev(r[0], streams[0]), point_rev(r[1], streams[1]));
    let (a, b) = (value_seed(streams[0]), value_seed(streams[1]));
    let seeds = [
        a,
        a.rotate_left(16) ^ 0x9e37_79b9,
        b,
        b.rotate_left(16) ^ 0x9e37_79b9,
    ];
    owen_scrambled_unit_f32x4([p[0], p[1], q[0], q[1]], seeds)
}

/// The shuffled index of [`owen_scrambled`], from and to the bit-reversed domain.
#[inline]
fn shuffle_rev(stream: u64, index_rev: u32) -> u32 {
    owen_scramble_rev(
        owen_scramble_rev(index_rev, stream as u32),
        (stream >> 32) as u32,
    )
}

/// The upper bits of the block to which the shuffle of [`owen_scrambled`] sends the indices
/// `[0, 2^16)`: XOR-ing them away sends that block onto the table (and keeps the shuffle
/// nested), so that indices past `2^16` continue the same sequence on demand.
#[inline]
fn pmj02_block(stream: u64) -> u32 {
    shuffle_rev(stream, 0).reverse_bits() & !(PMJ02_TABLE_LEN as u32 - 1)
}

/// The sample of `index` in a sequence organised in blocks of `block` samples, each block a
/// stratified set whose members are visited in a random order per stream: the block number,
/// the position inside the block the index is sent to, and the block's key.
#[inline]
fn block_permuted(stream: u64, index: u32, block: &DivMod) -> (u32, u32, u64) {
    let (b, i) = block.div_rem(index);
    let key = mix64(stream ^ (b as u64).wrapping_mul(GOLDEN_GAMMA));
    // two keyed rounds: one of Kensler's hashed permutations leaves some pairs of draws
    // structured at power-of-two lengths (the conformance suite sees them); two do not
    let once = Permutation::with_divider(block, key as u32).apply(i);
    (
        b,
        Permutation::with_divider(block, (key >> 32) as u32).apply(once),
        key,
    )
}

/// The pmj02 point at the shuffled reversed index `r` of draw `i` of `stream`, bit-reversed:
/// from the table for the first `2^16` samples, on demand past them.
#[inline(always)]
fn pmj02_point_rev(table: &[[u32; 2]], i: u32, r: u32, stream: u64) -> [u32; 2] {
    let j = r.reverse_bits();
    if (i as usize) < PMJ02_TABLE_LEN {
        // the shuffle sends [0, 2^16) to an aligned block: its low bits index it
        table[j as usize & (PMJ02_TABLE_LEN - 1)]
    } else {
        let p = Pmj02Stochastic::point_at_fixed(PMJ02_SEED, j ^ pmj02_block(stream));
        [p[0].reverse_bits(), p[1].reverse_bits()]
    }
}

impl Sequence {
    /// The registered name of the underlying sampler.
    pub fn name(&self) -> &'static str {
        match self {
            Sequence::Random => "random",
            Sequence::Jittered => "jittered",
            Sequence::Pmj02(_) => "pmj02",
            Sequence::Sobol => "sobol",
            Sequence::Halton => "halton",
            Sequence::Lattice => "lattice",
            Sequence::ZSobol(_) => "zsobol",
            Sequence::ZPmj02(_) => "zpmj02",
        }
    }

    /// The 2D point `index` of the copy of the sequence selected by `stream` (a well-mixed
    /// 64-bit value).
    #[inline(always)]
    pub(crate) fn sample_2d(
        &self,
        stream: u64,
        index: SampleIndex,
        spp: &SamplesPerPixel,
    ) -> [f32; 2] {
        let (i, i_rev) = (index.get(), index.reversed());
        match self {
            Sequence::Random => {
                let h = hash_u64(stream, i as u64);
                [
                    unit_f32_from_u32(h as u32),
                    unit_f32_from_u32((h >> 32) as u32),
                ]
            }
            Sequence::Jittered => {
                let (_, k, key) = block_permuted(stream, i, &spp.cells);
                let (row, col) = spp.side.div_rem(k);
                let h = hash_u64(key, k as u64);
                spp.strata
                    .place2([col, row], [h as u32, (h >> 32) as u32])
                    .to_array()
            }
            Sequence::Pmj02(table) => {
                owen_scrambled(stream, i_rev, |r| pmj02_point_rev(table, i, r, stream))
            }
            Sequence::Sobol | Sequence::ZSobol(_) => {
                owen_scrambled(stream, i_rev, sobol::point01_rev)
            }
            Sequence::ZPmj02(_) => owen_scrambled(stream, i_rev, stochastic::digital_point01_rev),
            Sequence::Lattice => {
                // phi_2 of the shuffled index is its bit reversal: the lattice in fixed point
                let r = shuffle_rev(stream, i_rev);
                let shift = mix64(stream);
                [
                    unit_f32_from_u32(r.wrapping_add(shift as u32)),
                    unit_f32_from_u32(
                        r.wrapping_mul(lattice::GENERATOR[1])
                            .wrapping_add((shift >> 32) as u32),
                    ),
                ]
            }
            Sequence::Halton => {
                let (b, j, _) = block_permuted(stream, i, &spp.block);
                let g = b as u64 * spp.block.divisor() as u64 + j as u64;
                [
                    halton::scrambled_radical_inverse(0, g, stream),
                    halton::scrambled_radical_inverse(1, g, stream),
                ]
            }
        }
    }

    /// A 1D value: the first coordinate of [`sample_2d`](Sequence::sample_2d).
    #[inline(always)]
    pub(crate) fn sample_1d(&self, stream: u64, index: SampleIndex, spp: &SamplesPerPixel) -> f32 {
        match self {
            // the second coordinate (base 3) is most of the cost: skip it
            Sequence::Halton => {
                let (b, j, _) = block_permuted(stream, index.get(), &spp.block);
                let g = b as u64 * spp.block.divisor() as u64 + j as u64;
                halton::scrambled_radical_inverse(0, g, stream)
            }
            _ => self.sample_2d(stream, index, spp)[0],
        }
    }

    /// Two 2D draws at once, of `streams[0]` and `streams[1]` at the same index: the same
    /// values as two calls of [`sample_2d`](Sequence::sample_2d), lane-parallel for the
    /// Owen-scrambled sequences.
    #[inline]
    pub(crate) fn sample_4d(
        &self,
        streams: [u64; 2],
        index: SampleIndex,
        spp: &SamplesPerPixel,
    ) -> [f32; 4] {
        let (i, i_rev) = (index.get(), index.reversed());
        match self {
            Sequence::Pmj02(table) => {
                owen_scrambled_pair(streams, i_rev, |r, s| pmj02_point_rev(table, i, r, s))
            }
            Sequence::Sobol | Sequence::ZSobol(_) => {
                owen_scrambled_pair(streams, i_rev, |r, _| sobol::point01_rev(r))
            }
            Sequence::ZPmj02(_) => {
                owen_scrambled_pair(streams, i_rev, |r, _| stochastic::digital_point01_rev(r))
            }
            _ => {
                let [a, b] = self.sample_2d(streams[0], index, spp);
                let [c, d] = self.sample_2d(streams[1], index, spp);
                [a, b, c, d]
            }
        }
    }

    /// The sample count nearest above `n` at which the sequence is best stratified (a square
    /// for jittered, a power of two for pmj02 and Sobol', `2^a 3^b` for Halton).
    pub fn round_count(&self, n: u32) -> u32 {
        let n = n.max(1);
        match self {
            Sequence::Random => n,
            Sequence::Halton => halton_block(n).0,
            Sequence::Jittered => {
                let s = n.isqrt();
                if s * s == n { n } else { (s + 1) * (s + 1) }
            }
            Sequence::Pmj02(_)
            | Sequence::Sobol
            | Sequence::Lattice
            | Sequence::ZSobol(_)
            | Sequence::ZPmj02(_) => n.checked_next_power_of_two().unwrap_or(1 << 31),
        }
    }

    /// Checks a samples-per-pixel count: at least 1, a square for jittered.
    pub fn check_spp(&self, spp: u32) -> Result<()> {
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

    /// The grids on which the first `n` samples of every draw lie, each cell holding the same
    /// number of points (empty where the sequence promises none at `n`).
    pub(crate) fn promised_strata(&self, spp: &SamplesPerPixel, n: u64) -> Vec<StrataGrid> {
        let whole_blocks = |m: u32| n > 0 && n.is_multiple_of(m as u64);
        match self {
            Sequence::Random => Vec::new(),
            Sequence::Jittered if whole_blocks(spp.cells.divisor()) => {
                let s = spp.side.divisor();
                vec![StrataGrid {
                    columns: s,
                    rows: s,
                }]
            }
            Sequence::Halton if whole_blocks(spp.block.divisor()) => {
                let (a, b) = spp.block_exponents;
                vec![StrataGrid {
                    columns: 1 << a,
                    rows: 3u32.pow(b),
                }]
            }
            Sequence::Pmj02(_) | Sequence::Sobol => pmj::pmj_grids(n, true),
            // inside a pixel's block of the global sequence: an aligned block, a net
            Sequence::ZSobol(_) | Sequence::ZPmj02(_) if n <= spp.z_block() as u64 => {
                pmj::pmj_grids(n, true)
            }
            Sequence::Lattice if n.is_power_of_two() && n <= 1 << 31 => vec![
                StrataGrid {
                    columns: n as u32,
                    rows: 1,
                },
                StrataGrid {
                    columns: 1,
                    rows: n as u32,
                },
            ],
            _ => Vec::new(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn halton_blocks_are_the_smallest_products_of_two_and_three() {
        for n in 1..2000u32 {
            let (m, a, b) = halton_block(n);
            assert_eq!(m as u64, (1u64 << a) * 3u64.pow(b));
            assert!(m >= n);
            // no 2^a 3^b in [n, m)
            for k in n..m {
                let mut r = k;
                while r % 2 == 0 {
                    r /= 2;
                }
                while r % 3 == 0 {
                    r /= 3;
                }
                assert_ne!(r, 1, "{k} = 2^a 3^b lies between {n} and {m}");
            }
        }
        assert_eq!(halton_block(u32::MAX).0, 1 << 31);
    }

    #[test]
    fn the_pmj02_table_and_the_on_demand_path_give_the_same_shuffle() {
        // Indices below 2^16 come from the table; the same (shuffled) point computed on demand
        // must agree, or the two halves of a prefix of 2^17 would not form one sequence.
        let table = pmj02_table();
        for stream in [1u64, 0xdead_beef_1234_5678, u64::MAX] {
            for index in [0u32, 1, 2, 77, 4095, 65535] {
                let j =
                    shuffle_rev(stream, index.reverse_bits()).reverse_bits() ^ pmj02_block(stream);
                assert!(
                    j < PMJ02_TABLE_LEN as u32,
                    "index {index} left the table: {j}"
                );
                let p = Pmj02Stochastic::point_at_fixed(PMJ02_SEED, j);
                assert_eq!(
                    table[j as usize],
                    [p[0].reverse_bits(), p[1].reverse_bits()]
                );
            }
        }
    }
}
