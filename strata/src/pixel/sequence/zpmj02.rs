//! `zpmj02`: as `zsobol`, over pmj02's digital form.

use super::{Pair2, Points, Row, Sequence, SppUse, power_of_two};
use crate::error::Result;
use crate::prelude::*;
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "zpmj02",
    suffix: "",
    build: |r, _| Sequence::zpmj02(r[0], r[1]),
    constructor: "`Sequence::zpmj02(width, height)`",
    spp: SppUse::PixelBlock,
    round: power_of_two,
    promise: "as `pmj02` per pixel; pixels along a scrambled Z curve",
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
    /// Z-ordered pmj02 for an image of `width x height` pixels (see [`Sequence::zsobol`]).
    pub fn zpmj02(width: u32, height: u32) -> Result<Self> {
        Self::z(
            &ROW,
            "Sequence::zpmj02",
            width,
            height,
            Points::Digital(Pair2::Pmj02),
        )
    }
}
