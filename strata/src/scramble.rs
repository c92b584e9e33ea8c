//! The randomizations of the base-2 digital sequences, each written once.
//!
//! Every Owen-scrambled sequence of the crate (the `sobol` and `pmj02-stochastic` samplers'
//! relatives, the path-tracer adapter's `sobol`, `pmj02`, `lattice`, `zsobol`, `zpmj02`)
//! randomizes with the two functions here, over one lane type, so that a fix to a scramble is
//! one edit in this file:
//!
//! * [`owen_scramble_rev`]: a nested uniform (Owen) scramble of a 32-bit fixed-point value in
//!   the *bit-reversed* domain, the hash of Burley, "Practical Hash-based Owen Scrambling" (JCGT
//!   2020) with Vegdahl's constants ("Building a Better LK Hash", 2021; pbrt-v4's
//!   `FastOwenScrambler`). In the reversed domain a nested scramble flips each bit by a function
//!   of the *less* significant bits, and additions and multiplications carry only upward, so the
//!   hash is nested by construction: the points of any aligned dyadic interval go to an aligned
//!   dyadic interval of the same size, which keeps every `(t, m, s)`-net property.
//! * [`shuffle_rev`]: a nested uniform shuffle of a sample *index* (aligned blocks of `2^m`
//!   indices map onto aligned blocks, so every power-of-two prefix of a sequence stays a net,
//!   while the order inside is random): a seeded XOR-multiply `n ^= n * e` (`e` even, itself a
//!   nested bijection) followed by one round of [`owen_scramble_rev`]. One plain round leaves
//!   pairs of draws nearly tied: restricted to the first `2^k` indices, the round's seeded
//!   steps (an addition and a multiplication) are affine modulo `2^k`, so the shuffles of two
//!   seeds are often close relatives. The seeded XOR-multiply in front is not affine, and a
//!   second, independent key enters there; measured with the pair test
//!   (the lab's `conformance::PairStudy`), one such round is as good as an ideal random nested
//!   shuffle, where the plain round fails.
//! * `owen_scramble_base4_rev`: the base-4 variant (each aligned pair of bits, a base-4
//!   digit, permuted by the digits below), Vegdahl's hash as in Blender Cycles.
//!
//! # Lanes
//!
//! The algorithms are generic over `Lanes`: scalar `u32`, the portable arrays `[u32; N]`
//! (which the compiler vectorizes inside `target_feature` functions), and two SIMD types whose
//! intrinsics live in this file only: `X2`, two values in lanes 0 and 2 of an SSE2 register
//! (so that one `pmuludq` multiplies both, where SSE2 has no 32-bit lane multiply), and `X4`,
//! four lanes with the multiply built from two `pmuludq`. Every lane type computes exactly the
//! bits of the scalar code (tested); the SIMD types fall back to the portable arrays off x86-64
//! and with the `portable` feature, which `.ci/run` uses to check the golden digests without
//! SIMD.
//!
//! Everything here is 32-bit integer arithmetic (wrapping multiplies and adds, shifts, XOR),
//! the arithmetic a GPU runs: the WGSL shader ([`crate::pixel::WGSL`]) writes the same
//! functions.

/// Wrapping 32-bit integer lanes: what the scrambles need.
pub(crate) trait Lanes: Copy {
    /// Every lane `x`.
    fn splat(x: u32) -> Self;
    /// Lane-wise XOR.
    fn xor(self, o: Self) -> Self;
    /// Lane-wise OR.
    fn or(self, o: Self) -> Self;
    /// Lane-wise wrapping addition.
    fn add(self, o: Self) -> Self;
    /// Lane-wise wrapping multiplication (the low 32 bits of each product).
    fn mul(self, o: Self) -> Self;
    /// Lane-wise logical shift right by `K` (`0 < K < 32`).
    fn shr<const K: i32>(self) -> Self;
    /// Lane-wise bit reversal.
    fn reverse_bits(self) -> Self;
}

