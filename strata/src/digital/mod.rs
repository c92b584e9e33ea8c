//! The generator matrices of the base-2 digital sequences, and their tables: one home.
//!
//! A base-2 digital sequence computes dimension `d` of point `i` as `C_d bits(i)` over GF(2):
//! each set bit `k` of the index XORs in column `k` of the generator matrix. Here a matrix is
//! 32 columns, column `k` for index bit `k`, each a 32-bit fixed-point value with
//! the first digit in the most significant bit.
//!
//! * **Sobol'** (Sobol', "On the distribution of points in a cube and the approximate
//!   evaluation of integrals", 1967): dimension 0 is van der Corput (the identity), dimension 1
//!   the Pascal matrix mod 2 (polynomial `x + 1`); together a (0,2)-sequence. Dimensions
//!   1..1000 from Joe and Kuo's direction numbers (S. Joe and F. Y. Kuo, "Constructing Sobol
//!   sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30, 2008): their
//!   file `new-joe-kuo-6.1000`, kept verbatim beside this module with its BSD licence
//!   (`LICENSE-new-joe-kuo-6`, Copyright (c) 2008 Frances Y. Kuo and Stephen Joe), turned into
//!   matrices at compile time by the standard recurrence (Bratley and Fox 1988).
//! * **(1,2)-Sobol'** (N. Bonneel, D. Coeurjolly, J.-C. Iehl, V. Ostromoukhov, "Sobol'
//!   Sequences with Guaranteed-Quality 2D Projections", ACM TOG 44(4), 2025): a Sobol'
//!   sequence of 692 dimensions whose pairs of dimensions `(2k, 2k+1)` are all
//!   (1,2)-sequences (pair 0, the identity and Pascal, a (0,2)-sequence), where Joe and Kuo's
//!   pairs have `t` from 3 to 12. Its initial direction numbers, derived from the matrices of
//!   UTK's `SamplerOneTwoSobol.hpp` (BSD licence), are kept beside this module in Joe and Kuo's
//!   layout (`new-one-two-sobol.692`, provenance and licence in `LICENSE-one-two-sobol`) and
//!   turned into matrices at compile time by the same recurrence. Its polynomials are
//!   irreducible and distinct, not all primitive (429 of 691 are), which is what a digital
//!   sequence needs; 308 have degree 32, the most the recurrence takes.
//! * **pmj02** as a digital sequence: the generator matrices behind Helmer, Christensen and
//!   Kensler's stochastic pmj02 ("Stochastic Generation of (t, s) Sample Sequences", EGSR 2021),
//!   the unsigned Stirling numbers of the first kind mod 2 (x: `C[r][c] = s(c, r)`, y:
//!   `s(c + 1, r + 1)`), also a (0,2)-sequence. Owen-scrambled, its points are distributed as
//!   the stochastic pmj02 sequence, whose partner offsets are read off the inverse matrices.
//!
//! Evaluation is by byte tables in the bit-reversed domain (four 256-entry tables per
//! dimension, one per byte of the reversed index: the index shuffle of [`crate::scramble`]
//! leaves its result reversed, and the Owen scramble wants the value reversed, so neither side
//! reverses). The WGSL shader computes dimensions 0-1 of both sequences instead by a handful
//! of shifts and XORs from the plain index, since a table would be per-thread memory; the
//! tests carry that form in Rust (`sobol01_rev`, `pmj02_rev`) and check it against the tables.

use crate::prelude::*;

/// A generator matrix: column `k` (for index bit `k`) as a 32-bit fixed-point value, first
/// digit in the most significant bit.
pub(crate) type Matrix = [u32; 32];

/// The four byte tables of one matrix in the bit-reversed domain: table `q` maps byte `q` of the
/// reversed index to the XOR of the reversed columns of its bits.
pub(crate) type ByteTables = [[u32; 256]; 4];

