//! The tables of the progressive blue-noise sequences (`sobolbn`): per pixel of a toroidal
//! tile, a *key* (the Owen scramble of the pixel's copy of the sequence) and a *rank* (an XOR
//! of its sample index), arranged offline so that neighbouring pixels' errors cancel at the
//! power-of-two counts the table was made for, without knowing the count (the table's header
//! has its figures).
//!
//! The scheme is Heitz, Belcour, Ostromoukhov, Coeurjolly and Iehl's ("A Low-Discrepancy
//! Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen Space", SIGGRAPH Talks
//! 2019) made progressive as OpenQMC's blue-noise samplers make it (Framestore, Apache-2.0,
//! `include/oqmc/sobolbn.h`: one table of (key, rank) read at `index ^ rank`, shifted on the
//! torus per draw): sample `i` of a pixel is the Owen-scrambled Sobol' point at `i ^ rank`, so
//! its first `2^m` samples are an aligned block of its scrambled sequence, a (0,m,2)-net, for
//! every `m`. The table is this crate's own, made by the lab's `bntable` program (its header
//! names the command, the seed and the run time). The built-in table adds a structure of its
//! own: the sixteen pixels of each aligned 4 x 4 block of the tile share the leading digits of
//! their scramble (the low 26 bits of the key) and XOR a block's rank with fixed patterns, so
//! that at every count the union of the block's samples (and of each 2 x 2 sub-block's) is
//! itself a net of 16 (4) times as many points, as a Z order told the count makes it
//! (Ahmed and Wonka 2020; pbrt-v4's `ZSobolSampler`), without being told the count. The lab's
//! `strata_lab::samplers::bntable` has the patterns, their t-values and the search that found
//! them.
//!
//! # One draw
//!
//! The draw at dimension `d` of pixel `(x, y)` reads the entry at `((x + s_x) mod W,
//! (y + s_y) mod W)` (`W` the tile's side; `s` a hash of the seed and `d`: every draw sees the
//! tile shifted anew, so every draw, not only the film position, is blue), at the pixel's
//! padded index (the [`Padding`](super::Padding) reorders the samples inside each shell and
//! keeps every power-of-two prefix's set, so the sets the table arranged stay), XOR-ed with the
//! rank; the point's two coordinates are Owen-scrambled under the key (and a second key hashed
//! from it), then XOR-ed with a digital shift drawn per seed, dimension and coordinate. The
//! shift keeps every net a net and the pixels' relative strata (a common shift of all of
//! them), and it makes each value uniform over seeds and two draws independent of each other,
//! which the table alone would not: every seed would draw from the table's finite set of
//! point sets, so that a pixel's expected value would be their mean, not the integral. The
//! table's optimiser sees its test integrands through such shifts.
//!
//! # Guarantees and limits
//!
//! Every power-of-two prefix of every draw of every pixel is a (0,m,2)-net, as `sobol`'s, under
//! the shell and the nested padding (which keep each prefix's set, so that the table's
//! arrangement holds); `Padding::Uniform` reorders whole blocks of the samples per pixel, and
//! keeps the arranged sets only at multiples of them.
//! Images larger than the tile wrap toroidally (pixel `x` reads column `x mod W`): a pixel and
//! its copy `W` pixels away draw alike up to their padding. The table orders the first
//! `2^16` samples (ranks below `2^16`); past them, and at counts above those the table was
//! optimised for (its header says), a pixel's samples are still its scrambled sequence's
//! aligned blocks, nets as `sobol`'s, with no blue-noise arrangement between pixels. In the
//! built-in table, past `2^12` samples two pixels of a 4 x 4 block can draw the same block of
//! indices, whose points then agree in their first 10 binary digits (the scramble the block
//! shares) and differ below them: their errors are alike (correlated, not equal) there.

use alloc::sync::Arc;
use core::ops::Deref;

use crate::digital::SOBOL01;
use crate::error::{Error, Result};
use crate::prelude::*;
use crate::scramble::{Lanes, Pair, X2, owen_scramble_lanes};

mod sobol_128;

/// The ranks of a table are below this: a table orders the first `2^16` samples of a pixel.
pub const MAX_RANK: u32 = 1 << 16;

/// The largest side of a table.
pub const MAX_SIDE: u32 = 1024;

/// A toroidal tile of (key, rank) pairs for [`Sequence::sobolbn_with`](super::Sequence::sobolbn_with):
/// the built-in one ([`BlueNoiseTable::builtin`]) or one a program made.
#[derive(Clone)]
pub struct BlueNoiseTable {
    /// `log2` of the side.
    side_bits: u32,
    /// Row-major entries: the key and the rank bit-reversed (the draws' domain).
    entries: Entries,
}

