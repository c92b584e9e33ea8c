//! Float conversion that never yields 1.0 and keeps points in their strata.
//!
//! Samplers compute in integer fixed point or in `f64` and convert to `f32` only at the edge. The
//! conversion must never produce 1.0: a renderer maps `[0,1)` to pixels, strata and table
//! indices, and a 1.0 lands one past the end. The naive `(i + u) / n` in `f32` *does* round to
//! 1.0 (for example `i = 2`, `u = 0.99999994`, `n = 3`), and rounding to nearest can also move a
//! point across a stratum boundary. The functions here avoid both:
//!
//! * [`unit_f32_from_u32`] keeps the top 24 bits of a 32-bit fixed-point value: every
//!   dyadic stratum of width `>= 2^-24` is preserved exactly.
//! * [`unit_f32_from_f64`] rounds toward zero and clamps to [`ONE_MINUS_EPSILON`].
//! * [`f32_in_stratum`] places `(k + u) / n` in `f32` so that `floor(x * n) == k` holds exactly
//!   (for `n <= 2^23`; finer strata are not all representable in `f32` near 1).

use crate::sampler::Point2;

/// The largest `f32` below 1 (`1 - 2^-24`).
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// `2^-32`: the weight of one unit of 32-bit fixed point.
pub(crate) const INV_2_POW_32: f64 = 1.0 / 4_294_967_296.0;

