//! Progressive multi-jittered sequences: well stratified at every power-of-two prefix, so a
//! renderer can stop at any sample count.
//!
//! * `pmj`: Christensen, Kensler, Kilpatrick, "Progressive Multi-Jittered Sample Sequences"
//!   (EGSR 2018). Each doubling puts a new point in the sub-quadrant diagonally opposite each
//!   old point; the next doubling fills one of the two remaining sub-quadrants of each cell
//!   (chosen by the paper's "ox-plowing" balance of rows and columns), then the last. Every new
//!   point takes a free 1D stratum at the new resolution. Guarantee: every prefix of `2^m` points
//!   has one point in each of the `2^m` x strata and y strata, and in each cell of the squarest
//!   grid (`2^k x 2^k` at `4^k` points, both `2^(k+1) x 2^k` and `2^k x 2^(k+1)` at `2 4^k`).
//! * `pmj02`: the same skeleton with every base-2 elementary interval (`2^a x 2^(m-a)`, all `a`)
//!   enforced at every power of two: each prefix of `2^m` points is a (0,m,2)-net. The valid
//!   strata are enumerated with Pharr's method (JCGT 2019; the bitsets of the crate's occupancy module). In the
//!   odd step one coin decides, for the whole pass, whether the third points flip the x half or
//!   the y half of the sub-quadrant (Simon Brown's rule): with it every *aligned block*
//!   `[k 2^m, (k+1) 2^m)` is a (0,m,2)-net too, so XOR-shuffling indices keeps the guarantees.
//! * `pmjbn`: best candidate (Mitchell 1991) on top: each new point is the candidate, among `K`
//!   drawn in the valid strata, farthest (toroidally) from the points so far. `pmjbn` has real
//!   freedom (about `sqrt(N)/4` free strata per axis) and gains clear blue noise. In `pmj02` the
//!   elementary intervals leave exactly one stratum pair per point, so best candidate can only
//!   move each point inside a `2^-m` square (its spacing barely changes: `docs/results.md`);
//!   `pmj02bn` ([`blue`]) chooses the sequence's structure instead.
//! * `pmj02-stochastic`: Helmer, Christensen, Kensler, "Stochastic Generation of (t, s) Sample
//!   Sequences" (EGSR 2021). Sample `2^k + i` copies the top `k` digits of sample
//!   `i ^ XOR[k]`, flips digit `k + 1` and draws the rest at random: O(1) per sample, and its
//!   distribution is that of an Owen-scrambled (0,2)-sequence. The XOR values are computed
//!   from the generator matrices' definition, not copied. It builds without `std` and is the
//!   renderer crate's (`strata::samplers::Pmj02Stochastic`).
//!
//! All of them store points as 32-bit fixed point (8 bytes per generated point; the occupancy
//! structures of the constructive ones add about `(m + 3) / 8` bytes per point at level `m`),
//! extend themselves by doubling when a sample past the end is asked for, and accept indices up
//! to `2^32 - 1`; after `2^32` samples the stream starts a new, independently seeded sequence.
//!
//! **Classes.** [`class4`] splits the indices into 4 interleaved classes by the XOR of their
//! base-4 digits; for `pmj02-stochastic` each class of a prefix of `2^m` points is itself a
//! (0, m-2, 2)-net (`m >= 2`), so 4 independent effects (e.g. lights) can each take a well
//! stratified quarter. [`class2`] (the high bit of `class4`) halves the sequence into two
//! classes stratified in about two thirds of the elementary shapes; no split by index makes
//! both halves full nets.

pub mod blue;
mod construct;

pub use blue::Pmj02Bn;
use construct::{Construction, Variant};

use crate::counts::CountRule;
use crate::entry::{BlueNoise, Built, Entry, Family, ParameterSpec, Rates};
use crate::{Error, Result};
use strata::float::unit_f32_from_u32;
use strata::samplers::{Epochs, MAX_SEQUENCE_LEN};
use strata::{Point2, Progression, Sampler, Seed, StrataGrid};

