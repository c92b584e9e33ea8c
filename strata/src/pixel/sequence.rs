//! The sequences the adapter draws from: one unit per sequence, one list of them.
//!
//! A *draw* is one call of `get_1d` / `get_2d` at a dimension `d` of a pixel sample. Every
//! draw of every pixel (and seed, and block of `2^32` samples) reads its own copy of a 2D
//! sequence. What makes two copies independent matters: within one pixel sample, the values of
//! different draws meet in one integrand (the lens, the light, the next bounce), so the
//! *pairing* of sample `i` of one draw with sample `i` of another must be random. An XOR of the
//! index or a digital shift of the values is not enough for a (0,2)-sequence: both keep sample
//! `i` of every copy in corresponding strata, so the copies stay tied together (correlations
//! near 1) and a pixel's estimate converges to a wrong value. The digital sequences, the
//! lattice and the joint sequences read their points at a *padded* index (the [`Padding`]:
//! each draw reorders the pixel's samples, see `padding.rs`), and scramble their values with
//! the draw's own keys.
//!
//! Each sequence is a unit of its own, in a file of its own under `sequence/`: its row (name,
//! how it is built by name, what the samples-per-pixel count does to it, the count it is best
//! at, what each draw promises and the grids that says, its source), its constructor, and the
//! kind of points its draws read ([`Points`]), which carries its tables. [`ROWS`] lists the
//! units, one line each; every list of names, every table of the documentation and every
//! program reads it, and every dispatch on what a sequence draws is an exhaustive `match` on
//! [`Points`], so a new kind of points is reached by the compiler everywhere it matters.
//!
//! [`Padding`]: super::Padding

mod halton;
mod jittered;
mod lattice;
mod pmj02;
mod random;
mod sobol;
mod sobol12;
mod sobolbn;
mod zjoint;
mod zpmj02;
mod zquad;
mod zsobol;
mod zsobol12;

use alloc::sync::Arc;

use crate::digital::{ByteTables, Matrix, PMJ02, PairTables, SOBOL01};
use crate::error::{Error, Result};
use crate::float::Strata;
use crate::hash::{DivMod, GOLDEN_GAMMA, Permutation, mix64};
use crate::prelude::*;
use crate::sampler::StrataGrid;

use super::BlueNoiseTable;

pub(crate) use halton::{draw as halton_draw, draw_1d as halton_draw_1d};
pub(crate) use jittered::draw as jittered_draw;

/// Every sequence, in the order of [`Sequence::NAMES`]: adding a sequence is its unit file
/// and one line here.
pub(crate) const ROWS: [&Row; 13] = [
    &random::ROW,
    &jittered::ROW,
    &pmj02::ROW,
    &sobol::ROW,
    &halton::ROW,
    &lattice::ROW,
    &zsobol::ROW,
    &zpmj02::ROW,
    &zquad::ROW,
    &zjoint::ROW,
    &sobol12::ROW,
    &zsobol12::ROW,
    &sobolbn::ROW,
];

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
/// (its blocks) and the Z-ordered sequences (the block of each pixel) use it; the others are
/// progressive and ignore it.
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

/// The two dimensions of a digital (0,2)-sequence a draw reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pair2 {
    /// Sobol' dimensions 0 and 1.
    Sobol,
    /// pmj02's digital form.
    Pmj02,
}

impl Pair2 {
    /// Their byte tables.
    #[inline(always)]
    pub(crate) fn tables(self) -> &'static PairTables {
        match self {
            Pair2::Sobol => &SOBOL01,
            Pair2::Pmj02 => &PMJ02,
        }
    }
}

/// What a sequence's draws read, with its tables: the dispatch of every draw.
#[derive(Clone)]
pub(crate) enum Points {
    /// Independent values, hashed from the sample index.
    Hashed,
    /// A jittered `s x s` set per block of samples (CPU only).
    Jittered,
    /// Scrambled Halton in blocks of `2^a 3^b` samples (CPU only).
    Halton,
    /// Two dimensions of a digital (0,2)-sequence at the padded index, Owen-scrambled.
    Digital(Pair2),
    /// The rank-1 lattice at the padded index, shifted.
    Lattice,
    /// Dimensions `0..=group` of a multi-dimensional digital sequence (their byte tables, built
    /// when the sequence is made and shared by its clones), one padded index per group.
    Joint(Arc<[ByteTables]>),
    /// Sobol' dimensions 0 and 1 at the padded index XOR-ed with the rank of a table entry,
    /// Owen-scrambled under its key (see `bluenoise.rs`).
    BlueNoise(BlueNoiseTable),
}

