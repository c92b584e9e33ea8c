//! Sobol' sequences, Owen-scrambled by hashing.
//!
//! * Sobol', "On the distribution of points in a cube and the approximate evaluation of
//!   integrals" (1967): dimension `d` of point `i` is `C_d bits(i)` over GF(2), a (t,s)-sequence
//!   in base 2. Dimension 0 is van der Corput (`C` the identity), dimension 1 uses the
//!   polynomial `x + 1` (`C` the Pascal matrix mod 2); together they form a (0,2)-sequence, so
//!   every prefix and aligned block of `2^m` points is a (0,m,2)-net.
//! * Direction numbers for dimensions 2.. are Joe and Kuo's `new-joe-kuo-6` (S. Joe and F. Y.
//!   Kuo, "Constructing Sobol sequences with better two-dimensional projections", SIAM J. Sci.
//!   Comput. 30, 2008; BSD-3-Clause, Copyright (c) 2008 Frances Y. Kuo and Stephen Joe), read
//!   from the `sobol` crate's copy of the table (feature `joe-kuo`, 1000 dimensions). The lean
//!   build has dimensions 0 and 1.
//! * Randomization: Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020). The index is
//!   shuffled by an Owen scramble of its bits (aligned blocks of `2^m` indices map to aligned
//!   blocks, so prefixes stay nets) and each dimension's value is Owen-scrambled with its own
//!   seed ([`crate::hash::owen_scramble`]): unbiased, decorrelated across seeds, nets kept.
//!
//! Evaluation is direct (no running state): indices up to `2^32 - 1`, any order, in O(1) by
//! four 256-entry tables per dimension (one per byte of the index).

#[cfg(feature = "std")]
use std::sync::OnceLock;

use super::Epochs;
use super::pmj::MAX_SEQUENCE_LEN;
use crate::error::Result;
use crate::float::unit_f32_from_u32;
use crate::hash::{Stream, hash32, owen_scramble_rev, owen_scrambled_unit_f32x4, stream_seed};
use crate::prelude::*;
#[cfg(feature = "std")]
use crate::registry::{CountRule, Entry, Family, Rates};
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};

/// Direction vectors of one dimension: column `k` (for index bit `k`) as a 32-bit fixed-point
/// value, most significant bit first.
type Matrix = [u32; 32];

/// The generator matrices of dimensions 0 and 1, computed.
const fn first_two() -> [Matrix; 2] {
    let mut vdc = [0u32; 32];
    let mut pascal = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        vdc[k] = 1 << (31 - k);
        // Pascal mod 2: column k has bit (31 - r) set for rows r <= k with binom(k, r) odd.
        let mut r = 0;
        while r <= k {
            if (k & r) == r {
                pascal[k] |= 1 << (31 - r);
            }
            r += 1;
        }
        k += 1;
    }
    [vdc, pascal]
}

/// The byte tables of dimensions 0 and 1, built at compile time: the (0,2)-sequence every
/// draw of the path-tracer adapter reads, with no lazy initialisation on the way.
static FIRST_TWO: [[[u32; 256]; 4]; 2] = {
    let m = first_two();
    [byte_tables(&m[0]), byte_tables(&m[1])]
};

/// The matrix of a dimension with primitive polynomial of degree `s`, inner coefficients `a`
/// (bit `s - 1 - l` is `a_l`) and initial direction integers `m` (odd, `m_k < 2^k`), by the
/// recurrence `V_k = V_{k-s} ^ (V_{k-s} >> s) ^ sum_{l=1}^{s-1} a_l V_{k-l}`.
#[cfg(any(test, feature = "joe-kuo"))]
pub(crate) fn direction_matrix(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut v = [0u32; 33]; // 1-based
    for k in 1..=32 {
        if k <= s {
            v[k] = m[k - 1] << (32 - k);
        } else {
            let mut x = v[k - s] ^ (v[k - s] >> s);
            for l in 1..s {
                if (a >> (s - 1 - l)) & 1 == 1 {
                    x ^= v[k - l];
                }
            }
            v[k] = x;
        }
    }
    let mut out = [0u32; 32];
    out.copy_from_slice(&v[1..]);
    out
}

/// Per dimension, four 256-entry tables in the bit-reversed index domain: table `q` maps byte
/// `q` of the reversed index to the XOR of the reversed direction vectors of its bits.
#[cfg(feature = "std")]
struct Tables {
    matrices: Vec<Matrix>,
    bytes: Vec<[[u32; 256]; 4]>,
}