/// The default number of best-candidate candidates (as in pmj-cpp and Helmer's code).
pub const DEFAULT_CANDIDATES: u32 = 100;

/// The largest candidate count accepted.
pub const MAX_CANDIDATES: u32 = 1 << 16;

/// The candidates parameter of the best-candidate variants.
const CANDIDATES: ParameterSpec = ParameterSpec::whole(
    "candidates",
    1,
    MAX_CANDIDATES,
    DEFAULT_CANDIDATES,
    "best-candidate candidates per sample, each in a valid stratum",
);

/// The registry entry of `pmj`.
pub(crate) const PMJ: Entry = Entry {
    name: "pmj",
    description: "progressive multi-jittered: 1D strata and squarest grid at every power of two",
    paper: "Christensen, Kensler, Kilpatrick 2018",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    promise: "1D strata and squarest grid at every `2^m` prefix",
    build: |p| Ok(Built::two(Pmj::new(p.seed))),
    ..Entry::DEFAULT
};

/// The registry entry of `pmjbn`.
pub(crate) const PMJBN: Entry = Entry {
    name: "pmjbn",
    description: "pmj with best-candidate blue noise (--candidates K, default 100)",
    paper: "Christensen et al. 2018; Mitchell 1991",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[CANDIDATES],
    promise: "`pmj` + best-candidate blue noise",
    blue_noise: Some(BlueNoise::published(
        "none found (Christensen et al. 2018 could not be checked here)",
    )),
    build: |p| {
        let k = CANDIDATES.read_whole(p);
        Ok(Built::two(Pmj::pmjbn(k, p.seed)?))
    },
    ..Entry::DEFAULT
};

/// The registry entry of `pmj02`.
pub(crate) const PMJ02: Entry = Entry {
    name: "pmj02",
    description: "progressive (0,m,2)-nets at every power of two (Pharr's strata enumeration)",
    paper: "Christensen et al. 2018; Pharr 2019",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    promise: "(0,m,2)-net at every `2^m` prefix and aligned block",
    rates: Rates::NETS,
    build: |p| Ok(Built::two(Pmj::pmj02(p.seed))),
    ..Entry::DEFAULT
};

/// The 4-class label of sample `index`: the XOR of its base-4 digits.
pub fn class4(index: u64) -> u8 {
    let lo = (index & 0x5555_5555_5555_5555).count_ones() & 1;
    let hi = (index & 0xaaaa_aaaa_aaaa_aaaa).count_ones() & 1;
    ((hi << 1) | lo) as u8
}

/// The 2-class label of sample `index` (the high bit of [`class4`]).
pub fn class2(index: u64) -> u8 {
    class4(index) >> 1
}

/// A PMJ-family sequence built by construction (pmj, pmjbn, pmj02).
///
/// ```
/// use strata::{Sampler, Seed};
/// use strata_lab::samplers::Pmj;
/// let mut s = Pmj::pmj02(Seed(7));
/// let pts: Vec<_> = (0..16).map(|_| s.next_sample()).collect();
/// // a (0,4,2)-net: one point in each 4 x 4 cell, and in each 16 x 1 and 1 x 16 stratum
/// let mut cells = vec![0; 16];
/// for p in &pts {
///     cells[(p[1] * 4.0) as usize * 4 + (p[0] * 4.0) as usize] += 1;
/// }
/// assert!(cells.iter().all(|&c| c == 1));
/// ```
#[derive(Clone, Debug)]
pub struct Pmj {
    epochs: Epochs,
    variant: Variant,
    construction: Construction,
    points: Vec<[u32; 2]>,
}

impl Pmj {
    fn with_variant(variant: Variant, seed: Seed) -> Self {
        let epochs = Epochs::new(MAX_SEQUENCE_LEN, seed);
        Pmj {
            construction: Construction::new(variant, epochs.key(0)),
            epochs,
            variant,
            points: Vec::new(),
        }
    }

