//! Which sample counts a fixed-count sampler accepts ([`CountRule`]), and the count arithmetic
//! behind the rules (squares, powers of two, Fibonacci numbers, the `q^t` of an orthogonal
//! array), exact in integers. Every fixed-count constructor checks its count through its rule,
//! so that the message names the nearest counts allowed.

use core::fmt;

use crate::error::{Error, Result};
use crate::prelude::*;

/// The largest count a fixed-count sampler accepts (`2^31`: indices within a block, and the
/// `m n` fine strata of a multi-jittered grid, stay 32-bit). Far beyond what a set built in
/// advance is useful for; progressive samplers go further.
pub const MAX_FIXED_COUNT: u64 = 1 << 31;

/// Which sample counts a sampler accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CountRule {
    /// Any count `>= 1`.
    Any,
    /// Perfect squares `s^2`.
    Square,
    /// `q^t` for a prime `q` or a prime power `q <= 256` (orthogonal arrays of strength `t`).
    OaPower(u32),
    /// Fibonacci numbers `1, 2, 3, 5, 8, ...` (Fibonacci lattices).
    Fibonacci,
    /// Powers of two `2^m` (digital nets).
    PowerOfTwo,
}

impl CountRule {
    /// Whether `n` is allowed.
    pub fn allows(&self, n: u64) -> bool {
        match self {
            CountRule::Any => n >= 1,
            CountRule::Square => n >= 1 && n.isqrt().pow(2) == n,
            CountRule::OaPower(t) => oa_root(n, *t).is_some(),
            CountRule::Fibonacci => fibonacci_numbers().any(|f| f == n),
            CountRule::PowerOfTwo => n.is_power_of_two(),
        }
    }

    /// Checks a fixed-count sampler's count (also at most [`MAX_FIXED_COUNT`]): the count as
    /// `u32`, or an error naming `sampler` and the nearest allowed counts. Every fixed-count
    /// constructor checks its count through its entry's rule.
    pub fn check(&self, sampler: &'static str, count: u64) -> Result<u32> {
        if let CountRule::OaPower(t) = self {
            let q = check_oa_count(sampler, count, *t)?;
            return Ok(q.pow(*t));
        }
        if count == 0 || count > MAX_FIXED_COUNT {
            return Err(Error::count(
                sampler,
                count,
                format!("the count must be between 1 and {MAX_FIXED_COUNT}"),
            ));
        }
        if !self.allows(count) {
            let allowed = match self {
                CountRule::Square => format!(
                    "the count must be a perfect square (nearest allowed: {})",
                    nearest_squares(count)
                ),
                other => format!(
                    "allowed counts: {other} (nearest: {})",
                    other.nearest(count)
                ),
            };
            return Err(Error::count(sampler, count, allowed));
        }
        Ok(count as u32)
    }

    /// The allowed count nearest to `n` (the smaller one on a tie): a count [`check`] accepts,
    /// so at least 1 and at most [`MAX_FIXED_COUNT`], for every `n`.
    ///
    /// [`check`]: CountRule::check
    pub fn nearest(&self, n: u64) -> u64 {
        let n = n.clamp(1, MAX_FIXED_COUNT);
        match self {
            CountRule::Any => n,
            CountRule::Square => {
                let r = n.isqrt();
                let (lo, hi) = (r * r, (r + 1) * (r + 1));
                if hi > MAX_FIXED_COUNT || (lo >= 1 && n - lo <= hi - n) {
                    lo
                } else {
                    hi
                }
            }
            CountRule::OaPower(_) => {
                let all = self.counts_between(1, n.saturating_mul(4).max(1 << 12));
                all.min_by_key(|&c| c.abs_diff(n)).unwrap_or(4)
            }
            CountRule::Fibonacci => fibonacci_numbers()
                .min_by_key(|&f| f.abs_diff(n))
                .unwrap_or(1),
            CountRule::PowerOfTwo => {
                let lo = 1u64 << (63 - n.leading_zeros());
                if n - lo <= lo || lo << 1 > MAX_FIXED_COUNT {
                    lo
                } else {
                    lo << 1
                }
            }
        }
    }