impl Lanes for u32 {
    #[inline(always)]
    fn splat(x: u32) -> Self {
        x
    }
    #[inline(always)]
    fn xor(self, o: Self) -> Self {
        self ^ o
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        self | o
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.wrapping_add(o)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.wrapping_mul(o)
    }
    #[inline(always)]
    fn shr<const K: i32>(self) -> Self {
        self >> K
    }
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        u32::reverse_bits(self)
    }
}

impl<const N: usize> Lanes for [u32; N] {
    #[inline(always)]
    fn splat(x: u32) -> Self {
        [x; N]
    }
    #[inline(always)]
    fn xor(self, o: Self) -> Self {
        core::array::from_fn(|k| self[k] ^ o[k])
    }
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        core::array::from_fn(|k| self[k] | o[k])
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        core::array::from_fn(|k| self[k].wrapping_add(o[k]))
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        core::array::from_fn(|k| self[k].wrapping_mul(o[k]))
    }
    #[inline(always)]
    fn shr<const K: i32>(self) -> Self {
        self.map(|x| x >> K)
    }
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        self.map(u32::reverse_bits)
    }
}

/// Two lanes of values: what a 2D draw computes in. [`X2`] on the CPU (SIMD), `[u32; 2]` as
/// the plain reference; the same bits.
pub(crate) trait Pair: Lanes {
    /// The lanes `v`.
    fn new(v: [u32; 2]) -> Self;
    /// Every lane as an `f32` in `[0, 1)` ([`crate::float::unit_f32_from_u32`]).
    fn unit_f32(self) -> [f32; 2];
}

impl Pair for [u32; 2] {
    #[inline(always)]
    fn new(v: [u32; 2]) -> Self {
        v
    }
    #[inline(always)]
    fn unit_f32(self) -> [f32; 2] {
        unit(self)
    }
}

impl Pair for X2 {
    #[inline(always)]
    fn new(v: [u32; 2]) -> Self {
        X2::new(v)
    }
    #[inline(always)]
    fn unit_f32(self) -> [f32; 2] {
        X2::unit_f32(self)
    }
}

/// The Owen scramble of `n` (bit-reversed domain) under `seed`: Burley's hash with Vegdahl's
/// constants. Bijective in `n`; every output bit is the input bit flipped by a function of the
/// less significant input bits and `seed`. `seed` must be well mixed (a hash output).
#[inline(always)]
pub(crate) fn owen_scramble_lanes<L: Lanes>(n: L, seed: L) -> L {
    let mut n = n.xor(n.mul(L::splat(LK[0])));
    n = n.add(seed);
    n = n.mul(seed.shr::<16>().or(L::splat(1)));
    n = n.xor(n.mul(L::splat(LK[1])));
    n.xor(n.mul(L::splat(LK[2])))
}

/// The even multipliers of the hash (Vegdahl's constants), shared by the base-2 and base-4
/// scrambles.
const LK: [u32; 3] = [0x3d20_adea, 0x0552_6c56, 0x53a2_2864];

/// The nested uniform shuffle of a bit-reversed index under the key pair `(even, key)`: the
/// seeded XOR-multiply `n ^= n * even` (`even` must be even), then one round of
/// [`owen_scramble_lanes`] under `key`. Both keys must be well mixed.
#[inline(always)]
pub(crate) fn shuffle_lanes<L: Lanes>(index_rev: L, even: L, key: L) -> L {
    owen_scramble_lanes(index_rev.xor(index_rev.mul(even)), key)
}

/// The Owen scramble of a 32-bit fixed-point value in the bit-reversed domain (see the
/// [module docs](self)); `seed` must be well mixed.
///
/// ```
/// use strata::scramble::owen_scramble_rev;
/// // bit 0 (the most significant digit, reversed) depends on the seed only
/// let s = 0x9e37_79b9;
/// assert_eq!(owen_scramble_rev(0, s) & 1, owen_scramble_rev(0xffff_fffe, s) & 1);
/// ```
#[inline]
pub fn owen_scramble_rev(n: u32, seed: u32) -> u32 {
    owen_scramble_lanes(n, seed)
}

