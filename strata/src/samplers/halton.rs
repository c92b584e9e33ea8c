//! The Halton sequence, Owen-scrambled digit by digit.
//!
//! Halton, "On the efficiency of certain quasi-random sequences of points in evaluating
//! multi-dimensional integrals" (1960): dimension `d` of point `i` is the radical inverse of `i`
//! in the `d`-th prime base. The first `2^a 3^b` points of dimensions 0 and 1 lie one per cell of
//! the `2^a x 3^b` grid, and every block of `b^k` consecutive indices (from a multiple of
//! `b^k`) is stratified in base `b`.
//!
//! Randomization: a nested (Owen) scramble in base `b`, as pbrt-v4's
//! `OwenScrambledRadicalInverse`: each digit is permuted by a permutation drawn for its node of
//! the digit tree, hashed from the seed, the dimension and the digits above it. Base 2 uses the
//! bit-level hash of [`crate::scramble::owen_scramble`]; base 3 draws one of its six permutations
//! per node (two levels per hash); larger bases draw a random affine map `d -> (a d + c) mod b`,
//! `a != 0` (Matousek's linear scrambling: each digit uniform, each pair of distinct digits
//! uniform over the distinct pairs). Digits are produced down to weight `2^-24`, including the
//! index's leading zeros, so the scrambled points are uniform. The stratification above is
//! kept; a test checks that digits under sibling nodes are independent across seeds (and that
//! a Cranley-Patterson shift, which ties them, fails it).
//!
//! Speed: the digit loop divides by multiplication and hashes each node once with no chain
//! between the digits' hashes; [`HaltonNd`] also keeps, per dimension, the permuted top digits
//! of every index residue modulo `b^L <= 2^14` (filled as indices reach them, 64 KiB at most per
//! dimension, none above base 127), so per point only the lower digits are hashed. Same values
//! as [`scrambled_radical_inverse`], which allocates nothing.

use crate::error::Result;
use crate::float::{Strata, unit_f32_from_u32};
use crate::hash::{DivMod, Stream, hash32, mix64, stream_seed};
use crate::prelude::*;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};
use crate::scramble::owen_scramble;

/// The number of prime bases (dimensions) available.
pub const MAX_DIMENSIONS: u32 = 1000;

/// The first [`MAX_DIMENSIONS`] primes, by a sieve at compile time.
pub const PRIMES: [u32; MAX_DIMENSIONS as usize] = {
    const LIMIT: usize = 7920; // the 1000th prime is 7919
    let mut composite = [false; LIMIT];
    let mut primes = [0u32; MAX_DIMENSIONS as usize];
    let (mut n, mut found) = (2usize, 0usize);
    while found < MAX_DIMENSIONS as usize {
        if !composite[n] {
            primes[found] = n as u32;
            found += 1;
            let mut k = n * n;
            while k < LIMIT {
                composite[k] = true;
                k += n;
            }
        }
        n += 1;
    }
    primes
};

/// The registry entry of `halton`.
/// The registered name.
const NAME: &str = "halton";

/// Digits are produced until the last one's weight is at most the inverse of this (the
/// spacing of `f32` in `[1/2, 1)`).
const RESOLUTION: u64 = 1 << 24;

/// The largest power of a base that `f32` strata can still place exactly.
const COARSEST: u64 = 1 << 23;

/// The finest `3^b` rows whose strata the points fill exactly: base 3 steps by 9, and
/// `9^7 <= COARSEST < 9^8`. Past it, a stratum is the `f32` rounding of its bounds and some
/// rows hold none (3^15 points filled 12,564,433 of 14,348,907 rows).
pub(crate) const MAX_PROMISED_POWER_OF_3: u32 = 14;

/// What the digit loop of one prime base needs, computed at compile time. Base 3 steps two
/// digits at a time (radix 9, see [`PAIRS_3`]); the others one.
#[derive(Clone, Copy)]
struct Digits {
    /// Division by the radix, by multiplication.
    div: DivMod,
    /// How many steps reach [`RESOLUTION`].
    count: u32,
    /// How many of them form the stratum among `radix^coarse <= COARSEST` strata.
    coarse: u32,
    /// Bits per step in a node's code (the step's digits + 1 must fit).
    code_bits: u32,
    /// The `base^coarse` strata.
    strata: Strata,
    /// `base^-(count - coarse)`, the weight of the finer digits' integer.
    fine_weight: f64,
}