    /// `pmj`: progressive multi-jittered (1D strata and the squarest 2D grid at every power of
    /// two).
    pub fn new(seed: Seed) -> Self {
        Self::with_variant(Variant::Pmj { candidates: 1 }, seed)
    }

    /// pmj02: a (0,m,2)-net at every power-of-two prefix and every aligned power-of-two block.
    pub fn pmj02(seed: Seed) -> Self {
        Self::with_variant(Variant::Pmj02 { candidates: 1 }, seed)
    }

    /// pmj with best-candidate placement among `candidates` (>= 1) per point.
    pub fn pmjbn(candidates: u32, seed: Seed) -> Result<Self> {
        Ok(Self::with_variant(
            Variant::Pmj {
                candidates: check_candidates(PMJBN.name, candidates)?,
            },
            seed,
        ))
    }

    /// Makes sure the first `count` samples exist (`count <= 2^32`), generating whole
    /// power-of-two passes.
    pub fn reserve(&mut self, count: u64) -> Result<()> {
        if count > MAX_SEQUENCE_LEN {
            return Err(Error::count(
                self.name(),
                count,
                format!("at most {MAX_SEQUENCE_LEN} per sequence"),
            ));
        }
        while (self.points.len() as u64) < count {
            self.construction.extend(&mut self.points);
        }
        Ok(())
    }

    /// Sample `index` (`< 2^32`) as 32-bit fixed point, generating the sequence up to it (hence
    /// `&mut` and the name: `sample*` methods take `&self`).
    pub fn generate_u32(&mut self, index: u32) -> [u32; 2] {
        while self.points.len() <= index as usize {
            self.construction.extend(&mut self.points);
        }
        self.points[index as usize]
    }

    /// Sample `index` (`< 2^32`), generating the sequence up to it.
    pub fn generate(&mut self, index: u32) -> Point2 {
        let p = self.generate_u32(index);
        [unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1])]
    }

    /// The samples generated so far, as 32-bit fixed point.
    pub fn generated(&self) -> &[[u32; 2]] {
        &self.points
    }
}

fn check_candidates(name: &'static str, candidates: u32) -> Result<u32> {
    CANDIDATES.check(name, candidates as f64)?;
    Ok(candidates)
}

impl Sampler for Pmj {
    fn name(&self) -> &'static str {
        match self.variant {
            Variant::Pmj { candidates: 1 } => PMJ.name,
            Variant::Pmj { .. } => PMJBN.name,
            Variant::Pmj02 { .. } => PMJ02.name,
        }
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let (i, new_epoch) = self.epochs.advance();
        if let Some(key) = new_epoch {
            // a new, independent sequence: never run out
            self.construction = Construction::new(self.variant, key);
            self.points = Vec::new();
        }
        self.generate(i as u32)
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        StrataGrid::net(n, matches!(self.variant, Variant::Pmj02 { .. }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_are_the_xor_of_base4_digits() {
        assert_eq!(class4(0), 0);
        assert_eq!(class4(1), 1);
        assert_eq!(class4(2), 2);
        assert_eq!(class4(3), 3);
        assert_eq!(class4(4), 1);
        assert_eq!(class4(5), 0);
        assert_eq!(class4(0b1110), 3 ^ 2);
        assert_eq!(class2(6), 1);
    }

    #[test]
    fn grids_list_the_squarest_first() {
        let g = StrataGrid::net(32, false);
        assert_eq!(
            g[0],
            StrataGrid {
                columns: 4,
                rows: 8
            }
        );
        assert_eq!(
            g[1],
            StrataGrid {
                columns: 8,
                rows: 4
            }
        );
        assert_eq!(StrataGrid::net(32, true).len(), 6);
        assert!(StrataGrid::net(33, true).is_empty());
    }
}
