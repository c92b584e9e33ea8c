//! Which sample counts a fixed-count sampler accepts ([`CountRule`]), and the count arithmetic
//! behind the rules (squares, powers of two, Fibonacci numbers), exact in integers. Every fixed-count constructor checks its count through its rule,
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
    /// so at least 1 and at most [`MAX_FIXED_COUNT`], for every `n`.
    ///
    /// [`check`]: CountRule::check
    pub fn nearest(&self, n: u64) -> u64 {
        self.nearest_within(n, MAX_FIXED_COUNT)
    }

    /// The allowed count nearest to `n` among those at most `max` (clamped to
    /// `1..=`[`MAX_FIXED_COUNT`]; the smaller one on a tie): a count
    /// [`check_within`](CountRule::check_within) accepts under the same `max`.
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
        // never a square above the limit
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
    }

    /// Every count a message suggests is one the same check accepts (messages once suggested
    /// squares and powers of two above the limit, and `2^25` for `2^26 - 1`).
    #[test]
    fn suggested_counts_are_allowed_under_the_same_limit() {
        let rules = [
            CountRule::Square,
            CountRule::PowerOfTwo,
            CountRule::Fibonacci,
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
}
