//! Stochastic pmj02: Helmer, Christensen, Kensler, "Stochastic Generation of (t, s) Sample
//! Sequences" (EGSR 2021).
//!
//! # The algorithm
//!
//! Sample 0 is uniform. Sample `2^k + i` (for `i < 2^k`) takes, in each dimension `d`, the
//! partner `j = i ^ XOR_d[k]`, copies the first `k` binary digits of the partner's coordinate,
//! flips digit `k + 1`, and draws all later digits at random. Every prefix and every aligned
//! block of `2^m` samples is then a (0,m,2)-net, distributed as an Owen-scrambled digital
//! (0,2)-sequence, at O(1) per sample. Any single sample can also be computed on its own in
//! O(log i) by following the partner chain ([`Pmj02Stochastic::point`]).
//!
//! # Where the XOR values come from
//!
//! Let `C` be the generator matrix of a base-2 digital sequence (upper triangular, unit
//! diagonal; digit `r` of the point is row `r` of `C` times the index bits). Samples `2^k + i`
//! and `j` agree in their first `k` digits and differ in digit `k` exactly when
//! `C (e_k + bits(i ^ j)) = e_k` in the first `k + 1` rows, i.e. `bits(i ^ j)` is column `k`
//! of `C^-1` without its diagonal entry. For pmj02 the generator matrices are the unsigned
//! Stirling numbers of the first kind mod 2; [`crate::digital`] computes them, inverts them over
//! GF(2) and reads the XOR values off the inverse's columns (the inverse is the matrix of
//! Stirling numbers of the second kind mod 2, which its tests check independently). The
//! path-tracer adapter's `pmj02` is the same digital sequence, Owen-scrambled.

use crate::float::unit_f32_from_u32;
use crate::hash::{hash_u64, stream_seed};
use crate::prelude::*;
use crate::sampler::{Point2, Progression, Sampler, Seed, StrataGrid};

use super::MAX_SEQUENCE_LEN;
use crate::samplers::Epochs;

/// The partner offsets of the construction, from the generator matrices of pmj02 as a digital
/// sequence ([`crate::digital`], where they are derived and tested).
use crate::digital::PMJ02_XORS as XORS;

/// The stochastic pmj02 sequence (progressive; O(1) per sample, 8 bytes per stored sample).
///
/// ```
/// use strata::{Sampler, Seed, samplers::Pmj02Stochastic};
/// let mut s = Pmj02Stochastic::new(Seed(3));
/// let a = s.next_sample();
/// // any sample can also be computed on its own
/// assert_eq!(Pmj02Stochastic::point(0, Seed(3)), a);
/// ```
#[derive(Clone, Debug)]
pub struct Pmj02Stochastic {
    epochs: Epochs,
    key: u64,
    points: Vec<[u32; 2]>,
}

/// The registered name.
const NAME: &str = "pmj02-stochastic";

impl Pmj02Stochastic {
    /// The sequence seeded by `seed`.
    pub fn new(seed: Seed) -> Self {
        let epochs = Epochs::new(MAX_SEQUENCE_LEN, seed);
        Pmj02Stochastic {
            key: epochs.key(0),
            epochs,
            points: Vec::new(),
        }
    }

    /// The random bits of sample `index` (x in the low half, y in the high half).
    #[inline]
    fn random(key: u64, index: u32) -> u64 {
        hash_u64(index as u64, key)
    }

    /// Generates up to `count` samples (`<= 2^32`), a whole power-of-two pass at a time.
    pub fn reserve(&mut self, count: u64) {
        let count = count.min(MAX_SEQUENCE_LEN);
        while (self.points.len() as u64) < count {
            self.extend();
        }
    }

    /// Appends the next pass (`2^k` samples; the first sample alone at the start).
    fn extend(&mut self) {
        let key = self.key;
        let n = self.points.len();
        if n == 0 {
            let r = Self::random(key, 0);
            self.points.push([r as u32, (r >> 32) as u32]);
            return;
        }
        let k = n.trailing_zeros() as usize;
        let bit = 0x8000_0000u32 >> k;
        let keep = !(bit.wrapping_sub(1)) & !bit; // the first k digits
        let (xx, xy) = (XORS[0][k] as usize, XORS[1][k] as usize);
        self.points.reserve(n);
        for i in 0..n {
            let r = Self::random(key, (n + i) as u32);
            let px = self.points[i ^ xx][0];
            let py = self.points[i ^ xy][1];
            let low = bit.wrapping_sub(1);
            let x = ((px & keep) | (!px & bit)) | (r as u32 & low);
            let y = ((py & keep) | (!py & bit)) | ((r >> 32) as u32 & low);
            self.points.push([x, y]);
        }
    }

