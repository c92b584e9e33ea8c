//! `zsobol12`: `sobol12` Z-ordered as `zjoint` is: the draws of a group share one pixel order
//! and read the (1,2)-Sobol' table instead of Joe and Kuo's.

use super::{Row, Sequence, SppUse, axes_up_to, group_by_name, power_of_two};
use crate::digital::ONE_TWO_SOBOL;
use crate::error::Result;

pub(crate) const ROW: Row = Row {
    name: "zsobol12",
    suffix: "`zsobol12-G`: groups of `G` dimensions, as `sobol12-G`",
    build: |r, s| {
        Sequence::zsobol12(
            r[0],
            r[1],
            group_by_name("zsobol12", s, super::sobol12::DEFAULT_GROUP)?,
        )
    },
    constructor: "`Sequence::zsobol12(width, height, group)`",
    spp: SppUse::PixelBlock,
    round: power_of_two,
    promise: "as `sobol12` per pixel; the Z order shared by a group's draws",
    strata: |spp, n| axes_up_to(1 << spp.z_bits(), n),
    source: "Bonneel et al. 2025; Ahmed, Wonka 2020",
};

impl Sequence {
    /// [`Sequence::sobol12`] Z-ordered as [`Sequence::zjoint`] is, for an image of `width x
    /// height` pixels: the draws of a group share one pixel order, and read the (1,2)-Sobol'
    /// table instead of Joe and Kuo's.
    pub fn zsobol12(width: u32, height: u32, group: u32) -> Result<Self> {
        let context = "Sequence::zsobol12";
        let (group, points) = Self::joint_points(context, group, &ONE_TWO_SOBOL)?;
        Ok(Sequence {
            group,
            ..Self::z(&ROW, context, width, height, points)?
        })
    }
}
