//! `sobolbn`: as `sobol`, but each pixel reads its copy of the sequence through an entry of a
//! toroidal table (an Owen scramble key and an XOR of the sample index), arranged offline so
//! that the error is blue noise in screen space at the power-of-two counts its table was made
//! for (1 to 64 samples, the built-in table about alike at each), without knowing the count:
//! for viewports and adaptive samplers (Heitz et al. 2019; made progressive as OpenQMC's
//! `SobolBnSampler`; the built-in table's 4 x 4 blocks draw nets together, as Ahmed and
//! Wonka's Z order told the count makes them). Each
//! draw reads the table shifted anew, so every draw is blue; see [`super::super::bluenoise`]
//! for the draw and its limits.

use super::{Points, Row, Sequence, SppUse, power_of_two};
use crate::pixel::BlueNoiseTable;
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "sobolbn",
    suffix: "",
    build: |_, _| Ok(Sequence::sobolbn()),
    constructor: "`Sequence::sobolbn()`",
    spp: SppUse::Ignored,
    round: power_of_two,
    promise: "as `sobol`; pixels through a table arranged so that the error is blue noise at 1 \
              to 64 samples (progressive)",
    strata: |_, n| StrataGrid::net(n, true),
    source: "Heitz et al. 2019, OpenQMC; Ahmed, Wonka 2020",
};

impl Sequence {
    /// Progressive blue-noise Sobol' with the built-in table ([`BlueNoiseTable::builtin`]).
    pub fn sobolbn() -> Self {
        Self::of(&ROW, Points::BlueNoise(BlueNoiseTable::builtin()))
    }

    /// Progressive blue-noise Sobol' with the table `table` (one made by the lab's `bntable`
    /// program with other options, for instance; [`BlueNoiseTable::new`] checks it).
    pub fn sobolbn_with(table: BlueNoiseTable) -> Self {
        Self::of(&ROW, Points::BlueNoise(table))
    }
}
