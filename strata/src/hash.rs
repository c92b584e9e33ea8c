//! Integer hashing, Kensler's stateless permutation, and the seeding of independent streams.
//!
//! Everything random in `strata` is derived from a user seed (`u64`) by the functions here, so
//! that the same seed gives the same bits on every platform and in any evaluation order:
//!
//! * [`mix64`] is a bijective 64-bit finalizer (Stafford's "Mix13" variant of the SplitMix64
//!   output function): every input bit affects every output bit with probability close to 1/2.
//! * [`stream_seed`] derives the seed of an independent stream (a block of a fixed-count sampler,
//!   a pixel, a dimension) from a stream number and a parent seed.
//! * [`hash_u64`] hashes an (index, key) pair to 64 uniform bits, used where a sampler needs random
//!   numbers addressed by index rather than drawn in order.
//! * [`permute`] / [`Permutation`] is Kensler's `permute(i, l, p)` from "Correlated Multi-Jittered
//!   Sampling" (Pixar Technical Memo 13-01, 2013): a pseudo-random bijection on `[0, l)` for *any*
//!   `l`, evaluated element by element in constant expected time, by hashing within the enclosing
//!   power of two and *cycle walking* until the value falls below `l`.
//! * `DivMod` divides by a run-time constant with a multiplication (Lemire, Kaser, Kurz,
//!   "Faster Remainder by Direct Computation", 2019), for the per-point index arithmetic of the
//!   stateless samplers.
//!
//! The scrambles of the digital sequences (Owen scrambling, the nested index shuffle) are in
//! [`crate::scramble`].

/// The 64-bit golden-ratio increment of SplitMix64, used to separate streams.
pub const GOLDEN_GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// The named streams of randomness derived from one key. Each use of a key (a permutation, a
/// scramble, a set of jitters) takes its own stream, so that no two uses see related bits; the
/// values are fixed forever, since every sampler's output depends on them. (The lab's samplers
/// name their own: orthogonal arrays `0x5eed`, Lloyd's jitter `0x110d`.)
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u64)]
pub(crate) enum Stream {
    /// Multi-jittered: the shuffles of the x sub-columns.
    MultiJitterX = 0x006d_6a58,
    /// Multi-jittered: the shuffles of the y sub-rows.
    MultiJitterY = 0x006d_6a59,
    /// Correlated multi-jittered: the sample order.
    CmjOrder = 0x636d_6a53,
    /// Correlated multi-jittered: the x shuffle.
    CmjX = 0x636d_6a58,
    /// Correlated multi-jittered: the y shuffle.
    CmjY = 0x636d_6a59,
    /// N-rooks: the column permutation.
    NRooksX = 0x6c61_7469_6e58,
    /// N-rooks: the row permutation.
    NRooksY = 0x6c61_7469_6e59,
    /// Sobol': the scramble of a seed.
    SobolScramble = 0x50b0,
    /// Halton: the digit permutations of dimension 0 (dimension `d` adds `d`).
    HaltonDigits = 0x4a17,
}

impl Stream {
    /// The stream's number.
    #[inline]
    pub(crate) const fn id(self) -> u64 {
        self as u64
    }

    /// A 32-bit key for this stream of `key` (for a [`Permutation`]).
    #[inline]
    pub(crate) const fn key32(self, key: u64) -> u32 {
        key32(key ^ self.id())
    }
}

/// A bijective 64-bit mixing function (Stafford's Mix13, the SplitMix64 finalizer).
///
/// ```
/// use strata::hash::mix64;
/// assert_ne!(mix64(1), mix64(2));
/// assert_eq!(mix64(7), mix64(7));
/// ```
#[inline]
pub const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The seed of stream number `stream` of the 64-bit `key` (a seed, or a key derived from one).
///
/// Distinct `(stream, key)` pairs give unrelated outputs; the function is used to give each block
/// of a fixed-count sampler, each pixel and each dimension its own independent randomness. The
/// arguments follow the crate's order: what is drawn (the stream), then the key.
///
/// ```
/// use strata::hash::stream_seed;
/// assert_ne!(stream_seed(0, 1), stream_seed(1, 1));
/// assert_ne!(stream_seed(0, 1), stream_seed(0, 2));
/// ```
#[inline]
pub const fn stream_seed(stream: u64, key: u64) -> u64 {
    mix64(mix64(key ^ 0x5851_f42d_4c95_7f2d).wrapping_add(stream.wrapping_mul(GOLDEN_GAMMA)))
}

/// 64 uniform bits addressed by `(index, key)`: a counter-based generator.
///
/// This is wyrand (Wang Yi's generator, which passes PractRand and BigCrush) evaluated at state
/// `key + index * increment`: one 64 x 64 -> 128-bit multiply, folded. `key` should itself be well
/// mixed (for example from [`stream_seed`]).
#[inline]
pub const fn hash_u64(index: u64, key: u64) -> u64 {
    const INCREMENT: u64 = 0xa076_1d64_78bd_642f;
    const XOR: u64 = 0xe703_7ed1_a0b4_28db;
    let s = key.wrapping_add(index.wrapping_add(1).wrapping_mul(INCREMENT));
    let r = (s ^ XOR) as u128 * s as u128;
    (r as u64) ^ ((r >> 64) as u64)
}