/// The four byte tables of one generator matrix (see [`Tables`]): the digital-sequence
/// machinery every base-2 digital sequence of the crate shares.
pub(crate) const fn byte_tables(m: &Matrix) -> [[u32; 256]; 4] {
    let mut t = [[0u32; 256]; 4];
    let mut q = 0;
    while q < 4 {
        let mut v = 0;
        while v < 256 {
            let mut x = 0u32;
            let mut j = 0;
            while j < 8 {
                if (v >> j) & 1 == 1 {
                    // reversed-index bit 8q + j is index bit 31 - (8q + j)
                    x ^= m[31 - (8 * q + j)].reverse_bits();
                }
                j += 1;
            }
            t[q][v] = x;
            v += 1;
        }
        q += 1;
    }
    t
}

#[cfg(feature = "std")]
fn build(matrices: Vec<Matrix>) -> Tables {
    let bytes = matrices.iter().map(byte_tables).collect();
    Tables { matrices, bytes }
}

#[cfg(feature = "std")]
fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        #[cfg_attr(not(feature = "joe-kuo"), allow(unused_mut))]
        let mut matrices: Vec<Matrix> = first_two().to_vec();
        #[cfg(feature = "joe-kuo")]
        {
            // Row d of the file (d >= 2) is our dimension d - 1; dimension 1 (x + 1) is already there.
            let params = sobol::params::JoeKuoD6::standard();
            for dim in params.dim_params.iter().skip(1) {
                matrices.push(direction_matrix(dim.m.len(), dim.a, &dim.m));
            }
        }
        build(matrices)
    })
}

/// The byte tables of dimension `dim`: dimensions 0 and 1 from the compile-time tables, the
/// others (with `std`) from the lazily built ones.
#[inline]
fn dim_tables(dim: u32) -> Option<&'static [[u32; 256]; 4]> {
    if dim < 2 {
        return Some(&FIRST_TWO[dim as usize]);
    }
    #[cfg(feature = "std")]
    return tables().bytes.get(dim as usize);
    #[cfg(not(feature = "std"))]
    None
}

/// The number of Sobol' dimensions available (1000 with the `joe-kuo` feature, else 2).
pub fn max_dimensions() -> u32 {
    #[cfg(feature = "std")]
    return tables().matrices.len() as u32;
    #[cfg(not(feature = "std"))]
    2
}

/// The generator matrix of dimension `dim` (columns for index bits 0..32, MSB-first values).
#[cfg(test)]
pub(crate) fn matrix(dim: u32) -> Option<[u32; 32]> {
    #[cfg(feature = "std")]
    return tables().matrices.get(dim as usize).copied();
    #[cfg(not(feature = "std"))]
    first_two().get(dim as usize).copied()
}

/// Point `index` of dimension `dim` of the plain (unscrambled) Sobol' sequence, 32-bit fixed
/// point; `None` past [`max_dimensions`].
pub fn sobol_u32(index: u32, dim: u32) -> Option<u32> {
    let t = dim_tables(dim)?;
    Some(lookup(t, index.reverse_bits()).reverse_bits())
}

/// Dimension `dim` of point `index` of the Owen-scrambled Sobol' sequence seeded by `seed`:
/// the value [`SobolNd`] gives (within its first `2^32` points), stateless and allocation-free.
/// `None` past [`max_dimensions`].
///
/// ```
/// use strata::{SamplerNd, Seed, samplers::{SobolNd, sobol}};
/// let mut s = SobolNd::new(2, Seed(4))?;
/// let mut p = [0f32; 2];
/// s.next_point(&mut p);
/// assert_eq!(sobol::owen_scrambled(0, 1, 4), Some(p[1]));
/// # Ok::<(), strata::Error>(())
/// ```
pub fn owen_scrambled(index: u32, dim: u32, seed: u64) -> Option<f32> {
    let t = dim_tables(dim)?;
    let s = Scramble::new(seed);
    Some(unit_f32_from_u32(s.sample_rev_u32(
        t,
        s.index_rev(index),
        dim,
    )))
}

/// The point of a digital sequence at a bit-reversed index, bit-reversed, from its byte tables.
#[inline]
pub(crate) fn lookup(t: &[[u32; 256]; 4], i_rev: u32) -> u32 {
    t[0][(i_rev & 0xff) as usize]
        ^ t[1][((i_rev >> 8) & 0xff) as usize]
        ^ t[2][((i_rev >> 16) & 0xff) as usize]
        ^ t[3][(i_rev >> 24) as usize]
}

