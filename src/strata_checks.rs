//! Statistical checks of the renderer crate's stateless functions that need the lab's
//! statistics (its chi-square tails): they live here, beside `stats`, rather than in `strata`.

use strata::hash::mix64;
use strata::samplers::halton::{PRIMES, scrambled_radical_inverse};

use crate::stats::chi_square_upper;

/// The worst p-value, over dimensions and index pairs that share their first `k` digits,
/// of a chi-square test that the pair's digits below the shared ones and the one after
/// them (distinct digits under one permutation) are independent across seeds.
fn sibling_independence_p(value: impl Fn(u64, usize, u64) -> f32) -> f64 {
    let (seeds, g) = (12_000u64, 8usize);
    let mut worst = 1.0f64;
    for dim in [1usize, 2, 4, 15] {
        let b = PRIMES[dim] as u64;
        for shared in 0..4u32 {
            let bk = b.pow(shared);
            if bk * b * g as u64 > 1 << 21 {
                continue; // past what an f32's digits resolve
            }
            for (i, j) in [(1u64, 1 + bk), (2, 2 + 2 * bk), (0, bk * (b - 1))] {
                let mut counts = vec![0u32; g * g];
                let below = |x: f32| ((x as f64 * (bk * b) as f64).fract() * g as f64) as usize;
                for s in 0..seeds {
                    let cx = below(value(i, dim, s)).min(g - 1);
                    let cy = below(value(j, dim, s)).min(g - 1);
                    counts[cx * g + cy] += 1;
                }
                let e = seeds as f64 / (g * g) as f64;
                let chi: f64 = counts.iter().map(|&c| (c as f64 - e).powi(2) / e).sum();
                worst = worst.min(chi_square_upper(chi, (g * g - 1) as f64));
            }
        }
    }
    worst
}

/// About 40 cases at 1e-6 each: a false alarm once in 25 000 runs.
const SIBLING_ALPHA: f64 = 1e-6;

#[test]
fn sibling_digits_are_scrambled_independently() {
    let p = sibling_independence_p(|i, dim, s| {
        scrambled_radical_inverse(i, dim as u32, strata::Seed(s)).unwrap()
    });
    assert!(p > SIBLING_ALPHA, "worst p {p:e}");
}

#[test]
fn a_random_shift_fails_the_sibling_test() {
    // Cranley-Patterson rotation of the plain radical inverse: uniform points whose deeper
    // digits are tied across indices, the flaw the nested scramble exists to remove
    let shifted = |mut i: u64, dim: usize, seed: u64| {
        let b = PRIMES[dim] as u64;
        let (mut x, mut w) = (0f64, 1f64);
        while i > 0 {
            w /= b as f64;
            x += (i % b) as f64 * w;
            i /= b;
        }
        let u = (mix64(seed ^ dim as u64) >> 11) as f64 / (1u64 << 53) as f64;
        ((x + u).fract()) as f32
    };
    assert!(sibling_independence_p(shifted) < SIBLING_ALPHA);
}
