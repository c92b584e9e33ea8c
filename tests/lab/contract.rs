//! The core contract: values in [0,1) (never 1.0), determinism by seed, the float edge cases,
//! Kensler's permute, and the registry's errors.

use crate::common::take;
use strata::Sampler;
use strata::float::{ONE_MINUS_EPSILON, f32_in_stratum, unit_f32_from_f64, unit_f32_from_u32};
use strata::hash::{Permutation, permute};
use strata_lab::Error;
use strata_lab::registry::{self, Params};

#[test]
fn every_sampler_stays_in_the_unit_square() {
    for entry in registry::entries() {
        for n in [1u64, 4, 9, 10, 256, 1000, 4096] {
            // relaxation and best candidate are slow in unoptimised test builds
            if !entry.counts.allows(n) || (entry.expensive && n > 256) {
                continue;
            }
            for seed in [0, 1, u64::MAX] {
                let mut s = entry
                    .build(&Params::new(n).seed(strata::Seed(seed)))
                    .unwrap();
                for p in take(s.as_mut(), 3 * n as usize) {
                    assert!(
                        (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]),
                        "{} n={n}: {p:?}",
                        entry.name
                    );
                }
            }
        }
    }
}

#[test]
fn same_seed_same_bits_other_seed_other_bits() {
    for entry in registry::entries() {
        let n = entry.counts.nearest(64);
        let run = |seed| {
            let mut s = entry.build(&Params::new(n).seed(seed)).unwrap();
            take(s.as_mut(), 2 * n as usize)
                .iter()
                .flat_map(|p| [p[0].to_bits(), p[1].to_bits()])
                .collect::<Vec<u32>>()
        };
        assert_eq!(run(strata::Seed(5)), run(strata::Seed(5)), "{}", entry.name);
        if entry.name == "regular" {
            // Deterministic by definition: the seed is ignored.
            assert_eq!(run(strata::Seed(5)), run(strata::Seed(6)));
        } else {
            let (a, b) = (run(strata::Seed(5)), run(strata::Seed(6)));
            let same = a.iter().zip(&b).filter(|(x, y)| x == y).count();
            assert!(
                same < a.len() / 10,
                "{}: seeds 5 and 6 share {same} of {} values",
                entry.name,
                a.len()
            );
        }
    }
}

#[test]
fn naive_f32_stratum_arithmetic_reaches_one_and_ours_does_not() {
    // (i + u) / n in f32 with u the largest float below 1 rounds to 1.0 for the last stratum.
    let u = ONE_MINUS_EPSILON;
    let mut naive_hits = 0;
    for n in 2u32..2000 {
        let i = n - 1;
        if (i as f32 + u) / n as f32 == 1.0 {
            naive_hits += 1;
        }
        for uu in [u as f64, 1.0 - 2f64.powi(-32), 1.0 - 2f64.powi(-53)] {
            let x = f32_in_stratum(i as u64, n as u64, uu);
            assert!(x < 1.0, "n={n}");
            assert_eq!((x as f64 * n as f64).floor() as u32, i, "n={n} u={uu}");
        }
    }
    assert!(
        naive_hits > 100,
        "the edge case should be common (found {naive_hits})"
    );
}

#[test]
fn stratum_placement_is_exact_at_both_ends_of_every_stratum() {
    for n in [3u64, 7, 10, 49, 1000, 4097, 65535, 1 << 20, (1 << 23) - 1] {
        let ks = [0, 1, n / 3, n / 2, n - 2, n - 1];
        for k in ks {
            for u in [
                0.0,
                1e-12,
                2f64.powi(-32),
                0.5,
                1.0 - 2f64.powi(-32),
                1.0 - 1e-16,
            ] {
                let x = f32_in_stratum(k, n, u);
                let cell = (x as f64 * n as f64).floor() as u64;
                assert_eq!(cell, k, "n={n} k={k} u={u} -> {x}");
            }
        }
    }
}

#[test]
fn conversions_never_yield_one() {
    assert!(unit_f32_from_u32(u32::MAX) < 1.0);
    assert_eq!(unit_f32_from_f64(1.0 - 1e-17), ONE_MINUS_EPSILON);
    assert_eq!(unit_f32_from_f64(0.999_999_999_9), ONE_MINUS_EPSILON);
    let mut x = 0.0f64;
    while x < 1.0 {
        assert!(unit_f32_from_f64(x) < 1.0);
        x += 0.000_123_7;
    }
}

