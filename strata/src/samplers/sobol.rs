//! Sobol' sequences, Owen-scrambled by hashing, and with the same machinery the binary form of
//! Faure's base-4 (0,4)-sequence (`faure4`).
//!
//! * Sobol', "On the distribution of points in a cube and the approximate evaluation of
//!   integrals" (1967): dimension `d` of point `i` is `C_d bits(i)` over GF(2), a (t,s)-sequence
//!   in base 2. Dimension 0 is van der Corput (`C` the identity), dimension 1 uses the
//!   polynomial `x + 1` (`C` the Pascal matrix mod 2); together they form a (0,2)-sequence, so
//!   every prefix and aligned block of `2^m` points is a (0,m,2)-net.
//! * Direction numbers for dimensions 2..1000 are Joe and Kuo's `new-joe-kuo-6` (S. Joe and F.
//!   Y. Kuo, "Constructing Sobol sequences with better two-dimensional projections", SIAM J.
//!   Sci. Comput. 30, 2008; BSD licence, Copyright (c) 2008 Frances Y. Kuo and Stephen Joe),
//!   their file kept in the source and turned into matrices at compile time
//!   ([`crate::digital`]).
//! * Randomization: Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020), with the
//!   shared functions of [`crate::scramble`] (the same as the path-tracer adapter's Sobol'):
//!   the index goes through a nested uniform shuffle (aligned blocks of `2^m` indices map to
//!   aligned blocks, so prefixes stay nets) and each dimension's value is Owen-scrambled with
//!   its own seed: unbiased, decorrelated across seeds, nets kept. The generator matrices and
//!   their tables are [`crate::digital`]'s.
//!
//! * `faure4`: the first four dimensions of Faure's (0,4)-sequence in base 4 (Faure,
//!   "Discrépance de suites associées à un système de numération (en dimension s)", Acta Arith.
//!   41, 1982), written as binary generator matrices of 2x2 blocks ([`crate::digital`] says
//!   how): every aligned block of `4^k` points a (0,k,4)-net in base 4, dimensions 0-1 and 2-3
//!   binary (0,2)-sequences, the other pairs `t <= 1` at `4^k` points. The sequence of the
//!   adapter's `zquad` ([`crate::pixel::Sequence::zquad`]), randomized as Sobol' is.
//!
//! Evaluation is direct (no running state): indices up to `2^32 - 1`, any order, in O(1) by
//! four 256-entry tables per dimension (one per byte of the index).

use super::{Epochs, MAX_SEQUENCE_LEN};
use crate::digital::{
    FAURE4, Matrix, NIBBLE_DIMENSIONS, ONE_TWO_DIMENSIONS, ONE_TWO_NIBBLES, ONE_TWO_SOBOL, SOBOL,
    SOBOL_DIMENSIONS, SOBOL_NIBBLES, apply, faure4_matrices, lookup, lookup_nibbles,
    sobol_first_tables,
};
use crate::error::Result;
use crate::float::unit_f32_from_u32;
use crate::hash::{GOLDEN_GAMMA, Stream, hash32, mix64};
use crate::prelude::*;
use crate::sampler::{Point2, Progression, Sampler, SamplerNd, Seed, StrataGrid};
use crate::scramble::{Lanes, X4, owen_scramble_lanes, shuffle_lanes};

/// Which generator matrices a [`Sobol`] or [`SobolNd`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Matrices {
    /// Sobol' (Joe-Kuo directions).
    Sobol,
    /// Faure's base-4 (0,4)-sequence, binary form: four dimensions.
    Faure4,
    /// (1,2)-Sobol' (Bonneel et al. 2025): 692 dimensions, every pair `(2k, 2k+1)` a
    /// (1,2)-sequence.
    OneTwo,
}