/// The Owen scramble of a 32-bit fixed-point value in natural bit order: the points of any
/// aligned dyadic interval map onto an aligned dyadic interval of the same size, so the
/// scramble keeps every `(t, m, s)`-net property of a point set while randomizing it.
///
/// ```
/// use strata::scramble::owen_scramble;
/// let s = 0x1234_5678;
/// // two values in the same half stay in one half
/// assert_eq!(owen_scramble(0, s) >> 31, owen_scramble(0x7fff_ffff, s) >> 31);
/// ```
#[inline]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    owen_scramble_rev(x.reverse_bits(), seed).reverse_bits()
}

/// The nested uniform shuffle of a sample index, in the bit-reversed domain: `index_rev` is
/// the index with its 32 bits reversed, and so is the result. `even` (an even number) and `key`
/// are the two keys of one shuffle (see the [module docs](self)); both must be well mixed.
///
/// ```
/// use strata::scramble::shuffle_rev;
/// // the first 16 indices are sent onto one aligned block of 16
/// let block = |i: u32| shuffle_rev(i.reverse_bits(), 0x9e37_79b8, 0x85eb_ca6b).reverse_bits() >> 4;
/// assert!((0..16).all(|i| block(i) == block(0)));
/// ```
#[inline]
pub fn shuffle_rev(index_rev: u32, even: u32, key: u32) -> u32 {
    shuffle_lanes(index_rev, even & !1, key)
}

/// A nested uniform scramble in base 4, in the bit-reversed domain: every base-4 digit (an
/// aligned pair of bits) permuted by a function of the less significant digits and `seed`.
/// Vegdahl's hash ("A fast hash for base-4 Owen scrambling", 2022, as in Blender Cycles):
/// [`owen_scramble_rev`] with a step that mixes the two bits of every pair.
#[inline]
pub(crate) fn owen_scramble_base4_rev(mut n: u32, seed: u32) -> u32 {
    const PAIRS: u32 = 0x5555_5555;
    n ^= n.wrapping_mul(LK[0]);
    n ^= (n >> 1) & (n << 1) & PAIRS;
    n = n.wrapping_add(seed);
    n = n.wrapping_mul((seed >> 16) | 1);
    n ^= (n >> 1) & (n << 1) & PAIRS;
    n ^= n.wrapping_mul(LK[1]);
    n ^ n.wrapping_mul(LK[2])
}

/// 32-bit fixed-point values as `f32` in `[0, 1)`, lane by lane: the top 24 bits, as
/// [`crate::float::unit_f32_from_u32`].
#[inline(always)]
fn unit<const N: usize>(v: [u32; N]) -> [f32; N] {
    v.map(crate::float::unit_f32_from_u32)
}

#[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
pub(crate) use sse2::{X2, X4};

#[cfg(not(all(target_arch = "x86_64", not(feature = "portable"))))]
pub(crate) use portable::{X2, X4};

/// The portable lane types: arrays, lane by lane.
#[cfg(not(all(target_arch = "x86_64", not(feature = "portable"))))]
mod portable {
    use super::{Lanes, unit};

    macro_rules! lanes {
        ($name:ident, $n:expr) => {
            #[doc = concat!(stringify!($n), " lanes, portable: an array.")]
            #[derive(Clone, Copy, Debug)]
            pub(crate) struct $name([u32; $n]);

            impl $name {
                /// The lanes `v`.
                #[inline(always)]
                pub(crate) fn new(v: [u32; $n]) -> Self {
                    $name(v)
                }
                /// The lanes as an array.
                #[inline(always)]
                #[cfg_attr(not(test), allow(dead_code))]
                pub(crate) fn to_array(self) -> [u32; $n] {
                    self.0
                }
                /// Every lane as an `f32` in `[0, 1)`.
                #[inline(always)]
                pub(crate) fn unit_f32(self) -> [f32; $n] {
                    unit(self.0)
                }
            }

            impl Lanes for $name {
                #[inline(always)]
                fn splat(x: u32) -> Self {
                    $name([x; $n])
                }
                #[inline(always)]
                fn xor(self, o: Self) -> Self {
                    $name(self.0.xor(o.0))
                }
                #[inline(always)]
                fn or(self, o: Self) -> Self {
                    $name(self.0.or(o.0))
                }
                #[inline(always)]
                fn add(self, o: Self) -> Self {
                    $name(self.0.add(o.0))
                }
                #[inline(always)]
                fn mul(self, o: Self) -> Self {
                    $name(self.0.mul(o.0))
                }
                #[inline(always)]
                fn shr<const K: i32>(self) -> Self {
                    $name(self.0.shr::<K>())
                }
                #[inline(always)]
                fn reverse_bits(self) -> Self {
                    $name(self.0.reverse_bits())
                }
            }
        };
    }

