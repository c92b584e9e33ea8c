//! `sobol`: each draw reads Sobol' dimensions 0 and 1 (a (0,2)-sequence: Sobol' 1967) at its
//! padded index, each coordinate Owen-scrambled under the draw's keys (Burley, "Practical
//! Hash-based Owen Scrambling", JCGT 2020), computed on demand from 8 KiB of tables
//! ([`crate::digital`]). Every power-of-two prefix of every draw is a (0,m,2)-net, whatever the
//! padding.

use super::{Pair2, Points, Row, Sequence, SppUse, power_of_two};
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "sobol",
    suffix: "",
    build: |_, _| Ok(Sequence::sobol()),
    constructor: "`Sequence::sobol()`",
    spp: SppUse::Ignored,
    round: power_of_two,
    promise: "every power-of-two prefix a (0,m,2)-net; Owen-scrambled",
    strata: |_, n| StrataGrid::net(n, true),
    source: "Sobol' 1967, Burley 2020",
};

impl Sequence {
    /// Sobol'.
    pub fn sobol() -> Self {
        Self::of(&ROW, Points::Digital(Pair2::Sobol))
    }
}
