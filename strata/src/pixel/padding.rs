//! How the samples of two draws meet: the padding's reorderings of a pixel's sample index.
//!
//! A draw reads its sequence at a *padded* index: the pixel's sample index reordered per draw,
//! so that sample `i` of one draw meets sample `i` of another as chance would pair them, while
//! every power-of-two prefix of every draw keeps the samples it had (and so stays the net it
//! was). Everything here is 32-bit integer arithmetic and two tables, the same on a GPU.
//!
//! # The shells
//!
//! The indices `[2^j, 2^(j+1))` (a *shell*; index 0 and index 1 each alone) are reordered by
//! a random affine map `u -> a u + b` over the field GF(2^j), `a != 0`, drawn per pixel, draw
//! and shell. The affine maps of a field are sharply 2-transitive: for any two samples of a
//! shell, their two places after the map are a uniformly random pair of distinct places, so
//! two draws (each with its own map) meet pair by pair as under independent uniform
//! permutations of the shell, and the second moments of everything two draws compute together
//! are those of uniform padding. Every power-of-two prefix `[0, 2^m)` is a union of whole
//! shells, so it keeps its samples: a net stays a net at every count, without knowing the
//! count. Different shells take independent maps (one hash of the pixel, the draw and the
//! shell), so samples of different shells also meet as chance pairs them.
//!
//! Positions and field elements are related through logarithms: the position `x` of a sample
//! in its shell stands for `g^x` (`g` a root of a primitive polynomial of degree `j`, so its
//! powers are every nonzero element), the last position `2^j - 1` for zero, and the map's
//! result `v` goes to the position `log_g v` (zero to the last). With `a = g^r`, the whole map
//! is `x -> log(g^((x + r) mod (2^j - 1)) + b)`: two table lookups ([`EXP`] and [`LOG`], 64 Ki
//! entries of 16 bits each, every `j <= 15`, built at compile time from the polynomials of
//! [`PRIMITIVE`]), an addition and an XOR. Reading positions as logarithms is a fixed bijection
//! on each side of the family, which keeps it sharply 2-transitive, and it matters: read as the
//! field elements' bits, two draws' places would be related by a multiplication over GF(2^j), a
//! binary matrix, so that their coarse strata are tied whenever that matrix has a deficient
//! rank on the coarse digits (the conformance suite's chi-square of two draws fails in one case
//! of ten); the discrete logarithm makes the relation between two draws' places nonlinear. `r`
//! is drawn in `[0, 2^j - 1)` by a multiply-high of a 32-bit hash (a bias below `2^-16`), `b`
//! from the hash's other bits.
//!
//! Shells from `2^16` on (`j >= 16`) are reordered by a nested scramble of the position
//! ([`crate::scramble`]'s Owen hash, keyed per pixel, draw and shell): still a bijection of the
//! shell, so prefixes keep their nets, but two draws are then paired as under
//! [`Padding::Nested`](super::Padding::Nested) inside those shells.
//!
//! # Uniform blocks
//!
//! [`Padding::Uniform`](super::Padding::Uniform) maps each aligned block of `B` samples
//! (`B = 2^k`, `k <= 15`) by the same kind of map over GF(2^k), keyed per pixel, draw and
//! block: the whole block is reordered, as pbrt-v4's padded Sobol' reorders a pixel's samples,
//! and only whole blocks keep their nets.

use crate::hash::hash32;
use crate::scramble::owen_scramble_rev;

/// The largest field of the tables: GF(2^15). Shells and blocks above it are reordered by a
/// nested scramble (shells) or kept (blocks).
pub(crate) const MAX_FIELD_BITS: u32 = 15;

/// Primitive polynomials of GF(2^j), `j = 0..=15`, without their `x^j` term (bit `k` the
/// coefficient of `x^k`): `x + 1`, `x^2 + x + 1`, `x^3 + x + 1`, `x^4 + x + 1`, `x^5 + x^2 + 1`,
/// `x^6 + x + 1`, `x^7 + x + 1`, `x^8 + x^4 + x^3 + x^2 + 1`, `x^9 + x^4 + 1`, `x^10 + x^3 + 1`,
/// `x^11 + x^2 + 1`, `x^12 + x^6 + x^4 + x + 1`, `x^13 + x^4 + x^3 + x + 1`,
/// `x^14 + x^10 + x^6 + x + 1`, `x^15 + x + 1` (the usual table of primitive polynomials, e.g.
/// Lidl and Niederreiter, "Finite Fields"; a test checks that each one's powers of `x` reach
/// every nonzero element, which is what primitive means).
pub(crate) const PRIMITIVE: [u32; 16] = [
    0, 0x1, 0x3, 0x3, 0x3, 0x5, 0x3, 0x3, 0x1d, 0x11, 0x9, 0x5, 0x53, 0x1b, 0x443, 0x3,
];

