//! `lattice`: the extensible rank-1 lattice (Cools, Kuo, Nuyens, "Constructing embedded
//! lattice rules for multivariate integration", SIAM J. Sci. Comput. 28, 2006) at the draw's
//! padded index, shifted on the torus by the draw's keys: one point per `1/n` along each axis
//! at every power of two `n`.

use super::{Points, Row, Sequence, SppUse, axes_up_to, power_of_two};

pub(crate) const ROW: Row = Row {
    name: "lattice",
    suffix: "",
    build: |_, _| Ok(Sequence::lattice()),
    constructor: "`Sequence::lattice()`",
    spp: SppUse::Ignored,
    round: power_of_two,
    promise: "`n x 1` and `1 x n` strata at every power of two; shifted",
    strata: |_, n| axes_up_to(u64::MAX, n),
    source: "Cools, Kuo, Nuyens 2006",
};

impl Sequence {
    /// The extensible rank-1 lattice.
    pub fn lattice() -> Self {
        Self::of(&ROW, Points::Lattice)
    }
}