impl Matrices {
    /// Dimension `dim` (which exists) at the bit-reversed index `index_rev`, bit-reversed: from
    /// the compile-time tables (byte tables of Sobol' dimensions 0-1 and of `faure4`, nibble
    /// tables of the first 64 dimensions of Sobol' and of (1,2)-Sobol'), column by column
    /// past them. No table is built at run time.
    #[inline(always)]
    fn point_rev(self, dim: u32, index_rev: u32) -> u32 {
        let d = dim as usize;
        match self {
            Matrices::Sobol | Matrices::OneTwo if d < 2 => lookup(
                sobol_first_tables(dim).expect("dimension 0 or 1"),
                index_rev,
            ),
            Matrices::Faure4 => lookup(&FAURE4[d], index_rev),
            Matrices::Sobol if d < NIBBLE_DIMENSIONS => {
                lookup_nibbles(&SOBOL_NIBBLES[d], index_rev)
            }
            Matrices::OneTwo if d < NIBBLE_DIMENSIONS => {
                lookup_nibbles(&ONE_TWO_NIBBLES[d], index_rev)
            }
            Matrices::Sobol => apply(&SOBOL[d], index_rev.reverse_bits()).reverse_bits(),
            Matrices::OneTwo => apply(&ONE_TWO_SOBOL[d], index_rev.reverse_bits()).reverse_bits(),
        }
    }

    /// The seed the randomization is keyed by: `faure4`'s is hashed anew, so that its
    /// scrambles are not `sobol`'s of the same seed (whose dimension 0 is the same matrix).
    fn seed(self, seed: Seed) -> Seed {
        match self {
            Matrices::Sobol => seed,
            Matrices::Faure4 => Seed(mix64(seed.0 ^ 0xfa_0e4d_0004)),
            Matrices::OneTwo => Seed(mix64(seed.0 ^ 0x0102_50b0_1000)),
        }
    }

    /// The name of the sampler.
    fn name(self) -> &'static str {
        match self {
            Matrices::Sobol => NAME,
            Matrices::Faure4 => FAURE4_NAME,
            Matrices::OneTwo => ONE_TWO_NAME,
        }
    }
}

/// The number of Sobol' dimensions: 1000 (Joe and Kuo's `new-joe-kuo-6.1000`).
pub const MAX_DIMENSIONS: u32 = SOBOL_DIMENSIONS;

/// Point `index` of dimension `dim` of the plain (unscrambled) Sobol' sequence, 32-bit fixed
/// point; `None` from [`MAX_DIMENSIONS`] on.
pub fn sobol_u32(index: u32, dim: u32) -> Option<u32> {
    Some(apply(SOBOL.get(dim as usize)?, index))
}

/// At most this many rank checks in [`projection_t_value`] (a few seconds).
const T_VALUE_BUDGET: u64 = 1 << 24;