/// Dimensions 0 and 1 of the plain (unscrambled) sequence at a bit-reversed index, both
/// bit-reversed: the path-tracer adapter shuffles the index and Owen-scrambles the values
/// around this, in the reversed domain where both are cheap.
#[inline]
pub(crate) fn point01_rev(index_rev: u32) -> [u32; 2] {
    [
        lookup(&FIRST_TWO[0], index_rev),
        lookup(&FIRST_TWO[1], index_rev),
    ]
}

/// Seeds of one scrambled copy of the sequence: the index shuffle and one value scramble per
/// dimension are hashed from it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Scramble {
    shuffle: u32,
    key: u32,
}

impl Scramble {
    /// The scramble for a 64-bit seed.
    pub fn new(seed: u64) -> Self {
        let s = stream_seed(seed, Stream::SobolScramble.id());
        Scramble {
            shuffle: hash32(s as u32, Stream::SobolShuffle.id() as u32),
            key: (s >> 32) as u32,
        }
    }

    /// The value-scramble seed of dimension `dim`.
    #[inline]
    fn dim_seed(&self, dim: u32) -> u32 {
        hash32(dim, self.key)
    }

    /// The shuffled index, in the bit-reversed domain.
    #[inline]
    fn index_rev(&self, index: u32) -> u32 {
        owen_scramble_rev(index.reverse_bits(), self.shuffle)
    }

    /// Dimensions `dim` and `dim + 1` of point `index`, as 32-bit fixed point (`dim + 1` must
    /// exist).
    #[inline]
    pub fn sample2_u32(&self, index: u32, dim: u32) -> [u32; 2] {
        let table = |d: u32| dim_tables(d).expect("the dimension exists");
        let i = self.index_rev(index);
        [
            self.sample_rev_u32(table(dim), i, dim),
            self.sample_rev_u32(table(dim + 1), i, dim + 1),
        ]
    }

    /// Dimension `dim` (byte tables `t`) at an already shuffled index `i_rev`.
    #[inline]
    fn sample_rev_u32(&self, t: &[[u32; 256]; 4], i_rev: u32, dim: u32) -> u32 {
        owen_scramble_rev(lookup(t, i_rev), self.dim_seed(dim)).reverse_bits()
    }
}

/// Consecutive points of one epoch of [`SobolNd`], from tables and seeds looked up once.
struct Rows<'a> {
    tables: &'a [&'static [[u32; 256]; 4]],
    seeds: &'a [u32],
    scramble: Scramble,
}

impl Rows<'_> {
    /// Points `start, start + 1, ..` into `out` (`D` values each), four dimensions per SIMD
    /// step.
    #[inline(always)]
    fn fill(&self, start: u32, out: &mut [f32]) {
        let d = self.tables.len();
        for (i, chunk) in (u64::from(start)..).zip(out.chunks_exact_mut(d)) {
            let ir = self.scramble.index_rev(i as u32);
            let mut k = 0;
            while k + 4 <= d {
                let n = [0, 1, 2, 3].map(|j| lookup(self.tables[k + j], ir));
                let s = [0, 1, 2, 3].map(|j| self.seeds[k + j]);
                chunk[k..k + 4].copy_from_slice(&owen_scrambled_unit_f32x4(n, s));
                k += 4;
            }
            self.tail(ir, k, chunk);
        }
    }

    /// Dimensions `k..` of one point, one at a time.
    #[inline(always)]
    fn tail(&self, ir: u32, k: usize, chunk: &mut [f32]) {
        let rest = self.tables[k..].iter().zip(&self.seeds[k..]);
        for (o, (t, s)) in chunk[k..].iter_mut().zip(rest) {
            *o = unit_f32_from_u32(owen_scramble_rev(lookup(t, ir), *s).reverse_bits());
        }
    }

    /// As [`fill`](Rows::fill), eight dimensions per step in plain lane loops that the
    /// compiler turns into AVX2 (`vpmulld`, byte-shuffle bit reversal); the same bits.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    #[target_feature(enable = "avx2")]
    unsafe fn fill_avx2(&self, start: u32, out: &mut [f32]) {
        let d = self.tables.len();
        for (i, chunk) in (u64::from(start)..).zip(out.chunks_exact_mut(d)) {
            let ir = self.scramble.index_rev(i as u32);
            let mut k = 0;
            while k + 8 <= d {
                let n: [u32; 8] = core::array::from_fn(|j| lookup(self.tables[k + j], ir));
                let s: [u32; 8] = core::array::from_fn(|j| self.seeds[k + j]);
                let v = crate::hash::owen_scramble_rev_lanes(n, s);
                for (o, x) in chunk[k..k + 8].iter_mut().zip(v) {
                    *o = unit_f32_from_u32(x.reverse_bits());
                }
                k += 8;
            }
            self.tail(ir, k, chunk);
        }
    }
}