/// The two multipliers of Wellons' `lowbias32` (`x ^= x >> 16; x *= M[0]; x ^= x >> 15;
/// x *= M[1]; x ^= x >> 16`), the one home of the constants: [`hash32`] and the pixel kernel's
/// lanes read them (the WGSL port spells them again; the GPU test compares the two).
pub(crate) const LOWBIAS32: [u32; 2] = [0x7feb_352d, 0x846c_a68b];

/// The high 32 bits of [`GOLDEN_GAMMA`] (`2^32 / phi`, odd), for 32-bit salts and multipliers.
pub(crate) const GOLDEN_GAMMA_32: u32 = (GOLDEN_GAMMA >> 32) as u32;

/// A bijective 32-bit hash of `x` under `key` (Wellons' "lowbias32" on `x ^ key`), for deriving
/// per-row or per-column permutation keys cheaply.
#[inline]
pub const fn hash32(x: u32, key: u32) -> u32 {
    let mut x = x ^ key;
    x ^= x >> 16;
    x = x.wrapping_mul(LOWBIAS32[0]);
    x ^= x >> 15;
    x = x.wrapping_mul(LOWBIAS32[1]);
    x ^ (x >> 16)
}

/// A 32-bit key derived from a 64-bit one (for [`permute`], whose key is 32 bits).
#[inline]
pub const fn key32(key: u64) -> u32 {
    (mix64(key) >> 32) as u32
}

/// Kensler's hashed permutation: the `i`-th element of a pseudo-random permutation of `[0, l)`
/// selected by `p`.
///
/// For a fixed `l` and `p`, `i -> permute(i, l, p)` is a bijection on `[0, l)`. The hash is a
/// sequence of invertible operations on the low `k` bits, where `2^k` is the smallest power of two
/// `>= l`; values that land in `[l, 2^k)` are hashed again (cycle walking), which takes fewer
/// than two rounds on average.
///
/// `l = 0` has no elements: the function then returns 0. An `i >= l` is reduced modulo `l` first
/// (cycle walking from outside `[0, l)` need not terminate, so it is never attempted).
///
/// ```
/// use strata::hash::permute;
/// let mut seen = vec![false; 10];
/// for i in 0..10 {
///     seen[permute(i, 10, 1234) as usize] = true;
/// }
/// assert!(seen.iter().all(|&s| s));
/// ```
#[inline]
pub fn permute(i: u32, l: u32, p: u32) -> u32 {
    match Permutation::new(l, p) {
        Some(perm) => perm.apply(if i < l { i } else { i % l }),
        None => 0,
    }
}

/// A precomputed [`permute`]: the mask and the final rotation are computed once, so that
/// [`apply`](Permutation::apply) costs only the hash rounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Permutation {
    len: u32,
    mask: u32,
    key: u32,
    /// `key % len`, so the final `(i + key) % len` is an add and a conditional subtract.
    offset: u32,
}

impl Permutation {
    /// The permutation of `[0, len)` selected by `key`; `None` when `len == 0`.
    #[inline]
    pub const fn new(len: u32, key: u32) -> Option<Self> {
        if len == 0 {
            return None;
        }
        let mask = if len == 1 {
            0
        } else {
            u32::MAX >> (len - 1).leading_zeros()
        };
        Some(Permutation {
            len,
            mask,
            key,
            offset: key % len,
        })
    }

    /// The permutation of `[0, d)` selected by `key`, where `len` divides by `d`: the same as
    /// [`Permutation::new`]`(d, key)` without its division, for code that builds many
    /// permutations of one length (one per row or column).
    #[inline]
    pub const fn with_divider(len: &DivMod, key: u32) -> Self {
        let d = len.divisor();
        let mask = if d == 1 {
            0
        } else {
            u32::MAX >> (d - 1).leading_zeros()
        };
        Permutation {
            len: d,
            mask,
            key,
            offset: len.div_rem(key).1,
        }
    }

    /// The number of elements permuted.
    #[inline]
    pub const fn len(&self) -> u32 {
        self.len
    }

    /// Always false: a permutation has at least one element (see [`Permutation::new`]).
    #[inline]
    pub const fn is_empty(&self) -> bool {
        false
    }

    /// The image of `i`, for `i < len`. (An `i >= len` gives an unspecified value in range; debug
    /// builds assert.)
    #[inline]
    pub fn apply(&self, i: u32) -> u32 {
        debug_assert!(
            i < self.len,
            "permutation index {i} out of range 0..{}",
            self.len
        );
        let mut i = self.fold(i);
        loop {
            i = self.round(i);
            if i < self.len {
                break;
            }
        }
        self.rotate(i)
    }