/// The entries of a table: the built-in one's, reversed at compile time, or a program's.
#[derive(Clone)]
enum Entries {
    Builtin(&'static [[u32; 2]]),
    Shared(Arc<[[u32; 2]]>),
}

impl Deref for Entries {
    type Target = [[u32; 2]];

    #[inline(always)]
    fn deref(&self) -> &[[u32; 2]] {
        match self {
            Entries::Builtin(e) => e,
            Entries::Shared(e) => e,
        }
    }
}

/// The built-in table's entries with their ranks bit-reversed (the draws' domain).
static BUILTIN: [[u32; 2]; sobol_128::ENTRIES.len()] = {
    let mut t = sobol_128::ENTRIES;
    let mut k = 0;
    while k < t.len() {
        t[k][1] = t[k][1].reverse_bits();
        k += 1;
    }
    t
};

impl core::fmt::Debug for BlueNoiseTable {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BlueNoiseTable")
            .field("side", &self.side())
            .finish_non_exhaustive()
    }
}

impl PartialEq for BlueNoiseTable {
    fn eq(&self, other: &Self) -> bool {
        self.side_bits == other.side_bits && *self.entries == *other.entries
    }
}

impl Eq for BlueNoiseTable {}

impl BlueNoiseTable {
    /// A table of `side x side` entries `(key, rank)`, row-major (`entries[y * side + x]`).
    /// Refused: a side that is not a power of two from 1 to [`MAX_SIDE`], a length other than
    /// `side^2`, a rank of [`MAX_RANK`] or more, and two equal entries (two pixels of one tile
    /// would draw the same samples).
    pub fn new(side: u32, entries: &[[u32; 2]]) -> Result<Self> {
        let context = "BlueNoiseTable::new";
        if !side.is_power_of_two() || side > MAX_SIDE {
            return Err(Error::parameter(
                context,
                "side",
                side,
                format!("a power of two from 1 to {MAX_SIDE}"),
            ));
        }
        let n = (side * side) as usize;
        if entries.len() != n {
            return Err(Error::input(
                context,
                format!(
                    "{} entries for a side of {side}: a table has side^2 = {n}",
                    entries.len()
                ),
            ));
        }
        if let Some(k) = entries.iter().position(|e| e[1] >= MAX_RANK) {
            return Err(Error::input(
                context,
                format!(
                    "entry {k} has rank {}: ranks are below {MAX_RANK} (a table orders the \
                     first 2^16 samples)",
                    entries[k][1]
                ),
            ));
        }
        let mut sorted = entries.to_vec();
        sorted.sort_unstable();
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Err(Error::input(
                context,
                format!(
                    "the entry (key {:#010x}, rank {}) appears twice: two pixels would draw the \
                     same samples",
                    w[0][0], w[0][1]
                ),
            ));
        }
        Ok(BlueNoiseTable {
            side_bits: side.trailing_zeros(),
            entries: Entries::Shared(
                entries
                    .iter()
                    .map(|&[key, rank]| [key, rank.reverse_bits()])
                    .collect(),
            ),
        })
    }

    /// The built-in table of `sobolbn` (see the [module docs](self)): no allocation, no check
    /// at run time (a test checks it as [`new`](Self::new) would).
    pub fn builtin() -> Self {
        BlueNoiseTable {
            side_bits: sobol_128::SIDE.trailing_zeros(),
            entries: Entries::Builtin(&BUILTIN),
        }
    }

    /// The side of the tile.
    pub fn side(&self) -> u32 {
        1 << self.side_bits
    }

    /// The entry `(key, rank)` at `pixel` of the tile, toroidally (`x mod side`,
    /// `y mod side`).
    pub fn entry(&self, pixel: [u32; 2]) -> [u32; 2] {
        let [key, rank_rev] = self.entry_rev(pixel);
        [key, rank_rev.reverse_bits()]
    }

    /// The shader's words of the table: `log2` of the side, then the entries (the key and the
    /// rank bit-reversed), row-major.
    pub(crate) fn gpu_words(&self) -> Vec<u32> {
        let mut words = Vec::with_capacity(1 + 2 * self.entries.len());
        words.push(self.side_bits);
        words.extend(self.entries.iter().flatten());
        words
    }

    /// The entry at `p` (toroidally), its rank bit-reversed.
    #[inline(always)]
    pub(crate) fn entry_rev(&self, p: [u32; 2]) -> [u32; 2] {
        let m = (1u32 << self.side_bits) - 1;
        self.entries[(((p[1] & m) << self.side_bits) | (p[0] & m)) as usize]
    }

    /// Sample `index` of an entry with rank `rank` and key `key`, before the draw's digital
    /// shift, as 32-bit fixed-point values: the Sobol' point (dimensions 0 and 1) at
    /// `index ^ rank`, Owen-scrambled under the entry's two keys. The lab's table optimiser
    /// measures entries with it; a draw at a padded index `j` is this point at `j`, XOR-ed with
    /// its shift.
    pub fn point_u32(index: u32, rank: u32, key: u32) -> [u32; 2] {
        point_rev::<[u32; 2]>(key, (index ^ rank).reverse_bits()).reverse_bits()
    }
}