/// The registered name.
const NAME: &str = "sobol";

/// The registry entry of `sobol`.
#[cfg(feature = "std")]
pub(crate) const ENTRY: Entry = Entry {
    name: NAME,
    description: "Sobol' (Joe-Kuo directions), Owen-scrambled by hashing, progressive, any --dims",
    paper: "Sobol' 1967; Joe, Kuo 2008; Burley 2020",
    family: Family::Qmc,
    progressive: true,
    counts: CountRule::Any,
    parameters: &[],
    promise: "(0,m,2)-nets in dims 0-1 at every `2^m`; up to 1000 dims",
    rates: Rates::NETS,
    expensive: false,
    build: |p| Ok(Box::new(Sobol::new(p.sampler_seed()))),
    nd: Some(|p, d| Ok(Box::new(SobolNd::new(d, p.sampler_seed())?))),
};

/// The scrambled Sobol' sequence in 2D (dimensions 0 and 1: a (0,2)-sequence), progressive.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Sobol};
/// let mut s = Sobol::new(Seed(7));
/// let pts: Vec<_> = (0..4).map(|_| s.next_sample()).collect();
/// // the first 4 points: one in each quadrant
/// let mut q: Vec<_> = pts.iter().map(|p| (p.x >= 0.5, p.y >= 0.5)).collect();
/// q.sort();
/// q.dedup();
/// assert_eq!(q.len(), 4);
/// ```
#[derive(Clone, Debug)]
pub struct Sobol {
    epochs: Epochs,
    scramble: Scramble,
}

impl Sobol {
    /// The sequence for `seed`.
    pub fn new(seed: Seed) -> Self {
        Sobol {
            epochs: Epochs::new(seed, MAX_SEQUENCE_LEN),
            scramble: Scramble::new(seed.0),
        }
    }

    /// Point `index` (2D) as 32-bit fixed point, without changing the stream position.
    pub fn sample_fixed(&self, index: u32) -> [u32; 2] {
        self.scramble.sample2_u32(index, 0)
    }

    /// Point `index` (2D), without changing the stream position.
    pub fn sample(&self, index: u32) -> Point2 {
        let [x, y] = self.scramble.sample2_u32(index, 0);
        Point2::new(unit_f32_from_u32(x), unit_f32_from_u32(y))
    }
}

/// The index of the next point, re-scrambling when a new epoch starts.
fn advance(epochs: &mut Epochs, scramble: &mut Scramble) -> u32 {
    let (i, new_epoch) = epochs.advance();
    if let Some(key) = new_epoch {
        *scramble = Scramble::new(key);
    }
    i as u32
}

impl Sampler for Sobol {
    fn name(&self) -> &'static str {
        NAME
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let i = advance(&mut self.epochs, &mut self.scramble);
        self.sample(i)
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        super::pmj::pmj_grids(n, true)
    }
}

/// The scrambled Sobol' sequence in `D` dimensions, progressive.
#[derive(Clone, Debug)]
pub struct SobolNd {
    epochs: Epochs,
    dims: u32,
    seed: u64,
    scramble: Scramble,
}

impl SobolNd {
    /// `dims` dimensions (1 to [`max_dimensions`]) seeded by `seed`.
    pub fn new(dims: u32, seed: Seed) -> Result<Self> {
        let max = max_dimensions();
        let why = if cfg!(feature = "joe-kuo") {
            ""
        } else {
            " (enable the `joe-kuo` feature for 1000)"
        };
        super::check_dims(NAME, dims, max, why)?;
        Ok(SobolNd {
            epochs: Epochs::new(seed, MAX_SEQUENCE_LEN),
            dims,
            seed: seed.0,
            scramble: Scramble::new(seed.0),
        })
    }
}

impl SobolNd {
    /// The scramble of epoch `e` (epoch 0 keyed by the seed itself, as the constructor does).
    fn epoch_scramble(&self, e: u64) -> Scramble {
        if e == 0 {
            Scramble::new(self.seed)
        } else {
            Scramble::new(self.epochs.key(e))
        }
    }
}