/// A 32-bit fixed-point fraction `x / 2^32` as an `f32` in `[0, 1)`, truncating to 24 bits.
///
/// Truncation (not rounding) keeps every point inside its dyadic stratum down to width `2^-24`.
///
/// ```
/// use strata::float::unit_f32_from_u32;
/// assert_eq!(unit_f32_from_u32(0), 0.0);
/// assert!(unit_f32_from_u32(u32::MAX) < 1.0);
/// assert_eq!(unit_f32_from_u32(1 << 31), 0.5);
/// ```
#[inline]
pub fn unit_f32_from_u32(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// A 32-bit fixed-point fraction `x / 2^32` as an `f64` in `[0, 1)` (exact).
#[inline]
pub fn unit_f64_from_u32(x: u32) -> f64 {
    x as f64 * INV_2_POW_32
}

/// The top 53 bits of a 64-bit random word as an `f64` in `[0, 1)` (exact, uniform on the
/// multiples of `2^-53`).
#[inline]
pub fn unit_f64_from_u64(x: u64) -> f64 {
    (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// An `f64` in `[0, 1)` as an `f32` in `[0, 1)`: rounds toward zero, maps NaN, negatives and
/// values below `2^-126` (where `f32` turns subnormal) to 0 and everything at or above the
/// largest `f32` below 1 to [`ONE_MINUS_EPSILON`].
///
/// ```
/// use strata::float::{unit_f32_from_f64, ONE_MINUS_EPSILON};
/// // 1 - 2^-30 rounds to 1.0 in f32; this function does not.
/// let x = 1.0 - 2f64.powi(-30);
/// assert_eq!(x as f32, 1.0);
/// assert_eq!(unit_f32_from_f64(x), ONE_MINUS_EPSILON);
/// ```
#[inline]
pub fn unit_f32_from_f64(x: f64) -> f32 {
    if x.is_nan() || x <= 0.0 {
        0.0
    } else if x < 1.0 {
        trunc_to_f32(x)
    } else {
        ONE_MINUS_EPSILON
    }
}

/// The point `(k + u) / n` of stratum `k` of `n` equal strata of `[0,1)`, as an `f32` that lies in
/// the stratum: `k <= x * n < k + 1` holds exactly for the returned `x` whenever `n <= 2^23`.
///
/// `u` is the position inside the stratum, in `[0, 1)`; `k < n`. Samplers that place many points
/// in strata of one size use the same computation with `1/n`
/// precomputed.
///
/// ```
/// use strata::float::f32_in_stratum;
/// let u = 1.0 - 2f64.powi(-32);
/// // naive f32 arithmetic rounds the last stratum's upper end to 1.0
/// assert_eq!((2.0f32 + u as f32) / 3.0, 1.0);
/// let x = f32_in_stratum(2, 3, u);
/// assert!(x < 1.0 && (x as f64 * 3.0).floor() == 2.0);
/// ```
#[inline]
pub fn f32_in_stratum(k: u64, n: u64, u: f64) -> f32 {
    Strata::new(n).place_f64(k, u)
}

/// The largest strata count [`Strata::place2`] handles in SIMD (stratum indices must fit `i32`).
#[cfg(target_arch = "x86_64")]
const MAX_SIMD_STRATA: f64 = 2_147_483_648.0;

/// `n` equal strata of `[0,1)`, for placing points inside a given stratum as `f32` (see
/// [`f32_in_stratum`] for the guarantee): the reciprocal computed once, for samplers that place
/// many points on one grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strata {
    n: f64,
    inv_n: f64,
}

impl Strata {
    /// `n >= 1` strata (`n = 0` is treated as 1).
    #[inline]
    pub const fn new(n: u64) -> Self {
        let n = if n == 0 { 1.0 } else { n as f64 };
        Strata { n, inv_n: 1.0 / n }
    }

    /// The point at fixed-point offset `jitter / 2^32` inside stratum `k` (`k < n`). The top 31
    /// bits of `jitter` are used.
    #[inline]
    pub fn place(&self, k: u32, jitter: u32) -> f32 {
        // 31 jitter bits, exactly as the SIMD path of `place2`, so every platform gives the
        // same bits.
        let u = (jitter >> 1) as f64 * (1.0 / 2_147_483_648.0);
        let x = (k as f64 + u) * self.inv_n;
        self.snap(k as f64, x as f32)
    }

    /// [`place`](Strata::place) for both coordinates of a 2D point whose axes have the same
    /// number of strata; written lane-wise so that the compiler keeps both in one SIMD register.
    #[inline]
    pub(crate) fn place2(&self, k: [u32; 2], jitter: [u32; 2]) -> Point2 {
        #[cfg(target_arch = "x86_64")]
        if self.n <= MAX_SIMD_STRATA {
            // SAFETY: SSE2 is part of the x86_64 baseline; k < n <= 2^31 fits in i32.
            return unsafe { self.place2_sse2(k, jitter) };
        }
        [self.place(k[0], jitter[0]), self.place(k[1], jitter[1])]
    }

    /// [`place2`](Strata::place2) in SSE2: both coordinates in the two lanes of one register,
    /// the same arithmetic as [`place`](Strata::place) and [`snap`](Strata::snap) (with 31 of
    /// the 32 jitter bits), about three times faster than the scalar code.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    unsafe fn place2_sse2(&self, k: [u32; 2], jitter: [u32; 2]) -> Point2 {
        use core::arch::x86_64::*;
        // SAFETY: SSE2 is part of the x86_64 baseline, so every intrinsic below is available;
        // the only memory access is an unaligned store into a local array of four floats.
        unsafe {
            let ki = _mm_set_epi32(0, 0, k[1] as i32, k[0] as i32);
            let ji = _mm_set_epi32(0, 0, (jitter[1] >> 1) as i32, (jitter[0] >> 1) as i32);
            let kf = _mm_cvtepi32_pd(ki);
            let u = _mm_mul_pd(_mm_cvtepi32_pd(ji), _mm_set1_pd(1.0 / 2_147_483_648.0));
            let x = _mm_mul_pd(_mm_add_pd(kf, u), _mm_set1_pd(self.inv_n));
            let x32 = _mm_cvtpd_ps(x);
            let xn = _mm_mul_pd(_mm_cvtps_pd(x32), _mm_set1_pd(self.n));
            // 64-bit lane masks -> the low 32-bit lanes (0 and 2 -> 0 and 1).
            let below = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmplt_pd(xn, kf)), 0b1000);
            let k1 = _mm_add_pd(kf, _mm_set1_pd(1.0));
            let above = _mm_shuffle_epi32(_mm_castpd_si128(_mm_cmpge_pd(xn, k1)), 0b1000);
            // mask -1 where true: below -> bits + 1, above -> bits - 1.
            let bits = _mm_add_epi32(_mm_sub_epi32(_mm_castps_si128(x32), below), above);
            // Only 1.0 itself can exceed the largest float below 1 (all bits are positive ints).
            let one_minus = _mm_set1_epi32(ONE_MINUS_EPSILON.to_bits() as i32);
            let bits = _mm_add_epi32(bits, _mm_cmpgt_epi32(bits, one_minus));
            let mut out = [0f32; 4];
            _mm_storeu_ps(out.as_mut_ptr(), _mm_castsi128_ps(bits));
            [out[0], out[1]]
        }
    }

    /// The point at offset `u` in `[0, 1)` inside stratum `k` (`k < n`).
    #[inline]
    pub(crate) fn place_f64(&self, k: u64, u: f64) -> f32 {
        // through i64 where it fits: one instruction instead of u64's sequence
        let k = if k <= i64::MAX as u64 {
            k as i64 as f64
        } else {
            k as f64
        };
        let x = (k + u) * self.inv_n;
        self.snap(k, x.min(1.0) as f32)
    }

    /// `x`, a float within one ulp of stratum `k`, moved into it. Rounding to `f32` (and of
    /// `1/n`) can leave x one float outside (only within one ulp of a boundary, or at 1.0).
    /// `x n` is exact in f64 (24-bit mantissa times a count below 2^29), so comparing it with
    /// `k` and `k + 1` tells exactly whether x is inside; stepping by one float is a +-1 on the
    /// bits of a non-negative float. Branch-free.
    #[inline]
    fn snap(&self, k: f64, x: f32) -> f32 {
        let xn = x as f64 * self.n;
        let bits = x.to_bits() + (xn < k) as u32 - (xn >= k + 1.0) as u32;
        f32::from_bits(bits.min(ONE_MINUS_EPSILON.to_bits()))
    }
}