/// The t-value of the projection onto dimensions `dims` (distinct) of the sequence named
/// `sampler` (`sobol`: its dimensions below [`MAX_DIMENSIONS`]; `faure4`: 0-3, and 4 for the
/// fifth matrix that `zquad`'s 2D draws at a group's last dimension read), as a `(t, m,
/// s)`-net in base `base` (2 or 4) of `base^m` points (`base^m <= 2^32`), from the generator
/// matrices (exact; kept by every Owen scramble and nested index shuffle). A base-4 net is a
/// statement about boxes of sides `4^-a`: `faure4`'s dimensions 0-3 are a (0,m,4)-net in base
/// 4 at every `m`, while as a base-2 net their `t` is positive.
///
/// Every aligned block of `base^m` points is such a net, and so is every Owen scramble or
/// nested index shuffle of it; `t = 0` for Sobol' dimensions 0 and 1 at every `m`, and the
/// draws of a `zjoint` group ([`crate::pixel::Sequence::zjoint`]) are these projections.
///
/// The cost: one rank check per way to split each strength `rho` among the `s` dimensions
/// (`C(rho + s - 1, s - 1)`), for `rho` up to `m - t + 1`, so about `C(m - t + s, s)` in all.
/// Past `2^24` checks (a few seconds) the answer is refused with an error rather than computed
/// for hours: many dimensions of a good projection at a large `m` (24 Sobol' dimensions at
/// `m = 32`, for one).
///
/// ```
/// use strata::samplers::sobol::projection_t_value;
/// assert_eq!(projection_t_value("sobol", &[0, 1], 16, 2)?, 0);
/// assert!(projection_t_value("sobol", &[0, 1, 2, 3], 16, 2)? > 0);
/// assert_eq!(projection_t_value("faure4", &[0, 1, 2, 3], 8, 4)?, 0);
/// assert_eq!(projection_t_value("faure4", &[2, 3], 16, 2)?, 0);
/// assert!(projection_t_value("sobol", &[0, 1, 2, 3], 8, 4)? > 0);
/// assert!(projection_t_value("faure4", &[0, 5], 8, 2).is_err());
/// assert!(projection_t_value("sobol", &[0, 1], 1 << 31, 2).is_err()); // m above 32
/// # Ok::<(), strata::Error>(())
/// ```
pub fn projection_t_value(sampler: &str, dims: &[u32], m: u32, base: u32) -> Result<u32> {
    let context = "sobol::projection_t_value";
    let bits = match base {
        2 => 1,
        4 => 2,
        _ => {
            return Err(crate::Error::input(
                context,
                format!("base {base}: the bases of these nets are 2 and 4"),
            ));
        }
    };
    let (matrix, max): (fn(u32) -> Option<Matrix>, u32) = match sampler {
        NAME => (|d| SOBOL.get(d as usize).copied(), MAX_DIMENSIONS),
        FAURE4_NAME => (|d| faure4_matrices().get(d as usize).copied(), 5),
        ONE_TWO_NAME => (
            |d| ONE_TWO_SOBOL.get(d as usize).copied(),
            ONE_TWO_DIMENSIONS,
        ),
        other => {
            return Err(crate::Error::input(
                context,
                format!("'{other}': the t-values are computed for 'sobol', 'sobol12' and 'faure4'"),
            ));
        }
    };
    if dims.is_empty() || m > 32 / bits {
        return Err(crate::Error::input(
            context,
            format!(
                "{} dimensions at m = {m} in base {base}: at least one dimension, and m from \
                 0 to {}",
                dims.len(),
                32 / bits
            ),
        ));
    }
    let mut matrices = Vec::with_capacity(dims.len());
    for (k, &d) in dims.iter().enumerate() {
        if dims[..k].contains(&d) {
            return Err(crate::Error::input(
                context,
                format!("dimension {d} is listed twice: the dimensions must be distinct"),
            ));
        }
        match matrix(d) {
            Some(m) => matrices.push(m),
            None => {
                return Err(crate::Error::input(
                    context,
                    format!("dimension {d}: {sampler} has dimensions 0 to {}", max - 1),
                ));
            }
        }
    }
    crate::digital::digital_t_value_within(&matrices, m, bits, T_VALUE_BUDGET).ok_or_else(|| {
        crate::Error::input(
            context,
            format!(
                "{} dimensions at m = {m}: the t-value needs more than 2^24 rank checks (one \
                 per way to split a strength among the dimensions); ask for fewer dimensions \
                 or a smaller m",
                dims.len()
            ),
        )
    })
}

/// Dimension `dim` of point `index` of the Owen-scrambled Sobol' sequence seeded by `seed`:
/// the value [`SobolNd`] gives (within its first `2^32` points), stateless and allocation-free.
/// `None` from [`MAX_DIMENSIONS`] on.
///
/// ```
/// use strata::{SamplerNd, Seed, samplers::{SobolNd, sobol}};
/// let mut s = SobolNd::new(2, Seed(4))?;
/// let mut p = [0f32; 2];
/// s.next_point(&mut p);
/// assert_eq!(sobol::owen_scrambled(0, 1, Seed(4)), Some(p[1]));
/// # Ok::<(), strata::Error>(())
/// ```
pub fn owen_scrambled(index: u32, dim: u32, seed: Seed) -> Option<f32> {
    if dim >= MAX_DIMENSIONS {
        return None;
    }
    let s = Scramble::new(seed.0);
    let v_rev = Matrices::Sobol.point_rev(dim, s.index_rev(index));
    Some(unit_f32_from_u32(
        owen_scramble_lanes(v_rev, s.dim_seed(dim)).reverse_bits(),
    ))
}