impl SamplerNd for SobolNd {
    fn name(&self) -> &'static str {
        NAME
    }

    fn dimensions(&self) -> u32 {
        self.dims
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    /// Constant time: the epoch and the index, re-keyed when the epoch changes.
    fn skip(&mut self, n: u64) -> bool {
        if let Some(e) = self.epochs.skip(n) {
            self.scramble = self.epoch_scramble(e);
        }
        true
    }

    /// As many `next_point` calls, bit-identical, with the per-dimension tables and scramble
    /// seeds looked up once per call and the dimensions scrambled in SIMD lanes (eight with
    /// AVX2 where the CPU has it, four with SSE2 otherwise).
    fn fill(&mut self, out: &mut [f32]) {
        let d = self.dims as usize;
        let tables: Vec<&'static [[u32; 256]; 4]> = (0..self.dims)
            .map(|k| dim_tables(k).expect("checked at construction"))
            .collect();
        let total = out.len() / d;
        let mut done = 0usize;
        while done < total {
            let (start, count, new_epoch) = self.epochs.take((total - done) as u64);
            if let Some(key) = new_epoch {
                self.scramble = Scramble::new(key);
            }
            let seeds: Vec<u32> = (0..self.dims).map(|k| self.scramble.dim_seed(k)).collect();
            let rows = Rows {
                tables: &tables,
                seeds: &seeds,
                scramble: self.scramble,
            };
            let block = &mut out[done * d..(done + count as usize) * d];
            done += count as usize;
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            if std::is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU has AVX2, checked just above.
                unsafe { rows.fill_avx2(start as u32, block) };
                continue;
            }
            rows.fill(start as u32, block);
        }
    }

    fn next_point(&mut self, out: &mut [f32]) {
        let i = advance(&mut self.epochs, &mut self.scramble);
        // one index shuffle for all dimensions of the point
        let ir = self.scramble.index_rev(i);
        for (d, o) in (0..self.dims).zip(out.iter_mut()) {
            let table = dim_tables(d).expect("checked at construction");
            *o = unit_f32_from_u32(self.scramble.sample_rev_u32(table, ir, d));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_and_skip_equal_point_by_point_across_an_epoch() {
        // (without the `joe-kuo` feature only 2 dimensions exist)
        for dims in [1u32, 2, 3, 4, 5, 8, 9, 13]
            .into_iter()
            .filter(|&d| d <= max_dimensions())
        {
            let mut a = SobolNd::new(dims, Seed(11)).unwrap();
            let mut b = a.clone();
            // near the end of the first 2^32-point sequence, so that both cross into epoch 1
            a.skip((1 << 32) - 5);
            b.skip((1 << 32) - 7);
            let mut p = vec![0f32; dims as usize];
            b.next_point(&mut p);
            b.next_point(&mut p);
            let mut filled = vec![0f32; 12 * dims as usize];
            a.fill(&mut filled);
            for (k, chunk) in filled.chunks_exact(dims as usize).enumerate() {
                b.next_point(&mut p);
                assert_eq!(
                    chunk.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    p.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                    "dims {dims}, point {k}"
                );
            }
            // and from the start
            let mut c = SobolNd::new(dims, Seed(3)).unwrap();
            let mut d = c.clone();
            let mut filled = vec![0f32; 40 * dims as usize];
            c.fill(&mut filled);
            for chunk in filled.chunks_exact(dims as usize) {
                d.next_point(&mut p);
                assert_eq!(chunk, &p[..]);
            }
        }
    }

    #[test]
    fn first_dimensions_are_van_der_corput_and_pascal() {
        // van der Corput: 0, 1/2, 1/4, 3/4, ...
        let v: Vec<u32> = (0..4).map(|i| sobol_u32(i, 0).unwrap()).collect();
        assert_eq!(v, [0, 1 << 31, 1 << 30, 3 << 30]);
        // dimension 1 is the recurrence with s = 1, a = 0, m = [1]
        assert_eq!(matrix(1).unwrap(), direction_matrix(1, 0, &[1]));
    }

    #[test]
    fn byte_tables_match_the_bit_loop() {
        for dim in 0..max_dimensions().min(40) {
            let m = matrix(dim).unwrap();
            for i in [0u32, 1, 2, 3, 255, 256, 0x1234_5678, u32::MAX] {
                let mut x = 0u32;
                for (k, col) in m.iter().enumerate() {
                    if (i >> k) & 1 == 1 {
                        x ^= col;
                    }
                }
                assert_eq!(sobol_u32(i, dim), Some(x), "dim {dim} index {i}");
            }
        }
    }
}
