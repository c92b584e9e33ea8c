//! `zquad`: as `zjoint` in groups of four dimensions, whose draws read the binary form of
//! Faure's base-4 (0,4)-sequence (Faure, "Discrépance de suites associées à un système de
//! numération (en dimension s)", Acta Arith. 41, 1982; [`crate::digital`] builds its 2x2-block
//! generator matrices): a pixel's first `4^k` samples of a group's four dimensions are a
//! (0,k,4)-net in base 4, and its draws at the group's first and third dimension are
//! (0,2)-sequences, as `zsobol`'s draws are. The property the SZ sequences of Ahmed, Pharr,
//! Ostromoukhov and Huang (TOG 2025) are built for, by a construction of our own (their paper
//! was not available to us).

use alloc::sync::Arc;

use super::{Points, Row, Sequence, SppUse, axes_up_to, power_of_two};
use crate::error::Result;

pub(crate) const ROW: Row = Row {
    name: "zquad",
    suffix: "",
    build: |r, _| Sequence::zquad(r[0], r[1]),
    constructor: "`Sequence::zquad(width, height)`",
    spp: SppUse::PixelBlock,
    round: power_of_two,
    promise: "the Z order shared by a group of 4 draws, which read the dimensions of a \
              base-4 (0,4)-sequence: jointly a (0,k,4)-net at `4^k`",
    strata: |spp, n| axes_up_to(1 << spp.z_bits(), n),
    source: "Ahmed, Wonka 2020; Faure 1982",
};

impl Sequence {
    /// Jointly Z-ordered over a base-4 (0,4)-sequence, for an image of `width x height` pixels
    /// (see [`Sequence::zsobol`]): [`Sequence::zjoint`] in groups of 4 dimensions, whose draws
    /// read the binary form of Faure's (0,4)-sequence in base 4 (Faure, "Discrépance de suites
    /// associées à un système de numération (en dimension s)", Acta Arith. 41, 1982) instead of
    /// Sobol' dimensions: a pixel's first `4^k` samples of a group's four dimensions are a
    /// (0,k,4)-net in base 4 (every box of `4^-a x 4^-b x 4^-c x 4^-d` with `a + b + c + d =
    /// k` holds one), its dimensions 0-1 and 2-3 (the draws at the group's first and third
    /// dimension) are binary (0,2)-sequences as `zsobol`'s draws are, and the other pairs of
    /// the four have `t = 1`. A 2D draw at a group's last dimension pairs it with a fifth
    /// matrix ([`crate::samplers::sobol::projection_t_value`] gives every pair's t).
    pub fn zquad(width: u32, height: u32) -> Result<Self> {
        let points = Points::Joint(Arc::from(&crate::digital::FAURE4[..]));
        Ok(Sequence {
            group: 4,
            ..Self::z(&ROW, "Sequence::zquad", width, height, points)?
        })
    }
}
