//! The sequences the adapter draws from, and how one draw is randomized.
//!
//! A *draw* is one call of `get_1d` / `get_2d` at a dimension `d` of a pixel sample. Every
//! draw of every pixel (and seed, and block of `2^32` samples) reads its own copy of a 2D
//! sequence, selected by its [draw keys](super::kernel). What makes two copies independent is
//! different per sequence, and it matters: within one pixel sample, the values of different
//! draws meet in one integrand (the lens, the light, the next bounce), so the *pairing* of
//! sample `i` of one draw with sample `i` of another must be random. An XOR of the index or a
//! digital shift of the values is not enough for a (0,2)-sequence: both keep sample `i` of
//! every copy in corresponding strata, so the copies stay tied together (correlations near 1)
//! and a pixel's estimate converges to a wrong value.
//!
//! * `sobol`, `pmj02`: the index goes through a nested uniform shuffle (aligned blocks of
//!   `2^m` indices map to aligned blocks, so every power-of-two prefix is still a
//!   (0,m,2)-net, while the order inside is scrambled: [`crate::scramble::shuffle_rev`]), then
//!   the digital (0,2)-sequence's point at the shuffled index has each coordinate
//!   Owen-scrambled (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020). `pmj02` is the
//!   digital form of pmj02 (Helmer, Christensen, Kensler, "Stochastic Generation of (t, s)
//!   Sample Sequences", EGSR 2021), whose Owen scrambling is distributed as their stochastic
//!   pmj02; both are computed on demand from 8 KiB of tables ([`crate::digital`]).
//! * `lattice`: the shuffled index's point of the rank-1 lattice, shifted on the torus.
//! * `zsobol`, `zpmj02`: as `sobol` and `pmj02`, but pixels take consecutive blocks of one
//!   global sequence along a scrambled Morton curve (screen-space blue-noise error; Ahmed and
//!   Wonka, "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical
//!   Ordering of Pixels", SIGGRAPH Asia 2020, as pbrt-v4's `ZSobolSampler`). Each draw orders
//!   the pixels anew: the Morton code's base-4 digits go through a nested scramble keyed by the
//!   image and the draw's dimension (Vegdahl's base-4 hash, then a random affine map of each
//!   digit position over GF(2)^2, so that every one of the 24 permutations of a digit occurs),
//!   which keeps every aligned `2^k x 2^k` tile of pixels on consecutive blocks and each
//!   pixel's block a (0,m,2)-net per draw. Only the image's digits are permuted, so a pixel's
//!   place depends on the image's size (its `ceil(log2(max side))`), not on its position alone.
//! * `zquad`: as `zjoint` in groups of four dimensions, whose draws read the binary form of
//!   Faure's base-4 (0,4)-sequence (Faure, Acta Arith. 41, 1982; [`crate::digital`] builds
//!   its 2x2-block generator matrices): a pixel's first `4^k` samples of a group's four
//!   dimensions are a (0,k,4)-net in base 4, and its draws at the group's first and third
//!   dimension are (0,2)-sequences, as `zsobol`'s draws are. The property the SZ sequences of
//!   Ahmed, Pharr, Ostromoukhov and Huang (TOG 2025) are built for, by a construction of our
//!   own (their paper was not available to us).
//! * `sobol12`, `zsobol12`: the draws of a group of dimensions share one index (shuffled
//!   once per group, as `sobol`'s is per draw) and read consecutive dimensions of the
//!   (1,2)-Sobol' sequence (Bonneel, Coeurjolly, Iehl, Ostromoukhov, "Sobol' Sequences with
//!   Guaranteed-Quality 2D Projections", ACM TOG 44(4), 2025), each value Owen-scrambled under
//!   the draw's own keys: a 2D draw at a group's even dimension is a (1,2)-sequence. `zsobol12`
//!   Z-orders the groups as `zjoint` does.
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
//!
//! `halton` and `jittered` divide by the block size and hash with 64-bit arithmetic: they run on
//! the CPU only. The others are the [kernel](super::kernel)'s, 32-bit throughout.

use alloc::sync::Arc;

use super::SampleIndex;
use super::kernel::{self, DrawKeys, PixelKeys};
use crate::digital::{ByteTables, PMJ02, PairTables, SOBOL01};
use crate::error::{Error, Result};
use crate::float::Strata;
use crate::hash::{DivMod, GOLDEN_GAMMA, Permutation, hash_u64, mix64};
use crate::prelude::*;
use crate::sampler::StrataGrid;
use crate::samplers::halton;
use crate::scramble::{Lanes, X2, join, owen_scramble_lanes};

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
            z_bits: spp
                .max(1)
                .checked_next_power_of_two()
                .map_or(32, u32::trailing_zeros)
                .min(31),
        }
    }

    /// `log2 B` of the Z-ordered sequences.
    #[inline]
    pub(crate) fn z_bits(&self) -> u32 {
        self.z_bits
    }

    /// The count.
    pub(crate) fn get(&self) -> u32 {
        self.spp
    }
}

/// What a sequence is, without its parameters: the kernel's dispatch. The discriminant is the
/// sequence's row in [`ROWS`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Kind {
    Random,
    Jittered,
    Pmj02,
    Sobol,
    Halton,
    Lattice,
    ZSobol,
    ZPmj02,
    ZQuad,
    ZJoint,
    Sobol12,
    ZSobol12,
}

/// What the samples-per-pixel count does to a sequence.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SppUse {
    /// Nothing: the sequence is progressive.
    Ignored,
    /// A square `s x s` is the size of each set (and must be a square).
    Square,
    /// Blocks of the smallest `2^a 3^b >= spp`.
    HaltonBlocks,
    /// Rounded up to a power of two: each pixel's block of the global sequence (Z order).
    PixelBlock,
}