    lanes!(X2, 2);
    lanes!(X4, 4);

    /// Two pairs of lanes as one set of four: `(a0, a1, b0, b1)`.
    #[inline(always)]
    pub(crate) fn join(a: X2, b: X2) -> X4 {
        X4([a.0[0], a.0[1], b.0[0], b.0[1]])
    }
}

#[cfg(not(all(target_arch = "x86_64", not(feature = "portable"))))]
pub(crate) use portable::join;
#[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
pub(crate) use sse2::join;

/// The SSE2 lane types (SSE2 is part of the x86-64 baseline, so no run-time detection).
#[cfg(all(target_arch = "x86_64", not(feature = "portable")))]
mod sse2 {
    use core::arch::x86_64::*;

    use super::Lanes;

    /// Two lanes in lanes 0 and 2 of an SSE2 register. SSE2 multiplies 32-bit lanes only in
    /// pairs (`pmuludq`: lanes 0 and 2, into 64-bit products whose low halves land back in
    /// lanes 0 and 2), so two values placed there are multiplied by one instruction; lanes 1
    /// and 3 hold don't-care bits that no lane-wise operation moves into lanes 0 and 2.
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct X2(__m128i);

    /// Four lanes of an SSE2 register (the multiply from two `pmuludq`).
    #[derive(Clone, Copy, Debug)]
    pub(crate) struct X4(__m128i);

    // SAFETY (every block in this module): SSE2 is part of the x86-64 baseline, so each
    // intrinsic is available; the only memory accesses are unaligned loads and stores of
    // local arrays of four lanes.

    impl X2 {
        /// The lanes `v`.
        #[inline(always)]
        pub(crate) fn new(v: [u32; 2]) -> Self {
            // SAFETY: see the module.
            X2(unsafe { _mm_set_epi32(0, v[1] as i32, 0, v[0] as i32) })
        }
        /// The lanes as an array.
        #[cfg(test)]
        pub(crate) fn to_array(self) -> [u32; 2] {
            let a = store(self.0);
            [a[0], a[2]]
        }
        /// Every lane as an `f32` in `[0, 1)` (the top 24 bits, exactly as
        /// [`crate::float::unit_f32_from_u32`]).
        #[inline(always)]
        pub(crate) fn unit_f32(self) -> [f32; 2] {
            // SAFETY: see the module.
            unsafe {
                let f = to_unit(self.0);
                let f = _mm_shuffle_ps(f, f, 0b00_00_10_00);
                let mut out = [0f32; 4];
                _mm_storeu_ps(out.as_mut_ptr(), f);
                [out[0], out[1]]
            }
        }
    }

    impl X4 {
        /// The lanes `v`.
        #[inline(always)]
        pub(crate) fn new(v: [u32; 4]) -> Self {
            // SAFETY: see the module.
            X4(unsafe { _mm_loadu_si128(v.as_ptr().cast()) })
        }
        /// The lanes as an array.
        #[inline(always)]
        pub(crate) fn to_array(self) -> [u32; 4] {
            store(self.0)
        }
        /// Every lane as an `f32` in `[0, 1)`.
        #[inline(always)]
        pub(crate) fn unit_f32(self) -> [f32; 4] {
            // SAFETY: see the module.
            unsafe {
                let mut out = [0f32; 4];
                _mm_storeu_ps(out.as_mut_ptr(), to_unit(self.0));
                out
            }
        }
    }

