//! `halton`: scrambled Halton in bases 2 and 3 for every draw (Halton, "On the efficiency of
//! certain quasi-random sequences of points in evaluating multi-dimensional integrals", Numer.
//! Math. 2, 1960), padded as Kollig and Keller ("Efficient Multidimensional Sampling",
//! Eurographics 2002) pad 2D sets: the index is permuted at random inside aligned blocks of
//! `M = 2^a 3^b` samples (the smallest such number at least the samples per pixel), so each
//! block is the stratified set of `M` Halton points (one per cell of `2^a x 3^b`) in an order of
//! its own per draw. Halton's digits tie every index permutation that keeps its prefixes to the
//! same strata, so the prefix property is kept per block, not at every `2^a 3^b` below `M`. It
//! divides by the block size and hashes with 64-bit arithmetic: CPU only.

use super::super::kernel::DrawKeys;
use super::{Points, Row, SamplesPerPixel, Sequence, SppUse, block_permuted, halton_block};
use crate::prelude::*;
use crate::sampler::StrataGrid;
use crate::samplers::halton;

pub(crate) const ROW: Row = Row {
    name: "halton",
    suffix: "",
    build: |_, _| Ok(Sequence::halton()),
    constructor: "`Sequence::halton()`",
    spp: SppUse::HaltonBlocks,
    round: |n| halton_block(n).0,
    promise: "each block's `2^a x 3^b` strata, one value each",
    strata: |spp, n| {
        let (a, b) = spp.block_exponents;
        if n > 0
            && n.is_multiple_of(spp.block.divisor() as u64)
            && a <= 24
            && b <= halton::MAX_PROMISED_POWER_OF_3
        {
            vec![StrataGrid {
                columns: 1 << a,
                rows: 3u32.pow(b),
            }]
        } else {
            Vec::new()
        }
    },
    source: "Halton 1960",
};

impl Sequence {
    /// Halton.
    pub fn halton() -> Self {
        Self::of(&ROW, Points::Halton)
    }
}

/// The Halton index the sample is sent to (its block's members in a random order).
#[inline]
fn index(k: &DrawKeys, index: u32, spp: &SamplesPerPixel) -> u64 {
    let (b, j, _) = block_permuted(k.stream(), index, &spp.block);
    b as u64 * spp.block.divisor() as u64 + j as u64
}

/// The draw.
#[inline]
pub(crate) fn draw(k: &DrawKeys, i: u32, spp: &SamplesPerPixel) -> [f32; 2] {
    let (g, s) = (index(k, i, spp), k.stream());
    [
        halton::radical_inverse_at(g, 0, s),
        halton::radical_inverse_at(g, 1, s),
    ]
}

/// A 1D draw: the first coordinate (the second, in base 3, is most of the cost).
#[inline]
pub(crate) fn draw_1d(k: &DrawKeys, i: u32, spp: &SamplesPerPixel) -> f32 {
    halton::radical_inverse_at(index(k, i, spp), 0, k.stream())
}