/// Seeds of one scrambled copy of the sequence: the index shuffle's two keys and one value
/// scramble per dimension are hashed from it. The randomization is [`crate::scramble`]'s, the
/// same as the path-tracer adapter's Sobol'.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Scramble {
    even: u32,
    shuffle: u32,
    key: u32,
    /// The shuffle of index 0, bit-reversed: XOR-ed onto every shuffled index, so that the
    /// first `2^m` indices go to the first `2^m` (the same nets, with small indices: fewer
    /// table lookups).
    zero: u32,
}

impl Scramble {
    /// The scramble for a 64-bit seed.
    pub fn new(seed: u64) -> Self {
        // one 64-bit mix (the one-value path pays it on every call): the shuffle's two keys,
        // and the key of the per-dimension value seeds, which `dim_seed` hashes again
        let s = mix64(seed ^ Stream::SobolScramble.id().wrapping_mul(GOLDEN_GAMMA));
        let (lo, hi) = (s as u32, (s >> 32) as u32);
        let (even, shuffle) = (lo & !1, hi);
        Scramble {
            even,
            shuffle,
            key: lo.rotate_left(16) ^ hi,
            zero: shuffle_lanes(0, even, shuffle),
        }
    }

    /// The value-scramble seed of dimension `dim`.
    #[inline]
    fn dim_seed(&self, dim: u32) -> u32 {
        hash32(dim, self.key)
    }

    /// The shuffled index, in the bit-reversed domain: a nested uniform shuffle (aligned
    /// blocks of `2^m` indices onto aligned blocks) made to keep each prefix `[0, 2^m)` in
    /// place by the XOR of the shuffle of 0 (itself a nested bijection).
    #[inline]
    fn index_rev(&self, index: u32) -> u32 {
        shuffle_lanes(index.reverse_bits(), self.even, self.shuffle) ^ self.zero
    }

    /// Dimensions 0 and 1 of point `index` of `matrices`, as 32-bit fixed point.
    #[inline]
    fn sample2_u32(&self, matrices: Matrices, index: u32) -> [u32; 2] {
        let i = self.index_rev(index);
        [0, 1]
            .map(|d| owen_scramble_lanes(matrices.point_rev(d, i), self.dim_seed(d)).reverse_bits())
    }
}

/// Consecutive points of one epoch of [`SobolNd`], with the value seeds looked up once.
struct Rows<'a> {
    matrices: Matrices,
    seeds: &'a [u32],
    scramble: Scramble,
}

impl Rows<'_> {
    /// Points `start, start + 1, ..` into `out` (`D` values each), four dimensions per SIMD
    /// step.
    #[inline(always)]
    fn fill(&self, start: u32, out: &mut [f32]) {
        let d = self.seeds.len();
        for (i, chunk) in (u64::from(start)..).zip(out.chunks_exact_mut(d)) {
            let ir = self.scramble.index_rev(i as u32);
            let mut k = 0;
            while k + 4 <= d {
                let n = X4::new([0, 1, 2, 3].map(|j| self.matrices.point_rev((k + j) as u32, ir)));
                let s = X4::new([0, 1, 2, 3].map(|j| self.seeds[k + j]));
                let v = owen_scramble_lanes(n, s).reverse_bits().unit_f32();
                chunk[k..k + 4].copy_from_slice(&v);
                k += 4;
            }
            self.tail(ir, k, chunk);
        }
    }

    /// Dimensions `k..` of one point, one at a time.
    #[inline(always)]
    fn tail(&self, ir: u32, k: usize, chunk: &mut [f32]) {
        for ((d, o), s) in (k..).zip(chunk[k..].iter_mut()).zip(&self.seeds[k..]) {
            let v = self.matrices.point_rev(d as u32, ir);
            *o = unit_f32_from_u32(owen_scramble_lanes(v, *s).reverse_bits());
        }
    }

    /// As [`fill`](Rows::fill), eight dimensions per step in plain lane loops that the
    /// compiler turns into AVX2 (`vpmulld`, byte-shuffle bit reversal); the same bits.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(all(feature = "std", target_arch = "x86_64", not(feature = "portable")))]
    #[target_feature(enable = "avx2")]
    unsafe fn fill_avx2(&self, start: u32, out: &mut [f32]) {
        let d = self.seeds.len();
        for (i, chunk) in (u64::from(start)..).zip(out.chunks_exact_mut(d)) {
            let ir = self.scramble.index_rev(i as u32);
            let mut k = 0;
            while k + 8 <= d {
                let n: [u32; 8] =
                    core::array::from_fn(|j| self.matrices.point_rev((k + j) as u32, ir));
                let s: [u32; 8] = core::array::from_fn(|j| self.seeds[k + j]);
                let v = owen_scramble_lanes(n, s).reverse_bits();
                for (o, x) in chunk[k..k + 8].iter_mut().zip(v) {
                    *o = unit_f32_from_u32(x);
                }
                k += 8;
            }
            self.tail(ir, k, chunk);
        }
    }
}

