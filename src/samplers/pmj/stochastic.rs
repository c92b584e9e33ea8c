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
//! O(log i) by following the partner chain ([`Pmj02Stochastic::point_at`]).
//!
//! # Where the XOR values come from
//!
//! Let `C` be the generator matrix of a base-2 digital sequence (upper triangular, unit
//! diagonal; digit `r` of the point is row `r` of `C` times the index bits). Samples `2^k + i`
//! and `j` agree in their first `k` digits and differ in digit `k` exactly when
//! `C (e_k + bits(i ^ j)) = e_k` in the first `k + 1` rows, i.e. `bits(i ^ j)` is column `k`
//! of `C^-1` without its diagonal entry. For pmj02 the generator matrices are the unsigned
//! Stirling numbers of the first kind mod 2 (x: rows and columns `0..`, y: shifted by one); we
//! compute them from their recurrence `s(n, k) = s(n-1, k-1) + (n-1) s(n-1, k)`, invert them over
//! GF(2), and read the XOR values off the inverse's columns. (The inverse is the matrix of
//! Stirling numbers of the second kind mod 2, which the tests check independently.)

use crate::float::unit_f32_from_u32;
use crate::hash::{hash_u64, stream_seed};
use crate::prelude::*;
#[cfg(feature = "std")]
use crate::registry::{CountRule, Entry, Family, Rates};
use crate::sampler::{Point2, Progression, Sampler, Seed, StrataGrid};

use super::{MAX_SEQUENCE_LEN, pmj_grids};
use crate::samplers::Epochs;

/// Number of digits (and XOR values) per dimension: 32-bit fixed point.
const DIGITS: usize = 32;

/// The unsigned Stirling numbers of the first kind mod 2, `s(n, k)` for `n, k < size`, as rows of
/// bits (`row[n] >> k & 1`), from the recurrence `s(n, k) = s(n-1, k-1) + (n-1) s(n-1, k)`.
const fn stirling_first_mod2<const N: usize>() -> [u64; N] {
    let mut rows = [0u64; N];
    rows[0] = 1; // s(0, 0) = 1
    let mut n = 1;
    while n < N {
        let prev = rows[n - 1];
        // (n - 1) s(n-1, k) contributes only when n - 1 is odd
        let keep = if (n - 1) % 2 == 1 { prev } else { 0 };
        rows[n] = (prev << 1) ^ keep;
        n += 1;
    }
    rows
}

/// The generator matrix of pmj02 dimension `dim` (0 = x, 1 = y) as 32 columns of bits:
/// `col[c] >> r & 1 = C[r][c]`, with `C[r][c] = s(c + dim, r + dim) mod 2`.
const fn generator(dim: usize) -> [u64; DIGITS] {
    let s = stirling_first_mod2::<{ DIGITS + 1 }>();
    let mut cols = [0u64; DIGITS];
    let mut c = 0;
    while c < DIGITS {
        let mut r = 0;
        while r < DIGITS {
            if (s[c + dim] >> (r + dim)) & 1 == 1 {
                cols[c] |= 1 << r;
            }
            r += 1;
        }
        c += 1;
    }
    cols
}

/// The inverse over GF(2) of an upper unit-triangular matrix given by columns, by back
/// substitution: column `c` of the inverse is the `v` with `C v = e_c`.
const fn inverse_upper(cols: [u64; DIGITS]) -> [u64; DIGITS] {
    let mut inv = [0u64; DIGITS];
    let mut c = 0;
    while c < DIGITS {
        // Solve C v = e_c from the bottom row up: v_r = [r == c] + sum_{t > r} C[r][t] v_t.
        let mut v = 0u64;
        let mut r = c as isize;
        while r >= 0 {
            let ru = r as usize;
            let mut bit = if ru == c { 1 } else { 0 };
            let mut t = ru + 1;
            while t <= c {
                if (cols[t] >> ru) & 1 == 1 && (v >> t) & 1 == 1 {
                    bit ^= 1;
                }
                t += 1;
            }
            v |= (bit as u64) << ru;
            r -= 1;
        }
        inv[c] = v;
        c += 1;
    }
    inv
}