static DIGITS: [Digits; MAX_DIMENSIONS as usize] = {
    let unused = Digits {
        div: DivMod::ONE,
        count: 0,
        coarse: 0,
        code_bits: 0,
        strata: Strata::new(1),
        fine_weight: 1.0,
    };
    let mut table = [unused; MAX_DIMENSIONS as usize];
    let mut i = 0;
    while i < MAX_DIMENSIONS as usize {
        let b = if PRIMES[i] == 3 { 9 } else { PRIMES[i] as u64 };
        let (mut count, mut coarse, mut scale, mut coarse_scale) = (0u32, 0u32, 1u64, 1u64);
        while scale < RESOLUTION {
            scale *= b;
            count += 1;
            if scale <= COARSEST {
                coarse = count;
                coarse_scale = scale;
            }
        }
        table[i] = Digits {
            div: match DivMod::new(b as u32) {
                Some(v) => v,
                None => DivMod::ONE,
            },
            count,
            coarse,
            code_bits: 64 - b.leading_zeros(), // digit + 1 <= radix
            strata: Strata::new(coarse_scale),
            fine_weight: 1.0 / (scale / coarse_scale) as f64,
        };
        i += 1;
    }
    table
};

/// Every permutation of three digits: base 3 draws one uniformly per node of the digit tree.
const PERMUTATIONS_3: [[u8; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// Base 3 two digits at a time: choice `v < 6^4` names a permutation of the first digit's
/// node (`v % 6`) and one for each of its three children (the next base-6 digits of `v`);
/// entry `[v][d0 + 3 d1]` is the pair permuted by them, `3 P0 + P1`. One hash per two levels,
/// the same nested scramble as one permutation per node.
const PAIRS_3: [[u8; 9]; 1296] = {
    let mut table = [[0u8; 9]; 1296];
    let mut v = 0;
    while v < 1296 {
        let mut d = 0;
        while d < 9 {
            let (d0, d1) = (d % 3, d / 3);
            let first = PERMUTATIONS_3[v % 6][d0];
            let child = (v / [6, 36, 216][d0]) % 6;
            table[v][d] = 3 * first + PERMUTATIONS_3[child][d1];
            d += 1;
        }
        v += 1;
    }
    table
};

/// Dimension `dim` of point `index` of the Halton sequence scrambled by `seed`.
///
/// Each base-`b` digit of the radical inverse is permuted by a permutation drawn for its node
/// of the digit tree (the digits above it): a nested, Owen-style scramble. Base 2 uses the
/// bit-level hash of [`crate::scramble::owen_scramble`]; base 3 draws among its six permutations;
/// larger bases draw a random affine map `d -> (a d + c) mod b` (`a != 0`: Matousek's linear
/// scrambling: every digit uniform, every pair of distinct digits uniform over the distinct
/// pairs). A node's key hashes the seed, the dimension and the digits above it; the keys of
/// different digits do not depend on each other, so their hashes overlap in the processor.
/// Digits run until their weight falls to `2^-24` or below (the spacing of `f32` in `[1/2, 1)`,
/// the resolution of the crate's other samplers) and include the index's leading zero digits,
/// so that the points are uniform. Base 3 draws two digits per hash.
/// Integer arithmetic and one rounding to `f32`: the same bits on every platform.
///
/// Dimensions `0..MAX_DIMENSIONS` ([`MAX_DIMENSIONS`], one prime base each), `None` from it on
/// (as [`sobol::owen_scrambled`](super::sobol::owen_scrambled)). Every `u64` index: dimension
/// 0 reads the index's low 32 bits (its digits past them weigh below `2^-32`, under the `f32`
/// resolution), the other bases read as many digits as reach the resolution.
///
/// ```
/// use strata::Seed;
/// use strata::samplers::halton::{MAX_DIMENSIONS, scrambled_radical_inverse};
/// assert!(scrambled_radical_inverse(7, 2, Seed(1)).is_some());
/// assert_eq!(scrambled_radical_inverse(7, MAX_DIMENSIONS, Seed(1)), None);
/// ```
pub fn scrambled_radical_inverse(index: u64, dim: u32, seed: Seed) -> Option<f32> {
    (dim < MAX_DIMENSIONS).then(|| radical_inverse_at(index, dim as usize, seed.0))
}

/// [`scrambled_radical_inverse`] at a dimension below [`MAX_DIMENSIONS`].
#[inline]
pub(crate) fn radical_inverse_at(index: u64, dim: usize, seed: u64) -> f32 {
    let key = dimension_key(seed, dim);
    if dim == 0 {
        return base_2(key, index);
    }
    radical_inverse(dim, key, Walk::from_root(index))
}

/// The key of dimension `dim`'s scramble.
#[inline]
fn dimension_key(seed: u64, dim: usize) -> u64 {
    stream_seed(Stream::HaltonDigits.id() + dim as u64, seed)
}

/// Base 2: the bit-level Owen scramble of the reversed index.
#[inline]
fn base_2(key: u64, index: u64) -> f32 {
    let bits = (index as u32).reverse_bits(); // indices beyond 2^32 wrap (documented)
    unit_f32_from_u32(owen_scramble(bits, hash32(key as u32, (key >> 32) as u32)))
}

/// Where the walk down the digit tree starts: `levels` steps done, their permuted digits as
/// the integer `top`, the code of the node below them, and the index's digits left.
#[derive(Clone, Copy)]
struct Walk {
    levels: u32,
    top: u64,
    code: u64,
    rest: u64,
}

impl Walk {
    #[inline]
    fn from_root(index: u64) -> Self {
        Walk {
            levels: 0,
            top: 0,
            code: 0,
            rest: index,
        }
    }
}

/// Dimension `dim >= 1` from `start` on.
#[inline(always)]
fn radical_inverse(dim: usize, key: u64, start: Walk) -> f32 {
    let t = &DIGITS[dim];
    let r = t.div.divisor() as u64;
    let mut tree = DigitTree {
        t,
        key,
        rest: start.rest,
        code: start.code,
        shift: start.levels * t.code_bits,
    };
    // the permuted digits: the first `t.coarse` name the stratum, the rest place x inside it,
    // so that f32 rounding cannot move x across a boundary of any coarser level
    let mut coarse = start.top;
    for _ in start.levels..t.coarse {
        coarse = coarse * r + tree.next() as u64;
    }
    let mut fine = 0u64;
    for _ in t.coarse..t.count {
        fine = fine * r + tree.next() as u64;
    }
    t.strata
        .place_f64(coarse, fine as i64 as f64 * t.fine_weight)
}

/// The most entries of a [`Dimension`]'s table of permuted top digits (64 KiB).
const PREFIX_ENTRIES: u32 = 1 << 14;

/// Bits of a table entry for the permuted top digits (`radix^levels <= PREFIX_ENTRIES`); the
/// node's code takes the other 18.
const TOP_BITS: u32 = 14;

/// One dimension of [`HaltonNd`]: its key and a table, filled as indices reach it, of the
/// permuted top digits and the node code for every residue of the index modulo
/// `radix^levels`, so that per point only the digits below them are hashed. The values are
/// those of [`scrambled_radical_inverse`].
#[derive(Clone, Debug)]
struct Dimension {
    dim: usize,
    key: u64,
    /// Digit steps the table covers (0: no table).
    levels: u32,
    /// Division by `radix^levels`.
    modulus: DivMod,
    /// Per residue `top | code << TOP_BITS`; 0 until computed (a code is never 0).
    table: Vec<u32>,
}

impl Dimension {
    /// Dimension `dim` for `seed`; the table's memory is reserved (zeroed pages are mapped
    /// lazily), its entries computed on first use.
    fn new(dim: usize, seed: u64) -> Self {
        let mut d = Dimension {
            dim,
            key: dimension_key(seed, dim),
            levels: 0,
            modulus: DivMod::ONE,
            table: Vec::new(),
        };
        if dim == 0 {
            return d; // base 2 is a bit-level hash already
        }
        let t = &DIGITS[dim];
        let r = t.div.divisor();
        let (mut levels, mut entries) = (0u32, 1u32);
        while entries * r <= PREFIX_ENTRIES && (levels + 1) * t.code_bits <= 32 - TOP_BITS {
            entries *= r;
            levels += 1;
        }
        if levels >= 2 {
            // one level saves too little for the memory (bases above 127)
            d.levels = levels;
            d.modulus = DivMod::new(entries).unwrap_or(DivMod::ONE);
            d.table = vec![0; entries as usize];
        }
        d
    }

    /// The dimension's value at `index`.
    #[inline]
    fn value(&mut self, index: u64) -> f32 {
        if self.dim == 0 {
            return base_2(self.key, index);
        }
        if self.levels == 0 {
            return radical_inverse(self.dim, self.key, Walk::from_root(index));
        }
        let (rest, residue) = match u32::try_from(index) {
            Ok(small) => {
                let (q, r) = self.modulus.div_rem(small);
                (q as u64, r)
            }
            Err(_) => {
                let m = self.modulus.divisor() as u64;
                (index / m, (index % m) as u32)
            }
        };
        let mut entry = self.table[residue as usize];
        if entry == 0 {
            let t = &DIGITS[self.dim];
            let mut tree = DigitTree {
                t,
                key: self.key,
                rest: residue as u64,
                code: 0,
                shift: 0,
            };
            let r = t.div.divisor();
            let top = (0..self.levels).fold(0u32, |acc, _| acc * r + tree.next());
            entry = top | (tree.code as u32) << TOP_BITS;
            self.table[residue as usize] = entry;
        }
        let start = Walk {
            levels: self.levels,
            top: (entry & ((1 << TOP_BITS) - 1)) as u64,
            code: (entry >> TOP_BITS) as u64,
            rest,
        };
        radical_inverse(self.dim, self.key, start)
    }
}

/// The walk down the digit tree of one index in one base: the index's digits, least
/// significant first (the radical inverse's most significant), each permuted at its node.
struct DigitTree<'a> {
    t: &'a Digits,
    key: u64,
    /// The index's digits not yet emitted.
    rest: u64,
    /// The node's code: the digits above it, each plus one, `code_bits` apart (a zero digit
    /// still counts, so "0" and "00" differ).
    code: u64,
    shift: u32,
}

impl DigitTree<'_> {
    /// The next permuted digit (pair of digits in base 3).
    #[inline(always)]
    fn next(&mut self) -> u32 {
        let node = mix64(self.key ^ self.code);
        let b = self.t.div.divisor();
        let digit = if self.rest == 0 {
            // the index's leading zeros (most digits of a small index): no division, and a
            // permutation's image of 0 is its offset
            0
        } else if let Ok(small) = u32::try_from(self.rest) {
            let (q, r) = self.t.div.div_rem(small);
            self.rest = q as u64;
            r
        } else {
            let r = (self.rest % b as u64) as u32;
            self.rest /= b as u64;
            r
        };
        self.code |= (digit as u64 + 1) << self.shift;
        self.shift += self.t.code_bits;
        let h = (node >> 32) as u32;
        if b == 9 {
            PAIRS_3[((node as u128 * 1296) >> 64) as usize][digit as usize] as u32
        } else {
            let offset = ((node as u32 as u64 * b as u64) >> 32) as u32;
            if digit == 0 {
                return offset;
            }
            let scale_by = 1 + ((h as u64 * (b - 1) as u64) >> 32) as u32;
            self.t.div.div_rem(scale_by * digit + offset).1
        }
    }
}