    /// The allowed counts in `[min, max]`, in increasing order (none above
    /// [`MAX_FIXED_COUNT`], which [`check`](CountRule::check) refuses), one at a time: a range of
    /// `any N >= 1` may hold `2^31` of them, so nothing is collected here (`.take(k)` what you
    /// need).
    pub fn counts_between(&self, min: u64, max: u64) -> Box<dyn Iterator<Item = u64>> {
        let min = min.max(1);
        let max = max.min(MAX_FIXED_COUNT);
        if min > max {
            return Box::new(core::iter::empty());
        }
        match *self {
            CountRule::Any => Box::new(min..=max),
            CountRule::Square => {
                let lo = {
                    let r = min.isqrt();
                    if r * r == min { r } else { r + 1 }
                };
                Box::new((lo..=max.isqrt()).map(|s| s * s))
            }
            CountRule::OaPower(t) => Box::new(
                (2u64..)
                    .map_while(move |q| q.checked_pow(t).filter(|&c| c <= max).map(|c| (q, c)))
                    .filter(move |&(q, c)| c >= min && supported_symbols(q as u32))
                    .map(|(_, c)| c),
            ),
            CountRule::Fibonacci => {
                Box::new(fibonacci_numbers().filter(move |&f| f >= min && f <= max))
            }
            CountRule::PowerOfTwo => Box::new(
                (0..64)
                    .map(|m| 1u64 << m)
                    .filter(move |&c| c >= min && c <= max),
            ),
        }
    }
}

impl fmt::Display for CountRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CountRule::Any => f.write_str("any N >= 1"),
            CountRule::Square => f.write_str("perfect squares"),
            CountRule::OaPower(t) => write!(f, "q^{t}, q prime (power)"),
            CountRule::Fibonacci => f.write_str("Fibonacci numbers"),
            CountRule::PowerOfTwo => f.write_str("powers of two"),
        }
    }
}

// The count arithmetic of the rules, in integers (exact, and without `std`'s `powf`).

/// The Fibonacci numbers that fit a fixed-count set (`F_2 = 1` to below `2^31`).
pub(crate) fn fibonacci_numbers() -> impl Iterator<Item = u64> {
    core::iter::successors(Some((1u64, 2u64)), |&(a, b)| Some((b, a + b)))
        .map(|(a, _)| a)
        .take_while(|&f| f <= MAX_FIXED_COUNT)
}

/// The largest prime power (not prime) supported as the number of symbols of an orthogonal
/// array.
pub const MAX_PRIME_POWER: u32 = 256;

/// `(p, n)` when `q = p^n` with `p` prime, `n >= 1` (trial division up to `sqrt q`).
pub fn prime_power(q: u32) -> Option<(u32, u32)> {
    if q < 2 {
        return None;
    }
    let p = (2u32..)
        .take_while(|d| (*d as u64) * (*d as u64) <= q as u64)
        .find(|&d| q.is_multiple_of(d))
        .unwrap_or(q);
    let (mut m, mut n) = (q, 0);
    while m.is_multiple_of(p) {
        m /= p;
        n += 1;
    }
    (m == 1).then_some((p, n))
}

/// True when `q` is a supported number of symbols: a prime, or a prime power up to
/// [`MAX_PRIME_POWER`].
pub(crate) fn supported_symbols(q: u32) -> bool {
    prime_power(q).is_some_and(|(_, n)| n == 1 || q <= MAX_PRIME_POWER)
}