/// Entries of [`EXP`]: `2^j` for each `j <= 15`, and a last one (0) that makes the length a
/// power of two, so that an index masked to 16 bits needs no bounds check.
pub(crate) const TABLE_LEN: usize = 1 << (MAX_FIELD_BITS + 1);

/// The powers of the primitive element of every GF(2^j), `j <= 15`, each element's `j` bits
/// reversed and placed at the top of the 16 bits: entry `2^j - 1 + e` is `g^e`
/// (`e = 0 ..= 2^j - 1`; `g^(2^j - 1) = g^0 = 1`). Entry 0 (`j = 0`) and the last entry are 0.
pub(crate) static EXP: [u16; TABLE_LEN] = exp_table();

const fn exp_table() -> [u16; TABLE_LEN] {
    let mut t = [0u16; TABLE_LEN];
    let mut j = 1;
    while j <= MAX_FIELD_BITS {
        let m = (1u32 << j) - 1;
        let mut v = 1u32;
        let mut e = 0;
        while e <= m {
            t[(m + e) as usize] = (v.reverse_bits() >> 16) as u16;
            v <<= 1;
            if v >> j & 1 == 1 {
                v ^= (1 << j) | PRIMITIVE[j as usize];
            }
            e += 1;
        }
        j += 1;
    }
    t
}

/// `floor(t m / 2^32)` for `m < 2^16`: a value in `[0, m)` drawn by the hash `t`. The shader
/// computes it from 16-bit halves (`((t >> 16) m + ((t & 0xffff) m >> 16)) >> 16`), which is
/// the same number (a test checks it).
#[inline(always)]
fn below(t: u32, m: u32) -> u32 {
    ((t as u64 * m as u64) >> 32) as u32
}

/// The parameters of the affine map of a shell or block of `m + 1 = 2^j` places (`j <= 15`,
/// `top` its `j` top bits) keyed by the hash `t`, in one word: `r` in `[0, m)` in the low 16
/// bits, drawn from `t` rotated (a multiply-high, mostly of its bits `16 - j .. 16`), and `b`,
/// the top `j` bits of `t`, in place (bits `32 - j ..`, above `r`'s: `rb & top` is `b`).
#[inline(always)]
fn affine_keys(t: u32, m: u32, top: u32) -> u32 {
    (t & top) | below(t.rotate_left(16), m)
}

/// The affine map of the [module docs](self) with the parameters `rb` ([`affine_keys`]) on the
/// position `x` of a shell or block of `m + 1 = 2^j` places, in the bit-reversed domain: the
/// field element `g^((x + r) mod m) + b` (or `b` at `x = m`, whose `g^x` stands for zero:
/// `live` is 0 there, else `top`).
#[inline(always)]
fn affine(rb: u32, x: u32, m: u32, live: u32, top: u32) -> u32 {
    let e = x + (rb & 0xffff);
    let e = if e >= m { e - m } else { e };
    ((EXP[((m + e) & 0xffff) as usize] as u32) << 16 & live) ^ (rb & top)
}

/// The draw's nonlinear reordering of its shell or block after the affine map, in the
/// bit-reversed domain: one round of the Owen hash ([`owen_scramble_rev`]) keyed by the draw's
/// `key`, kept to the positions (`top`): every position bit flipped by a function of the bits
/// below it (the index's higher bits, the shell's top bit included), a nested bijection of
/// the shell or block.
///
/// The affine maps alone pair two draws *linearly*: a sample's places in two draws are related
/// by a multiplication over GF(2^j), so that the two draws' coarse strata are tied through a
/// binary matrix, whose rank on the coarse digits is often deficient (the conformance suite's
/// chi-square of two draws fails in one case of ten). Neither a fixed nonlinear relabelling
/// (the discrete logarithm, a fixed random permutation: two draws' pairing is then a conjugate
/// of an affine map, with its cycle structure) nor one or two keyed multiplies per draw pass
/// the pair study at every seed on `sobol`, whose first coordinate is the index itself; this
/// round keeps every seed's largest statistic near 1130 (the bound is 1400; the nested shuffle
/// alone, 1266), and keeps the pairs uniform (a bijection after a sharply 2-transitive family,
/// keyed apart from it).
#[inline(always)]
fn mix(v: u32, top: u32, key: u32) -> u32 {
    owen_scramble_rev(v, key) & top
}

/// Salt of the shells' keys per shell.
const SHELL: u32 = crate::hash::GOLDEN_GAMMA_32;

