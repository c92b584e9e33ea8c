//! `zjoint`: jointly Z-ordered Sobol'. Every draw of a group of dimensions of a pixel sample
//! reads the group's index (one pixel order and one padding per group, keyed by its first
//! dimension), and the draws take *distinct* dimensions of the multi-dimensional Sobol'
//! sequence (Joe and Kuo's directions, [`crate::digital`]), each Owen-scrambled under its own
//! key: a pixel's samples are stratified jointly across the draws of a group, not only draw by
//! draw, and neighbouring pixels take neighbouring blocks of the joint sequence (Ahmed and
//! Wonka 2020); groups are independent of each other.

use super::{Row, Sequence, SppUse, axes_up_to, group_by_name, power_of_two};
use crate::digital::SOBOL;
use crate::error::Result;

/// The dimensions of a group by name: the default
/// [`DimensionLayout`](super::super::DimensionLayout)'s blocks (the camera's, each bounce's).
const DEFAULT_GROUP: u32 = 8;

pub(crate) const ROW: Row = Row {
    name: "zjoint",
    suffix: "`zjoint-G`: groups of `G` dimensions, a power of two from 2 to 512 (default 8)",
    build: |r, s| Sequence::zjoint(r[0], r[1], group_by_name("zjoint", s, DEFAULT_GROUP)?),
    constructor: "`Sequence::zjoint(width, height, group)`",
    spp: SppUse::PixelBlock,
    round: power_of_two,
    promise: "the Z order shared by a group's draws, which read distinct Sobol' dimensions",
    // every draw's two coordinates are 1D (0,1)-sequences (only the first draw of a group is
    // a 2D net); the same grids as the lattice's
    strata: |spp, n| axes_up_to(1 << spp.z_bits(), n),
    source: "Ahmed, Wonka 2020; Joe, Kuo 2008",
};

impl Sequence {
    /// Jointly Z-ordered Sobol' for an image of `width x height` pixels (see
    /// [`Sequence::zsobol`]), its dimensions in groups of `group` (a power of two from 2 to
    /// 512; 8, the default by name, matches the default
    /// [`DimensionLayout`](super::super::DimensionLayout), one group per bounce): every draw of a
    /// group of a pixel sample reads the same Z-ordered index (one pixel order and one padding
    /// per group), and the draws take *distinct* dimensions of the multi-dimensional Sobol'
    /// sequence (the draw at dimension `d` reads Sobol' dimensions `d mod group` and the next),
    /// each Owen-scrambled under its own key. A pixel's samples are then stratified jointly
    /// across the draws of a group, not only draw by draw, and neighbouring pixels take
    /// neighbouring blocks of the joint sequence; groups are independent of each other.
    ///
    /// Within a group only Sobol' dimensions 0 and 1 (the first draw) are a `(0, 2)`-sequence;
    /// the others' pairs have the t-values of consecutive Joe-Kuo dimensions
    /// ([`crate::samplers::sobol::projection_t_value`]), so a lone draw past the first is less
    /// finely stratified than `zsobol`'s. Reads `group + 1` Sobol' dimensions, whose tables
    /// (4 KiB each) it builds when it is made. On a GPU as every kernel sequence
    /// ([`PixelSampler::gpu_parameters`](super::super::PixelSampler::gpu_parameters)).
    pub fn zjoint(width: u32, height: u32, group: u32) -> Result<Self> {
        let context = "Sequence::zjoint";
        let (group, points) = Self::joint_points(context, group, &SOBOL)?;
        Ok(Sequence {
            group,
            ..Self::z(&ROW, context, width, height, points)?
        })
    }
}
