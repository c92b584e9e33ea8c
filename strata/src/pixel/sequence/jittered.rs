//! `jittered`: a jittered `s x s` set per block of `spp = s^2` samples (Cook, "Stochastic
//! Sampling in Computer Graphics", TOG 5(1), 1986), its cells visited in a hashed random order
//! per draw, so that two draws are paired as by independent uniform permutations of the block.
//! It divides by the block size and hashes with 64-bit arithmetic: CPU only.

use super::super::kernel::DrawKeys;
use super::{Points, Row, SamplesPerPixel, Sequence, SppUse, block_permuted};
use crate::hash::hash_u64;
use crate::prelude::*;
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "jittered",
    suffix: "",
    build: |_, _| Ok(Sequence::jittered()),
    constructor: "`Sequence::jittered()`",
    spp: SppUse::Square,
    round: |n| {
        let s = n.isqrt();
        if s * s == n {
            n
        } else if s < 65535 {
            (s + 1) * (s + 1)
        } else {
            65535 * 65535
        }
    },
    promise: "one value per cell of `s x s` in each set of `spp`",
    strata: |spp, n| {
        if n > 0 && n.is_multiple_of(spp.cells.divisor() as u64) {
            let s = spp.side.divisor();
            vec![StrataGrid {
                columns: s,
                rows: s,
            }]
        } else {
            Vec::new()
        }
    },
    source: "Cook 1986",
};

impl Sequence {
    /// Jittered sets (the samples per pixel must be a square).
    pub fn jittered() -> Self {
        Self::of(&ROW, Points::Jittered)
    }
}

/// The draw: the cell the index is sent to in its block's `s x s` set, jittered.
#[inline]
pub(crate) fn draw(k: &DrawKeys, index: u32, spp: &SamplesPerPixel) -> [f32; 2] {
    let (_, c, key) = block_permuted(k.stream(), index, &spp.cells);
    let (row, col) = spp.side.div_rem(c);
    let h = hash_u64(c as u64, key);
    spp.strata.place2([col, row], [h as u32, (h >> 32) as u32])
}