impl Points {
    /// Whether the draws read a padded index (so that the [`Padding`](super::Padding) changes
    /// them); the others permute whole blocks already, or hash.
    #[inline(always)]
    pub(crate) fn padded(&self) -> bool {
        match self {
            Points::Digital(_) | Points::Lattice | Points::Joint(_) | Points::BlueNoise(_) => true,
            Points::Hashed | Points::Jittered | Points::Halton => false,
        }
    }

    /// Whether [`get_2d`](super::PixelSampler::get_2d) computes the draw at `d + 2` with the
    /// one at `d` in one pass (the 32-bit kernel's), rather than one after the other.
    #[inline(always)]
    pub(crate) fn pairs_draws(&self) -> bool {
        self.kernel().is_some()
    }

    /// The kernel's number in the shader (`None`: CPU only): 0 hashed, 1 Sobol', 2 pmj02,
    /// 3 lattice, 4 joint, 5 blue-noise table.
    #[inline(always)]
    pub(crate) fn kernel(&self) -> Option<u32> {
        match self {
            Points::Hashed => Some(0),
            Points::Digital(Pair2::Sobol) => Some(1),
            Points::Digital(Pair2::Pmj02) => Some(2),
            Points::Lattice => Some(3),
            Points::Joint(_) => Some(4),
            Points::BlueNoise(_) => Some(5),
            Points::Jittered | Points::Halton => None,
        }
    }
}

/// One adapter sequence, declared once: its name, how it is built by name, what the
/// samples-per-pixel count does to it, what each draw promises and the grids that says, and
/// its source. [`Sequence::NAMES`], [`Sequence::name`], [`Sequence::by_name`],
/// [`Sequence::table`] (the module docs' table, the programs' lists) read these rows; what the
/// draws read is the [`Points`] its constructor chooses.
pub(crate) struct Row {
    pub(crate) name: &'static str,
    /// The suffix the name takes (`zjoint-G`), in words; `""` for none.
    suffix: &'static str,
    /// The sequence for an image of `resolution` (the Z-ordered ones) and the suffix after
    /// `name-` (`None` without one; never `Some` for a row whose `suffix` is empty).
    build: fn([u32; 2], Option<&str>) -> Result<Sequence>,
    /// The constructor, as the docs write it.
    constructor: &'static str,
    pub(crate) spp: SppUse,
    /// The sample count nearest above `n` (at least 1) at which the sequence is best
    /// stratified, below `2^32`.
    round: fn(u32) -> u32,
    /// What each draw's samples promise, in words.
    promise: &'static str,
    /// The grids on which the first `n` samples of every draw lie, each cell holding the same
    /// number of points (empty where the sequence promises none at `n`).
    strata: fn(&SamplesPerPixel, u64) -> Vec<StrataGrid>,
    source: &'static str,
}

/// [`Row::round`] of the sequences stratified at powers of two.
fn power_of_two(n: u32) -> u32 {
    n.checked_next_power_of_two().unwrap_or(1 << 31)
}

/// [`Row::strata`] of the sequences whose every draw's two coordinates are 1D
/// (0,1)-sequences at every power of two up to `limit` samples: one point per `1/n` along each
/// axis.
fn axes_up_to(limit: u64, n: u64) -> Vec<StrataGrid> {
    if n.is_power_of_two() && n <= limit.min(1 << 31) {
        StrataGrid::axes(n as u32)
    } else {
        Vec::new()
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

/// One of the adapter's sequences, chosen at run time: build it with a constructor
/// ([`Sequence::sobol`], [`Sequence::zsobol`], ...) or by name ([`Sequence::by_name`]); every
/// constructor validates its arguments, so a `Sequence` is always usable.
#[derive(Clone)]
pub struct Sequence {
    row: &'static Row,
    /// The image of a Z-ordered sequence (`[0, 0]` for the others).
    resolution: [u32; 2],
    /// What the draws read.
    points: Points,
    /// The dimensions of a group whose draws share one index (a power of two); 1 for the
    /// sequences whose every draw is its own group.
    group: u32,
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
        (self.name(), self.resolution, self.group) == (other.name(), other.resolution, other.group)
    }
}

impl Eq for Sequence {}

impl core::hash::Hash for Sequence {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        (self.name(), self.resolution, self.group).hash(state);
    }
}