/// The scrambled Halton sequence in 2D (bases 2 and 3), progressive.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Halton};
/// let mut s = Halton::new(Seed(3));
/// // the first 6 points: one per cell of the 2 x 3 grid
/// let mut cells: Vec<_> = (0..6).map(|_| { let p = s.next_sample(); ((p[0] * 2.0) as u32, (p[1] * 3.0) as u32) }).collect();
/// cells.sort();
/// cells.dedup();
/// assert_eq!(cells.len(), 6);
/// ```
#[derive(Clone, Debug)]
pub struct Halton {
    keys: [u64; 2],
    next: u64,
}

impl Halton {
    /// The sequence for `seed`.
    pub fn new(seed: Seed) -> Self {
        Halton {
            keys: [0, 1].map(|d| dimension_key(seed.0, d)),
            next: 0,
        }
    }

    /// Point `index` (2D): [`scrambled_radical_inverse`] in dimensions 0 and 1.
    pub fn sample(&self, index: u64) -> Point2 {
        [
            base_2(self.keys[0], index),
            radical_inverse(1, self.keys[1], Walk::from_root(index)),
        ]
    }
}

impl Sampler for Halton {
    fn name(&self) -> &'static str {
        NAME
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let p = self.sample(self.next);
        self.next = self.next.wrapping_add(1);
        p
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        // n = 2^a 3^b: one point per cell of 2^a x 3^b
        let (mut m, mut a, mut b) = (n, 0u32, 0u32);
        while m > 0 && m % 2 == 0 {
            m /= 2;
            a += 1;
        }
        while m > 0 && m % 3 == 0 {
            m /= 3;
            b += 1;
        }
        if m != 1 || a > 24 || b > MAX_PROMISED_POWER_OF_3 {
            return Vec::new();
        }
        vec![StrataGrid {
            columns: 1 << a,
            rows: 3u32.pow(b),
        }]
    }
}