    /// The images of two indices, computed in lockstep so that the two dependency chains of
    /// multiplications overlap (faster than two calls to [`apply`](Permutation::apply)); the
    /// results are identical to `apply`'s.
    #[inline]
    pub(crate) fn apply2(&self, i: [u32; 2]) -> [u32; 2] {
        debug_assert!(i[0] < self.len && i[1] < self.len);
        let (mut a, mut b) = (self.fold(i[0]), self.fold(i[1]));
        let (mut a_done, mut b_done) = (false, false);
        loop {
            // A finished chain keeps its value (a conditional move, not a branch).
            let (ra, rb) = (self.round(a), self.round(b));
            a = if a_done { a } else { ra };
            b = if b_done { b } else { rb };
            a_done |= a < self.len;
            b_done |= b < self.len;
            if a_done && b_done {
                break;
            }
        }
        [self.rotate(a), self.rotate(b)]
    }

    /// Brings an out-of-range index into range (cycle walking from outside `[0, len)` need not
    /// terminate); the identity on valid indices.
    #[inline]
    fn fold(&self, i: u32) -> u32 {
        let i = i & self.mask;
        if i >= self.len { i - self.len } else { i }
    }

    /// One round of Kensler's hash: a bijection on `[0, mask]`.
    #[inline]
    fn round(&self, mut i: u32) -> u32 {
        let (w, p) = (self.mask, self.key);
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^ (i >> 5)
    }

    /// Kensler's final `(i + key) % len`, without a division: both terms are below `len`, and
    /// their sum is taken in 64 bits (past `2^31` it does not fit a `u32`).
    #[inline]
    fn rotate(&self, i: u32) -> u32 {
        let (j, len) = (i as u64 + self.offset as u64, self.len as u64);
        (if j >= len { j - len } else { j }) as u32
    }
}

/// Division and remainder by a run-time constant `d >= 1`, by multiplication.
///
/// Lemire's direct computation: with `M = ceil(2^64 / d)`, `n / d = floor(M n / 2^64)` for every
/// 32-bit `n`. `d = 1` (where `M` would overflow) is handled separately.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DivMod {
    d: u32,
    m: u64,
}

impl DivMod {
    /// Division by 1.
    pub(crate) const ONE: DivMod = DivMod { d: 1, m: 0 };

    /// The divider for `d`; `None` when `d == 0`.
    #[inline]
    pub const fn new(d: u32) -> Option<Self> {
        if d == 0 {
            return None;
        }
        let m = if d == 1 { 0 } else { u64::MAX / d as u64 + 1 };
        Some(DivMod { d, m })
    }

    /// The divisor.
    #[inline]
    pub const fn divisor(&self) -> u32 {
        self.d
    }

    /// `(n / d, n % d)`.
    #[inline]
    pub const fn div_rem(&self, n: u32) -> (u32, u32) {
        if self.d == 1 {
            return (n, 0);
        }
        let q = ((self.m as u128 * n as u128) >> 64) as u32;
        (q, n - q * self.d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn divmod_matches_hardware_division() {
        let divisors = [
            1u32,
            2,
            3,
            7,
            10,
            255,
            256,
            257,
            65535,
            65536,
            1 << 31,
            u32::MAX,
        ];
        let numerators = [
            0u32,
            1,
            2,
            3,
            99,
            1000,
            65535,
            1 << 20,
            u32::MAX - 1,
            u32::MAX,
        ];
        for &d in &divisors {
            let dm = DivMod::new(d).unwrap();
            for &n in &numerators {
                assert_eq!(dm.div_rem(n), (n / d, n % d), "{n} / {d}");
            }
            let mut x = 12345u64;
            for _ in 0..1000 {
                x = mix64(x);
                let n = x as u32;
                assert_eq!(dm.div_rem(n), (n / d, n % d), "{n} / {d}");
            }
        }
        assert!(DivMod::new(0).is_none());
    }

    #[test]
    fn permutation_matches_reference_formula() {
        // Kensler's original ends with `(i + p) % l`; ours with a precomputed offset.
        for l in [1u32, 2, 3, 5, 16, 17, 100, 1000] {
            for p in [0u32, 1, 0xdead_beef, u32::MAX] {
                let perm = Permutation::new(l, p).unwrap();
                for i in 0..l {
                    let v = perm.apply(i);
                    assert!(v < l);
                    assert_eq!(v, permute(i, l, p));
                    let j = (i + 1) % l;
                    assert_eq!(perm.apply2([i, j]), [v, perm.apply(j)]);
                    let dm = DivMod::new(l).unwrap();
                    assert_eq!(Permutation::with_divider(&dm, p), perm);
                }
            }
        }
    }

    #[test]
    fn permute_never_hangs_out_of_range() {
        assert_eq!(permute(5, 0, 7), 0);
        for i in [3u32, 100, u32::MAX] {
            assert!(permute(i, 3, 9) < 3);
        }
    }
}