impl SppUse {
    /// The words of the sequence table.
    const fn words(self) -> &'static str {
        match self {
            SppUse::Ignored => "ignored (progressive)",
            SppUse::Square => "a square `s x s`: the size of each set",
            SppUse::HaltonBlocks => "blocks of the smallest `2^a 3^b >= spp`",
            SppUse::PixelBlock => "rounded up to a power of two: each pixel's block",
        }
    }
}

/// One adapter sequence, declared once: its name, how it is built by name, what the
/// samples-per-pixel count does to it, what each draw promises, its source, and its number in
/// the kernel and the shader. [`Sequence::NAMES`], [`Sequence::name`], [`Sequence::by_name`],
/// [`Sequence::table`] (the module docs' table, the programs' lists) read these rows; the draws
/// dispatch on [`Kind`] (the kernel arm). Adding a sequence is its kernel arm, one row, its WGSL
/// and a case in the GPU test.
pub(crate) struct Row {
    #[cfg_attr(not(test), allow(dead_code))] // (row k is Kind k: its test reads it)
    pub(crate) kind: Kind,
    pub(crate) name: &'static str,
    /// The suffix the name takes (`zjoint-G`), in words; `""` for none.
    suffix: &'static str,
    /// The sequence for an image of `resolution` (the Z-ordered ones) and the suffix after
    /// `name-` (`None` without one; never `Some` for a row whose `suffix` is empty).
    make: fn([u32; 2], Option<&str>) -> Result<Sequence>,
    /// The constructor, as the docs write it.
    build: &'static str,
    pub(crate) spp: SppUse,
    /// What each draw's samples promise.
    promise: &'static str,
    source: &'static str,
    /// The kernel's and the shader's number (`None`: CPU only).
    pub(crate) shader: Option<u32>,
    /// Whether [`Padding::Uniform`](super::Padding::Uniform) changes it (the digital
    /// sequences and the lattice).
    pub(crate) pads: bool,
}

/// Every sequence, in the order of [`Sequence::NAMES`] (row `k` is the sequence of [`Kind`]
/// `k`: a test checks it).
pub(crate) const ROWS: [Row; 12] = [
    Row {
        kind: Kind::Random,
        name: "random",
        suffix: "",
        make: |_, _| Ok(Sequence::random()),
        build: "`Sequence::random()`",
        spp: SppUse::Ignored,
        promise: "independent uniform values (hashed)",
        source: "-",
        shader: Some(0),
        pads: false,
    },
    Row {
        kind: Kind::Jittered,
        name: "jittered",
        suffix: "",
        make: |_, _| Ok(Sequence::jittered()),
        build: "`Sequence::jittered()`",
        spp: SppUse::Square,
        promise: "one value per cell of `s x s` in each set of `spp`",
        source: "Cook 1986",
        shader: None,
        pads: false,
    },
    Row {
        kind: Kind::Pmj02,
        name: "pmj02",
        suffix: "",
        make: |_, _| Ok(Sequence::pmj02()),
        build: "`Sequence::pmj02()`",
        spp: SppUse::Ignored,
        promise: "every power-of-two prefix a (0,m,2)-net; Owen-scrambled",
        source: "Christensen et al. 2018, Helmer et al. 2021",
        shader: Some(2),
        pads: true,
    },
    Row {
        kind: Kind::Sobol,
        name: "sobol",
        suffix: "",
        make: |_, _| Ok(Sequence::sobol()),
        build: "`Sequence::sobol()`",
        spp: SppUse::Ignored,
        promise: "every power-of-two prefix a (0,m,2)-net; Owen-scrambled",
        source: "Sobol' 1967, Burley 2020",
        shader: Some(1),
        pads: true,
    },
    Row {
        kind: Kind::Halton,
        name: "halton",
        suffix: "",
        make: |_, _| Ok(Sequence::halton()),
        build: "`Sequence::halton()`",
        spp: SppUse::HaltonBlocks,
        promise: "each block's `2^a x 3^b` strata, one value each",
        source: "Halton 1960",
        shader: None,
        pads: false,
    },
    Row {
        kind: Kind::Lattice,
        name: "lattice",
        suffix: "",
        make: |_, _| Ok(Sequence::lattice()),
        build: "`Sequence::lattice()`",
        spp: SppUse::Ignored,
        promise: "`n x 1` and `1 x n` strata at every power of two; shifted",
        source: "Cools, Kuo, Nuyens 2006",
        shader: Some(3),
        pads: true,
    },
    Row {
        kind: Kind::ZSobol,
        name: "zsobol",
        suffix: "",
        make: |r, _| Sequence::zsobol(r[0], r[1]),
        build: "`Sequence::zsobol(width, height)`",
        spp: SppUse::PixelBlock,
        promise: "as `sobol` per pixel; pixels along a scrambled Z curve (blue-noise error)",
        source: "Ahmed, Wonka 2020",
        shader: Some(4),
        pads: true,
    },
    Row {
        kind: Kind::ZPmj02,
        name: "zpmj02",
        suffix: "",
        make: |r, _| Sequence::zpmj02(r[0], r[1]),
        build: "`Sequence::zpmj02(width, height)`",
        spp: SppUse::PixelBlock,
        promise: "as `pmj02` per pixel; pixels along a scrambled Z curve",
        source: "Ahmed, Wonka 2020",
        shader: Some(5),
        pads: true,
    },
    Row {
        kind: Kind::ZQuad,
        name: "zquad",
        suffix: "",
        make: |r, _| Sequence::zquad(r[0], r[1]),
        build: "`Sequence::zquad(width, height)`",
        spp: SppUse::PixelBlock,
        promise: "the Z order shared by a group of 4 draws, which read the dimensions of a \
                  base-4 (0,4)-sequence: jointly a (0,k,4)-net at `4^k`",
        source: "Ahmed, Wonka 2020; Faure 1982",
        // the same shader as zjoint: the table says which matrices
        shader: Some(6),
        pads: true,
    },
    Row {
        kind: Kind::ZJoint,
        name: "zjoint",
        suffix: "`zjoint-G`: groups of `G` dimensions, a power of two from 2 to 512 (default 8)",
        make: |r, s| Sequence::zjoint(r[0], r[1], group_by_name("zjoint", s, DEFAULT_JOINT_GROUP)?),
        build: "`Sequence::zjoint(width, height, group)`",
        spp: SppUse::PixelBlock,
        promise: "the Z order shared by a group's draws, which read distinct Sobol' dimensions",
        source: "Ahmed, Wonka 2020; Joe, Kuo 2008",
        shader: Some(6),
        pads: true,
    },
    Row {
        kind: Kind::Sobol12,
        name: "sobol12",
        suffix: "`sobol12-G`: groups of `G` dimensions, a power of two from 2 to 512 (default 4)",
        make: |_, s| Sequence::sobol12(group_by_name("sobol12", s, DEFAULT_ONE_TWO_GROUP)?),
        build: "`Sequence::sobol12(group)`",
        spp: SppUse::Ignored,
        promise: "one index per group of draws; the 2D draw at a group's dimension `2k` a \
                  (1,2)-sequence (`2k = 0`: a (0,2)-sequence); Owen-scrambled",
        source: "Bonneel et al. 2025",
        shader: Some(7),
        pads: true,
    },
    Row {
        kind: Kind::ZSobol12,
        name: "zsobol12",
        suffix: "`zsobol12-G`: groups of `G` dimensions, as `sobol12-G`",
        make: |r, s| {
            Sequence::zsobol12(
                r[0],
                r[1],
                group_by_name("zsobol12", s, DEFAULT_ONE_TWO_GROUP)?,
            )
        },
        build: "`Sequence::zsobol12(width, height, group)`",
        spp: SppUse::PixelBlock,
        promise: "as `sobol12` per pixel; the Z order shared by a group's draws",
        source: "Bonneel et al. 2025; Ahmed, Wonka 2020",
        shader: Some(6),
        pads: true,
    },
];

