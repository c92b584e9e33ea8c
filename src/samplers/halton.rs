//! The Halton sequence, Owen-scrambled digit by digit.
//!
//! Halton, "On the efficiency of certain quasi-random sequences of points in evaluating
//! multi-dimensional integrals" (1960): dimension `d` of point `i` is the radical inverse of `i`
//! in the `d`-th prime base. The first `2^a 3^b` points of dimensions 0 and 1 lie one per cell of
//! the `2^a x 3^b` grid.
//!
//! Randomization: each digit is permuted by a Kensler permutation ([`Permutation`]) whose key
//! hashes the seed, the dimension and the digits already emitted (a nested, Owen-style scramble
//! in base `b`, as pbrt-v4's `OwenScrambledRadicalInverse`); base 2 uses the bit-level hash
//! scramble of [`crate::hash::owen_scramble`]. Digits are produced until they no longer change
//! the 32-bit result, including the trailing zero digits of the index, so the scrambled points
//! are uniform. The stratification above is kept.

use crate::error::Result;
use crate::float::{Strata, unit_f32_from_u32};
use crate::hash::{GOLDEN_GAMMA, Permutation, Stream, hash32, mix64, owen_scramble, stream_seed};
use crate::registry::{CountRule, Entry, Rates};
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// The number of prime bases (dimensions) available.
pub const MAX_DIMENSIONS: usize = 1000;

/// The first [`MAX_DIMENSIONS`] primes, by a sieve at compile time.
pub const PRIMES: [u32; MAX_DIMENSIONS] = {
    const LIMIT: usize = 7920; // the 1000th prime is 7919
    let mut composite = [false; LIMIT];
    let mut primes = [0u32; MAX_DIMENSIONS];
    let (mut n, mut found) = (2usize, 0usize);
    while found < MAX_DIMENSIONS {
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
pub(crate) const ENTRY: Entry = Entry {
    name: "halton",
    description: "Halton, Owen-scrambled digits, progressive, any --dims up to 1000",
    paper: "Halton 1960",
    progressive: true,
    counts: CountRule::Any,
    parameters: &[],
    promise: "one point per cell of `2^a x 3^b` at `N = 2^a 3^b`; 1000 dims",
    rates: Rates::NONE,
    expensive: false,
    build: |p| Ok(Box::new(Halton::new(p.sampler_seed()))),
    nd: Some(|p, d| Ok(Box::new(HaltonNd::new(d, p.sampler_seed())?))),
};

/// Dimension `dim` of point `index` of the Halton sequence scrambled by `seed`.
pub fn scrambled_radical_inverse(dim: usize, index: u64, seed: u64) -> f32 {
    let base = PRIMES[dim] as u64;
    let key = stream_seed(seed, Stream::HaltonDigits.id() + dim as u64);
    if base == 2 {
        let bits = (index as u32).reverse_bits(); // indices beyond 2^32 wrap (documented)
        return unit_f32_from_u32(owen_scramble(bits, hash32(key as u32, (key >> 32) as u32)));
    }
    let mut a = index;
    let (mut reversed, mut scale, mut coarse, mut level) = (0u64, 1u64, 1u64, 0u64);
    // digits until the next one's weight falls below 2^-32; `coarse` = the largest power of the
    // base up to 2^23, whose strata f32 can still place exactly
    while scale < 1 << 32 {
        let digit = (a % base) as u32;
        a /= base;
        // the node of the digit tree: its level and the digits above it (both, so that the
        // prefixes "0" and "00" get independent permutations)
        let node = mix64(key ^ reversed ^ level.wrapping_mul(GOLDEN_GAMMA));
        let perm = Permutation::new(base as u32, (node >> 32) as u32).expect("base >= 2");
        level += 1;
        reversed = reversed * base + perm.apply(digit) as u64;
        scale *= base;
        if scale <= 1 << 23 {
            coarse = scale;
        }
    }
    // x = reversed / scale, placed in its stratum of 1/coarse so that f32 rounding cannot move
    // it across a boundary of any level b^j <= coarse
    let fine = scale / coarse;
    Strata::new(coarse).place_f64(reversed / fine, (reversed % fine) as f64 / fine as f64)
}

/// The scrambled Halton sequence in 2D (bases 2 and 3), progressive.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Halton};
/// let mut s = Halton::new(Seed(3));
/// // the first 6 points: one per cell of the 2 x 3 grid
/// let mut cells: Vec<_> = (0..6).map(|_| { let p = s.next_sample(); ((p.x * 2.0) as u32, (p.y * 3.0) as u32) }).collect();
/// cells.sort();
/// cells.dedup();
/// assert_eq!(cells.len(), 6);
/// ```
#[derive(Clone, Debug)]
pub struct Halton {
    seed: u64,
    next: u64,
}

impl Halton {
    /// The sequence for `seed`.
    pub fn new(seed: Seed) -> Self {
        Halton {
            seed: seed.0,
            next: 0,
        }
    }

    /// Point `index` (2D).
    pub fn sample(&self, index: u64) -> Point2 {
        Point2::new(
            scrambled_radical_inverse(0, index, self.seed),
            scrambled_radical_inverse(1, index, self.seed),
        )
    }
}

impl Sampler for Halton {
    fn name(&self) -> &'static str {
        ENTRY.name
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
        if m != 1 || a > 31 || b > 19 {
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
    seed: u64,
    dims: u32,
    next: u64,
}

impl HaltonNd {
    /// `dims` dimensions (1 to [`MAX_DIMENSIONS`]) seeded by `seed`.
    pub fn new(dims: u32, seed: Seed) -> Result<Self> {
        super::check_dims(
            ENTRY.name,
            dims,
            MAX_DIMENSIONS as u32,
            " (one prime base per dimension)",
        )?;
        Ok(HaltonNd {
            seed: seed.0,
            dims,
            next: 0,
        })
    }
}

impl SamplerNd for HaltonNd {
    fn name(&self) -> &'static str {
        ENTRY.name
    }

    fn dimensions(&self) -> u32 {
        self.dims
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_point(&mut self, out: &mut [f32]) {
        for (d, o) in out.iter_mut().enumerate().take(self.dims as usize) {
            *o = scrambled_radical_inverse(d, self.next, self.seed);
        }
        self.next = self.next.wrapping_add(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primes_are_the_first_thousand() {
        assert_eq!(&PRIMES[..6], &[2, 3, 5, 7, 11, 13]);
        assert_eq!(PRIMES[999], 7919);
    }

    #[test]
    fn every_dimension_is_stratified_in_its_base() {
        for dim in [0usize, 1, 2, 5, 30] {
            let b = PRIMES[dim] as u64;
            let n = b * b;
            let mut seen = vec![false; n as usize];
            for i in 0..n {
                let x = scrambled_radical_inverse(dim, i, 17);
                let cell = (x as f64 * n as f64) as usize;
                assert!(!seen[cell], "dim {dim}: cell {cell} twice");
                seen[cell] = true;
            }
        }
    }
}
