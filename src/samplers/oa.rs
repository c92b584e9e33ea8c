//! Orthogonal-array sampling: Jarosz, Enayet, Kensler, Kilpatrick, Christensen, "Orthogonal
//! Array Sampling for Monte Carlo Rendering" (EGSR 2019).
//!
//! An orthogonal array OA(N, D, q, t) is an `N x D` table over `q` symbols in which every `t`
//! columns contain each of the `q^t` symbol combinations exactly once. Read each row as a sample
//! and each symbol as a stratum of `[0,1)`, and every `t`-dimensional projection is jittered on
//! the `q^t` grid, for any number of dimensions `D` up to the construction's limit: the answer
//! to the curse of dimensionality for the projections that matter.
//!
//! * [`Bose`] (Bose 1938): strength 2, `N = q^2`, up to `q + 1` dimensions; row `i = a0 + q a1`
//!   has columns `a0`, `a1` and `a0 + j a1` for the field elements `j != 0`.
//! * [`Bush`] (Bush 1952): strength `t`, `N = q^t`, up to `q` dimensions; the `t` base-`q` digits
//!   of `i` are the coefficients of a polynomial, evaluated at the field element `j` for column
//!   `j`.
//!
//! `q` is a prime or a prime power (`q <= 256` for powers, with Galois-field arithmetic from
//! tables built at construction: `GF(p^n)` is polynomials over `GF(p)` modulo the first monic
//! irreducible polynomial of degree `n`). Strata are shuffled per dimension with Kensler's
//! [`Permutation`]; inside its stratum each coordinate takes a *multi-jittered* sub-stratum so
//! that every 1D projection is also stratified into `N` strata: for Bose the sub-stratum is a
//! permutation of a partner column (two columns of a strength-2 array pair every symbol with
//! every other, so the `q` samples of a stratum get distinct sub-strata); for Bush it is a
//! permutation of `i / q`, the index without its lowest digit (for fixed high digits the column
//! is a bijection of the lowest one). Everything is computed sample by sample, as in the paper.

use crate::counts::{CountRule, prime_power};
use crate::entry::{Built, Entry, Family, ParameterSpec, Params};
use crate::{Error, Result};
use strata::float::Strata;
use strata::hash::{DivMod, Permutation, hash_u64, hash32, key32, stream_seed};
use strata::samplers::{Blocks, Fixed};
use strata::{Point2, Seed, StrataGrid};

/// The stream of a block key from which the sub-stratum permutations are keyed.
const SUBSTRATA_STREAM: u64 = 0x5eed;

/// The number of symbols `q` of an array of `count = q^t` points, the count checked by the
/// arrays' rule ([`CountRule::OaPower`]: `q` a prime, or a prime power up to
/// [`MAX_PRIME_POWER`]).
fn symbols(name: &'static str, count: u64, t: u32) -> Result<u32> {
    let n = CountRule::OaPower(t).check(name, count)? as u64;
    Ok((2u32..)
        .find(|&q| (q as u64).pow(t) >= n)
        .expect("n = q^t for some q >= 2"))
}

/// Checks an array's columns: `dims` from 1 to `max`, `why` the limit.
fn check_dims(name: &'static str, dims: u32, max: u32, why: &str) -> Result<()> {
    if dims == 0 || dims > max {
        return Err(Error::parameter(
            name,
            "dims",
            dims,
            format!("1 to {max} ({why})"),
        ));
    }
    Ok(())
}

/// The registry entry of `oa-bose`.
pub(crate) const BOSE: Entry = Entry {
    name: "oa-bose",
    description: "orthogonal array, strength 2 (N = q^2, up to q+1 dims), multi-jittered",
    paper: "Jarosz et al. 2019",
    family: Family::Multidim,
    counts: CountRule::OaPower(2),
    promise: "every 2D projection on `q x q`, every 1D into `N`",
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(Bose::new(p.count, 2, p.seed)?),
            d => Built::nd(Bose::new(p.count, d, p.seed)?),
        })
    },
    ..Entry::DEFAULT
};

/// The registry entry of `oa-bush`.
pub(crate) const BUSH: Entry = Entry {
    name: "oa-bush",
    description: "orthogonal array, strength T (--strength T; N = q^T, up to q dims), multi-jittered",
    paper: "Jarosz et al. 2019",
    family: Family::Multidim,
    counts: CountRule::OaPower(3),
    parameters: &[STRENGTH],
    promise: "every t-D projection on `q^t`, every 1D into `N`",
    any_dims: true,
    build: |p| {
        Ok(match p.dims {
            2 => Built::two(bush(p, 2)?),
            d => Built::nd(bush(p, d)?),
        })
    },
    ..Entry::DEFAULT
};