/// The group size of a joint sequence named `name-G` (`suffix` the `G`; `default` without).
fn group_by_name(name: &str, suffix: Option<&str>, default: u32) -> Result<u32> {
    match suffix {
        None => Ok(default),
        Some(g) => g.parse::<u32>().map_err(|_| {
            Error::input(
                "Sequence::by_name",
                format!(
                    "'{name}-{g}': {name}-G takes a group size G, a power of two from 2 to \
                     {MAX_JOINT_GROUP}"
                ),
            )
        }),
    }
}

/// The names of [`ROWS`], in order.
const NAMES: [&str; ROWS.len()] = {
    let mut names = [""; ROWS.len()];
    let mut k = 0;
    while k < ROWS.len() {
        names[k] = ROWS[k].name;
        k += 1;
    }
    names
};

impl Kind {
    /// The sequence's row.
    #[inline]
    pub(crate) fn row(self) -> &'static Row {
        &ROWS[self as usize]
    }

    /// Whether pixels read blocks of one global sequence (Z order).
    pub(crate) fn z_ordered(self) -> bool {
        self.row().spp == SppUse::PixelBlock
    }
}

/// One of the adapter's sequences, chosen at run time: build it with a constructor
/// ([`Sequence::sobol`], [`Sequence::zsobol`], ...) or by name ([`Sequence::by_name`]); every
/// constructor validates its arguments, so a `Sequence` is always usable.
#[derive(Clone)]
pub struct Sequence {
    kind: Kind,
    /// The image of a Z-ordered sequence (`[0, 0]` for the others).
    resolution: [u32; 2],
    /// The digital sequence a `sobol`, `pmj02`, `zsobol` or `zpmj02` reads (one branch on the
    /// draw path instead of a dispatch on the kind).
    digital: Option<&'static PairTables>,
    /// The dimensions of a group of `zjoint` (a power of two, at least 2) or `zquad` (4),
    /// whose draws share one index; 1 for the other sequences (every draw its own group).
    group: u32,
    /// The byte tables `zjoint` (Sobol') and `zquad` (Faure, base 4) read, built when the
    /// sequence is made and shared by its clones (empty for the others).
    joint: Arc<[ByteTables]>,
}

impl core::fmt::Debug for Sequence {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Sequence")
            .field("name", &self.name())
            .field("resolution", &self.resolution)
            .field("group", &self.group)
            .finish()
    }
}

impl PartialEq for Sequence {
    fn eq(&self, other: &Self) -> bool {
        (self.kind, self.resolution, self.group) == (other.kind, other.resolution, other.group)
    }
}

impl Eq for Sequence {}

impl core::hash::Hash for Sequence {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        (self.kind, self.resolution, self.group).hash(state);
    }
}

/// The dimensions of a group of [`Sequence::zjoint`] by name: the default
/// [`DimensionLayout`](super::DimensionLayout)'s blocks (the camera's, each bounce's).
const DEFAULT_JOINT_GROUP: u32 = 8;

/// The dimensions of a group of [`Sequence::sobol12`] and [`Sequence::zsobol12`] by name: two
/// 2D draws, the table's pairs `(0, 1)` and `(2, 3)`. The (1,2)-Sobol' table's other pairs are
/// worse than Joe and Kuo's (`t` up to 10 among its first 9 dimensions, against 5), and the
/// conformance suite's chi-square of two draws of a group of 8 fails (dimensions 1 and 5);
/// in groups of 4 every pair of the draws has `t <= 3` and the suite passes.
const DEFAULT_ONE_TWO_GROUP: u32 = 4;