/// `floor(n^(1/t))` for `t >= 1`, exactly (bisection on `r^t <= n`).
fn root_floor(n: u64, t: u32) -> u64 {
    if t <= 1 || n < 2 {
        return n;
    }
    // r^t <= n < 2^64 gives r < 2^ceil(64/t)
    let (mut lo, mut hi) = (1u64, 1u64 << 64u32.div_ceil(t).min(63));
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if mid.checked_pow(t).is_some_and(|p| p <= n) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// `q` when `n = q^t` with a supported number of symbols `q`.
fn oa_root(n: u64, t: u32) -> Option<u64> {
    if t == 0 {
        return None;
    }
    let q = root_floor(n, t);
    let supported = u32::try_from(q).is_ok_and(supported_symbols);
    (q >= 2 && q.checked_pow(t) == Some(n) && supported).then_some(q)
}

/// The allowed symbol counts nearest to a requested sample count, for error messages: the
/// supported `q` with `q^t` just below and above `count`.
fn nearest_oa_counts(count: u64, t: u32) -> String {
    let supported = supported_symbols;
    let floor = root_floor(count, t);
    let ceil = if floor.checked_pow(t) == Some(count) {
        floor
    } else {
        floor + 1
    };
    let below = (2..=floor.max(2) as u32 + 1)
        .rev()
        .find(|&q| supported(q) && (q as u64).pow(t) <= count);
    let above = (ceil.max(2) as u32..).find(|&q| supported(q) && (q as u64).pow(t) >= count);
    match (below, above) {
        (Some(b), Some(a)) if b != a => format!(
            "{} ({b}^{t}) or {} ({a}^{t})",
            (b as u64).pow(t),
            (a as u64).pow(t)
        ),
        (_, Some(a)) => format!("{} ({a}^{t})", (a as u64).pow(t)),
        _ => "none".into(),
    }
}

/// Checks `count = q^t` for a supported `q`, returning `q` (the orthogonal arrays' check,
/// [`CountRule::OaPower`]).
pub(crate) fn check_oa_count(name: &'static str, count: u64, t: u32) -> Result<u32> {
    let rule = || {
        format!(
            "the count must be q^{t} for a prime q, or a prime power q <= {MAX_PRIME_POWER}, at most {MAX_FIXED_COUNT}"
        )
    };
    if count > MAX_FIXED_COUNT {
        // no search for the nearest counts up there: say the rule and the largest
        let largest = nearest_oa_counts(MAX_FIXED_COUNT, t);
        return Err(Error::count(
            name,
            count,
            format!("{} (the largest allowed are about {largest})", rule()),
        ));
    }
    match oa_root(count, t) {
        Some(q) if count >= 4 => Ok(q as u32),
        _ => Err(Error::count(
            name,
            count,
            format!(
                "{} (nearest allowed: {})",
                rule(),
                nearest_oa_counts(count, t)
            ),
        )),
    }
}

/// The perfect squares nearest to `n` (one if `n` is a square, else the one below and the one
/// above), for error messages.
pub(crate) fn nearest_squares(n: u64) -> String {
    let r = n.isqrt();
    if n == 0 {
        return "1".to_string();
    }
    if r * r == n {
        return format!("{n}");
    }
    format!("{} or {}", r * r, (r + 1) * (r + 1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_squares_brackets_the_count() {
        assert_eq!(nearest_squares(10), "9 or 16");
        assert_eq!(nearest_squares(16), "16");
        assert_eq!(nearest_squares(0), "1");
        assert_eq!(nearest_squares(2), "1 or 4");
    }

    #[test]
    fn count_rules_list_allowed_counts() {
        let list = |r: CountRule, a, b| r.counts_between(a, b).collect::<Vec<u64>>();
        assert_eq!(list(CountRule::Square, 2, 30), vec![4, 9, 16, 25]);
        assert_eq!(list(CountRule::Square, 16, 16), vec![16]);
        assert_eq!(list(CountRule::Any, 0, 3), vec![1, 2, 3]);
        assert!(list(CountRule::Square, 17, 24).is_empty());
        assert_eq!(CountRule::Square.nearest(1000), 1024);
        assert_eq!(CountRule::Square.nearest(12), 9);
        assert_eq!(CountRule::Square.nearest(0), 1);
        assert_eq!(CountRule::Any.nearest(7), 7);
        assert!(CountRule::Square.check("jittered", 10).is_err());
        assert_eq!(CountRule::Square.check("jittered", 9).unwrap(), 9);
        let f: Vec<u64> = fibonacci_numbers().take(10).collect();
        assert_eq!(f, [1, 2, 3, 5, 8, 13, 21, 34, 55, 89]);
        assert_eq!(list(CountRule::OaPower(3), 60, 130), vec![64, 125]);
    }

    #[test]
    fn integer_roots_are_exact() {
        let edges = [
            u32::MAX as u64,
            MAX_FIXED_COUNT,
            1 << 53,
            (1 << 53) + 1,
            u64::MAX - 1,
            u64::MAX,
        ];
        for t in 1..=70u32 {
            for n in (0..3000u64).chain(edges) {
                let r = root_floor(n, t);
                assert!(
                    r.checked_pow(t).is_some_and(|p| p <= n),
                    "{n}^(1/{t}) = {r}"
                );
                let above = r.checked_add(1).and_then(|r| r.checked_pow(t));
                assert!(above.is_none_or(|p| p > n), "{n}^(1/{t}) = {r}");
            }
        }
        for t in 2..=16u32 {
            for q in [2u64, 3, 5, 255, 256, 65521, 4_294_967_291] {
                if let Some(n) = q.checked_pow(t) {
                    assert_eq!(root_floor(n, t), q);
                    assert_eq!(root_floor(n - 1, t), q - 1);
                }
            }
        }
    }

    #[test]
    fn the_oa_rule_is_the_rounded_float_root_it_replaced() {
        // the rule as it was computed before it moved here, with `powf` (tests have `std`):
        // the same answer on every count next to a power, for every strength the arrays take
        let float_root = |n: u64, t: u32| (n as f64).powf(1.0 / t as f64).round() as u64;
        for t in 2..=16u32 {
            for q in 2u64.. {
                let Some(c) = q.checked_pow(t).filter(|&c| c <= MAX_FIXED_COUNT + 1) else {
                    break;
                };
                for n in [c - 1, c, c + 1] {
                    let q = float_root(n, t);
                    let old = q >= 2 && q.checked_pow(t) == Some(n) && supported_symbols(q as u32);
                    assert_eq!(oa_root(n, t).is_some(), old, "{n} = q^{t}");
                    if old && n >= 4 {
                        assert_eq!(check_oa_count("x", n, t).unwrap() as u64, q);
                    }
                }
            }
        }
    }
}
