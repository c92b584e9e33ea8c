//! `sobol12`: the draws of a group of dimensions share one padded index and read consecutive
//! dimensions of the (1,2)-Sobol' sequence (Bonneel, Coeurjolly, Iehl, Ostromoukhov, "Sobol'
//! Sequences with Guaranteed-Quality 2D Projections", ACM TOG 44(4), 2025), each value
//! Owen-scrambled under the draw's own keys: a 2D draw at a group's even dimension is a
//! (1,2)-sequence, the first a (0,2)-sequence.

use super::{Row, Sequence, SppUse, axes_up_to, group_by_name, power_of_two};
use crate::digital::ONE_TWO_SOBOL;
use crate::error::Result;

/// The dimensions of a group by name (and of `zsobol12`'s): two 2D draws, the table's pairs
/// `(0, 1)` and `(2, 3)`. The (1,2)-Sobol' table's other pairs are worse than Joe and Kuo's
/// (`t` up to 10 among its first 9 dimensions, against 5), and the conformance suite's
/// chi-square of two draws of a group of 8 fails (dimensions 1 and 5); in groups of 4 every
/// pair of the draws has `t <= 3` and the suite passes.
pub(super) const DEFAULT_GROUP: u32 = 4;

pub(crate) const ROW: Row = Row {
    name: "sobol12",
    suffix: "`sobol12-G`: groups of `G` dimensions, a power of two from 2 to 512 (default 4)",
    build: |_, s| Sequence::sobol12(group_by_name("sobol12", s, DEFAULT_GROUP)?),
    constructor: "`Sequence::sobol12(group)`",
    spp: SppUse::Ignored,
    round: power_of_two,
    promise: "one index per group of draws; the 2D draw at a group's dimension `2k` a \
              (1,2)-sequence (`2k = 0`: a (0,2)-sequence); Owen-scrambled",
    // as zjoint: the grids every draw keeps (the 2D draws at even dimensions are (1,m,2)-nets
    // too, the draw at a group's start a (0,m,2)-net)
    strata: |_, n| axes_up_to(u64::MAX, n),
    source: "Bonneel et al. 2025",
};

impl Sequence {
    /// (1,2)-Sobol' draws from one index per group of `group` dimensions (a power of two
    /// from 2 to 512; 4, the default by name, is two 2D draws, see below): every draw of a
    /// group of a pixel sample reads the group's index (one padding per group, keyed by its
    /// first dimension), and the draw at the group's dimension `o` reads dimensions `o` and
    /// `o + 1` of the (1,2)-Sobol' sequence of N. Bonneel, D. Coeurjolly, J.-C. Iehl and V.
    /// Ostromoukhov ("Sobol' Sequences with Guaranteed-Quality 2D Projections", ACM TOG 44(4),
    /// 2025), each coordinate Owen-scrambled under the draw's own keys. The 2D draws at even
    /// dimensions of a group are (1,2)-sequences (each aligned block of `2^m` samples, every
    /// prefix included, a (1,m,2)-net: two samples in each elementary interval of area
    /// `2^(1-m)`), the first a (0,2)-sequence, where padded `sobol`'s draws are each a
    /// (0,2)-sequence but pair with each other at random: here the draws of a group are one
    /// point set, stratified jointly where the table's pairs of dimensions are. Draws past a
    /// group start a new group (padded to it, as `sobol` pads every draw), so a path of any
    /// length is served. Larger groups tie more draws together, but through the table's
    /// other pairs of dimensions, which are worse than Joe and Kuo's: in groups of 8 the
    /// draws at a group's dimensions 1 and 5 fail the lab's chi-square test of two draws
    /// (`t = 3` at 4096 samples), in groups of 4 every pair has `t <= 3` at every `2^m`
    /// (`t <= 1` but for the pairs (0, 3) and (1, 3)). Reads `group + 1` of the table's 692
    /// dimensions, whose tables (4 KiB each) it builds when it is made.
    pub fn sobol12(group: u32) -> Result<Self> {
        let (group, points) = Self::joint_points("Sequence::sobol12", group, &ONE_TWO_SOBOL)?;
        Ok(Sequence {
            group,
            ..Self::of(&ROW, points)
        })
    }
}