/// `x` in `[0, 1]` rounded toward zero to `f32`, branch-free; values below 2^-126 flush to 0.
#[inline]
fn trunc_to_f32(x: f64) -> f32 {
    const REBIAS: u64 = (1023 - 127) << 23;
    const MIN_NORMAL: u64 = (1023 - 126) << 52;
    let bits = x.to_bits();
    let t = f32::from_bits((bits >> 29).wrapping_sub(REBIAS) as u32);
    if bits >= MIN_NORMAL { t } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_minus_epsilon_is_the_largest_float_below_one() {
        assert_eq!(ONE_MINUS_EPSILON.next_up(), 1.0);
    }

    #[test]
    fn simd_and_scalar_placement_agree_bit_for_bit() {
        let mut h = 0x1234_5678_9abc_def0u64;
        for n in [
            1u64,
            2,
            3,
            7,
            100,
            4097,
            65536,
            1 << 20,
            (1 << 31) - 1,
            1 << 31,
        ] {
            let strata = Strata::new(n);
            for _ in 0..2000 {
                h = crate::hash::mix64(h);
                let k = [(h % n) as u32, ((h >> 20) % n) as u32];
                let j = [(h >> 7) as u32, (h >> 29) as u32];
                let p = strata.place2(k, j);
                assert_eq!(p[0].to_bits(), strata.place(k[0], j[0]).to_bits());
                assert_eq!(p[1].to_bits(), strata.place(k[1], j[1]).to_bits());
                if n <= 1 << 23 {
                    assert_eq!((p[0] as f64 * n as f64) as u32, k[0]);
                    assert_eq!((p[1] as f64 * n as f64) as u32, k[1]);
                }
            }
            // the extremes of the last stratum
            let last = (n - 1) as u32;
            for j in [0, 1, u32::MAX - 1, u32::MAX] {
                let p = strata.place2([last, 0], [j, j]);
                assert!(p[0] < 1.0 && p[1] < 1.0);
            }
        }
    }

    #[test]
    fn f64_conversion_rounds_down() {
        for &x in &[0.1f64, 1.0 / 3.0, 0.999_999_999, 0.5 + 1e-12] {
            let y = unit_f32_from_f64(x);
            assert!(y as f64 <= x);
            assert!((y.next_up() as f64) > x || y == ONE_MINUS_EPSILON);
        }
        assert_eq!(unit_f32_from_f64(f64::NAN), 0.0);
        assert_eq!(unit_f32_from_f64(-1.0), 0.0);
        assert_eq!(unit_f32_from_f64(1.0), ONE_MINUS_EPSILON);
        assert_eq!(unit_f32_from_f64(f64::INFINITY), ONE_MINUS_EPSILON);
    }
}