/// The generator matrices of Sobol' dimensions 0 (van der Corput) and 1 (Pascal mod 2).
pub(crate) const fn sobol01_matrices() -> [Matrix; 2] {
    let mut vdc = [0u32; 32];
    let mut pascal = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        vdc[k] = 1 << (31 - k);
        // Pascal mod 2: column k has digit r for r <= k with binom(k, r) odd (r a submask of k)
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

/// Bits of the Stirling numbers of the first kind mod 2: `s(n, k)` is bit `k` of row `n`,
/// from `s(n, k) = s(n-1, k-1) + (n-1) s(n-1, k)`.
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

/// The generator matrix of pmj02 dimension `dim` (0 = x, 1 = y): `C[r][c] = s(c + dim, r + dim)
/// mod 2`, as columns of bits (`col[c] >> r & 1`, digit `r` counted from the top).
const fn pmj02_columns(dim: usize) -> [u64; 32] {
    let s = stirling_first_mod2::<33>();
    let mut cols = [0u64; 32];
    let mut c = 0;
    while c < 32 {
        let mut r = 0;
        while r < 32 {
            if (s[c + dim] >> (r + dim)) & 1 == 1 {
                cols[c] |= 1 << r;
            }
            r += 1;
        }
        c += 1;
    }
    cols
}

/// The generator matrices of pmj02's two dimensions.
pub(crate) const fn pmj02_matrices() -> [Matrix; 2] {
    let mut out = [[0u32; 32]; 2];
    let mut d = 0;
    while d < 2 {
        let cols = pmj02_columns(d);
        let mut k = 0;
        while k < 32 {
            out[d][k] = (cols[k] as u32).reverse_bits(); // digit r (LSB-first) -> bit 31 - r
            k += 1;
        }
        d += 1;
    }
    out
}

/// The inverse over GF(2) of an upper unit-triangular matrix given by columns of bits, by back
/// substitution: column `c` of the inverse is the `v` with `C v = e_c`.
const fn inverse_upper(cols: [u64; 32]) -> [u64; 32] {
    let mut inv = [0u64; 32];
    let mut c = 0;
    while c < 32 {
        // v_r = [r == c] + sum_{r < t <= c} C[r][t] v_t, from the bottom row up
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

/// `XOR_d[k]` of the stochastic pmj02 construction (Helmer et al. 2021): sample `2^k + i` takes
/// the first `k` digits of sample `i ^ XOR_d[k]` and flips digit `k + 1`. Samples `2^k + i` and
/// `j` agree in their first `k` digits and differ in digit `k` exactly when `bits(i ^ j)` is
/// column `k` of `C^-1` without its diagonal, so the values are read off the inverse.
pub(crate) const PMJ02_XORS: [[u32; 32]; 2] = {
    let mut out = [[0u32; 32]; 2];
    let mut d = 0;
    while d < 2 {
        let inv = inverse_upper(pmj02_columns(d));
        let mut k = 0;
        while k < 32 {
            out[d][k] = (inv[k] & !(1u64 << k)) as u32;
            k += 1;
        }
        d += 1;
    }
    out
};

/// The byte tables of one generator matrix (see [`ByteTables`]).
pub(crate) const fn byte_tables(m: &Matrix) -> ByteTables {
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

/// The point of a digital sequence at a bit-reversed index, bit-reversed, from its byte tables.
#[inline(always)]
pub(crate) fn lookup(t: &ByteTables, index_rev: u32) -> u32 {
    let high = t[2][((index_rev >> 16) & 0xff) as usize] ^ t[3][(index_rev >> 24) as usize];
    // an index below 2^16 (every prefix the padding keeps in place) has no low reversed bytes
    if index_rev & 0xffff == 0 {
        return high;
    }
    high ^ t[0][(index_rev & 0xff) as usize] ^ t[1][((index_rev >> 8) & 0xff) as usize]
}

/// The byte tables of two dimensions interleaved, so that one lookup per byte gives both (the
/// 2D draws of the path-tracer adapter read them).
pub(crate) struct PairTables([[[u32; 2]; 256]; 4]);

impl core::fmt::Debug for PairTables {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("PairTables { .. }")
    }
}

impl PairTables {
    /// The interleaved tables of two matrices.
    const fn new(m: &[Matrix; 2]) -> Self {
        let (a, b) = (byte_tables(&m[0]), byte_tables(&m[1]));
        let mut t = [[[0u32; 2]; 256]; 4];
        let mut q = 0;
        while q < 4 {
            let mut v = 0;
            while v < 256 {
                t[q][v] = [a[q][v], b[q][v]];
                v += 1;
            }
            q += 1;
        }
        PairTables(t)
    }

    /// Both dimensions at a bit-reversed index, both bit-reversed.
    #[inline(always)]
    pub(crate) fn point_rev(&self, index_rev: u32) -> [u32; 2] {
        let t = &self.0;
        let (c, d) = (
            t[2][((index_rev >> 16) & 0xff) as usize],
            t[3][(index_rev >> 24) as usize],
        );
        let high = [c[0] ^ d[0], c[1] ^ d[1]];
        // an index below 2^16 (every prefix the padding keeps in place) has no low reversed
        // bytes
        if index_rev & 0xffff == 0 {
            return high;
        }
        let (a, b) = (
            t[0][(index_rev & 0xff) as usize],
            t[1][((index_rev >> 8) & 0xff) as usize],
        );
        [high[0] ^ a[0] ^ b[0], high[1] ^ a[1] ^ b[1]]
    }
}

/// Product in GF(4) = GF(2)[w] / (w^2 + w + 1), elements as 2-bit integers (bit 0 the
/// coefficient of 1, bit 1 that of `w`).
const fn gf4_mul(a: u32, b: u32) -> u32 {
    // (a0 + a1 w)(b0 + b1 w) = a0 b0 + (a0 b1 + a1 b0) w + a1 b1 (w + 1)
    let (a0, a1, b0, b1) = (a & 1, a >> 1, b & 1, b >> 1);
    let one = (a0 & b0) ^ (a1 & b1);
    let w = (a0 & b1) ^ (a1 & b0) ^ (a1 & b1);
    one | (w << 1)
}

/// The binary generator matrices of the first four dimensions of Faure's (0,4)-sequence in base
/// 4, then a fifth (Sobol' dimension 4): see [`FAURE4`].
///
/// Base-4 dimension `j` has the generator matrix `C_j[r][c] = binom(c, r) a_j^(c - r)` over
/// GF(4) with `a_j = j` (0, 1, `w`, `w^2`; `0^0 = 1`): Faure, "Discrépance de suites associées à
/// un système de numération (en dimension s)", Acta Arith. 41 (1982). Index digit `c` of base 4
/// is index bits `2c` (the coefficient of 1) and `2c + 1` (of `w`); output digit `r` of base 4
/// is the element `x_r` mapped by a per-dimension `L_j` of GL(2, GF(2)), its two bits the binary
/// digits `2r` (high) and `2r + 1` (low). `L_j` maps the bits `(x0, x1)` of `x_r` to the low
/// and high bits: `(x1, x0)` in dimensions 0 and 2, `(x0, x0 + x1)` in dimensions 1 and 3.
/// These are the choices that make dimensions 0-1 and 2-3 binary (0,2)-sequences too (a
/// digit-wise bijection keeps every base-4 t-value).
pub(crate) const fn faure4_matrices() -> [Matrix; 5] {
    let mut out = [[0u32; 32]; 5];
    let mut j = 0;
    while j < 4 {
        let a = j as u32;
        let mut c = 0; // index digit
        while c < 16 {
            let mut r = 0; // output digit
            while r <= c {
                // binom(c, r) mod 2, times a^(c - r)
                if (c & r) == r {
                    let mut e = 1u32;
                    let mut k = 0;
                    while k < c - r {
                        e = gf4_mul(e, a);
                        k += 1;
                    }
                    // index bit 2c is the element 1, bit 2c + 1 the element w
                    let mut h = 0;
                    while h < 2 {
                        let x = gf4_mul(e, 1 << h);
                        let (x0, x1) = (x & 1, x >> 1);
                        let (lo, hi) = if j % 2 == 0 { (x1, x0) } else { (x0, x0 ^ x1) };
                        out[j][2 * c + h] |= (hi << (31 - 2 * r)) | (lo << (30 - 2 * r));
                        h += 1;
                    }
                }
                r += 1;
            }
            c += 1;
        }
        j += 1;
    }
    // Sobol' dimension 4 (Joe-Kuo: degree 3, a = 2, m = 1, 1, 1), the Joe-Kuo dimension with
    // the smallest worst t-value against the four (5, over m = 1..32)
    out[4] = direction_matrix(3, 2, &[1, 1, 1]);
    out
}

/// The binary form of Faure's (0,4)-sequence in base 4 (see [`faure4_matrices`]), byte
/// tables: dimensions 0-3, every aligned block of `4^k` points a (0,k,4)-net in base 4, and
/// dimensions 0-1 and 2-3 binary (0,2)-sequences (dimension 0 is van der Corput), the other
/// pairs of the four `t <= 1` at `4^k` points (`t <= 2` at the odd powers of two); dimension
/// 4, Sobol' dimension 4, is the partner of a 2D draw at dimension 3 (`t` up to 5 against each
/// of the four). What `zquad` reads.
pub(crate) static FAURE4: [ByteTables; 5] = {
    let m = faure4_matrices();
    [
        byte_tables(&m[0]),
        byte_tables(&m[1]),
        byte_tables(&m[2]),
        byte_tables(&m[3]),
        byte_tables(&m[4]),
    ]
};

/// Sobol' dimensions 0-1, interleaved byte tables (built at compile time: no lazy
/// initialisation on the draw path).
pub(crate) static SOBOL01: PairTables = PairTables::new(&sobol01_matrices());

/// pmj02's dimensions, interleaved byte tables.
pub(crate) static PMJ02: PairTables = PairTables::new(&pmj02_matrices());

/// Sobol' dimensions 0 and 1 of point `index` (the plain index, not reversed), both
/// bit-reversed, computed without tables: dimension 0 (van der Corput) reversed is the index
/// itself; dimension 1 (Pascal mod 2: digit `r` is the XOR of the index bits `c` with `r` a
/// submask of `c`) is the superset-sum transform, five shift-mask-XOR steps.
#[cfg(test)]
#[inline]
pub(crate) const fn sobol01_rev(index: u32) -> [u32; 2] {
    let mut y = index;
    y ^= (y >> 1) & 0x5555_5555;
    y ^= (y >> 2) & 0x3333_3333;
    y ^= (y >> 4) & 0x0f0f_0f0f;
    y ^= (y >> 8) & 0x00ff_00ff;
    y ^= (y >> 16) & 0x0000_ffff;
    [index, y]
}

/// pmj02's two dimensions of point `index` (plain), both bit-reversed, without tables.
///
/// With `s(n, k) = binom(floor(n / 2), k - ceil(n / 2)) mod 2` (the Stirling numbers of the
/// first kind mod 2), digit `r` of `x` is the coefficient of `t^r` in `U(t + t^2) + t V(t +
/// t^2)`, where `U` and `V` are the polynomials whose coefficients are the even and the odd
/// index bits; `y` is `U(t + t^2) + (1 + t) V(t + t^2)`. Substituting `t + t^2` is four
/// shift-mask-XOR steps on the spread bits.
#[cfg(test)]
#[inline]
pub(crate) const fn pmj02_rev(index: u32) -> [u32; 2] {
    let u = substitute(index & 0x5555_5555);
    let v = substitute((index >> 1) & 0x5555_5555);
    let x = u ^ (v << 1);
    [x, x ^ v]
}

#[cfg(test)]
/// `W(t + t^2)` over GF(2) for `W(t) = sum_a w_a t^a`, `w_a` at bit `2a` (`a < 16`), as
/// coefficients by bit. Bottom-up doubling: blocks of `2^(k+1)` bits hold the results for
/// `2^k` coefficients; merging two blocks adds `(t^(2^k) + t^(2^(k+1))) P_hi`, and `P_hi` already
/// sits at `t^(2^(k+1))`, so only `P_hi >> 2^k` is added.
const fn substitute(mut w: u32) -> u32 {
    w ^= (w & 0xcccc_cccc) >> 1;
    w ^= (w & 0xf0f0_f0f0) >> 2;
    w ^= (w & 0xff00_ff00) >> 4;
    w ^= (w & 0xffff_0000) >> 8;
    w
}

/// The matrix of a Sobol' dimension with primitive polynomial of degree `s`, inner
/// coefficients `a` (bit `s - 1 - l` is `a_l`) and initial direction integers `m` (odd, `m_k <
/// 2^k`), by the recurrence `V_k = V_{k-s} ^ (V_{k-s} >> s) ^ sum_{l=1}^{s-1} a_l V_{k-l}`.
pub(crate) const fn direction_matrix(s: usize, a: u32, m: &[u32]) -> Matrix {
    let mut v = [0u32; 33]; // 1-based
    let mut k = 1;
    while k <= 32 {
        if k <= s {
            v[k] = m[k - 1] << (32 - k);
        } else {
            let mut x = v[k - s] ^ (v[k - s] >> s);
            let mut l = 1;
            while l < s {
                if (a >> (s - 1 - l)) & 1 == 1 {
                    x ^= v[k - l];
                }
                l += 1;
            }
            v[k] = x;
        }
        k += 1;
    }
    let mut out = [0u32; 32];
    let mut c = 0;
    while c < 32 {
        out[c] = v[c + 1];
        c += 1;
    }
    out
}

/// Sobol' dimensions 0 and 1, byte tables (built at compile time).
static SOBOL_FIRST: [ByteTables; 2] = {
    let m = sobol01_matrices();
    [byte_tables(&m[0]), byte_tables(&m[1])]
};

/// The number of Sobol' dimensions: dimension 0 (van der Corput) and the 999 of Joe and Kuo's
/// `new-joe-kuo-6.1000`.
pub(crate) const SOBOL_DIMENSIONS: u32 = 1000;

/// Joe and Kuo's primitive polynomials and initial direction numbers for Sobol' dimensions
/// 1..1000, as they publish them (`new-joe-kuo-6.1000`, the first 1000 lines of
/// `new-joe-kuo-6.21201`; BSD licence, `LICENSE-new-joe-kuo-6` beside it): a header line, then
/// one line per dimension, `d s a m_1 .. m_s`, our dimension `d - 1`.
const JOE_KUO: &str = include_str!("new-joe-kuo-6.1000");

/// The generator matrices of every Sobol' dimension, built at compile time from [`JOE_KUO`]
/// by the standard recurrence ([`direction_matrix`]): 128 KiB, no lazy initialisation.
pub(crate) static SOBOL: [Matrix; SOBOL_DIMENSIONS as usize] = parse_joe_kuo(JOE_KUO.as_bytes());

/// The nibble tables of Sobol''s first [`NIBBLE_DIMENSIONS`] dimensions.
pub(crate) static SOBOL_NIBBLES: [NibbleTables; NIBBLE_DIMENSIONS] = first_nibbles(&SOBOL);

/// The next whole number in `text` at or after `*at` (skipping spaces, tabs and line ends),
/// and whether it ended its line.
const fn next_number(text: &[u8], at: &mut usize) -> (u32, bool) {
    while *at < text.len() && matches!(text[*at], b' ' | b'\t' | b'\r' | b'\n') {
        *at += 1;
    }
    let mut n = 0u32;
    let mut digits = 0;
    while *at < text.len() && text[*at].is_ascii_digit() {
        n = n * 10 + (text[*at] - b'0') as u32;
        *at += 1;
        digits += 1;
    }
    assert!(digits > 0, "new-joe-kuo-6: a number expected");
    // the rest of the line is blank or the next number
    let mut k = *at;
    while k < text.len() && matches!(text[k], b' ' | b'\t' | b'\r') {
        k += 1;
    }
    (n, k >= text.len() || text[k] == b'\n')
}

/// Nibble tables of one generator matrix: entry `[q][v]` is the point, bit-reversed, of the
/// bit-reversed index whose nibble `q` is `v` and whose other bits are 0 (512 bytes, where byte
/// tables take 4 KiB): the samplers' tables for every dimension below [`NIBBLE_DIMENSIONS`],
/// built at compile time.
pub(crate) type NibbleTables = [[u32; 16]; 8];

/// The dimensions of Sobol' and of (1,2)-Sobol' that have [`NibbleTables`] (32 KiB each); the
/// others are evaluated column by column.
pub(crate) const NIBBLE_DIMENSIONS: usize = 64;

/// The nibble tables of one generator matrix.
pub(crate) const fn nibble_tables(m: &Matrix) -> NibbleTables {
    let mut t = [[0u32; 16]; 8];
    let mut q = 0;
    while q < 8 {
        let mut v = 0;
        while v < 16 {
            let mut x = 0u32;
            let mut k = 0;
            while k < 4 {
                if (v >> k) & 1 == 1 {
                    // reversed-index bit 4q + k is index bit 31 - (4q + k)
                    x ^= m[31 - (4 * q + k)].reverse_bits();
                }
                k += 1;
            }
            t[q][v] = x;
            v += 1;
        }
        q += 1;
    }
    t
}

/// The nibble tables of the first [`NIBBLE_DIMENSIONS`] matrices of `m`.
const fn first_nibbles(m: &[Matrix]) -> [NibbleTables; NIBBLE_DIMENSIONS] {
    let mut t = [[[0u32; 16]; 8]; NIBBLE_DIMENSIONS];
    let mut d = 0;
    while d < NIBBLE_DIMENSIONS {
        t[d] = nibble_tables(&m[d]);
        d += 1;
    }
    t
}

/// The point of a digital sequence at a bit-reversed index, bit-reversed, from its nibble
/// tables.
#[inline(always)]
pub(crate) fn lookup_nibbles(t: &NibbleTables, index_rev: u32) -> u32 {
    let high = t[4][((index_rev >> 16) & 15) as usize]
        ^ t[5][((index_rev >> 20) & 15) as usize]
        ^ t[6][((index_rev >> 24) & 15) as usize]
        ^ t[7][(index_rev >> 28) as usize];
    // an index below 2^16 has no low reversed nibbles
    if index_rev & 0xffff == 0 {
        return high;
    }
    high ^ t[0][(index_rev & 15) as usize]
        ^ t[1][((index_rev >> 4) & 15) as usize]
        ^ t[2][((index_rev >> 8) & 15) as usize]
        ^ t[3][((index_rev >> 12) & 15) as usize]
}

/// The number of dimensions of the (1,2)-Sobol' sequence.
pub(crate) const ONE_TWO_DIMENSIONS: u32 = 692;

/// The (1,2)-Sobol' sequence's polynomials and initial direction numbers in Joe and Kuo's
/// layout (`new-one-two-sobol.692`; provenance and BSD licence in `LICENSE-one-two-sobol`
/// beside it): our dimension `d - 1`.
const ONE_TWO: &str = include_str!("new-one-two-sobol.692");

/// The generator matrices of the (1,2)-Sobol' sequence (Bonneel et al. 2025), built at compile
/// time from [`ONE_TWO`] by the standard recurrence: 87 KiB. Dimensions 0 and 1 are Sobol''s.
pub(crate) static ONE_TWO_SOBOL: [Matrix; ONE_TWO_DIMENSIONS as usize] =
    parse_joe_kuo(ONE_TWO.as_bytes());

/// The nibble tables of the (1,2)-Sobol' sequence's first [`NIBBLE_DIMENSIONS`] dimensions.
pub(crate) static ONE_TWO_NIBBLES: [NibbleTables; NIBBLE_DIMENSIONS] =
    first_nibbles(&ONE_TWO_SOBOL);

/// The Sobol' matrices of a table in Joe and Kuo's format (a header line, then `d s a m_1 ..
/// m_s` per line, `d` from 2 up), dimension 0 the identity. Checks what the recurrence
/// needs: the lines in order, `1 <= s <= 32`, `a < 2^(s-1)`, each `m_k` odd and below `2^k`.
const fn parse_joe_kuo<const N: usize>(text: &[u8]) -> [Matrix; N] {
    let mut out = [[0u32; 32]; N];
    out[0] = sobol01_matrices()[0];
    // skip the header line
    let mut at = 0;
    while at < text.len() && text[at] != b'\n' {
        at += 1;
    }
    let mut dim = 1;
    while dim < N {
        let (d, _) = next_number(text, &mut at);
        assert!(
            d as usize == dim + 1,
            "new-joe-kuo-6: the lines must be in order"
        );
        let (s, _) = next_number(text, &mut at);
        assert!(s >= 1 && s <= 32, "new-joe-kuo-6: degree out of range");
        let (a, _) = next_number(text, &mut at);
        assert!(a < 1 << (s - 1), "new-joe-kuo-6: coefficients out of range");
        let mut m = [0u32; 32];
        let mut k = 0;
        while k < s as usize {
            let (v, end) = next_number(text, &mut at);
            assert!(
                v % 2 == 1 && (v as u64) < 1u64 << (k + 1),
                "new-joe-kuo-6: m_k must be odd, < 2^k"
            );
            assert!(
                end == (k + 1 == s as usize),
                "new-joe-kuo-6: s numbers m_k per line"
            );
            m[k] = v;
            k += 1;
        }
        out[dim] = direction_matrix(s as usize, a, &m);
        dim += 1;
    }
    out
}

/// The generator matrix of Sobol' dimension `dim` (`None` from [`SOBOL_DIMENSIONS`] on).
#[inline]
#[cfg(test)]
pub(crate) fn sobol_matrix(dim: u32) -> Option<&'static Matrix> {
    SOBOL.get(dim as usize)
}

/// The byte tables of Sobol' dimensions 0 and 1 (built at compile time); `None` for the others,
/// whose tables a sampler builds from [`sobol_matrix`] when it is made.
#[inline]
pub(crate) fn sobol_first_tables(dim: u32) -> Option<&'static ByteTables> {
    SOBOL_FIRST.get(dim as usize)
}

/// `C bits(index)` for the generator matrix `m`, one column per set bit: the point of a digital
/// sequence without tables (for the stateless functions past the tabulated dimensions).
#[inline]
pub(crate) fn apply(m: &Matrix, index: u32) -> u32 {
    let (mut x, mut i, mut k) = (0u32, index, 0);
    while i != 0 {
        if i & 1 == 1 {
            x ^= m[k];
        }
        i >>= 1;
        k += 1;
    }
    x
}

/// The t-value of the first `2^m` points (`m <= 32`) of the digital sequence with generator
/// matrices `matrices` as a base-2 `(t, m, s)`-net (`s` the number of matrices): `m` minus the
/// largest strength `rho` for which, for every choice of `d_1 + ... + d_s = rho` leading digits,
/// the rows of those digits (over the first `m` index bits) are linearly independent; the same
/// for every aligned block of `2^m` points, and under any Owen scramble or nested index shuffle.
/// (Niederreiter 1992, Theorem 4.28; a digital net's t-value is its matrices' rank property.)
#[cfg(test)]
pub(crate) fn digital_t_value(matrices: &[Matrix], m: u32) -> u32 {
    digital_t_value_in(matrices, m, 1)
}

/// The t-value of the first `b^m` points of a digital sequence in base `b = 2^bits` (`bits` 1
/// or 2, `bits * m <= 32`) whose binary generator matrices are `matrices`, as a base-`b` `(t, m,
/// s)`-net: a base-4 digit is two binary digits, so a base-4 elementary interval of depth `d`
/// is a binary one of depth `2d`, and the rank criterion is the binary one over the first
/// `bits * m` index bits with the depths taken in steps of `bits` rows.
#[cfg(test)]
pub(crate) fn digital_t_value_in(matrices: &[Matrix], m: u32, bits: u32) -> u32 {
    digital_t_value_within(matrices, m, bits, u64::MAX).unwrap()
}

/// [`digital_t_value_in`] with at most `budget` rank checks (one per composition of a strength
/// into the matrices' depths; there are `C(rho + s - 1, s - 1)` at strength `rho`): `None` when
/// the answer would take more.
pub(crate) fn digital_t_value_within(
    matrices: &[Matrix],
    m: u32,
    bits: u32,
    budget: u64,
) -> Option<u32> {
    let index_bits = (m * bits) as usize;
    // row r (digit 2^-(r+1)) of matrix j over index bits 0..m bits, as a word
    let row = |j: usize, r: usize| -> u32 {
        (0..index_bits).fold(0u32, |w, i| w | ((matrices[j][i] >> (31 - r)) & 1) << i)
    };
    let independent = |rows: &[u32]| -> bool {
        // Gaussian elimination over GF(2): each row must keep a pivot (leading bit) of its own
        let mut basis = [0u32; 32];
        rows.iter().all(|&r| {
            let mut x = r;
            while x != 0 {
                let lead = (31 - x.leading_zeros()) as usize;
                if basis[lead] == 0 {
                    basis[lead] = x;
                    return true;
                }
                x ^= basis[lead];
            }
            false
        })
    };
    let s = matrices.len();
    // every composition of rho into s parts (each at most 32), depth first
    fn compositions(
        s: usize,
        rho: u32,
        max: u32,
        parts: &mut Vec<u32>,
        f: &mut dyn FnMut(&[u32]) -> bool,
    ) -> bool {
        if parts.len() + 1 == s {
            if rho > max {
                return true;
            }
            parts.push(rho);
            let ok = f(parts);
            parts.pop();
            return ok;
        }
        for d in 0..=rho.min(max) {
            parts.push(d);
            let ok = compositions(s, rho - d, max, parts, f);
            parts.pop();
            if !ok {
                return false;
            }
        }
        true
    }
    let mut strength = 0;
    let mut rows = Vec::new();
    let mut checks = 0u64;
    for rho in 1..=m {
        let ok = compositions(
            s,
            rho,
            32 / bits,
            &mut Vec::new(),
            &mut |parts: &[u32]| {
                checks += 1;
                if checks > budget {
                    return false;
                }
                rows.clear();
                for (j, &d) in parts.iter().enumerate() {
                    rows.extend((0..(d * bits) as usize).map(|r| row(j, r)));
                }
                independent(&rows)
            },
        );
        if checks > budget {
            return None;
        }
        if !ok {
            break;
        }
        strength = rho;
    }
    Some(m - strength)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `C bits(i)` by the definition.
    fn apply(m: &Matrix, i: u32) -> u32 {
        (0..32)
            .filter(|k| (i >> k) & 1 == 1)
            .fold(0, |x, k| x ^ m[k as usize])
    }

    fn indices() -> impl Iterator<Item = u32> {
        let mut h = 9u64;
        (0..4096u32)
            .chain([u32::MAX, u32::MAX - 1, 1 << 31, 0xdead_beef])
            .chain((0..20_000).map(move |_| {
                h = crate::hash::mix64(h);
                h as u32
            }))
    }

    #[test]
    fn tables_and_computed_forms_agree_with_the_matrices() {
        let (s, p) = (sobol01_matrices(), pmj02_matrices());
        for i in indices() {
            let r = i.reverse_bits();
            let want_s = [
                apply(&s[0], i).reverse_bits(),
                apply(&s[1], i).reverse_bits(),
            ];
            let want_p = [
                apply(&p[0], i).reverse_bits(),
                apply(&p[1], i).reverse_bits(),
            ];
            assert_eq!(SOBOL01.point_rev(r), want_s, "sobol table, index {i}");
            assert_eq!(sobol01_rev(i), want_s, "sobol computed, index {i}");
            assert_eq!(PMJ02.point_rev(r), want_p, "pmj02 table, index {i}");
            assert_eq!(pmj02_rev(i), want_p, "pmj02 computed, index {i}");
            for d in 0..2 {
                assert_eq!(lookup(&SOBOL_FIRST[d], r), want_s[d]);
            }
            // the nibble tables of every tabulated dimension, against the matrices
            for d in [0, 1, 2, 7, NIBBLE_DIMENSIONS - 1] {
                assert_eq!(
                    lookup_nibbles(&SOBOL_NIBBLES[d], r),
                    apply(&SOBOL[d], i).reverse_bits()
                );
                assert_eq!(
                    lookup_nibbles(&ONE_TWO_NIBBLES[d], r),
                    apply(&ONE_TWO_SOBOL[d], i).reverse_bits()
                );
            }
        }
    }

    #[test]
    fn the_sobol_matrices_are_the_ones_the_sobol_crate_built() {
        // A digest of all 1000 matrices as the `sobol` crate's copy of the same file gave them
        // (its `JoeKuoD6::standard()` through the same recurrence), computed with that crate
        // before it was dropped: the table here was not altered on its way in.
        let mut h = 0u64;
        for m in &SOBOL {
            for &c in m {
                h = crate::hash::mix64(h ^ c as u64).wrapping_add(crate::hash::GOLDEN_GAMMA);
            }
        }
        assert_eq!(h, 0x54dc_7872_6bd6_acca);
        // and the digest sees one changed bit
        let mut g = 0u64;
        for (d, m) in SOBOL.iter().enumerate() {
            for (k, &c) in m.iter().enumerate() {
                let c = if (d, k) == (999, 31) { c ^ 1 } else { c };
                g = crate::hash::mix64(g ^ c as u64).wrapping_add(crate::hash::GOLDEN_GAMMA);
            }
        }
        assert_ne!(g, h);
    }

    #[test]
    fn every_sobol_matrix_is_its_recurrence_over_a_primitive_polynomial() {
        // each row of the file: degree s, a primitive polynomial x^s + a_1 x^(s-1) + .. + 1
        // over GF(2) (order of x is 2^s - 1), and column k of the matrix is m_k 2^(32-k) for
        // the first s columns, odd m_k below 2^k; the columns are linearly independent
        // (upper triangular with a unit diagonal): the matrix is invertible
        let text = JOE_KUO.lines().skip(1);
        for (line, m) in text.zip(&SOBOL[1..]) {
            let v: Vec<u64> = line
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            let (s, a) = (v[1] as u32, v[2]);
            let poly = (1u64 << s) | (a << 1) | 1;
            // the order of x modulo poly
            let mulx = |p: u64| {
                let q = p << 1;
                if q >> s & 1 == 1 { q ^ poly } else { q }
            };
            let (mut p, mut order) = (mulx(1), 1u64);
            while p != 1 {
                p = mulx(p);
                order += 1;
            }
            assert_eq!(order, (1u64 << s) - 1, "line {line}: not primitive");
            for k in 0..s as usize {
                assert_eq!(m[k] as u64, v[3 + k] << (31 - k), "line {line}");
            }
            for (k, &c) in m.iter().enumerate() {
                // digit k (bit 31 - k) set, none below it
                assert_eq!(c.trailing_zeros(), 31 - k as u32, "line {line}: column {k}");
            }
        }
    }

    #[test]
    fn the_one_two_matrices_are_utk_s() {
        // the first 32 columns of dimensions 2, 3, 345, 690 and 691 as UTK's
        // SamplerOneTwoSobol.hpp lists them (commit 4c195da; see LICENSE-one-two-sobol): the
        // table here, through the recurrence, gives UTK's matrices
        let utk: [(usize, [u32; 32]); 5] = [
            (
                2,
                [
                    0x80000000, 0x40000000, 0xe0000000, 0xb0000000, 0x68000000, 0xf4000000,
                    0x86000000, 0x4f000000, 0xe8800000, 0xb4400000, 0x66e00000, 0xffb00000,
                    0x80e80000, 0x40b40000, 0xe0660000, 0xb0ff0000, 0x68808000, 0xf4404000,
                    0x86e0e000, 0x4fb0b000, 0xe8e86800, 0xb4b4f400, 0x66668600, 0xffff4f00,
                    0x80006880, 0x4000f440, 0xe00086e0, 0xb0004fb0, 0x6800e8e8, 0xf400b4b4,
                    0x86006666, 0x4f00ffff,
                ],
            ),
            (
                3,
                [
                    0x80000000, 0x40000000, 0x20000000, 0xf0000000, 0xc8000000, 0x64000000,
                    0xd2000000, 0x37000000, 0xa0800000, 0xb0400000, 0xe8200000, 0x94f00000,
                    0x1ac80000, 0x53640000, 0x72520000, 0x87770000, 0x48008000, 0x24004000,
                    0xf2002000, 0xc700f000, 0x6880c800, 0xd4406400, 0x3a20d200, 0xa3f03700,
                    0xba48a080, 0xe324b040, 0x9a72e820, 0x138794f0, 0x52c89ac8, 0x77641364,
                    0x80525252, 0x40777777,
                ],
            ),
            (
                345,
                [
                    0x80000000, 0xc0000000, 0xe0000000, 0x70000000, 0xc8000000, 0xa4000000,
                    0xfa000000, 0x8f000000, 0x39800000, 0x59400000, 0x2b200000, 0xd5900000,
                    0xe0080000, 0x949c0000, 0xf29e0000, 0x82e90000, 0x298a8000, 0x55abc000,
                    0xbc5d6000, 0x63983000, 0x5224e800, 0x5ac23400, 0x39874200, 0x9c6f6300,
                    0x0e212780, 0x86418c40, 0x05cdcda0, 0x4331ed50, 0x9db7be68, 0x38ce4c2c,
                    0xb547c606, 0xc641f6fd,
                ],
            ),
            (
                690,
                [
                    0x80000000, 0x40000000, 0x60000000, 0x50000000, 0x48000000, 0xfc000000,
                    0xc6000000, 0xdf000000, 0x20800000, 0xe8c00000, 0xfda00000, 0xa0100000,
                    0x74580000, 0xdd740000, 0xa5660000, 0x145b0000, 0xa8618000, 0xc440c000,
                    0xeb602000, 0x06b03000, 0xd6c81800, 0xececb400, 0x40323a00, 0xc06d1900,
                    0x22827f80, 0x24a58840, 0x4b6ef560, 0x0d174db0, 0xd4437c48, 0xe675c52c,
                    0x83965612, 0x5bf3e23d,
                ],
            ),
            (
                691,
                [
                    0x80000000, 0xc0000000, 0x60000000, 0x50000000, 0x88000000, 0xbc000000,
                    0xba000000, 0x83000000, 0x68800000, 0x24400000, 0x4b200000, 0x51900000,
                    0xc1980000, 0xd6b40000, 0xbffa0000, 0x91370000, 0x2a918000, 0x4c804000,
                    0xd3c0a000, 0x02803000, 0x0fd0d800, 0xad983400, 0x46c80600, 0x52b43900,
                    0x0e8deb80, 0x225d4cc0, 0x6b77ef60, 0x65463ab0, 0x3f137008, 0x34b0d72c,
                    0xd740954e, 0xe5e1fccd,
                ],
            ),
        ];
        for (d, columns) in utk {
            assert_eq!(ONE_TWO_SOBOL[d], columns, "dimension {d}");
        }
        assert_eq!(ONE_TWO_SOBOL[..2], sobol01_matrices());
    }

    /// The product of two polynomials over GF(2) modulo `p` (degree `s <= 32`), bit `k` the
    /// coefficient of `x^k`.
    fn mul_mod(a: u64, b: u64, p: u64, s: u32) -> u64 {
        let (mut r, mut a, mut b) = (0u64, a, b);
        while b != 0 {
            if b & 1 == 1 {
                r ^= a;
            }
            b >>= 1;
            a <<= 1;
            if a >> s & 1 == 1 {
                a ^= p;
            }
        }
        r
    }

    /// `x^(2^k)` modulo `p`.
    fn x_pow_2k(k: u32, p: u64, s: u32) -> u64 {
        let mut x = if s == 1 { 2 ^ p } else { 2 };
        for _ in 0..k {
            x = mul_mod(x, x, p, s);
        }
        x
    }

    /// The greatest common divisor of two polynomials over GF(2).
    fn gcd(mut a: u64, mut b: u64) -> u64 {
        while b != 0 {
            while a != 0 && 63 - a.leading_zeros() >= 63 - b.leading_zeros() {
                a ^= b << ((63 - a.leading_zeros()) - (63 - b.leading_zeros()));
            }
            core::mem::swap(&mut a, &mut b);
        }
        a
    }

    #[test]
    fn every_one_two_matrix_is_its_recurrence_over_a_distinct_irreducible_polynomial() {
        // Rabin's test: x^(2^s) = x mod p, and x^(2^(s/q)) - x coprime to p for each prime q
        // dividing s. The polynomials are irreducible (not all primitive: 429 of 691 are) and
        // distinct, as the dimensions of a digital sequence need
        let mut seen = Vec::new();
        let mut primitive = 0;
        for (line, m) in ONE_TWO.lines().skip(1).zip(&ONE_TWO_SOBOL[1..]) {
            let v: Vec<u64> = line
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            let (s, a) = (v[1] as u32, v[2]);
            let p = (1u64 << s) | (a << 1) | 1;
            assert_eq!(
                x_pow_2k(s, p, s),
                if s == 1 { 2 ^ p } else { 2 },
                "line {line}"
            );
            for q in
                (2..=s).filter(|q| s.is_multiple_of(*q) && (2..*q).all(|r| !q.is_multiple_of(r)))
            {
                let x = x_pow_2k(s / q, p, s) ^ 2;
                assert_eq!(gcd(p, x), 1, "line {line}: reducible");
            }
            assert!(!seen.contains(&p), "line {line}: a polynomial twice");
            seen.push(p);
            // primitive when x^((2^s - 1) / r) != 1 for every prime r dividing 2^s - 1
            let order = (1u64 << s) - 1;
            let mut n = order;
            let mut factors = Vec::new();
            let mut r = 2;
            while r * r <= n {
                if n.is_multiple_of(r) {
                    factors.push(r);
                    while n.is_multiple_of(r) {
                        n /= r;
                    }
                }
                r += 1;
            }
            if n > 1 {
                factors.push(n);
            }
            let pow = |mut e: u64| {
                let (mut acc, mut base) = (1u64, if s == 1 { 2 ^ p } else { 2 });
                while e != 0 {
                    if e & 1 == 1 {
                        acc = mul_mod(acc, base, p, s);
                    }
                    base = mul_mod(base, base, p, s);
                    e >>= 1;
                }
                acc
            };
            if factors.iter().all(|f| pow(order / f) != 1) {
                primitive += 1;
            }
            for k in 0..s as usize {
                assert_eq!(m[k] as u64, v[3 + k] << (31 - k), "line {line}");
            }
        }
        assert_eq!(seen.len(), 691);
        assert_eq!(primitive, 429);
    }

    /// The largest t of the pair of dimensions `(2k, 2k + 1)` of `matrices` over `2^m` points,
    /// `m = 1..=32` (the rank criterion), for each `k`.
    fn pair_t_values(matrices: &[Matrix]) -> Vec<u32> {
        (0..matrices.len() / 2)
            .map(|k| {
                let pair = [matrices[2 * k], matrices[2 * k + 1]];
                (1..=32)
                    .map(|m| digital_t_value_in(&pair, m, 1))
                    .max()
                    .unwrap()
            })
            .collect()
    }

    #[test]
    fn every_one_two_pair_is_a_one_two_sequence() {
        // Bonneel et al.'s property, exactly: the pair (2k, 2k + 1) is a (1,2)-sequence at every
        // 2^m up to 2^32, pair 0 a (0,2)-sequence
        let t = pair_t_values(&ONE_TWO_SOBOL);
        assert_eq!(t.len(), 346);
        assert_eq!(t[0], 0);
        for (k, &t) in t.iter().enumerate().skip(1) {
            assert_eq!(t, 1, "pair ({}, {}): t = {t}", 2 * k, 2 * k + 1);
        }
        // the same test on Joe and Kuo's first 692 dimensions fails: their pairs have t of 3
        // to 12
        let jk = pair_t_values(&SOBOL[..692]);
        assert_eq!(jk[0], 0);
        assert!(jk[1..].iter().all(|&t| (3..=12).contains(&t)), "{jk:?}");
    }

    #[test]
    fn the_first_dimensions_are_van_der_corput_and_pascal() {
        let v: Vec<u32> = (0..4).map(|i| sobol01_rev(i)[0].reverse_bits()).collect();
        assert_eq!(v, [0, 1 << 31, 1 << 30, 3 << 30]);
        // dimension 1 is the recurrence with s = 1, a = 0, m = [1]
        assert_eq!(sobol01_matrices()[1], direction_matrix(1, 0, &[1]));
    }

    #[test]
    fn both_pairs_are_0_2_sequences() {
        // every prefix and aligned block of 2^m points, m <= 12, fills every elementary interval
        for point in [sobol01_rev, pmj02_rev] {
            for m in 0..=12u32 {
                let n = 1u32 << m;
                for start in [0u32, n, 5 * n, 1 << 20] {
                    for a in 0..=m {
                        let mut seen = vec![false; n as usize];
                        for i in start..start + n {
                            let [x, y] = point(i).map(u32::reverse_bits);
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
    }

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
        for (k, (&x, &y)) in PMJ02_XORS[0]
            .iter()
            .zip(&PMJ02_XORS[1])
            .enumerate()
            .take(20)
        {
            let want_x: u32 = (0..k)
                .map(|r| (stirling_second_mod2(k, r) as u32) << r)
                .sum();
            let want_y: u32 = (0..k)
                .map(|r| (stirling_second_mod2(k + 1, r + 1) as u32) << r)
                .sum();
            assert_eq!(x, want_x, "x, k = {k}");
            assert_eq!(y, want_y, "y, k = {k}");
        }
        // the first values, as published with the paper's supplemental code
        assert_eq!(
            &PMJ02_XORS[0][..11],
            &[0, 0, 2, 6, 6, 0xe, 0x36, 0x4e, 0x16, 0x2e, 0x276]
        );
        assert_eq!(
            &PMJ02_XORS[1][..11],
            &[0, 1, 3, 3, 7, 0x1b, 0x27, 0xb, 0x17, 0x13b, 0x367]
        );
    }

    #[test]
    fn byte_tables_match_the_bit_loop() {
        for dim in 0..SOBOL_DIMENSIONS {
            let m = sobol_matrix(dim).unwrap();
            let t = byte_tables(m);
            for i in [0u32, 1, 2, 3, 255, 256, 0x1234_5678, u32::MAX] {
                assert_eq!(lookup(&t, i.reverse_bits()).reverse_bits(), apply(m, i));
                assert_eq!(super::apply(m, i), apply(m, i));
            }
        }
    }

    #[test]
    fn digital_t_values_match_the_points_counted() {
        // the rank criterion against the elementary intervals counted on the points, for pairs
        // of Sobol' dimensions with t from 0 up, at several m
        for (a, b) in [(0u32, 1u32), (0, 2), (1, 2), (2, 3), (3, 5), (4, 7), (6, 7)] {
            let (ma, mb) = (*sobol_matrix(a).unwrap(), *sobol_matrix(b).unwrap());
            for m in [1u32, 3, 6, 9] {
                assert_eq!(
                    digital_t_value(&[ma, mb], m),
                    counted_t(&[ma, mb], m, 1),
                    "dims {a},{b} m {m}"
                );
            }
        }
        // Sobol' 0-1 is a (0,2)-sequence; a matrix repeated is as bad as it gets
        let (m0, m1) = (SOBOL[0], SOBOL[1]);
        assert!((1..=20).all(|m| digital_t_value(&[m0, m1], m) == 0));
        assert_eq!(digital_t_value(&[m0, m0], 8), 7);
    }

    /// The t-value of points counted in elementary boxes of base `b = 2^bits`: the smallest
    /// `t` for which every box of volume `b^(t - k)` holds `b^t` of the `b^k` points.
    fn counted_t(matrices: &[Matrix], k: u32, bits: u32) -> u32 {
        let n = 1u32 << (bits * k);
        let pts: Vec<Vec<u32>> = (0..n)
            .map(|i| matrices.iter().map(|m| apply(m, i)).collect())
            .collect();
        let s = matrices.len();
        (0..=k)
            .find(|&t| {
                let rho = k - t;
                // every split of rho base-4 digits over the s coordinates
                let mut parts = vec![0u32; s];
                let mut ok = true;
                loop {
                    if parts.iter().sum::<u32>() == rho {
                        let mut counts = std::collections::HashMap::new();
                        for p in &pts {
                            let cell: Vec<u32> = p
                                .iter()
                                .zip(&parts)
                                .map(|(&v, &d)| if d == 0 { 0 } else { v >> (32 - bits * d) })
                                .collect();
                            *counts.entry(cell).or_insert(0u32) += 1;
                        }
                        ok &= counts.len() as u64 == 1u64 << (bits * rho)
                            && counts.values().all(|&c| c == 1 << (bits * t));
                    }
                    // next tuple of digits 0..=rho
                    let mut q = 0;
                    while q < s && parts[q] == rho {
                        parts[q] = 0;
                        q += 1;
                    }
                    if q == s {
                        break;
                    }
                    parts[q] += 1;
                }
                ok
            })
            .unwrap()
    }

    #[test]
    fn faure4_is_a_base4_zero_four_sequence_with_binary_zero_two_pairs() {
        let m = faure4_matrices();
        // the rank criterion against the points counted in base-4 boxes, t = 0 and t > 0
        for set in [&[0usize, 1, 2, 3][..], &[0, 1, 4], &[1, 2, 3, 4], &[0, 2]] {
            let ms: Vec<Matrix> = set.iter().map(|&j| m[j]).collect();
            for k in 1..=4 {
                assert_eq!(
                    digital_t_value_in(&ms, k, 2),
                    counted_t(&ms, k, 2),
                    "dims {set:?} at 4^{k}"
                );
            }
        }
        // dimensions 0-3: every aligned block of 4^k points a (0,k,4)-net in base 4
        for k in 1..=16 {
            assert_eq!(digital_t_value_in(&m[..4], k, 2), 0, "4^{k}");
        }
        // dimension 0 is van der Corput; 0-1 and 2-3 binary (0,2)-sequences, the other pairs
        // of the four t <= 1 at 4^k points and t <= 2 at the odd powers of two
        assert_eq!(m[0], sobol01_matrices()[0]);
        for mm in 1..=32 {
            for (a, b) in [(0, 1), (2, 3)] {
                assert_eq!(
                    digital_t_value(&[m[a], m[b]], mm),
                    0,
                    "dims {a},{b} at 2^{mm}"
                );
            }
            for (a, b) in [(0, 2), (0, 3), (1, 2), (1, 3)] {
                let t = digital_t_value(&[m[a], m[b]], mm);
                assert!(t <= 1 + mm % 2, "dims {a},{b} at 2^{mm}: t = {t}");
            }
            for a in 0..4 {
                assert!(
                    digital_t_value(&[m[a], m[4]], mm) <= 5,
                    "dims {a},4 at 2^{mm}"
                );
            }
        }
        // a repeated base-4 dimension is as bad as it gets: the counting sees it
        assert_eq!(digital_t_value_in(&[m[1], m[1]], 4, 2), 3);
    }

    #[test]
    fn a_t_value_past_its_budget_is_refused_not_computed() {
        // (was: hours for 24 dimensions at m = 32) the checks are counted: Sobol' dimensions
        // 0-1 at m = 20 reach strength 20 through 1 + 2 + ... + 21 - 1 = 230 compositions
        let m: Vec<Matrix> = (0..2).map(|d| *sobol_matrix(d).unwrap()).collect();
        assert_eq!(digital_t_value_within(&m, 20, 1, 230), Some(0));
        assert_eq!(digital_t_value_within(&m, 20, 1, 229), None);
        let many: Vec<Matrix> = (0..24).map(|d| *sobol_matrix(d).unwrap()).collect();
        assert_eq!(digital_t_value_within(&many, 32, 1, 1 << 16), None);
    }

    #[test]
    fn the_fifth_faure4_matrix_is_sobol_dimension_four() {
        assert_eq!(&faure4_matrices()[4], sobol_matrix(4).unwrap());
    }
}