    /// Sample `index` as 32-bit fixed point, generating the sequence up to it (hence `&mut`
    /// and the name: `sample*` methods take `&self`).
    pub fn generate_u32(&mut self, index: u32) -> [u32; 2] {
        while self.points.len() <= index as usize {
            self.extend();
        }
        self.points[index as usize]
    }

    /// Sample `index`, generating the sequence up to it.
    pub fn generate(&mut self, index: u32) -> Point2 {
        let p = self.generate_u32(index);
        [unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1])]
    }

    /// The samples generated so far, as 32-bit fixed point.
    pub fn generated(&self) -> &[[u32; 2]] {
        &self.points
    }

    /// Sample `index` of the sequence seeded by `seed`, computed without storing the sequence:
    /// O(log index) by walking the partner chain. Bit-identical to the stored sequence.
    /// (The seed last, as in every stateless function of the crate.)
    pub fn point(index: u32, seed: Seed) -> Point2 {
        let p = Self::point_u32(index, seed);
        [unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1])]
    }

    /// [`point`](Pmj02Stochastic::point) as 32-bit fixed point.
    pub fn point_u32(index: u32, seed: Seed) -> [u32; 2] {
        let key = stream_seed(0, seed.0);
        [
            Self::coordinate_at(key, index, 0),
            Self::coordinate_at(key, index, 1),
        ]
    }

    /// One coordinate of sample `index`. Walking the partner chain from `index` down to sample
    /// 0, each link of level `k` (index in `[2^k, 2^(k+1))`) supplies, from its random bits, the
    /// digits between its own digit `k` and the digits already known; its digit `k` is the flip
    /// of its partner's, so the next link supplies it flipped.
    fn coordinate_at(key: u64, index: u32, dim: usize) -> u32 {
        let pick = |r: u64| if dim == 0 { r as u32 } else { (r >> 32) as u32 };
        // Digit position p (from the top, 0-based) is the bit 0x8000_0000 >> p. `need` is the
        // lowest position still unknown; positions below it are fixed.
        let below = |p: u32| if p >= 31 { 0 } else { u32::MAX >> (p + 1) }; // positions > p
        let mut value = 0u32;
        let mut need = 31u32;
        let mut pending_flip = 0u32;
        let mut idx = index;
        while idx != 0 {
            let k = 31 - idx.leading_zeros();
            // positions k+1 ..= need
            let take = below(k) & !below(need);
            value |= (pick(Self::random(key, idx)) ^ pending_flip) & take;
            pending_flip = 0x8000_0000u32 >> k;
            need = k;
            idx = (idx - (1 << k)) ^ XORS[dim][k as usize];
        }
        value | ((pick(Self::random(key, 0)) ^ pending_flip) & !below(need))
    }
}

impl Sampler for Pmj02Stochastic {
    fn name(&self) -> &'static str {
        NAME
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    #[inline]
    fn next_sample(&mut self) -> Point2 {
        let mut p = [[0.0; 2]];
        self.fill(&mut p);
        p[0]
    }

    fn fill(&mut self, out: &mut [Point2]) {
        let mut rest = out;
        while !rest.is_empty() {
            let (start, k, new_epoch) = self.epochs.take(rest.len() as u64);
            if let Some(key) = new_epoch {
                self.key = key;
                self.points = Vec::new();
            }
            self.reserve(start + k);
            let (head, tail) = rest.split_at_mut(k as usize);
            for (o, p) in head
                .iter_mut()
                .zip(&self.points[start as usize..(start + k) as usize])
            {
                *o = [unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1])];
            }
            rest = tail;
        }
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        StrataGrid::net(n, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn random_access_equals_the_stored_sequence() {
        for seed in [0u64, 5, u64::MAX] {
            let mut s = Pmj02Stochastic::new(Seed(seed));
            s.reserve(4096);
            for i in (0..4096u32).chain([4095]) {
                assert_eq!(
                    Pmj02Stochastic::point_u32(i, Seed(seed)),
                    s.generated()[i as usize],
                    "seed {seed} index {i}"
                );
            }
        }
    }
}