/// `XOR_d[k]`: column `k` of the inverse generator matrix without its diagonal.
const fn xor_values(dim: usize) -> [u32; DIGITS] {
    let inv = inverse_upper(generator(dim));
    let mut out = [0u32; DIGITS];
    let mut k = 0;
    while k < DIGITS {
        out[k] = (inv[k] & !(1u64 << k)) as u32;
        k += 1;
    }
    out
}

/// The XOR values of pmj02's two dimensions, computed at compile time.
pub(crate) const XORS: [[u32; DIGITS]; 2] = [xor_values(0), xor_values(1)];

/// pmj02 as a digital sequence: dimensions 0 and 1 of the base-2 digital (0,2)-sequence whose
/// generator matrices are [`generator`]`(0)` and `(1)`, at a bit-reversed index, bit-reversed.
/// Owen-scrambled, its points are distributed as the stochastic pmj02 sequence (Helmer et al.
/// 2021, who derive the construction from these matrices); the Z-ordered adapter sequence
/// `zpmj02` reads it at 32-bit indices, where no table of the stochastic sequence would fit.
pub(crate) fn digital_point01_rev(index_rev: u32) -> [u32; 2] {
    [
        crate::samplers::sobol::lookup(&DIGITAL_TABLES[0], index_rev),
        crate::samplers::sobol::lookup(&DIGITAL_TABLES[1], index_rev),
    ]
}

/// The byte tables of [`digital_point01_rev`], built at compile time.
static DIGITAL_TABLES: [[[u32; 256]; 4]; 2] = [digital_tables(0), digital_tables(1)];

const fn digital_tables(dim: usize) -> [[u32; 256]; 4] {
    let cols = generator(dim);
    let mut m = [0u32; 32];
    let mut k = 0;
    while k < DIGITS {
        m[k] = (cols[k] as u32).reverse_bits(); // row r (digit r from the top) -> bit 31 - r
        k += 1;
    }
    crate::samplers::sobol::byte_tables(&m)
}

/// The stochastic pmj02 sequence (progressive; O(1) per sample, 8 bytes per stored sample).
///
/// ```
/// use strata::{Sampler, Seed, samplers::Pmj02Stochastic};
/// let mut s = Pmj02Stochastic::new(Seed(3));
/// let a = s.next_sample();
/// // any sample can also be computed on its own
/// assert_eq!(Pmj02Stochastic::point_at(Seed(3), 0), a);
/// ```
#[derive(Clone, Debug)]
pub struct Pmj02Stochastic {
    epochs: Epochs,
    key: u64,
    points: Vec<[u32; 2]>,
}

/// The registered name.
const NAME: &str = "pmj02-stochastic";

/// The registry entry of `pmj02-stochastic`.
#[cfg(feature = "std")]
pub(crate) const ENTRY: Entry = Entry {
    name: NAME,
    description: "pmj02 by stochastic generation, O(1) per sample",
    paper: "Helmer, Christensen, Kensler 2021",
    family: Family::Pmj,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[],
    promise: "as `pmj02`, O(1) per sample, stratified classes",
    rates: Rates::NETS,
    expensive: false,
    build: |p| Ok(Box::new(Pmj02Stochastic::new(p.sampler_seed()))),
    nd: None,
};

impl Pmj02Stochastic {
    /// The sequence seeded by `seed`.
    pub fn new(seed: Seed) -> Self {
        let epochs = Epochs::new(seed, MAX_SEQUENCE_LEN);
        Pmj02Stochastic {
            key: epochs.key(0),
            epochs,
            points: Vec::new(),
        }
    }