/// What the shell padding needs of a sample index, computed once per pixel sample (every draw
/// of the sample reorders the same shell): [`Shell::map_rev`] is then a hash, a table lookup
/// and a round of the Owen hash per draw. The hash's part ([`Shell::keys`]) depends on the
/// pixel, the shell and the draw only, so the samples of one shell of a pixel may share it
/// ([`Shell::mixed`]): the sampler keeps it per draw while the pixel and the shell stay.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Shell {
    /// The pixel's padding key, mixed with the shell.
    salt: u32,
    /// The position inside the shell.
    x: u32,
    /// `2^j - 1`: the shell is `[2^j, 2^(j+1))` (0 for the indices 0 and 1).
    m: u32,
    /// The top `j` bits, or 0 when the position stands for the field's zero (`x = m`).
    live: u32,
    /// The top `j` bits (the position's, bit-reversed).
    top: u32,
    /// The index's top bit, reversed (0 for index 0).
    marker: u32,
    /// From `2^16` on (`j > 15`, past the tables): [`Shell::nested_rev`] reorders the shell.
    nested: bool,
}

impl Shell {
    /// The shell of `index`, for the pixel whose padding key is `key`.
    #[inline]
    pub(crate) fn new(index: u32, key: u32) -> Self {
        let j = 31 - (index | 1).leading_zeros();
        let m = ((1u64 << j) - 1) as u32;
        let x = index & m;
        let top = !(u32::MAX >> j);
        Shell {
            salt: key ^ j.wrapping_mul(SHELL),
            x,
            m,
            live: if x == m { 0 } else { top },
            top,
            marker: if index == 0 { 0 } else { 0x8000_0000 >> j },
            nested: j > MAX_FIELD_BITS,
        }
    }

    /// The padded index of the draw at `dim`, bit-reversed: the sample's position inside its
    /// shell mapped by the draw's map.
    #[inline(always)]
    pub(crate) fn map_rev(&self, dim: u32, key: u32) -> u32 {
        if self.nested {
            return self.nested_rev(hash32(dim, self.salt));
        }
        self.mixed(self.keys(dim), key)
    }

    /// The parameters of the affine map of the draw at `dim` on this shell (below `2^16`: not
    /// [`nested`](Self::nested)), the same for every sample of the shell in the pixel.
    #[inline(always)]
    pub(crate) fn keys(&self, dim: u32) -> u32 {
        affine_keys(hash32(dim, self.salt), self.m, self.top)
    }

    /// [`map_rev`](Self::map_rev) from the draw's [`keys`](Self::keys) (below `2^16`).
    #[inline(always)]
    pub(crate) fn mixed(&self, keys: u32, key: u32) -> u32 {
        self.marker
            | mix(
                affine(keys, self.x, self.m, self.live, self.top),
                self.top,
                key,
            )
    }

    /// Whether the shell is past the tables (from `2^16` on), where the draws' maps are nested
    /// scrambles.
    #[inline(always)]
    pub(crate) fn nested(&self) -> bool {
        self.nested
    }

    /// Whether `other` is a shell of the same size (with the same pixel's key: the same
    /// [`keys`](Self::keys) for every draw).
    #[inline(always)]
    pub(crate) fn same_size(&self, other: &Shell) -> bool {
        self.m == other.m
    }

    /// [`map_rev`](Self::map_rev) without the mix (the affine map alone), for the Z-ordered
    /// sequences, whose global index is then shuffled as a whole by the nested shuffle (see the
    /// sampler): it brings the nonlinearity, and it moves samples 0 and 1 of a pixel's block too
    /// (which every shell keeps), without which they would sit in the same strata in every
    /// pixel under the image's shared value scramble (a red error).
    #[inline(always)]
    pub(crate) fn affine_rev(&self, dim: u32) -> u32 {
        if self.nested {
            return self.nested_rev(hash32(dim, self.salt));
        }
        self.affine_keyed(self.keys(dim))
    }

    /// [`affine_rev`](Self::affine_rev) from the draw's [`keys`](Self::keys) (below `2^16`).
    #[inline(always)]
    pub(crate) fn affine_keyed(&self, keys: u32) -> u32 {
        self.marker | affine(keys, self.x, self.m, self.live, self.top)
    }

    /// Shells from `2^16` on: the position nested-scrambled (the reversed domain's Owen hash
    /// flips each bit of the position by the bits above it, the index's top bit included, and
    /// the bits above are put back).
    #[cold]
    fn nested_rev(&self, t: u32) -> u32 {
        let marker = (self.m + 1).reverse_bits();
        let index_rev = marker | self.x.reverse_bits();
        (owen_scramble_rev(index_rev, t) & self.top) | marker
    }
}

/// Salt of the uniform blocks' keys.
const BLOCK: u32 = 0x7061_6431;

