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
            CountRule::OaPower(t) => {
                (1..=MAX_OA_STRENGTH).contains(t)
                    && (4..=MAX_FIXED_COUNT).contains(&n)
                    && oa_root(n, *t).is_some()
            }
            CountRule::Fibonacci => fibonacci_numbers().any(|f| f == n),
            CountRule::PowerOfTwo => n.is_power_of_two(),
        }
    }

    /// Checks a fixed-count sampler's count (also at most [`MAX_FIXED_COUNT`]): the count as
    /// `u32`, or an error naming `sampler` and the nearest allowed counts. Every fixed-count
    /// constructor checks its count through its entry's rule.
    pub fn check(&self, sampler: &'static str, count: u64) -> Result<u32> {
        self.check_within(sampler, count, MAX_FIXED_COUNT)
    }

    /// [`check`](CountRule::check) for a caller with a lower limit of its own (a program's
    /// largest count): counts above `max` (clamped to `1..=`[`MAX_FIXED_COUNT`]) are refused,
    /// and the counts the message suggests are all at most `max`.
    pub fn check_within(&self, sampler: &'static str, count: u64, max: u64) -> Result<u32> {
        let max = max.clamp(1, MAX_FIXED_COUNT);
        if let CountRule::OaPower(t) = self {
            let q = check_oa_count(sampler, count, *t, max)?;
            return Ok(q.pow(*t));
        }
        if count == 0 || (count > max && *self == CountRule::Any) {
            return Err(Error::count(
                sampler,
                count,
                format!("the count must be between 1 and {max}"),
            ));
        }
        if count > max || !self.allows(count) {
            let at_most = if count > max {
                format!(", at most {max}")
            } else {
                String::new()
            };
            let allowed = match self {
                CountRule::Square => format!(
                    "the count must be a perfect square{at_most} (nearest allowed: {})",
                    nearest_squares(count, max)
                ),
                other => format!(
                    "allowed counts: {other}{at_most} (nearest: {})",
                    other.nearest_within(count, max)
                ),
            };
            return Err(Error::count(sampler, count, allowed));
        }
        Ok(count as u32)
    }

    /// The allowed count nearest to `n` (the smaller one on a tie): a count [`check`] accepts,
    /// so at least 1 and at most [`MAX_FIXED_COUNT`], for every `n` (but for `OaPower(t)` with
    /// `t` 0 or above [`MAX_OA_STRENGTH`], which allows no count: 1).
    ///
    /// [`check`]: CountRule::check
    pub fn nearest(&self, n: u64) -> u64 {
        self.nearest_within(n, MAX_FIXED_COUNT)
    }

    /// The allowed count nearest to `n` among those at most `max` (clamped to
    /// `1..=`[`MAX_FIXED_COUNT`]; the smaller one on a tie): a count
    /// [`check_within`](CountRule::check_within) accepts under the same `max`, whenever one
    /// is allowed. When none is (`OaPower(t)` with a `max` below its smallest count, `4` or
    /// `2^t`), the smallest allowed count, which is above `max`.
    pub fn nearest_within(&self, n: u64, max: u64) -> u64 {
        let max = max.clamp(1, MAX_FIXED_COUNT);
        let n = n.clamp(1, max);
        // of two allowed counts `lo <= n <= hi`, the nearer one (`hi` only when allowed)
        let pick = |lo: u64, hi: u64| {
            if hi > max || (lo >= 1 && n - lo <= hi - n) {
                lo
            } else {
                hi
            }
        };
        match self {
            CountRule::Any => n,
            CountRule::Square => {
                let r = n.isqrt();
                pick(r * r, (r + 1) * (r + 1))
            }
            CountRule::OaPower(t) if !(1..=MAX_OA_STRENGTH).contains(t) => 1,
            CountRule::OaPower(t) => {
                let power = |q: u32| (q as u64).pow(*t);
                match oa_bracket(n, *t, max) {
                    (Some(b), Some(a)) => {
                        let (lo, hi) = (power(b), power(a));
                        if n - lo <= hi - n { lo } else { hi }
                    }
                    (Some(b), None) => power(b),
                    (None, Some(a)) => power(a),
                    // nothing at most `max` (a limit below the smallest count): the smallest
                    (None, None) => (2u64..)
                        .filter(|&q| supported_symbols(q as u32))
                        .map(|q| q.pow(*t))
                        .find(|&c| c >= 4)
                        .unwrap_or(4),
                }
            }
            CountRule::Fibonacci => fibonacci_numbers()
                .take_while(|&f| f <= max)
                .min_by_key(|&f| f.abs_diff(n))
                .unwrap_or(1),
            CountRule::PowerOfTwo => {
                let lo = 1u64 << (63 - n.leading_zeros());
                pick(lo, lo << 1)
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
            CountRule::OaPower(t) if !(1..=MAX_OA_STRENGTH).contains(&t) => {
                Box::new(core::iter::empty())
            }
            CountRule::OaPower(t) => Box::new(
                (2u64..)
                    .map_while(move |q| q.checked_pow(t).filter(|&c| c <= max).map(|c| (q, c)))
                    .filter(move |&(q, c)| c >= min.max(4) && supported_symbols(q as u32))
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

/// The supported `q` with `q^t` at most `count`, and the one with `q^t` at least `count` and
/// at most `max` (each `None` where there is none), for strengths `t` from 1 to
/// [`MAX_OA_STRENGTH`]: a walk from the `t`-th root to the nearest supported `q` on each side
/// (primes are dense: a few hundred steps at most below `2^31`).
fn oa_bracket(count: u64, t: u32, max: u64) -> (Option<u32>, Option<u32>) {
    let floor = root_floor(count, t).min(u32::MAX as u64) as u32;
    let ceil = if (floor as u64).checked_pow(t) == Some(count) {
        floor
    } else {
        floor.saturating_add(1)
    };
    let power = |q: u32| (q as u64).checked_pow(t);
    let below = (2..=floor.max(1))
        .rev()
        .find(|&q| supported_symbols(q) && power(q).is_some_and(|c| (4..=count).contains(&c)));
    let above = (ceil.max(2)..)
        .map_while(|q| power(q).filter(|&c| c <= max).map(|_| q))
        .find(|&q| supported_symbols(q) && power(q).is_some_and(|c| c >= 4));
    (below, above)
}

/// The largest strength `t` of [`CountRule::OaPower`] that allows a count (`2^31` is the
/// largest count, and `q >= 2`); strengths 0 and above it allow none.
pub const MAX_OA_STRENGTH: u32 = 31;

/// The allowed symbol counts nearest to a requested sample count, for error messages: the
/// supported `q` with `q^t` just below and above `count` (the one above only up to `max`).
fn nearest_oa_counts(count: u64, t: u32, max: u64) -> String {
    let show = |q: u32| format!("{} ({q}^{t})", (q as u64).pow(t));
    match oa_bracket(count, t, max) {
        (Some(b), Some(a)) if b != a => format!("{} or {}", show(b), show(a)),
        (_, Some(a)) => show(a),
        (Some(b), None) => show(b),
        (None, None) => "none".into(),
    }
}

/// Checks `count = q^t` for a supported `q` and `count <= max`, returning `q` (the orthogonal
/// arrays' check, [`CountRule::OaPower`]).
fn check_oa_count(name: &'static str, count: u64, t: u32, max: u64) -> Result<u32> {
    if !(1..=MAX_OA_STRENGTH).contains(&t) {
        return Err(Error::count(
            name,
            count,
            format!(
                "an orthogonal array of strength {t} has no count: strengths are 1 to \
                 {MAX_OA_STRENGTH}"
            ),
        ));
    }
    // the limit is named when it is what refuses the count (the rest of the message is the
    // same for callers with different limits)
    let rule = || {
        let at_most = if count > max {
            format!(", at most {max}")
        } else {
            String::new()
        };
        format!(
            "the count must be q^{t} for a prime q, or a prime power q <= {MAX_PRIME_POWER}{at_most}"
        )
    };
    if count > max {
        // no search for the nearest counts up there: say the rule and the largest
        let largest = match oa_bracket(max, t, max) {
            (None, None) => format!("no count of strength {t} is at most {max}"),
            _ => format!(
                "the largest allowed are about {}",
                nearest_oa_counts(max, t, max)
            ),
        };
        return Err(Error::count(name, count, format!("{} ({largest})", rule())));
    }
    match oa_root(count, t) {
        Some(q) if count >= 4 => Ok(q as u32),
        _ => Err(Error::count(
            name,
            count,
            format!(
                "{} (nearest allowed: {})",
                rule(),
                nearest_oa_counts(count, t, max)
            ),
        )),
    }
}

/// The perfect squares at most `max` nearest to `n` (`n` if it is one, else the one below and
/// the one above), for error messages.
pub(crate) fn nearest_squares(n: u64, max: u64) -> String {
    let r = n.isqrt();
    if r * r == n && (1..=max).contains(&n) {
        return format!("{n}");
    }
    let below = r.min(max.isqrt());
    let above = (r + 1).checked_mul(r + 1).filter(|&a| a <= max);
    match (below, above) {
        (0, Some(a)) => format!("{a}"),
        (b, Some(a)) => format!("{} or {a}", b * b),
        (b, None) => format!("{}", (b * b).max(1)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_squares_brackets_the_count() {
        let m = MAX_FIXED_COUNT;
        assert_eq!(nearest_squares(10, m), "9 or 16");
        assert_eq!(nearest_squares(16, m), "16");
        assert_eq!(nearest_squares(0, m), "1");
        assert_eq!(nearest_squares(2, m), "1 or 4");
        // issue 38, N17: never a square above the limit
        assert_eq!(nearest_squares(m - 1, m), "2147395600");
        assert_eq!(nearest_squares(u64::MAX, m), "2147395600");
        assert_eq!(nearest_squares(20, 16), "16");
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
                        assert_eq!(
                            check_oa_count("x", n, t, MAX_FIXED_COUNT).unwrap() as u64,
                            q
                        );
                    }
                }
            }
        }
    }

    /// Every count a message suggests is one the same check accepts (issue 38, N17: messages
    /// suggested squares, powers of two and `q^t` above the limit, and `2^25` for `2^26 - 1`).
    #[test]
    fn suggested_counts_are_allowed_under_the_same_limit() {
        let rules = [
            CountRule::Square,
            CountRule::PowerOfTwo,
            CountRule::Fibonacci,
            CountRule::OaPower(2),
            CountRule::OaPower(3),
            CountRule::OaPower(4),
        ];
        for rule in rules {
            for max in [1 << 12, 1 << 26, 1000, MAX_FIXED_COUNT] {
                for count in [max - 1, max + 1, max, 3 * max / 4, u64::MAX, 1 << 40, 2, 5] {
                    let Err(e) = rule.check_within("x", count, max) else {
                        continue;
                    };
                    let message = e.to_string();
                    let at = ["(nearest", "about"].iter().find_map(|w| message.find(w));
                    let tail = &message[at.expect(&message)..];
                    let suggested: Vec<u64> = tail
                        .split(|c: char| !c.is_ascii_digit() && c != '^')
                        .filter(|w| !w.is_empty() && !w.contains('^'))
                        .filter_map(|w| w.parse().ok())
                        .collect();
                    assert!(!suggested.is_empty(), "{message}");
                    for c in suggested.iter().filter(|&&c| c > 256) {
                        assert!(
                            rule.check_within("x", *c, max).is_ok(),
                            "{rule} under {max}, {count}: suggests {c}: {message}"
                        );
                    }
                }
            }
            let n = rule.nearest_within(u64::MAX, 1 << 26);
            assert!(rule.check_within("x", n, 1 << 26).is_ok(), "{rule}: {n}");
        }
        assert_eq!(CountRule::PowerOfTwo.nearest((1 << 26) - 1), 1 << 26);
        assert_eq!(CountRule::PowerOfTwo.nearest(5), 4);
        assert_eq!(CountRule::PowerOfTwo.nearest(6), 4);
        assert_eq!(CountRule::PowerOfTwo.nearest(7), 8);
    }

    /// Strengths that allow no count, and strength 1 at the largest counts (the second
    /// hostile pass of issue 38: `OaPower(0).nearest` never returned, `OaPower(1)` searched
    /// 2^31 candidates, `OaPower(40)` suggested 4, `OaPower(u32::MAX)` wrapped).
    #[test]
    fn every_strength_answers_at_once() {
        for t in [0u32, 32, 40, u32::MAX] {
            let r = CountRule::OaPower(t);
            assert_eq!(r.nearest(5), 1);
            assert_eq!(r.nearest(u64::MAX), 1);
            assert!(!r.allows(4) && !r.allows(1 << 31));
            assert_eq!(r.counts_between(1, u64::MAX).count(), 0);
            let e = r.check("x", 5).unwrap_err().to_string();
            assert!(e.contains("strengths are 1 to 31"), "{e}");
        }
        let one = CountRule::OaPower(1);
        for n in [1u64, 5, 1000, 1 << 31, u64::MAX] {
            let c = one.nearest(n);
            assert!(one.check("x", c).is_ok(), "{n}: {c}");
        }
        assert_eq!(one.nearest(1 << 31), 2_147_483_647); // the largest prime below 2^31
        assert_eq!(CountRule::OaPower(31).nearest(5), 1 << 31);
        for t in 2..=31 {
            let r = CountRule::OaPower(t);
            for n in [0u64, 1, 3, 100, 1 << 20, MAX_FIXED_COUNT, u64::MAX] {
                let c = r.nearest(n);
                assert!(r.check("x", c).is_ok(), "t {t}, {n}: {c}");
            }
        }
    }
}