/// The scrambled Halton sequence in `D` dimensions (the first `D` primes), progressive.
#[derive(Clone, Debug)]
pub struct HaltonNd {
    dims: Vec<Dimension>,
    next: u64,
}

impl HaltonNd {
    /// `dims` dimensions (1 to [`MAX_DIMENSIONS`]) seeded by `seed`.
    pub fn new(dims: u32, seed: Seed) -> Result<Self> {
        super::check_dims(
            NAME,
            dims,
            MAX_DIMENSIONS,
            " (one prime base per dimension)",
        )?;
        Ok(HaltonNd {
            dims: (0..dims as usize)
                .map(|d| Dimension::new(d, seed.0))
                .collect(),
            next: 0,
        })
    }
}

impl SamplerNd for HaltonNd {
    fn name(&self) -> &'static str {
        NAME
    }

    fn dimensions(&self) -> u32 {
        self.dims.len() as u32
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_point(&mut self, out: &mut [f32]) {
        for (d, o) in self.dims.iter_mut().zip(out.iter_mut()) {
            *o = d.value(self.next);
        }
        self.next = self.next.wrapping_add(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_promised_rows_of_base_3_are_those_placed_exactly() {
        // base 3 steps two digits at a time: its exact strata are 9^coarse = 3^(2 coarse)
        assert_eq!(DIGITS[1].coarse * 2, MAX_PROMISED_POWER_OF_3);
        let s = Halton::new(Seed(3));
        let n = 3u64.pow(MAX_PROMISED_POWER_OF_3);
        assert_eq!(s.strata(n).len(), 1);
        assert!(s.strata(n * 3).is_empty(), "3^15 rows are not all filled");
        let mut filled = vec![false; n as usize];
        for i in 0..n {
            filled[(s.sample(i)[1] as f64 * n as f64) as usize] = true;
        }
        assert_eq!(filled.iter().filter(|&&f| f).count() as u64, n);
    }

    #[test]
    fn primes_are_the_first_thousand() {
        assert_eq!(&PRIMES[..6], &[2, 3, 5, 7, 11, 13]);
        assert_eq!(PRIMES[999], 7919);
    }

    #[test]
    fn every_dimension_is_stratified_in_its_base() {
        // the largest power of the base up to 20 000 (base 3: nine digits, across its pairs),
        // for the first block of indices and a later one
        for dim in [0usize, 1, 2, 5, 30] {
            let b = PRIMES[dim] as u64;
            let mut n = b;
            while n * b <= 20_000 {
                n *= b;
            }
            for start in [0, 7 * n] {
                let mut seen = vec![false; n as usize];
                for i in start..start + n {
                    let x = radical_inverse_at(i, dim, 17);
                    let cell = (x as f64 * n as f64) as usize;
                    assert!(!seen[cell], "dim {dim}: cell {cell} twice");
                    seen[cell] = true;
                }
            }
        }
    }

    #[test]
    fn tables_give_the_stateless_values() {
        // HaltonNd's top-digit tables, filled as indices reach them, against the walk from the
        // root: every dimension kind (base 2, base-3 pairs, tables of 6 to 2 levels, no table),
        // indices in the first and later passes over each table, and past 2^32
        let dims = [0usize, 1, 2, 3, 4, 10, 30, 31, 200, 999];
        let mut s = HaltonNd::new(1000, Seed(5)).unwrap();
        let mut out = vec![0f32; 1000];
        let indices = (0..3000u64).chain([16_383, 16_384, 1 << 20, u32::MAX as u64, 1 << 40]);
        for i in indices.clone().chain(indices) {
            s.next = i;
            s.next_point(&mut out);
            for &d in &dims {
                assert_eq!(
                    out[d],
                    scrambled_radical_inverse(i, d as u32, crate::Seed(5)).unwrap(),
                    "dim {d} index {i}"
                );
            }
        }
    }
}