    /// Two pairs of lanes as one set of four: `(a0, a1, b0, b1)`.
    #[inline(always)]
    pub(crate) fn join(a: X2, b: X2) -> X4 {
        // SAFETY: see the module.
        X4(unsafe {
            _mm_castps_si128(_mm_shuffle_ps(
                _mm_castsi128_ps(a.0),
                _mm_castsi128_ps(b.0),
                0b10_00_10_00,
            ))
        })
    }

    #[inline(always)]
    fn store(v: __m128i) -> [u32; 4] {
        let mut out = [0u32; 4];
        // SAFETY: see the module.
        unsafe { _mm_storeu_si128(out.as_mut_ptr().cast(), v) };
        out
    }

    /// `(x >> 8) * 2^-24` in every lane: exact, as the scalar conversion.
    #[inline(always)]
    unsafe fn to_unit(x: __m128i) -> __m128 {
        // SAFETY: see the module.
        unsafe {
            _mm_mul_ps(
                _mm_cvtepi32_ps(_mm_srli_epi32(x, 8)),
                _mm_set1_ps(1.0 / 16_777_216.0),
            )
        }
    }

    /// Swaps the bit groups of width `S` selected by `mask` with their neighbours.
    #[inline(always)]
    unsafe fn swap<const S: i32>(x: __m128i, mask: u32) -> __m128i {
        // SAFETY: see the module.
        unsafe {
            let m = _mm_set1_epi32(mask as i32);
            _mm_or_si128(
                _mm_slli_epi32(_mm_and_si128(x, m), S),
                _mm_and_si128(_mm_srli_epi32(x, S), m),
            )
        }
    }

    /// The bits of every 32-bit lane reversed.
    #[inline(always)]
    unsafe fn reverse(x: __m128i) -> __m128i {
        // SAFETY: see the module.
        unsafe {
            let x = swap::<1>(x, 0x5555_5555);
            let x = swap::<2>(x, 0x3333_3333);
            let x = swap::<4>(x, 0x0f0f_0f0f);
            let x = swap::<8>(x, 0x00ff_00ff);
            _mm_or_si128(_mm_slli_epi32(x, 16), _mm_srli_epi32(x, 16))
        }
    }

    /// The low 32 bits of the lane-wise products of four lanes, from two `pmuludq`.
    #[inline(always)]
    unsafe fn mullo4(a: __m128i, b: __m128i) -> __m128i {
        // SAFETY: see the module.
        unsafe {
            let even = _mm_mul_epu32(a, b);
            let odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
            _mm_unpacklo_epi32(
                _mm_shuffle_epi32(even, 0b00_00_10_00),
                _mm_shuffle_epi32(odd, 0b00_00_10_00),
            )
        }
    }