#[test]
fn permute_is_a_bijection_for_many_lengths_and_seeds() {
    let mut lengths: Vec<u32> = (1..=300).collect();
    lengths.extend([
        511, 512, 513, 1000, 1023, 1024, 1025, 4096, 65535, 65536, 65537, 100_003,
    ]);
    let seeds = [0u32, 1, 2, 0x1234_5678, 0xdead_beef, u32::MAX];
    let mut seen = Vec::new();
    for &l in &lengths {
        for &p in &seeds {
            seen.clear();
            seen.resize(l as usize, false);
            let perm = Permutation::new(l, p).unwrap();
            for i in 0..l {
                let v = perm.apply(i);
                assert!(v < l, "permute({i}, {l}, {p}) = {v}");
                assert!(!seen[v as usize], "permute(., {l}, {p}) repeats {v}");
                seen[v as usize] = true;
            }
        }
    }
}

#[test]
fn permute_depends_on_the_seed() {
    for l in [8u32, 100, 1000] {
        let a: Vec<u32> = (0..l).map(|i| permute(i, l, 1)).collect();
        let b: Vec<u32> = (0..l).map(|i| permute(i, l, 2)).collect();
        let fixed_points = a.iter().zip(&b).filter(|(x, y)| x == y).count();
        assert!(
            fixed_points < (l as usize / 4).max(3),
            "l={l}: {fixed_points} equal images"
        );
    }
}

#[test]
fn registry_errors_say_what_is_allowed() {
    match registry::build("nope", &Params::new(4)) {
        Err(Error::UnknownSampler { known, .. }) => assert!(known.contains(&"cmj")),
        other => panic!("expected UnknownSampler, got {:?}", other.map(|s| s.name())),
    }
    for name in ["regular", "jittered", "multijittered"] {
        let e = registry::build(name, &Params::new(10)).expect_err("10 is not a square");
        let msg = e.to_string();
        assert!(msg.contains("9 or 16"), "{msg}");
    }
    for name in ["cmj", "nrooks", "random"] {
        assert!(
            registry::build(name, &Params::new(10)).is_ok(),
            "{name} takes any count"
        );
        let e = registry::build(name, &Params::new(0)).expect_err("0 is refused");
        assert!(e.to_string().contains("0 samples"), "{e}");
    }
    let mut p = Params::new(16);
    p.set("radius", 0.5);
    let e = registry::build("jittered", &p).expect_err("jittered takes no radius");
    assert!(e.to_string().contains("radius"), "{e}");
}

#[test]
fn samplers_report_their_progression() {
    for entry in registry::entries() {
        let s = entry.build(&Params::new(entry.counts.nearest(16))).unwrap();
        assert_eq!(
            s.progression().is_progressive(),
            entry.progressive,
            "{}",
            entry.name
        );
        assert_eq!(s.name(), entry.name);
    }
}

#[test]
fn skip_lands_where_drawing_would_or_moves_nothing() {
    let mut skipping = Vec::new();
    for entry in registry::entries()
        .iter()
        .filter(|e| e.progressive && !e.expensive)
    {
        for k in [0u64, 1, 7, 1000, 4099] {
            let params = Params::new(64).seed(strata::Seed(5));
            let mut s = entry.build(&params).unwrap();
            let mut drawn = entry.build(&params).unwrap();
            take(drawn.as_mut(), k as usize);
            if s.skip(k) {
                skipping.push(entry.name);
                assert_eq!(
                    take(s.as_mut(), 33),
                    take(drawn.as_mut(), 33),
                    "{}: skip({k})",
                    entry.name
                );
            } else {
                let mut fresh = entry.build(&params).unwrap();
                assert_eq!(
                    take(s.as_mut(), 9),
                    take(fresh.as_mut(), 9),
                    "{}",
                    entry.name
                );
            }
        }
    }
    // the constant-time skips the docs promise (Python's fast_forward relies on them)
    for name in ["sobol", "lattice"] {
        assert!(skipping.contains(&name), "{name} does not skip");
    }
}