/// The Bush array the registry builds: strength from the parameters (default 3).
fn bush(p: &Params, dims: u32) -> Result<Fixed<Bush>> {
    let strength = STRENGTH.read_whole(p);
    Bush::new(p.count, strength, dims, p.seed)
}

/// `--strength`: the strength of a Bush array.
const STRENGTH: ParameterSpec = ParameterSpec::whole(
    "strength",
    2,
    16,
    3,
    "the array's strength t: every t-dimensional projection is stratified on q^t cells",
);

pub use crate::counts::MAX_PRIME_POWER;

/// A finite field `GF(q)`: arithmetic modulo a prime, or tables for a prime power.
#[derive(Clone, Debug)]
pub(crate) struct Field {
    q: u32,
    /// For prime powers: `q x q` addition and multiplication tables.
    add: Vec<u16>,
    mul: Vec<u16>,
}

impl Field {
    /// `GF(q)`: `q` prime (any size), or a prime power up to [`MAX_PRIME_POWER`].
    pub fn new(q: u32) -> Option<Self> {
        let (p, n) = prime_power(q)?;
        if n == 1 {
            return Some(Field {
                q,
                add: Vec::new(),
                mul: Vec::new(),
            });
        }
        if q > MAX_PRIME_POWER {
            return None;
        }
        // polynomials over GF(p) as base-p digit vectors (coefficient k = digit k)
        let digits = |mut v: u32| -> Vec<u32> {
            (0..n)
                .map(|_| {
                    let d = v % p;
                    v /= p;
                    d
                })
                .collect()
        };
        let value = |c: &[u32]| c.iter().rev().fold(0u32, |acc, &d| acc * p + d);
        let poly_mod = |a: &[u32], m: &[u32]| -> Vec<u32> {
            // remainder of a (any degree) modulo the monic m (degree m.len() - 1)
            let mut r = a.to_vec();
            let dm = m.len() - 1;
            while r.len() > dm {
                let lead = *r.last().expect("non-empty");
                let shift = r.len() - 1 - dm;
                for (k, &c) in m.iter().enumerate() {
                    r[shift + k] = (r[shift + k] + p * p - (lead * c) % p) % p;
                }
                r.pop();
            }
            r
        };
        let poly_mul = |a: &[u32], b: &[u32]| -> Vec<u32> {
            let mut r = vec![0u32; a.len() + b.len() - 1];
            for (i, &x) in a.iter().enumerate() {
                for (j, &y) in b.iter().enumerate() {
                    r[i + j] = (r[i + j] + x * y) % p;
                }
            }
            r
        };
        // the first monic irreducible of degree n: no monic factor of degree 1..=n/2
        let monic = |coeffs: u32, degree: u32| -> Vec<u32> {
            let mut c: Vec<u32> = (0..degree)
                .map({
                    let mut v = coeffs;
                    move |_| {
                        let d = v % p;
                        v /= p;
                        d
                    }
                })
                .collect();
            c.push(1);
            c
        };
        let irreducible = (0..p.pow(n)).map(|c| monic(c, n)).find(|m| {
            m[0] != 0
                && (1..=n / 2).all(|d| {
                    (0..p.pow(d)).all(|c| poly_mod(m, &monic(c, d)).iter().any(|&x| x != 0))
                })
        })?;
        let (mut add, mut mul) = (vec![0u16; (q * q) as usize], vec![0u16; (q * q) as usize]);
        for a in 0..q {
            let da = digits(a);
            for b in 0..q {
                let db = digits(b);
                let sum: Vec<u32> = da.iter().zip(&db).map(|(x, y)| (x + y) % p).collect();
                add[(a * q + b) as usize] = value(&sum) as u16;
                let mut prod = poly_mod(&poly_mul(&da, &db), &irreducible);
                prod.resize(n as usize, 0);
                mul[(a * q + b) as usize] = value(&prod) as u16;
            }
        }
        Some(Field { q, add, mul })
    }

    /// `a + b`.
    #[inline]
    pub fn add(&self, a: u32, b: u32) -> u32 {
        if self.add.is_empty() {
            let s = a + b;
            if s >= self.q { s - self.q } else { s }
        } else {
            self.add[(a * self.q + b) as usize] as u32
        }
    }