    macro_rules! common {
        ($name:ident) => {
            #[inline(always)]
            fn splat(x: u32) -> Self {
                // SAFETY: see the module.
                $name(unsafe { _mm_set1_epi32(x as i32) })
            }
            #[inline(always)]
            fn xor(self, o: Self) -> Self {
                // SAFETY: see the module.
                $name(unsafe { _mm_xor_si128(self.0, o.0) })
            }
            #[inline(always)]
            fn or(self, o: Self) -> Self {
                // SAFETY: see the module.
                $name(unsafe { _mm_or_si128(self.0, o.0) })
            }
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                // SAFETY: see the module.
                $name(unsafe { _mm_add_epi32(self.0, o.0) })
            }
            #[inline(always)]
            fn shr<const K: i32>(self) -> Self {
                // SAFETY: see the module.
                $name(unsafe { _mm_srli_epi32(self.0, K) })
            }
            #[inline(always)]
            fn reverse_bits(self) -> Self {
                // SAFETY: see the module.
                $name(unsafe { reverse(self.0) })
            }
        };
    }

    impl Lanes for X2 {
        common!(X2);
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            // SAFETY: see the module.
            X2(unsafe { _mm_mul_epu32(self.0, o.0) })
        }
    }

    impl Lanes for X4 {
        common!(X4);
        #[inline(always)]
        fn mul(self, o: Self) -> Self {
            // SAFETY: see the module.
            X4(unsafe { mullo4(self.0, o.0) })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::mix64;

    /// Pseudo-random words for the lane tests.
    fn words(n: usize) -> impl Iterator<Item = [u32; 4]> {
        let mut h = 5u64;
        (0..n).map(move |_| {
            h = mix64(h);
            let g = mix64(h);
            [h as u32, (h >> 32) as u32, g as u32, (g >> 32) as u32]
        })
    }

    #[test]
    fn every_lane_type_computes_the_scalar_bits() {
        for w in words(20_000) {
            let s = w.map(|v| mix64(v as u64) as u32);
            let want: [u32; 4] = core::array::from_fn(|k| owen_scramble_lanes(w[k], s[k]));
            let want_shuffle: [u32; 4] =
                core::array::from_fn(|k| shuffle_lanes(w[k], s[k] & !1, s[k].rotate_left(7)));
            assert_eq!(owen_scramble_lanes(w, s), want);
            assert_eq!(owen_scramble_lanes(X4::new(w), X4::new(s)).to_array(), want);
            let a = X2::new([w[0], w[1]]);
            let b = X2::new([w[2], w[3]]);
            let sa = X2::new([s[0], s[1]]);
            let sb = X2::new([s[2], s[3]]);
            let (ra, rb) = (owen_scramble_lanes(a, sa), owen_scramble_lanes(b, sb));
            assert_eq!(ra.to_array(), [want[0], want[1]]);
            assert_eq!(rb.to_array(), [want[2], want[3]]);
            assert_eq!(join(ra, rb).to_array(), want);
            let evens = X4::new(s.map(|v| v & !1));
            let keys = X4::new(s.map(|v| v.rotate_left(7)));
            assert_eq!(
                shuffle_lanes(X4::new(w), evens, keys).to_array(),
                want_shuffle
            );
            let floats = want.map(|v| crate::float::unit_f32_from_u32(v.reverse_bits()));
            assert_eq!(
                X4::new(want).reverse_bits().unit_f32().map(f32::to_bits),
                floats.map(f32::to_bits)
            );
            assert_eq!(
                ra.reverse_bits().unit_f32().map(f32::to_bits),
                [floats[0].to_bits(), floats[1].to_bits()]
            );
            assert_eq!(
                X4::new(w).reverse_bits().to_array(),
                w.map(u32::reverse_bits)
            );
        }
    }

    #[test]
    fn the_scrambles_are_nested_bijections() {
        for seed in [1u32, 0x9e37_79b9, u32::MAX] {
            let s = crate::hash::hash32(seed, 7);
            // values sharing their top k bits keep sharing their top k bits
            for k in [1u32, 4, 10, 20] {
                for base in [0u32, 0x1234_5678, 0xfedc_ba98] {
                    let top = |v: u32| v >> (32 - k);
                    let other = base ^ ((1 << (32 - k)) - 1);
                    assert_eq!(top(owen_scramble(base, s)), top(owen_scramble(other, s)));
                    let sh = |v: u32| shuffle_rev(v.reverse_bits(), s << 1, !s).reverse_bits();
                    assert_eq!(top(sh(base)), top(sh(other)), "shuffle, k = {k}");
                }
            }
            // bijections on 12-bit prefixes
            let mut seen = vec![false; 1 << 12];
            let mut seen_shuffle = vec![false; 1 << 12];
            for v in 0..1u32 << 12 {
                let w = owen_scramble(v << 20, s) >> 20;
                assert!(!seen[w as usize]);
                seen[w as usize] = true;
                let i = shuffle_rev((v << 20).reverse_bits(), s << 1, !s).reverse_bits() >> 20;
                assert!(!seen_shuffle[i as usize]);
                seen_shuffle[i as usize] = true;
            }
        }
    }
}