/// The name of the sampler.
const NAME: &str = "sobol";

/// The name of the base-4 Faure sequence's sampler.
const FAURE4_NAME: &str = "faure4";

/// The name of the (1,2)-Sobol' sampler.
const ONE_TWO_NAME: &str = "sobol12";

/// The number of (1,2)-Sobol' dimensions: 692 (Bonneel et al. 2025).
pub const ONE_TWO_MAX_DIMENSIONS: u32 = ONE_TWO_DIMENSIONS;

/// The scrambled Sobol' sequence in 2D (dimensions 0 and 1: a (0,2)-sequence), progressive.
///
/// ```
/// use strata::{Sampler, Seed, samplers::Sobol};
/// let mut s = Sobol::new(Seed(7));
/// let pts: Vec<_> = (0..4).map(|_| s.next_sample()).collect();
/// // the first 4 points: one in each quadrant
/// let mut q: Vec<_> = pts.iter().map(|p| (p[0] >= 0.5, p[1] >= 0.5)).collect();
/// q.sort();
/// q.dedup();
/// assert_eq!(q.len(), 4);
/// ```
#[derive(Clone, Debug)]
pub struct Sobol {
    epochs: Epochs,
    seed: u64,
    scramble: Scramble,
    matrices: Matrices,
}

impl Sobol {
    /// The sequence for `seed`.
    pub fn new(seed: Seed) -> Self {
        Self::with(Matrices::Sobol, seed)
    }

    /// Dimensions 0-1 of the binary form of Faure's base-4 (0,4)-sequence (`faure4`, the
    /// sequence of the adapter's `zquad`; see the module docs), randomized as Sobol' is, with
    /// its seed hashed apart from Sobol''s.
    pub fn faure4(seed: Seed) -> Self {
        Self::with(Matrices::Faure4, seed)
    }

    /// Dimensions 0-1 of the (1,2)-Sobol' sequence (`sobol12`, [`SobolNd::one_two`]): Sobol''s
    /// own (0,2)-sequence, randomized as [`Sobol::new`] is, with its seed hashed apart, so
    /// that it is the first two dimensions of `SobolNd::one_two` of the same seed.
    pub fn one_two(seed: Seed) -> Self {
        Self::with(Matrices::OneTwo, seed)
    }

    /// Dimensions 0-1 of the sequence of `matrices` for `seed`.
    fn with(matrices: Matrices, seed: Seed) -> Self {
        let seed = matrices.seed(seed);
        Sobol {
            epochs: Epochs::new(MAX_SEQUENCE_LEN, seed),
            seed: seed.0,
            scramble: Scramble::new(seed.0),
            matrices,
        }
    }

    /// Point `index` (2D) as 32-bit fixed point, without changing the stream position.
    pub fn sample_u32(&self, index: u32) -> [u32; 2] {
        self.scramble.sample2_u32(self.matrices, index)
    }

    /// Point `index` (2D), without changing the stream position.
    pub fn sample(&self, index: u32) -> Point2 {
        let [x, y] = self.sample_u32(index);
        [unit_f32_from_u32(x), unit_f32_from_u32(y)]
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
        self.matrices.name()
    }

    fn progression(&self) -> Progression {
        Progression::Progressive
    }

    fn next_sample(&mut self) -> Point2 {
        let i = advance(&mut self.epochs, &mut self.scramble);
        self.sample(i)
    }

    /// Constant time: the epoch and the index, re-keyed when the epoch changes.
    fn skip(&mut self, n: u64) -> bool {
        if let Some(e) = self.epochs.skip(n) {
            self.scramble = if e == 0 {
                Scramble::new(self.seed)
            } else {
                Scramble::new(self.epochs.key(e))
            };
        }
        true
    }

