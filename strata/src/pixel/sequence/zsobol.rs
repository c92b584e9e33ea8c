//! `zsobol`: as `sobol`, but pixels take consecutive blocks of one global sequence along a
//! scrambled Morton curve, so that the error is blue noise in screen space (Ahmed and Wonka,
//! "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering
//! of Pixels", SIGGRAPH Asia 2020, as pbrt-v4's `ZSobolSampler`). Each draw orders the pixels
//! anew: the Morton code's base-4 digits go through a nested scramble keyed by the image and
//! the draw's dimension (Vegdahl's base-4 hash, then a random affine map of each digit position
//! over GF(2)^2, so that every one of the 24 permutations of a digit occurs), which keeps every
//! aligned `2^k x 2^k` tile of pixels on consecutive blocks and each pixel's block a
//! (0,m,2)-net per draw. Only the image's digits are permuted, so a pixel's place depends on
//! the image's size (its `ceil(log2(max side))`), not on its position alone. Inside its block
//! a pixel's samples are padded as `sobol`'s are; the values are scrambled under keys shared
//! by the whole image.

use super::{Pair2, Points, Row, Sequence, SppUse, power_of_two};
use crate::error::Result;
use crate::prelude::*;
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "zsobol",
    suffix: "",
    build: |r, _| Sequence::zsobol(r[0], r[1]),
    constructor: "`Sequence::zsobol(width, height)`",
    spp: SppUse::PixelBlock,
    round: power_of_two,
    promise: "as `sobol` per pixel; pixels along a scrambled Z curve (blue-noise error)",
    // inside a pixel's block of the global sequence: an aligned block, a net
    strata: |spp, n| {
        if n <= 1u64 << spp.z_bits() {
            StrataGrid::net(n, true)
        } else {
            Vec::new()
        }
    },
    source: "Ahmed, Wonka 2020",
};

impl Sequence {
    /// Z-ordered Sobol' for an image of `width x height` pixels (each 1 to 65536): the image
    /// must be known up front, since neighbouring pixels take neighbouring blocks of one
    /// sequence. Pixels outside it get independent values.
    pub fn zsobol(width: u32, height: u32) -> Result<Self> {
        Self::z(
            &ROW,
            "Sequence::zsobol",
            width,
            height,
            Points::Digital(Pair2::Sobol),
        )
    }
}