/// The largest group of [`Sequence::zjoint`] (a path of 63 bounces at 8 dimensions each).
const MAX_JOINT_GROUP: u32 = 512;

/// The largest side of the image of a Z-ordered sequence (the Morton code of a pixel has 32
/// bits).
const MAX_Z_RESOLUTION: u32 = 1 << 16;

impl Sequence {
    fn of(kind: Kind) -> Self {
        Sequence {
            kind,
            resolution: [0, 0],
            digital: Self::digital_table(kind),
            group: 1,
            joint: Arc::from([]),
        }
    }

    /// The digital sequence a kind reads, if it is a digital one.
    fn digital_table(kind: Kind) -> Option<&'static PairTables> {
        match kind {
            Kind::Sobol | Kind::ZSobol => Some(&SOBOL01),
            Kind::Pmj02 | Kind::ZPmj02 => Some(&PMJ02),
            _ => None,
        }
    }
    /// Independent uniform values.
    pub fn random() -> Self {
        Self::of(Kind::Random)
    }
    /// Jittered sets (the samples per pixel must be a square).
    pub fn jittered() -> Self {
        Self::of(Kind::Jittered)
    }
    /// pmj02 (its digital form, Owen-scrambled).
    pub fn pmj02() -> Self {
        Self::of(Kind::Pmj02)
    }
    /// Sobol'.
    pub fn sobol() -> Self {
        Self::of(Kind::Sobol)
    }
    /// Halton.
    pub fn halton() -> Self {
        Self::of(Kind::Halton)
    }
    /// The extensible rank-1 lattice.
    pub fn lattice() -> Self {
        Self::of(Kind::Lattice)
    }
    /// Z-ordered Sobol' for an image of `width x height` pixels (each 1 to 65536): the image
    /// must be known up front, since neighbouring pixels take neighbouring blocks of one
    /// sequence. Pixels outside it get independent values.
    pub fn zsobol(width: u32, height: u32) -> Result<Self> {
        Self::z(Kind::ZSobol, "Sequence::zsobol", width, height)
    }
    /// Z-ordered pmj02 for an image of `width x height` pixels (see [`Sequence::zsobol`]).
    pub fn zpmj02(width: u32, height: u32) -> Result<Self> {
        Self::z(Kind::ZPmj02, "Sequence::zpmj02", width, height)
    }

    fn z(kind: Kind, context: &'static str, width: u32, height: u32) -> Result<Self> {
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
        Ok(Sequence {
            resolution: [width, height],
            ..Self::of(kind)
        })
    }

    /// Jointly Z-ordered Sobol' for an image of `width x height` pixels (see
    /// [`Sequence::zsobol`]), its dimensions in groups of `group` (a power of two from 2 to
    /// 512; 8, the default by name, matches the default
    /// [`DimensionLayout`](super::DimensionLayout), one group per bounce): every draw of a
    /// group of a pixel sample reads the same Z-ordered index (one pixel order, one padding
    /// and one index shuffle per group), and the draws take *distinct* dimensions of the
    /// multi-dimensional Sobol' sequence (the draw at dimension `d` reads Sobol' dimensions
    /// `d mod group` and the next), each Owen-scrambled under its own key. A pixel's samples
    /// are then stratified jointly across the draws of a group, not only draw by draw, and
    /// neighbouring pixels take neighbouring blocks of the joint sequence; groups are
    /// independent of each other.
    ///
    /// Within a group only Sobol' dimensions 0 and 1 (the first draw) are a `(0, 2)`-sequence;
    /// the others' pairs have the t-values of consecutive Joe-Kuo dimensions
    /// ([`crate::samplers::sobol::projection_t_value`]), so a lone draw past the first is less
    /// finely stratified than `zsobol`'s. Reads `group + 1` Sobol' dimensions, whose tables
    /// (4 KiB each) it builds when it is made. On a GPU: [`WGSL_ZJOINT`](super::WGSL_ZJOINT)
    /// with [`gpu_joint_table`](Self::gpu_joint_table).
    pub fn zjoint(width: u32, height: u32, group: u32) -> Result<Self> {
        let context = "Sequence::zjoint";
        let mut s = Self::z(Kind::ZJoint, context, width, height)?;
        s.set_group(context, group, &crate::digital::SOBOL)?;
        Ok(s)
    }

    /// (1,2)-Sobol' draws from one index per group of `group` dimensions (a power of two
    /// from 2 to 512; 4, the default by name, is two 2D draws, see below): every draw of a
    /// group of a pixel sample
    /// reads the group's index (one padding and one index shuffle per group, keyed by its
    /// first dimension), and the draw at the group's dimension `o` reads dimensions `o` and
    /// `o + 1` of the (1,2)-Sobol' sequence of N. Bonneel, D. Coeurjolly, J.-C. Iehl and V.
    /// Ostromoukhov ("Sobol' Sequences with Guaranteed-Quality 2D Projections", ACM TOG 44(4),
    /// 2025), each coordinate Owen-scrambled under the draw's own keys. The 2D draws at even
    /// dimensions of a group are (1,2)-sequences (each aligned block of `2^m` samples, every
    /// prefix included, a (1,m,2)-net: two samples in each elementary interval of area
    /// `2^(1-m)`), the first a (0,2)-sequence, where padded `sobol`'s draws are each a
    /// (0,2)-sequence but pair with each other at random: here the draws of a group are one
    /// point set, stratified jointly where the table's pairs of dimensions are. Draws past a
    /// group start a new group (padded to it, as `sobol` pads every draw), so a path of any
    /// length is served. Larger groups tie more draws together, but through the table's
    /// other pairs of dimensions, which are worse than Joe and Kuo's: in groups of 8 the
    /// draws at a group's dimensions 1 and 5 fail the lab's chi-square test of two draws
    /// (`t = 3` at 4096 samples), in groups of 4 every pair has `t <= 3` at every `2^m`
    /// (`t <= 1` but for the pairs (0, 3) and (1, 3)). Reads `group + 1` of the table's 692
    /// dimensions, whose tables (4 KiB each) it builds when it is made. On a GPU: sequence 7 of
    /// [`WGSL_ZJOINT`](super::WGSL_ZJOINT) with [`gpu_joint_table`](Self::gpu_joint_table).
    pub fn sobol12(group: u32) -> Result<Self> {
        let mut s = Self::of(Kind::Sobol12);
        s.set_group("Sequence::sobol12", group, &crate::digital::ONE_TWO_SOBOL)?;
        Ok(s)
    }

    /// [`Sequence::sobol12`] Z-ordered as [`Sequence::zjoint`] is, for an image of `width x
    /// height` pixels: the draws of a group share one pixel order, and read the (1,2)-Sobol'
    /// table instead of Joe and Kuo's. On a GPU as `zjoint`.
    pub fn zsobol12(width: u32, height: u32, group: u32) -> Result<Self> {
        let context = "Sequence::zsobol12";
        let mut s = Self::z(Kind::ZSobol12, context, width, height)?;
        s.set_group(context, group, &crate::digital::ONE_TWO_SOBOL)?;
        Ok(s)
    }

    /// Sets the group of a joint sequence (a power of two from 2 to [`MAX_JOINT_GROUP`]) and
    /// builds the tables of its dimensions `0..=group` of `matrices`.
    fn set_group(
        &mut self,
        context: &'static str,
        group: u32,
        matrices: &[crate::digital::Matrix],
    ) -> Result<()> {
        if !group.is_power_of_two() || !(2..=MAX_JOINT_GROUP).contains(&group) {
            return Err(Error::parameter(
                context,
                "group",
                group,
                format!("a power of two from 2 to {MAX_JOINT_GROUP} dimensions"),
            ));
        }
        self.group = group;
        self.joint = matrices[..=group as usize]
            .iter()
            .map(crate::digital::byte_tables)
            .collect();
        Ok(())
    }

    /// Jointly Z-ordered over a base-4 (0,4)-sequence, for an image of `width x height` pixels
    /// (see [`Sequence::zsobol`]): [`Sequence::zjoint`] in groups of 4 dimensions, whose draws
    /// read the binary form of Faure's (0,4)-sequence in base 4 (Faure, "Discrépance de suites
    /// associées à un système de numération (en dimension s)", Acta Arith. 41, 1982) instead of
    /// Sobol' dimensions: a pixel's first `4^k` samples of a group's four dimensions are a
    /// (0,k,4)-net in base 4 (every box of `4^-a x 4^-b x 4^-c x 4^-d` with `a + b + c + d =
    /// k` holds one), its dimensions 0-1 and 2-3 (the draws at the group's first and third
    /// dimension) are binary (0,2)-sequences as `zsobol`'s draws are, and the other pairs of
    /// the four have `t = 1`. A 2D draw at a group's last dimension pairs it with a fifth
    /// matrix ([`crate::samplers::sobol::projection_t_value`] gives every pair's t). On a GPU
    /// as `zjoint` ([`gpu_joint_table`](Self::gpu_joint_table)).
    pub fn zquad(width: u32, height: u32) -> Result<Self> {
        let mut s = Self::z(Kind::ZQuad, "Sequence::zquad", width, height)?;
        s.group = 4;
        s.joint = Arc::from(&crate::digital::FAURE4[..]);
        Ok(s)
    }

    /// The names the adapter knows, in the order of [`Sequence::table`] (`zjoint` also as
    /// `zjoint-G`, groups of `G` dimensions).
    pub const NAMES: &'static [&'static str] = &NAMES;

    /// The table of every sequence (Markdown: name, constructor, what the samples-per-pixel
    /// count does, what each draw promises, whether the [`WGSL`](super::WGSL) shader has it, the
    /// source), as the [module docs](super#sequences) show it; generated from the one row
    /// that declares each sequence.
    pub fn table() -> String {
        let mut t = String::from(
            "| name | build | samples per pixel | each draw's samples | GPU | source |\n\
             |---|---|---|---|---|---|\n",
        );
        for row in &ROWS {
            let gpu = match row.shader {
                Some(id) => format!("sequence {id}"),
                None => String::from("CPU only"),
            };
            let name = if row.suffix.is_empty() {
                format!("`{}`", row.name)
            } else {
                format!("`{}` ({})", row.name, row.suffix)
            };
            t.push_str(&format!(
                "| {name} | {} | {} | {} | {gpu} | {} |\n",
                row.build,
                row.spp.words(),
                row.promise,
                row.source
            ));
        }
        t
    }

    /// The sequence named `name` (one of [`Sequence::NAMES`], or `zjoint-G`), the Z-ordered
    /// ones for an image of `resolution` (`[width, height]`; the others ignore it).
    pub fn by_name(name: &str, resolution: [u32; 2]) -> Result<Self> {
        if let Some(row) = ROWS.iter().find(|r| r.name == name) {
            return (row.make)(resolution, None);
        }
        if let Some(row) = ROWS.iter().find(|r| {
            name.len() > r.name.len() + 1
                && name.starts_with(r.name)
                && name.as_bytes()[r.name.len()] == b'-'
        }) {
            let suffix = &name[row.name.len() + 1..];
            if row.suffix.is_empty() {
                return Err(Error::input(
                    "Sequence::by_name",
                    format!("'{name}': {} takes no suffix", row.name),
                ));
            }
            return (row.make)(resolution, Some(suffix));
        }
        Err(Error::input(
            "Sequence::by_name",
            format!(
                "no path-tracer sequence named '{name}'; the sequences: {}",
                Self::NAMES.join(", ")
            ),
        ))
    }

    /// The name of the sequence (without the suffix: `zjoint` for every group size).
    pub fn name(&self) -> &'static str {
        self.kind.row().name
    }

    /// The dimensions of a group whose draws share one index: the group size of `zjoint`,
    /// `zquad` (4), `sobol12` and `zsobol12`; 1 for the other sequences.
    pub fn group(&self) -> u32 {
        self.group
    }

    /// The table of a joint sequence (`zjoint`, `zquad`, `sobol12`, `zsobol12`) for the
    /// [`WGSL_ZJOINT`](super::WGSL_ZJOINT) shader (`None` for the other sequences): word 0 the
    /// group size `G`, then the 32 generator columns, in the bit-reversed domain, of each of
    /// the dimensions `0..=G` the draws read (Sobol' for `zjoint`; for `zquad` the four base-4
    /// Faure matrices and the fifth; (1,2)-Sobol' for `sobol12` and `zsobol12`) (column
    /// `j` of dimension `d` at word `1 + 32 d + j`: the XOR of the columns of the set bits of a
    /// reversed index is its point, reversed). `1 + 32 (G + 1)` words: 97 for groups of 2,
    /// 161 for `zquad`, 16 417 (64 KiB) for 512. Upload it as the shader's `strata_joint` storage buffer.
    pub fn gpu_joint_table(&self) -> Option<Vec<u32>> {
        if !self.is_joint() {
            return None;
        }
        let dims = &self.joint[..];
        let mut words = Vec::with_capacity(1 + 32 * dims.len());
        words.push(self.group);
        for t in dims {
            words.extend((0..32).map(|j| t[j / 8][1 << (j % 8)]));
        }
        Some(words)
    }

    /// Whether the draws of a group share one index (`zjoint`, `zquad`, `sobol12`,
    /// `zsobol12`).
    fn is_joint(&self) -> bool {
        matches!(
            self.kind,
            Kind::ZJoint | Kind::ZQuad | Kind::Sobol12 | Kind::ZSobol12
        )
    }

    /// The first dimension of the group of `dim`: the dimension that keys the index of the
    /// draw at `dim` (its pixel place, padding and index shuffle); `dim` itself but in
    /// `zjoint`.
    #[inline(always)]
    pub(crate) fn group_start(&self, dim: u32) -> u32 {
        dim & !(self.group - 1)
    }

    /// The image of a Z-ordered sequence (`None` for the others).
    pub fn resolution(&self) -> Option<[u32; 2]> {
        self.kind.z_ordered().then_some(self.resolution)
    }

    /// Whether the draws are the kernel's 32-bit arithmetic, which the WGSL shader also runs:
    /// every sequence but `jittered` and `halton`.
    pub fn runs_on_gpu(&self) -> bool {
        self.kind.row().shader.is_some()
    }

    pub(crate) fn kind(&self) -> Kind {
        self.kind
    }

    /// The digital sequence a kernel sequence reads.
    #[inline(always)]
    fn pair_tables(&self) -> &'static PairTables {
        match self.kind {
            Kind::Pmj02 | Kind::ZPmj02 => &PMJ02,
            _ => &SOBOL01,
        }
    }

    /// The 2D draw at `dim` of the sample `index` of a pixel (or tile) with keys `keys`.
    #[inline(always)]
    pub(crate) fn sample_2d(
        &self,
        keys: &PixelKeys,
        index: SampleIndex,
        dim: u32,
        spp: &SamplesPerPixel,
    ) -> [f32; 2] {
        let k = || DrawKeys::new(keys, dim);
        if let Some(table) = self.digital {
            return kernel::digital::<X2>(table, &k(), index).unit_f32();
        }
        match self.kind {
            Kind::Random => kernel::random::<X2>(&k(), index).unit_f32(),
            Kind::Lattice => kernel::lattice::<X2>(&k(), index).unit_f32(),
            Kind::Jittered => jittered(&k(), index.get(), spp),
            Kind::ZJoint | Kind::ZQuad | Kind::Sobol12 | Kind::ZSobol12 => {
                kernel::joint::<X2>(&self.joint, keys, self.group_start(dim), dim, index).unit_f32()
            }
            Kind::Halton => {
                let k = k();
                let g = halton_index(&k, index.get(), spp);
                let s = k.stream();
                [
                    halton::scrambled_radical_inverse(g, 0, s),
                    halton::scrambled_radical_inverse(g, 1, s),
                ]
            }
            // (taken above, through `digital`)
            Kind::Sobol | Kind::Pmj02 | Kind::ZSobol | Kind::ZPmj02 => {
                kernel::digital::<X2>(self.pair_tables(), &k(), index).unit_f32()
            }
        }
    }

    /// A 1D value: the first coordinate of [`sample_2d`](Sequence::sample_2d).
    #[inline(always)]
    pub(crate) fn sample_1d(
        &self,
        keys: &PixelKeys,
        index: SampleIndex,
        dim: u32,
        spp: &SamplesPerPixel,
    ) -> f32 {
        match self.kind {
            // the second coordinate (base 3) is most of the cost: skip it
            Kind::Halton => {
                let k = DrawKeys::new(keys, dim);
                halton::scrambled_radical_inverse(halton_index(&k, index.get(), spp), 0, k.stream())
            }
            _ => self.sample_2d(keys, index, dim, spp)[0],
        }
    }

    /// Two 2D draws at once, at `dim` and `dim + 2` of one sample: the same values as two calls
    /// of [`sample_2d`](Sequence::sample_2d), the kernel sequences' value scrambles and
    /// conversions four lanes at a time.
    #[inline(always)]
    pub(crate) fn sample_4d(
        &self,
        keys: &PixelKeys,
        index: SampleIndex,
        dim: u32,
        spp: &SamplesPerPixel,
    ) -> [f32; 4] {
        self.sample_2x2d([(keys, index), (keys, index)], dim, spp)
    }

    /// Two 2D draws at `dim` and `dim + 2`, each with its own keys and index (the Z-ordered
    /// sequences place a pixel per draw), computed together where the kernel can.
    #[inline(always)]
    pub(crate) fn sample_2x2d(
        &self,
        draws: [(&PixelKeys, SampleIndex); 2],
        dim: u32,
        spp: &SamplesPerPixel,
    ) -> [f32; 4] {
        let [(ka, ia), (kb, ib)] = draws;
        let (a, b) = (
            DrawKeys::new(ka, dim),
            DrawKeys::new(kb, dim.wrapping_add(2)),
        );
        match self.kind {
            Kind::Random => join(kernel::random(&a, ia), kernel::random(&b, ib)).unit_f32(),
            Kind::Sobol | Kind::Pmj02 | Kind::ZSobol | Kind::ZPmj02 => {
                let t = self.pair_tables();
                let (p, q) = (
                    X2::new(t.point_rev(kernel::shuffled(&a, ia))),
                    X2::new(t.point_rev(kernel::shuffled(&b, ib))),
                );
                let (p, q) = (
                    owen_scramble_lanes(p, X2::new(a.v)),
                    owen_scramble_lanes(q, X2::new(b.v)),
                );
                join(p, q).reverse_bits().unit_f32()
            }
            Kind::Lattice => join(kernel::lattice(&a, ia), kernel::lattice(&b, ib)).unit_f32(),
            Kind::Jittered
            | Kind::Halton
            | Kind::ZJoint
            | Kind::ZQuad
            | Kind::Sobol12
            | Kind::ZSobol12 => {
                let [x, y] = self.sample_2d(ka, ia, dim, spp);
                let [z, w] = self.sample_2d(kb, ib, dim.wrapping_add(2), spp);
                [x, y, z, w]
            }
        }
    }

    /// Whether [`sample_2x2d`](Sequence::sample_2x2d) computes its two draws in one pass (the
    /// kernel sequences), rather than one after the other (`jittered`, `halton`).
    #[inline(always)]
    pub(crate) fn pairs_draws(&self) -> bool {
        !matches!(self.kind, Kind::Jittered | Kind::Halton)
    }

    /// The kernel's 32-bit fixed-point values of the 2D draw at `dim` (what the shader computes);
    /// `None` for `jittered` and `halton`, which are not part of the kernel.
    pub(crate) fn sample_2d_u32(
        &self,
        keys: &PixelKeys,
        index: SampleIndex,
        dim: u32,
    ) -> Option<[u32; 2]> {
        let k = DrawKeys::new(keys, dim);
        Some(match self.kind {
            Kind::Random => kernel::random::<[u32; 2]>(&k, index),
            Kind::Sobol | Kind::Pmj02 | Kind::ZSobol | Kind::ZPmj02 => {
                kernel::digital::<[u32; 2]>(self.pair_tables(), &k, index)
            }
            Kind::Lattice => kernel::lattice::<[u32; 2]>(&k, index),
            Kind::ZJoint | Kind::ZQuad | Kind::Sobol12 | Kind::ZSobol12 => {
                kernel::joint::<[u32; 2]>(&self.joint, keys, self.group_start(dim), dim, index)
            }
            Kind::Jittered | Kind::Halton => return None,
        })
    }

    /// Whether [`Padding::Uniform`](super::Padding::Uniform) changes this sequence (the
    /// digital sequences and the lattice).
    #[inline]
    pub(crate) fn pads_uniformly(&self) -> bool {
        self.kind.row().pads
    }

    /// The sample count nearest above `n` at which the sequence is best stratified (a square
    /// for jittered, a power of two for pmj02 and Sobol', `2^a 3^b` for Halton), at most the
    /// largest such count below `2^32`.
    pub fn round_count(&self, n: u32) -> u32 {
        let n = n.max(1);
        match self.kind {
            Kind::Random => n,
            Kind::Halton => halton_block(n).0,
            Kind::Jittered => {
                let s = n.isqrt();
                if s * s == n {
                    n
                } else if s < 65535 {
                    (s + 1) * (s + 1)
                } else {
                    65535 * 65535
                }
            }
            Kind::Pmj02
            | Kind::Sobol
            | Kind::Lattice
            | Kind::ZSobol
            | Kind::ZPmj02
            | Kind::ZQuad
            | Kind::ZJoint
            | Kind::Sobol12
            | Kind::ZSobol12 => n.checked_next_power_of_two().unwrap_or(1 << 31),
        }
    }

    /// Checks a samples-per-pixel count: at least 1, a square for jittered.
    pub(crate) fn check_spp(&self, spp: u32) -> Result<()> {
        let name = self.name();
        if spp == 0 {
            return Err(Error::count(name, 0, "at least 1 sample per pixel"));
        }
        if self.kind.row().spp == SppUse::Square {
            let s = spp.isqrt();
            if s * s != spp {
                return Err(Error::count(
                    name,
                    spp as u64,
                    format!(
                        "{name} needs a square number of samples per pixel (nearest allowed: {})",
                        crate::counts::nearest_squares(spp as u64, u32::MAX as u64)
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
        match self.kind {
            Kind::Random => Vec::new(),
            Kind::Jittered if whole_blocks(spp.cells.divisor()) => {
                let s = spp.side.divisor();
                vec![StrataGrid {
                    columns: s,
                    rows: s,
                }]
            }
            Kind::Halton if whole_blocks(spp.block.divisor()) => {
                let (a, b) = spp.block_exponents;
                vec![StrataGrid {
                    columns: 1 << a,
                    rows: 3u32.pow(b),
                }]
            }
            Kind::Pmj02 | Kind::Sobol => StrataGrid::net(n, true),
            // inside a pixel's block of the global sequence: an aligned block, a net
            Kind::ZSobol | Kind::ZPmj02 if n <= 1u64 << spp.z_bits() => StrataGrid::net(n, true),
            // every draw's two coordinates are 1D (0, 1)-sequences (only the first draw of a
            // group is a 2D net); the same grids as the lattice's
            Kind::ZJoint | Kind::ZQuad | Kind::ZSobol12
                if n.is_power_of_two() && n <= (1u64 << spp.z_bits()).min(1 << 31) =>
            {
                StrataGrid::axes(n as u32)
            }
            // as zjoint: the grids every draw keeps (the 2D draws at even dimensions are
            // (1,m,2)-nets too, the draw at a group's start a (0,m,2)-net)
            Kind::Sobol12 if n.is_power_of_two() && n <= 1 << 31 => StrataGrid::axes(n as u32),
            Kind::Lattice if n.is_power_of_two() && n <= 1 << 31 => StrataGrid::axes(n as u32),
            _ => Vec::new(),
        }
    }
}

/// The sample of `index` in a sequence organised in blocks of `block` samples, each block a
/// stratified set whose members are visited in a random order per draw: the block number,
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

/// `jittered`: the cell the index is sent to in its block's `s x s` set, jittered.
#[inline]
fn jittered(k: &DrawKeys, index: u32, spp: &SamplesPerPixel) -> [f32; 2] {
    let (_, c, key) = block_permuted(k.stream(), index, &spp.cells);
    let (row, col) = spp.side.div_rem(c);
    let h = hash_u64(key, c as u64);
    spp.strata.place2([col, row], [h as u32, (h >> 32) as u32])
}

/// `halton`: the Halton index the sample is sent to (its block's members in a random order).
#[inline]
fn halton_index(k: &DrawKeys, index: u32, spp: &SamplesPerPixel) -> u64 {
    let (b, j, _) = block_permuted(k.stream(), index, &spp.block);
    b as u64 * spp.block.divisor() as u64 + j as u64
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
    fn row_k_is_the_sequence_of_kind_k_and_every_name_builds_it() {
        for (k, row) in ROWS.iter().enumerate() {
            assert_eq!(row.kind as usize, k, "{}", row.name);
            let s = Sequence::by_name(row.name, [16, 16]).unwrap();
            assert_eq!((s.kind, s.name()), (row.kind, row.name));
            assert_eq!(s.runs_on_gpu(), row.shader.is_some());
            // a suffix only where the row takes one
            assert_eq!(
                Sequence::by_name(&format!("{}-2", row.name), [16, 16]).is_ok(),
                !row.suffix.is_empty(),
                "{}",
                row.name
            );
        }
        assert_eq!(Sequence::NAMES.len(), ROWS.len());
        let e = Sequence::by_name("zsobol", [0, 16])
            .unwrap_err()
            .to_string();
        assert!(e.contains("1 to 65536"), "{e}");
        let e = Sequence::by_name("sobolx", [16, 16])
            .unwrap_err()
            .to_string();
        assert!(e.contains("zjoint"), "{e}");
    }

    #[test]
    fn the_module_docs_table_is_the_generated_one() {
        // the pixel module docs include docs/sequences.md: it must be `Sequence::table()`
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/sequences.md");
        let table = Sequence::table();
        if std::env::var_os("STRATA_BLESS").is_some() {
            std::fs::write(path, &table).unwrap();
        }
        let docs = std::fs::read_to_string(path).unwrap();
        assert_eq!(
            docs, table,
            "docs/sequences.md is stale (STRATA_BLESS=1 rewrites it)"
        );
        let module = include_str!("mod.rs");
        assert!(module.contains("include_str!(\"../../docs/sequences.md\")"));
        // one row per name, in order, and its GPU column as `gpu_parameters` says
        let rows: Vec<&str> = table.lines().skip(2).collect();
        assert_eq!(rows.len(), Sequence::NAMES.len());
        for (row, name) in rows.iter().zip(Sequence::NAMES) {
            assert!(row.starts_with(&format!("| `{name}`")), "{row}");
            let spp = if *name == "jittered" { 16 } else { 8 };
            let s = super::super::PixelSampler::new(
                Sequence::by_name(name, [8, 8]).unwrap(),
                spp,
                crate::Seed(1),
            )
            .unwrap();
            let gpu = s
                .gpu_parameters()
                .map(|g| format!("sequence {}", g.sequence));
            assert!(
                row.contains(&format!("| {} |", gpu.as_deref().unwrap_or("CPU only"))),
                "{row}"
            );
        }
    }

    #[test]
    fn round_counts_are_counts_the_sequence_accepts_over_the_whole_range() {
        for name in Sequence::NAMES {
            let s = Sequence::by_name(name, [16, 16]).unwrap();
            for n in [
                0u32,
                1,
                2,
                3,
                17,
                1000,
                1 << 30,
                (1 << 31) + 1,
                u32::MAX - 1,
                u32::MAX,
            ] {
                let r = s.round_count(n);
                assert!(r >= 1, "{name} {n}");
                assert!(
                    s.check_spp(r).is_ok(),
                    "{name}: round_count({n}) = {r} is refused"
                );
            }
        }
    }
}
