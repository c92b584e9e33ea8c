//! `pmj02`: as `sobol`, over the digital form of pmj02 (Christensen, Kensler, Kilpatrick,
//! "Progressive Multi-Jittered Sample Sequences", EGSR 2018; Helmer, Christensen, Kensler,
//! "Stochastic Generation of (t, s) Sample Sequences", EGSR 2021), whose Owen scrambling is
//! distributed as their stochastic pmj02. Every power-of-two prefix of every draw is a
//! (0,m,2)-net.

use super::{Pair2, Points, Row, Sequence, SppUse, power_of_two};
use crate::sampler::StrataGrid;

pub(crate) const ROW: Row = Row {
    name: "pmj02",
    suffix: "",
    build: |_, _| Ok(Sequence::pmj02()),
    constructor: "`Sequence::pmj02()`",
    spp: SppUse::Ignored,
    round: power_of_two,
    promise: "every power-of-two prefix a (0,m,2)-net; Owen-scrambled",
    strata: |_, n| StrataGrid::net(n, true),
    source: "Christensen et al. 2018, Helmer et al. 2021",
};

impl Sequence {
    /// pmj02 (its digital form, Owen-scrambled).
    pub fn pmj02() -> Self {
        Self::of(&ROW, Points::Digital(Pair2::Pmj02))
    }
}