    fn strata(&self, n: u64) -> Vec<StrataGrid> {
        StrataGrid::net(n, true)
    }
}

/// The scrambled Sobol' sequence in `D` dimensions, progressive.
#[derive(Clone, Debug)]
pub struct SobolNd {
    epochs: Epochs,
    dims: u32,
    seed: u64,
    scramble: Scramble,
    matrices: Matrices,
}

impl SobolNd {
    /// `dims` dimensions (1 to [`MAX_DIMENSIONS`]) seeded by `seed`.
    pub fn new(dims: u32, seed: Seed) -> Result<Self> {
        Self::with(Matrices::Sobol, dims, seed)
    }

    /// `dims` dimensions (1 to 692) of the (1,2)-Sobol' sequence (N. Bonneel, D. Coeurjolly,
    /// J.-C. Iehl, V. Ostromoukhov, "Sobol' Sequences with Guaranteed-Quality 2D Projections",
    /// ACM TOG 44(4), 2025; [`crate::digital`] has the table's provenance), randomized as
    /// [`SobolNd::new`] is, its seed hashed apart: every pair of dimensions `(2k, 2k+1)` is a
    /// (1,2)-sequence (each aligned block of `2^m` points a (1,m,2)-net), the pair `(0, 1)` a
    /// (0,2)-sequence (Sobol''s own), where Joe and Kuo's pairs have `t` from 3 to 12. Other
    /// pairs have `t` as large as Joe and Kuo's ([`projection_t_value`] with `"sobol12"`).
    pub fn one_two(dims: u32, seed: Seed) -> Result<Self> {
        Self::with(Matrices::OneTwo, dims, seed)
    }

    /// `dims` dimensions (1 to 4) of the binary form of Faure's base-4 (0,4)-sequence
    /// (`faure4`), as [`Sobol::faure4`].
    pub fn faure4(dims: u32, seed: Seed) -> Result<Self> {
        Self::with(Matrices::Faure4, dims, seed)
    }