    /// The random bits of sample `index` (x in the low half, y in the high half).
    #[inline]
    fn random(key: u64, index: u32) -> u64 {
        hash_u64(key, index as u64)
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

    /// Sample `index` as 32-bit fixed point, generating the sequence up to it.
    pub fn sample_fixed(&mut self, index: u32) -> [u32; 2] {
        while self.points.len() <= index as usize {
            self.extend();
        }
        self.points[index as usize]
    }

    /// Sample `index`, generating the sequence up to it.
    pub fn sample(&mut self, index: u32) -> Point2 {
        let p = self.sample_fixed(index);
        Point2::new(unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1]))
    }

    /// The samples generated so far, as 32-bit fixed point.
    pub fn generated(&self) -> &[[u32; 2]] {
        &self.points
    }

    /// Sample `index` of the sequence seeded by `seed`, computed without storing the sequence:
    /// O(log index) by walking the partner chain. Bit-identical to the stored sequence.
    pub fn point_at(seed: Seed, index: u32) -> Point2 {
        let p = Self::point_at_fixed(seed, index);
        Point2::new(unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1]))
    }

    /// [`point_at`](Pmj02Stochastic::point_at) as 32-bit fixed point.
    pub fn point_at_fixed(seed: Seed, index: u32) -> [u32; 2] {
        let key = stream_seed(seed.0, 0);
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
        let mut p = [Point2::ZERO];
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
                *o = Point2::new(unit_f32_from_u32(p[0]), unit_f32_from_u32(p[1]));
            }
            rest = tail;
        }
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        pmj_grids(n, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Stirling numbers of the second kind mod 2 from their own recurrence
    /// `S(n, k) = k S(n-1, k) + S(n-1, k-1)`.
    fn stirling_second_mod2(n: usize, k: usize) -> u64 {
        let mut t = vec![vec![0u64; n + 2]; n + 2];
        t[0][0] = 1;
        for i in 1..=n {
            for j in 1..=i {
                t[i][j] = ((j as u64 % 2) * t[i - 1][j] + t[i - 1][j - 1]) % 2;
            }
        }
        t[n][k]
    }

    #[test]
    fn xor_values_match_stirling_numbers_of_the_second_kind() {
        for (k, (&x, &y)) in XORS[0].iter().zip(&XORS[1]).enumerate().take(20) {
            let want_x: u32 = (0..k)
                .map(|r| (stirling_second_mod2(k, r) as u32) << r)
                .sum();
            let want_y: u32 = (0..k)
                .map(|r| (stirling_second_mod2(k + 1, r + 1) as u32) << r)
                .sum();
            assert_eq!(x, want_x, "x, k = {k}");
            assert_eq!(y, want_y, "y, k = {k}");
        }
        // The first values, as published with the paper's supplemental code.
        assert_eq!(
            &XORS[0][..11],
            &[0, 0, 2, 6, 6, 0xe, 0x36, 0x4e, 0x16, 0x2e, 0x276]
        );
        assert_eq!(
            &XORS[1][..11],
            &[0, 1, 3, 3, 7, 0x1b, 0x27, 0xb, 0x17, 0x13b, 0x367]
        );
    }

    #[test]
    fn the_digital_form_is_a_0_2_sequence() {
        // every prefix and aligned block of 2^m points, m <= 12, fills every elementary interval
        for m in 0..=12u32 {
            let n = 1u32 << m;
            for start in [0u32, n, 5 * n, 1 << 20] {
                for a in 0..=m {
                    let mut seen = vec![false; n as usize];
                    for i in start..start + n {
                        let p = digital_point01_rev(i.reverse_bits());
                        let (x, y) = (p[0].reverse_bits(), p[1].reverse_bits());
                        let top =
                            |v: u32, b: u32| if b == 0 { 0 } else { (v >> (32 - b)) as usize };
                        let cell = (top(y, m - a) << a) | top(x, a);
                        assert!(
                            !seen[cell],
                            "m {m} start {start} shape {a}: cell {cell} twice"
                        );
                        seen[cell] = true;
                    }
                }
            }
        }
    }

    #[test]
    fn random_access_equals_the_stored_sequence() {
        for seed in [0u64, 5, u64::MAX] {
            let mut s = Pmj02Stochastic::new(Seed(seed));
            s.reserve(4096);
            for i in (0..4096u32).chain([4095]) {
                assert_eq!(
                    Pmj02Stochastic::point_at_fixed(Seed(seed), i),
                    s.generated()[i as usize],
                    "seed {seed} index {i}"
                );
            }
        }
    }
}
