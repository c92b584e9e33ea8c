//! Which sample counts a sampler of the lab accepts ([`CountRule`]): the renderer crate's rules
//! ([`strata::counts::CountRule`]: any count, squares, Fibonacci numbers, powers of two) and the
//! orthogonal arrays' `q^t` (Bose 1938, Bush 1952: `q` symbols, a prime or a prime power, and
//! strength `t`), exact in integers. Every fixed-count constructor checks its count through its
//! entry's rule, so that the message names the nearest counts allowed.

use std::fmt;

use strata::counts::{CountRule as Rule, MAX_FIXED_COUNT};

use crate::{Error, Result};

/// Which sample counts a sampler accepts: the renderer crate's rules, and `q^t`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum CountRule {
    /// Any count `>= 1`.
    Any,
    /// Perfect squares `s^2`.
    Square,
    /// `q^t` for a prime `q` or a prime power `q <=` [`MAX_PRIME_POWER`] (orthogonal arrays of
    /// strength `t`).
    OaPower(u32),
    /// Fibonacci numbers `1, 2, 3, 5, 8, ...` (Fibonacci lattices).
    Fibonacci,
    /// Powers of two `2^m` (digital nets).
    PowerOfTwo,
}

impl CountRule {
    /// The renderer crate's rule (`Ok`), or the strength `t` of `OaPower(t)` (`Err`).
    fn strata(self) -> std::result::Result<Rule, u32> {
        match self {
            CountRule::Any => Ok(Rule::Any),
            CountRule::Square => Ok(Rule::Square),
            CountRule::Fibonacci => Ok(Rule::Fibonacci),
            CountRule::PowerOfTwo => Ok(Rule::PowerOfTwo),
            CountRule::OaPower(t) => Err(t),
        }
    }

    /// Whether `n` is allowed.
    pub fn allows(&self, n: u64) -> bool {
        match self.strata() {
            Ok(rule) => rule.allows(n),
            Err(t) => {
                (1..=MAX_OA_STRENGTH).contains(&t)
                    && (4..=MAX_FIXED_COUNT).contains(&n)
                    && oa_root(n, t).is_some()
            }
        }
    }

    /// Checks a fixed-count sampler's count (also at most [`MAX_FIXED_COUNT`]): the count as
    /// `u32`, or an error naming `sampler` and the nearest allowed counts.
    pub fn check(&self, sampler: &'static str, count: u64) -> Result<u32> {
        self.check_within(sampler, count, MAX_FIXED_COUNT)
    }

    /// [`check`](CountRule::check) for a caller with a lower limit of its own (a program's
    /// largest count): counts above `max` (clamped to `1..=`[`MAX_FIXED_COUNT`]) are refused,
    /// and the counts the message suggests are all at most `max`.
    pub fn check_within(&self, sampler: &'static str, count: u64, max: u64) -> Result<u32> {
        match self.strata() {
            Ok(rule) => Ok(rule.check_within(sampler, count, max)?),
            Err(t) => {
                let q = check_oa_count(sampler, count, t, max.clamp(1, MAX_FIXED_COUNT))?;
                Ok(q.pow(t))
            }
        }
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
        let t = match self.strata() {
            Ok(rule) => return rule.nearest_within(n, max),
            Err(t) => t,
        };
        if !(1..=MAX_OA_STRENGTH).contains(&t) {
            return 1;
        }
        let max = max.clamp(1, MAX_FIXED_COUNT);
        let n = n.clamp(1, max);
        let power = |q: u32| (q as u64).pow(t);
        match oa_bracket(n, t, max) {
            (Some(b), Some(a)) => {
                let (lo, hi) = (power(b), power(a));
                if n - lo <= hi - n { lo } else { hi }
            }
            (Some(b), None) => power(b),
            (None, Some(a)) => power(a),
            // nothing at most `max` (a limit below the smallest count): the smallest
            (None, None) => (2u64..)
                .filter(|&q| supported_symbols(q as u32))
                .map(|q| q.pow(t))
                .find(|&c| c >= 4)
                .unwrap_or(4),
        }
    }

    /// The allowed counts in `[min, max]`, in increasing order (none above
    /// [`MAX_FIXED_COUNT`], which [`check`](CountRule::check) refuses), one at a time
    /// (`.take(k)` what you need).
    pub fn counts_between(&self, min: u64, max: u64) -> Box<dyn Iterator<Item = u64>> {
        let t = match self.strata() {
            Ok(rule) => return rule.counts_between(min, max),
            Err(t) => t,
        };
        let (min, max) = (min.max(4), max.min(MAX_FIXED_COUNT));
        if min > max || !(1..=MAX_OA_STRENGTH).contains(&t) {
            return Box::new(std::iter::empty());
        }
        Box::new(
            (2u64..)
                .map_while(move |q| q.checked_pow(t).filter(|&c| c <= max).map(|c| (q, c)))
                .filter(move |&(q, c)| c >= min && supported_symbols(q as u32))
                .map(|(_, c)| c),
        )
    }
}

impl fmt::Display for CountRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.strata() {
            Ok(rule) => rule.fmt(f),
            Err(t) => write!(f, "q^{t}, q prime (power)"),
        }
    }
}

// The count arithmetic of `q^t`, in integers (exact, without `powf`).

/// The largest prime power (not prime) supported as the number of symbols of an orthogonal
/// array.
pub const MAX_PRIME_POWER: u32 = 256;

/// `(p, n)` when `q = p^n` with `p` prime, `n >= 1` (trial division up to `sqrt q`).
pub(crate) fn prime_power(q: u32) -> Option<(u32, u32)> {
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

/// The largest strength `t` of [`CountRule::OaPower`] that allows a count (`2^31`, the
/// largest fixed count, is `2^t` for `t = 31`); strengths 0 and above it allow none.
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_renderer_crate_s_rules_read_the_same_through_the_lab() {
        let pairs = [
            (CountRule::Any, Rule::Any),
            (CountRule::Square, Rule::Square),
            (CountRule::Fibonacci, Rule::Fibonacci),
            (CountRule::PowerOfTwo, Rule::PowerOfTwo),
        ];
        for (lab, rule) in pairs {
            assert_eq!(lab.strata(), Ok(rule));
            assert_eq!(lab.to_string(), rule.to_string());
            for n in [0u64, 1, 2, 10, 16, 21, 1000, 1 << 31, u64::MAX] {
                assert_eq!(lab.allows(n), rule.allows(n), "{rule} {n}");
                assert_eq!(lab.nearest(n), rule.nearest(n), "{rule} {n}");
                assert_eq!(
                    lab.check("x", n).map_err(|e| e.to_string()),
                    rule.check("x", n).map_err(|e| e.to_string())
                );
            }
        }
        let list = |r: CountRule, a, b| r.counts_between(a, b).collect::<Vec<u64>>();
        assert_eq!(list(CountRule::OaPower(3), 60, 130), vec![64, 125]);
        assert_eq!(list(CountRule::OaPower(2), 0, 10), vec![4, 9]);
    }

    /// Every count a message suggests is one the same check accepts (messages once suggested
    /// `q^t` above the limit).
    #[test]
    fn suggested_counts_are_allowed_under_the_same_limit() {
        for rule in [2, 3, 4].map(CountRule::OaPower) {
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

    /// Strengths that allow no count, and strength 1 at the largest counts (strengths
    /// once misbehaved: `OaPower(0).nearest` never returned, `OaPower(1)` searched
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