    /// `dims` dimensions of the sequence of `matrices`.
    fn with(matrices: Matrices, dims: u32, seed: Seed) -> Result<Self> {
        let seed = matrices.seed(seed);
        match matrices {
            Matrices::Sobol => super::check_dims(NAME, dims, MAX_DIMENSIONS, "")?,
            Matrices::OneTwo => super::check_dims(
                ONE_TWO_NAME,
                dims,
                ONE_TWO_DIMENSIONS,
                " dimensions, the (1,2)-Sobol' table's",
            )?,
            Matrices::Faure4 => super::check_dims(
                FAURE4_NAME,
                dims,
                4,
                " (a base-4 (0,s)-sequence has at most 4 dimensions)",
            )?,
        }
        Ok(SobolNd {
            epochs: Epochs::new(MAX_SEQUENCE_LEN, seed),
            dims,
            seed: seed.0,
            scramble: Scramble::new(seed.0),
            matrices,
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
        self.matrices.name()
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
        let total = out.len() / d;
        let mut done = 0usize;
        while done < total {
            let (start, count, new_epoch) = self.epochs.take((total - done) as u64);
            if let Some(key) = new_epoch {
                self.scramble = Scramble::new(key);
            }
            let seeds: Vec<u32> = (0..self.dims).map(|k| self.scramble.dim_seed(k)).collect();
            let rows = Rows {
                matrices: self.matrices,
                seeds: &seeds,
                scramble: self.scramble,
            };
            let block = &mut out[done * d..(done + count as usize) * d];
            done += count as usize;
            #[cfg(all(feature = "std", target_arch = "x86_64", not(feature = "portable")))]
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
            let v = self.matrices.point_rev(d, ir);
            *o =
                unit_f32_from_u32(owen_scramble_lanes(v, self.scramble.dim_seed(d)).reverse_bits());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_two_pairs_fill_every_elementary_interval_twice() {
        // the scrambled points of SobolNd::one_two: in each aligned block of 2^m points, every
        // pair (2k, 2k+1) puts exactly 2 points in each elementary interval of area 2^(1-m)
        // (a (1,m,2)-net), pair 0 one in each of area 2^-m; Joe and Kuo's pair (2, 3) does not
        let dims = 12u32;
        let n = 1usize << 10;
        let points = |mut s: SobolNd| {
            let mut v = vec![0f32; 3 * n * dims as usize];
            s.fill(&mut v);
            v
        };
        let counts = |v: &[f32], a: usize, b: usize, start: usize, m: u32, t: u32| -> bool {
            let k = m - t; // cells of area 2^-k
            (0..=k).all(|x_bits| {
                let mut c = vec![0u32; 1 << k];
                for i in start..start + (1 << m) {
                    let (x, y) = (v[i * dims as usize + a], v[i * dims as usize + b]);
                    let cx = (x * (1u64 << x_bits) as f32) as usize;
                    let cy = (y * (1u64 << (k - x_bits)) as f32) as usize;
                    c[(cy << x_bits) | cx] += 1;
                }
                c.iter().all(|&c| c == 1 << t)
            })
        };
        let v = points(SobolNd::one_two(dims, Seed(3)).unwrap());
        for m in 1..=10u32 {
            for start in [0, 1 << m, n] {
                assert!(counts(&v, 0, 1, start, m, 0), "pair 0, m {m}");
                for k in 1..dims as usize / 2 {
                    assert!(
                        counts(&v, 2 * k, 2 * k + 1, start, m, 1),
                        "pair {k}, m {m}, start {start}"
                    );
                }
            }
        }
        let jk = points(SobolNd::new(dims, Seed(3)).unwrap());
        assert!((1..=10).any(|m| !counts(&jk, 2, 3, 0, m, 1)));
        assert!(SobolNd::one_two(692, Seed(1)).is_ok());
        let e = SobolNd::one_two(693, Seed(1)).unwrap_err().to_string();
        assert!(e.contains("1 to 692"), "{e}");
    }

    #[test]
    fn fill_and_skip_equal_point_by_point_across_an_epoch() {
        for dims in [1u32, 2, 3, 4, 5, 8, 9, 13, 1000] {
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
    fn faure4_points_are_base4_nets_and_its_2d_form_is_dimensions_0_1() {
        // every aligned block of 4^k points of the scrambled 4D sequence: one point in each
        // base-4 box of volume 4^-k (k = 1..4), counted on the points
        let mut s = SobolNd::with(Matrices::Faure4, 4, Seed(5)).unwrap();
        assert_eq!(s.name(), "faure4");
        let mut pts = vec![0f32; 4 * 512];
        s.fill(&mut pts);
        for k in 1..=4u32 {
            let n = 1usize << (2 * k);
            for block in [0usize, 1] {
                let pts = &pts[4 * n * block..4 * n * (block + 1)];
                for a in 0..=k {
                    for b in 0..=k - a {
                        for c in 0..=k - a - b {
                            let d = k - a - b - c;
                            let mut seen = std::collections::HashSet::new();
                            for p in pts.chunks_exact(4) {
                                let cell: Vec<u32> = p
                                    .iter()
                                    .zip([a, b, c, d])
                                    .map(|(&v, e)| (v * 4f32.powi(e as i32)) as u32)
                                    .collect();
                                assert!(seen.insert(cell), "4^{k} block {block} box {a}{b}{c}{d}");
                            }
                        }
                    }
                }
            }
        }
        // the 2D sampler is dimensions 0-1 of the same scrambled sequence; faure4 is keyed
        // apart from sobol (same seed, other values, though dimension 0 is the same matrix)
        let mut two = Sobol::with(Matrices::Faure4, Seed(5));
        for p in pts.chunks_exact(4).take(64) {
            let q = two.next_sample();
            assert_eq!(q, [p[0], p[1]]);
        }
        assert_ne!(
            Sobol::with(Matrices::Faure4, Seed(5)).sample(3),
            Sobol::new(Seed(5)).sample(3)
        );
        // at most four dimensions
        let e = SobolNd::with(Matrices::Faure4, 5, Seed(5)).unwrap_err();
        assert!(e.to_string().contains("1 to 4"), "{e}");
    }
}