/// The second scramble key of an entry, from its key: a multiply-xorshift (the key is random,
/// so one round decorrelates the two coordinates' scrambles).
#[inline(always)]
pub(crate) fn second_key(key: u32) -> u32 {
    let x = key.wrapping_mul(0x9e37_79b9);
    x ^ (x >> 16)
}

/// The Owen-scrambled Sobol' point at the bit-reversed index `index_rev` under the key `key`
/// (and its [`second_key`]), in the bit-reversed domain.
#[inline(always)]
pub(crate) fn point_rev<P: Pair>(key: u32, index_rev: u32) -> P {
    let p = P::new(SOBOL01.point_rev(index_rev));
    owen_scramble_lanes(p, P::new([key, second_key(key)]))
}

/// The same point as an [`X2`] (the CPU draws' lanes).
#[inline(always)]
pub(crate) fn point_rev_x2(key: u32, index_rev: u32) -> X2 {
    point_rev::<X2>(key, index_rev)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_builtin_table_is_valid_and_its_entries_prefixes_are_nets() {
        // the built-in, reversed at compile time, is what `new` makes of its file
        let t = BlueNoiseTable::builtin();
        assert_eq!(t.side(), sobol_128::SIDE);
        assert!(t == BlueNoiseTable::new(sobol_128::SIDE, &sobol_128::ENTRIES).unwrap());
        // every prefix of 2^m samples of an entry is an aligned block of its sequence: a
        // (0,m,2)-net, one point per elementary interval of every shape
        for (x, y) in [(0u32, 0u32), (5, 77), (127, 127)] {
            let [key, rank] = t.entry([x, y]);
            for m in 0..=8u32 {
                let n = 1u32 << m;
                for a in 0..=m {
                    let mut seen = vec![false; n as usize];
                    for i in 0..n {
                        let [u, v] = BlueNoiseTable::point_u32(i, rank, key);
                        // the elementary interval of 2^a x 2^(m-a) cells holding the point
                        let cell =
                            ((u as u64) >> (32 - a)) << (m - a) | (v as u64) >> (32 - (m - a));
                        assert!(!seen[cell as usize], "({x},{y}) m {m} shape {a}");
                        seen[cell as usize] = true;
                    }
                }
            }
        }
    }

    #[test]
    fn bad_tables_are_refused_with_what_is_allowed() {
        let ok = [[1u32, 0], [2, 0], [3, 1], [4, 5]];
        assert!(BlueNoiseTable::new(2, &ok).is_ok());
        let e = BlueNoiseTable::new(3, &ok).unwrap_err().to_string();
        assert!(e.contains("power of two"), "{e}");
        let e = BlueNoiseTable::new(2048, &ok).unwrap_err().to_string();
        assert!(e.contains("1024"), "{e}");
        let e = BlueNoiseTable::new(2, &ok[..3]).unwrap_err().to_string();
        assert!(e.contains("3 entries"), "{e}");
        let e = BlueNoiseTable::new(2, &[[1, 0], [2, 0], [3, 1], [4, 1 << 16]])
            .unwrap_err()
            .to_string();
        assert!(e.contains("rank 65536"), "{e}");
        let e = BlueNoiseTable::new(2, &[[1, 0], [2, 0], [3, 1], [1, 0]])
            .unwrap_err()
            .to_string();
        assert!(e.contains("twice"), "{e}");
        // entries wrap toroidally
        let t = BlueNoiseTable::new(2, &ok).unwrap();
        assert_eq!(t.entry([3, 5]), t.entry([1, 1]));
        assert_eq!(t.entry([1, 1]), [4, 5]);
    }
}