/// The largest group of a joint sequence (a path of 63 bounces at 8 dimensions each).
const MAX_JOINT_GROUP: u32 = 512;

/// The largest side of the image of a Z-ordered sequence (the Morton code of a pixel has 32
/// bits).
const MAX_Z_RESOLUTION: u32 = 1 << 16;

impl Sequence {
    /// The sequence of `row` reading `points`, every draw its own group.
    fn of(row: &'static Row, points: Points) -> Self {
        Sequence {
            row,
            resolution: [0, 0],
            points,
            group: 1,
        }
    }

    /// A Z-ordered sequence for an image of `width x height` pixels (each 1 to 65536).
    fn z(
        row: &'static Row,
        context: &'static str,
        width: u32,
        height: u32,
        points: Points,
    ) -> Result<Self> {
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
            ..Self::of(row, points)
        })
    }

    /// The points of a joint sequence whose draws come in groups of `group` dimensions (a
    /// power of two from 2 to [`MAX_JOINT_GROUP`]) and read dimensions `0..=group` of
    /// `matrices` (whose tables it builds here), with the group.
    fn joint_points(
        context: &'static str,
        group: u32,
        matrices: &[Matrix],
    ) -> Result<(u32, Points)> {
        if !group.is_power_of_two() || !(2..=MAX_JOINT_GROUP).contains(&group) {
            return Err(Error::parameter(
                context,
                "group",
                group,
                format!("a power of two from 2 to {MAX_JOINT_GROUP} dimensions"),
            ));
        }
        let tables = matrices[..=group as usize]
            .iter()
            .map(crate::digital::byte_tables)
            .collect();
        Ok((group, Points::Joint(tables)))
    }

    /// The names the adapter knows, in the order of [`Sequence::table`] (the joint ones also
    /// as `name-G`, groups of `G` dimensions).
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
        for row in ROWS {
            let sequence = (row.build)([16, 16], None).expect("every row builds by its name");
            let gpu = if sequence.runs_on_gpu() {
                "yes"
            } else {
                "CPU only"
            };
            let name = if row.suffix.is_empty() {
                format!("`{}`", row.name)
            } else {
                format!("`{}` ({})", row.name, row.suffix)
            };
            t.push_str(&format!(
                "| {name} | {} | {} | {} | {gpu} | {} |\n",
                row.constructor,
                row.spp.words(),
                row.promise,
                row.source
            ));
        }
        t
    }

    /// The sequence named `name` (one of [`Sequence::NAMES`], or `name-G` for the joint ones),
    /// the Z-ordered ones for an image of `resolution` (`[width, height]`; the others ignore
    /// it).
    pub fn by_name(name: &str, resolution: [u32; 2]) -> Result<Self> {
        if let Some(row) = ROWS.iter().find(|r| r.name == name) {
            return (row.build)(resolution, None);
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
            return (row.build)(resolution, Some(suffix));
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
        self.row.name
    }

    /// The dimensions of a group whose draws share one index: the group size of `zjoint`,
    /// `zquad` (4), `sobol12` and `zsobol12`; 1 for the other sequences.
    pub fn group(&self) -> u32 {
        self.group
    }

    /// The first dimension of the group of `dim`: the dimension that keys the index of the
    /// draw at `dim` (its pixel place, padding and index shuffle); `dim` itself but in the
    /// joint sequences.
    #[inline(always)]
    pub(crate) fn group_start(&self, dim: u32) -> u32 {
        dim & !(self.group - 1)
    }

    /// The image of a Z-ordered sequence (`None` for the others).
    pub fn resolution(&self) -> Option<[u32; 2]> {
        self.z_ordered().then_some(self.resolution)
    }

    /// Whether pixels read blocks of one global sequence (Z order).
    #[inline(always)]
    pub(crate) fn z_ordered(&self) -> bool {
        self.row.spp == SppUse::PixelBlock
    }

    /// Whether the draws are the kernel's 32-bit arithmetic, which the WGSL shader also runs:
    /// every sequence but `jittered` and `halton`.
    pub fn runs_on_gpu(&self) -> bool {
        self.points.kernel().is_some()
    }

    /// What the draws read.
    #[inline(always)]
    pub(crate) fn points(&self) -> &Points {
        &self.points
    }

    /// The shader's words after the padding's table (see
    /// [`GpuParameters::tables`](super::GpuParameters::tables)): for a joint sequence, the group
    /// size `G`, then the 32 generator columns, in the bit-reversed domain, of each dimension
    /// `0..=G` the draws read; for a blue-noise sequence, `log2` of its table's side, then its
    /// entries (the key and the rank bit-reversed, row-major); empty for the other sequences.
    pub(crate) fn gpu_words(&self) -> Vec<u32> {
        match &self.points {
            Points::Joint(dims) => {
                let mut words = Vec::with_capacity(1 + 32 * dims.len());
                words.push(self.group);
                for t in dims.iter() {
                    words.extend((0..32).map(|j| t[j / 8][1 << (j % 8)]));
                }
                words
            }
            Points::BlueNoise(t) => t.gpu_words(),
            Points::Hashed
            | Points::Jittered
            | Points::Halton
            | Points::Digital(_)
            | Points::Lattice => Vec::new(),
        }
    }

    /// The sample count nearest above `n` at which the sequence is best stratified (a square
    /// for jittered, a power of two for pmj02 and Sobol', `2^a 3^b` for Halton), at most the
    /// largest such count below `2^32` (for Halton, at most `2^31`, its largest block).
    pub fn round_count(&self, n: u32) -> u32 {
        (self.row.round)(n.max(1))
    }

    /// Checks a samples-per-pixel count: at least 1, a square for jittered.
    pub(crate) fn check_spp(&self, spp: u32) -> Result<()> {
        let name = self.name();
        if spp == 0 {
            return Err(Error::count(name, 0, "at least 1 sample per pixel"));
        }
        if self.row.spp == SppUse::Square {
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
        (self.row.strata)(spp, n)
    }
}

/// The sample of `index` in a sequence organised in blocks of `block` samples, each block a
/// stratified set whose members are visited in a random order per draw (`jittered`, `halton`):
/// the block number, the position inside the block the index is sent to, and the block's key.
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

/// The group size of a joint sequence named `name-G` (`suffix` the `G`, written as a plain
/// decimal number; `default` without a suffix).
fn group_by_name(name: &str, suffix: Option<&str>, default: u32) -> Result<u32> {
    let Some(g) = suffix else {
        return Ok(default);
    };
    let canonical = !g.is_empty()
        && g.bytes().all(|b| b.is_ascii_digit())
        && !(g.len() > 1 && g.starts_with('0'));
    match g.parse::<u32>() {
        Ok(v) if canonical => Ok(v),
        _ => Err(Error::input(
            "Sequence::by_name",
            format!(
                "'{name}-{g}': {name}-G takes a group size G written in decimal digits, a power \
                 of two from 2 to {MAX_JOINT_GROUP}"
            ),
        )),
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
    fn every_name_builds_its_row_and_only_the_documented_suffixes() {
        for row in ROWS {
            let s = Sequence::by_name(row.name, [16, 16]).unwrap();
            assert_eq!((s.name(), s.row.constructor), (row.name, row.constructor));
            // a suffix only where the row takes one
            assert_eq!(
                Sequence::by_name(&format!("{}-2", row.name), [16, 16]).is_ok(),
                !row.suffix.is_empty(),
                "{}",
                row.name
            );
            if !row.suffix.is_empty() {
                for bad in ["+4", "04", "4 ", "", "-4", "0x4"] {
                    let e = Sequence::by_name(&format!("{}-{bad}", row.name), [16, 16]);
                    assert!(e.is_err(), "{}-{bad} is accepted", row.name);
                }
            }
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
            let gpu = if s.gpu_parameters().is_ok() {
                "yes"
            } else {
                "CPU only"
            };
            assert!(row.contains(&format!("| {gpu} |")), "{row}");
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
                assert!(r >= 1 && r >= n.min(1 << 31), "{name} {n}: {r}");
                assert!(
                    s.check_spp(r).is_ok(),
                    "{name}: round_count({n}) = {r} is refused"
                );
            }
        }
    }
}