    /// `a b`.
    #[inline]
    pub fn mul(&self, a: u32, b: u32) -> u32 {
        if self.mul.is_empty() {
            ((a as u64 * b as u64) % self.q as u64) as u32
        } else {
            self.mul[(a * self.q + b) as usize] as u32
        }
    }
}

/// Per-block, per-dimension permutation keys: the stratum key and the sub-stratum key.
fn dim_keys(key: u64, dims: u32) -> impl Iterator<Item = (u32, u32)> {
    (0..dims as u64).map(move |j| {
        let k = stream_seed(j, key);
        (key32(k), key32(k ^ SUBSTRATA_STREAM))
    })
}

/// Bose orthogonal-array sets: strength 2, `N = q^2`, up to `q + 1` dimensions.
#[derive(Clone, Debug)]
pub struct Bose {
    field: Field,
    q: DivMod,
    dims: u32,
    strata: Strata,
    /// Per dimension: the block's stratum permutation and its sub-stratum key.
    keys: Vec<(Permutation, u32)>,
    key: u64,
}

impl Bose {
    /// `count = q^2` samples in `dims` dimensions (`dims <= q + 1`), seeded by `seed`.
    pub fn new(count: u64, dims: u32, seed: Seed) -> Result<Fixed<Self>> {
        let q = symbols(BOSE.name, count, 2)?;
        check_dims(
            BOSE.name,
            dims,
            q + 1,
            "a Bose array has at most q + 1 columns",
        )?;
        let field = Field::new(q).expect("checked");
        Ok(Fixed::new(
            Bose {
                field,
                q: DivMod::new(q).expect("q >= 2"),
                dims,
                strata: Strata::new(count),
                keys: Vec::new(),
                key: 0,
            },
            seed,
        )?)
    }

    /// Samples per set.
    pub fn count(&self) -> u32 {
        self.q.divisor() * self.q.divisor()
    }

    /// Symbol `j` of row `i`: `a0`, `a1`, then `a0 + (j - 1) a1`.
    #[inline]
    fn symbol(&self, j: u32, a0: u32, a1: u32) -> u32 {
        match j {
            0 => a0,
            1 => a1,
            _ => self.field.add(a0, self.field.mul(j - 1, a1)),
        }
    }
}

impl Blocks for Bose {
    const NAME: &'static str = BOSE.name;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn set_dims(&self) -> u32 {
        self.dims
    }

    /// Every pair of dimensions is stratified on the `q x q` grid (strength 2).
    fn pair_strata(&self, _x: u32, _y: u32) -> Option<StrataGrid> {
        let q = self.q.divisor();
        Some(StrataGrid {
            columns: q,
            rows: q,
        })
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        self.keys.clear();
        self.keys.extend(
            dim_keys(key, self.dims).map(|(ks, kb)| (Permutation::with_divider(&self.q, ks), kb)),
        );
    }

    fn point(&self, i: u32) -> Point2 {
        let mut p = [0.0f32; 2];
        self.point_into(i, &mut p);
        p
    }

    fn point_into(&self, i: u32, out: &mut [f32]) {
        let q = self.q.divisor();
        let (a1, a0) = self.q.div_rem(i);
        for (j, o) in out.iter_mut().enumerate().take(self.dims as usize) {
            let j = j as u32;
            let (perm, kb) = &self.keys[j as usize];
            let stratum = perm.apply(self.symbol(j, a0, a1));
            // partner column: 1 for column 0, else 0
            let partner = self.symbol(if j == 0 { 1 } else { 0 }, a0, a1);
            let sub = Permutation::with_divider(&self.q, hash32(stratum, *kb)).apply(partner);
            let jitter = hash_u64((i as u64) << 16 | j as u64, self.key) as u32;
            *o = self.strata.place(stratum * q + sub, jitter);
        }
    }
}

/// Bush orthogonal-array sets: strength `t`, `N = q^t`, up to `q` dimensions.
#[derive(Clone, Debug)]
pub struct Bush {
    field: Field,
    q: DivMod,
    t: u32,
    /// `q^(t-1)`: the sub-strata per stratum.
    sub_count: u32,
    dims: u32,
    strata: Strata,
    /// Per dimension: the block's stratum and sub-stratum permutations.
    keys: Vec<(Permutation, Permutation)>,
    key: u64,
}

