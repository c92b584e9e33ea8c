//! `random`: independent uniform values, two `lowbias32` hashes of an affine map of the sample
//! index per draw ([`kernel::random`](super::super::kernel::random)); the baseline every
//! stratified sequence is measured against.

use super::{Points, Row, Sequence, SppUse};
use crate::prelude::*;

pub(crate) const ROW: Row = Row {
    name: "random",
    suffix: "",
    build: |_, _| Ok(Sequence::random()),
    constructor: "`Sequence::random()`",
    spp: SppUse::Ignored,
    round: |n| n,
    promise: "independent uniform values (hashed)",
    strata: |_, _| Vec::new(),
    source: "-",
};

impl Sequence {
    /// Independent uniform values.
    pub fn random() -> Self {
        Self::of(&ROW, Points::Hashed)
    }
}