/// [`Padding::Uniform`](super::Padding::Uniform): the index's position inside its aligned
/// block of `2^bits` samples mapped by the map of its pixel (`key`), draw (`dim`) and block,
/// bit-reversed. Blocks of one sample or of more than `2^15` keep their order.
#[inline]
pub(crate) fn uniform_rev(index: u32, bits: u32, key: u32, dim: u32, mix_key: u32) -> u32 {
    if bits == 0 || bits > MAX_FIELD_BITS {
        return index.reverse_bits();
    }
    let m = (1u32 << bits) - 1;
    let x = index & m;
    let top = !(u32::MAX >> bits);
    let t = hash32(dim, hash32(index >> bits, key ^ BLOCK ^ bits));
    let live = if x == m { 0 } else { top };
    (index & !m).reverse_bits()
        | mix(
            affine(affine_keys(t, m, top), x, m, live, top),
            top,
            mix_key,
        )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::mix64;

    #[test]
    fn every_polynomial_is_primitive_and_the_table_its_powers() {
        for j in 1..=MAX_FIELD_BITS {
            let m = (1u32 << j) - 1;
            let mut seen = vec![false; 1 << j];
            for e in 0..m {
                let v = (EXP[(m + e) as usize] >> (16 - j)) as u32;
                assert!(v != 0 && !seen[v as usize], "j {j}: g^{e} repeats");
                seen[v as usize] = true;
            }
            assert_eq!(EXP[(2 * m) as usize], EXP[m as usize], "j {j}: g^m = 1");
            // g^1 is x itself: bit 1, reversed to bit 14 of the 16
            if j >= 2 {
                assert_eq!(EXP[(m + 1) as usize], 1 << 14, "j {j}");
            }
        }
        assert_eq!(EXP[0], 0);
    }

    #[test]
    fn the_multiply_high_is_the_shaders_16_bit_form() {
        let mut h = 3u64;
        for m in (0..1u32 << 16).step_by(7).chain([0xffff, 1, 2]) {
            for _ in 0..8 {
                h = mix64(h);
                let t = h as u32;
                let gpu = ((t >> 16) * m + (((t & 0xffff) * m) >> 16)) >> 16;
                assert_eq!(below(t, m), gpu, "t {t:#x} m {m}");
                assert!(m == 0 || below(t, m) < m);
            }
        }
    }

    #[test]
    fn every_shell_is_a_bijection_onto_itself() {
        for key in [0u32, 7, 0x9e37_79b9] {
            for dim in [0u32, 3, 1000] {
                let n = 1u32 << 17;
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let p = Shell::new(i, key).map_rev(dim, key ^ dim).reverse_bits();
                    // same shell (the same highest bit; 0 stays 0)
                    assert_eq!(p.checked_ilog2(), i.checked_ilog2(), "{i} -> {p}");
                    assert!(!seen[p as usize], "{p} twice");
                    seen[p as usize] = true;
                }
            }
        }
        // and near the top of the index range
        for i in [u32::MAX, u32::MAX - 1, 1 << 31, (1 << 31) + 5] {
            assert_eq!(
                Shell::new(i, 9).map_rev(4, 77).reverse_bits().ilog2(),
                i.ilog2()
            );
        }
    }

    #[test]
    fn two_samples_of_a_shell_go_to_every_pair_of_positions_equally_often() {
        // sharply 2-transitive: over keys, the images of two positions of a shell are a
        // uniform pair of distinct positions (chi-square, false alarm below 1e-6)
        for (j, pair) in [(2u32, [0u32, 3]), (3, [1, 2]), (3, [0, 7]), (5, [4, 17])] {
            let n = 1u32 << j;
            let cells = (n * (n - 1)) as usize;
            let mut counts = vec![0u32; cells];
            let trials = 300 * cells as u32;
            for key in 0..trials {
                let k = mix64(key as u64) as u32;
                let [a, b] = pair.map(|x| Shell::new(n + x, k).map_rev(5, !k).reverse_bits() - n);
                assert_ne!(a, b);
                counts[(a * (n - 1) + if b > a { b - 1 } else { b }) as usize] += 1;
            }
            let e = trials as f64 / cells as f64;
            let chi2: f64 = counts.iter().map(|&c| (c as f64 - e).powi(2) / e).sum();
            let df = (cells - 1) as f64;
            assert!(
                chi2 < df + 6.0 * (2.0 * df).sqrt() + 10.0,
                "j {j} {pair:?}: chi2 {chi2} df {df}"
            );
        }
    }

    #[test]
    fn uniform_blocks_are_bijections_of_each_block() {
        for bits in [1u32, 2, 4, 7] {
            let n = 1u32 << bits;
            for block in [0u32, 3] {
                let mut seen = std::collections::HashSet::new();
                for i in 0..n {
                    let j = uniform_rev(block * n + i, bits, 77, 3, 99).reverse_bits();
                    assert_eq!(j / n, block);
                    assert!(seen.insert(j));
                }
            }
        }
        assert_eq!(uniform_rev(12345, 0, 1, 2, 3), 12345u32.reverse_bits());
        assert_eq!(uniform_rev(12345, 16, 1, 2, 3), 12345u32.reverse_bits());
    }
}