impl Bush {
    /// `count = q^strength` samples in `dims` dimensions (`dims <= q`), strength `>= 2`.
    pub fn new(count: u64, strength: u32, dims: u32, seed: Seed) -> Result<Fixed<Self>> {
        STRENGTH.check(BUSH.name, strength as f64)?;
        let q = symbols(BUSH.name, count, strength)?;
        check_dims(BUSH.name, dims, q, "a Bush array has at most q columns")?;
        Ok(Fixed::new(
            Bush {
                field: Field::new(q).expect("checked"),
                q: DivMod::new(q).expect("q >= 2"),
                t: strength,
                sub_count: (count / q as u64) as u32,
                dims,
                strata: Strata::new(count),
                keys: Vec::new(),
                key: 0,
            },
            seed,
        )?)
    }

    /// Samples per set.
    pub fn count(&self) -> u32 {
        self.q.divisor().pow(self.t)
    }
}

impl Blocks for Bush {
    const NAME: &'static str = BUSH.name;

    fn set_len(&self) -> u32 {
        self.count()
    }

    fn set_dims(&self) -> u32 {
        self.dims
    }

    /// Every pair of dimensions is stratified on the `q x q` grid (`q^(t-2)` points per cell:
    /// strength `t >= 2`).
    fn pair_strata(&self, _x: u32, _y: u32) -> Option<StrataGrid> {
        let q = self.q.divisor();
        Some(StrataGrid {
            columns: q,
            rows: q,
        })
    }

    fn begin_block(&mut self, key: u64) {
        self.key = key;
        self.keys.clear();
        let sub_count = self.sub_count;
        self.keys.extend(dim_keys(key, self.dims).map(|(ks, kb)| {
            (
                Permutation::with_divider(&self.q, ks),
                Permutation::new(sub_count, kb).expect("q^(t-1) >= 1"),
            )
        }));
    }

    fn point(&self, i: u32) -> Point2 {
        let mut p = [0.0f32; 2];
        self.point_into(i, &mut p);
        p
    }

    fn point_into(&self, i: u32, out: &mut [f32]) {
        let sub_count = self.sub_count;
        let (high, _) = self.q.div_rem(i); // i / q: the index without its lowest digit
        let mut digits = [0u32; 16];
        let mut v = i;
        for d in digits.iter_mut().take(self.t as usize) {
            let (rest, digit) = self.q.div_rem(v);
            *d = digit;
            v = rest;
        }
        for (j, o) in out.iter_mut().enumerate().take(self.dims as usize) {
            let j = j as u32;
            // Horner: sum_k d_k j^k
            let mut phi = 0u32;
            for k in (0..self.t as usize).rev() {
                phi = self.field.add(self.field.mul(phi, j), digits[k]);
            }
            let (perm, sub_perm) = &self.keys[j as usize];
            let stratum = perm.apply(phi);
            let sub = sub_perm.apply(high);
            let jitter = hash_u64((i as u64) << 16 | j as u64, self.key) as u32;
            *o = self.strata.place(stratum * sub_count + sub, jitter);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn galois_fields_are_fields() {
        for q in [2u32, 3, 4, 5, 8, 9, 16, 25, 27, 49, 64, 81, 121, 125, 128] {
            let f = Field::new(q).unwrap();
            for a in 0..q {
                // every nonzero element has an inverse; multiplication by a is a bijection
                let mut seen = vec![false; q as usize];
                for b in 0..q {
                    seen[f.mul(a, b) as usize] = true;
                    assert_eq!(f.add(a, b), f.add(b, a));
                }
                if a != 0 {
                    assert!(seen.iter().all(|&s| s), "GF({q}): {a} has no inverse");
                }
            }
            // distributivity on a sample of triples
            for (a, b, c) in [(1, 2, 3), (q - 1, q / 2, 1), (2 % q, q - 1, q - 1)] {
                assert_eq!(
                    f.mul(a, f.add(b, c)),
                    f.add(f.mul(a, b), f.mul(a, c)),
                    "GF({q})"
                );
            }
        }
        assert!(Field::new(6).is_none());
        assert!(Field::new(512).is_none());
        assert!(Field::new(65521).is_some());
    }

    #[test]
    fn count_errors_name_the_nearest_allowed() {
        let e = symbols("oa-bose", 100, 2).unwrap_err().to_string();
        assert!(e.contains("81 (9^2) or 121 (11^2)"), "{e}");
        let e = symbols("oa-bush", 100, 3).unwrap_err().to_string();
        assert!(e.contains("64 (4^3) or 125 (5^3)"), "{e}");
        assert_eq!(symbols("oa-bose", 49, 2).unwrap(), 7);
        assert_eq!(symbols("oa-bush", 512, 3).unwrap(), 8);
    }
}
