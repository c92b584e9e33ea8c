//! Spectra against theory and against the direct sum: the fast path equals the reference,
//! random sampling is white, jittered sampling matches its closed form, regular sampling peaks
//! on its lattice, DC is N, the expected spectrum does not depend on the thread count, and the
//! files read back as written.

use crate::common::take;
use strata_lab::registry::{self, Params};
use strata_lab::spectrum::{self, Spectrum, expected_spectrum, periodogram, periodogram_direct};

fn set(name: &str, n: u64, seed: u64) -> Vec<[f32; 2]> {
    let mut s = registry::build(name, &Params::new(n).seed(strata::Seed(seed))).unwrap();
    take(s.as_mut(), n as usize)
}

fn max_abs_diff(a: &Spectrum, b: &Spectrum) -> f64 {
    a.values()
        .iter()
        .zip(b.values())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn fast_equals_direct_within_1e_minus_6_everywhere() {
    let cases: Vec<(&str, Vec<[f32; 2]>, u32)> = vec![
        ("random", set("random", 700, 3), 48),
        ("jittered", set("jittered", 1024, 4), 64),
        // regular: |F| = N at the lattice peaks, the hardest case for absolute accuracy
        ("regular", set("regular", 1024, 1), 96),
        ("regular-4096", set("regular", 4096, 1), 130),
        ("cmj", set("cmj", 2000, 5), 40),
        ("one point", vec![[0.123, 0.987]], 32),
        ("coincident", vec![[0.5, 0.25]; 64], 16),
        (
            "corners",
            vec![
                [0.0f32; 2],
                [0.999_999_94, 0.999_999_94],
                [0.0, 0.999_999_94],
            ],
            20,
        ),
    ];
    for (what, pts, k) in cases {
        let fast = periodogram(&pts, k).unwrap();
        let direct = periodogram_direct(&pts, k).unwrap();
        let err = max_abs_diff(&fast, &direct);
        assert!(err < 1e-6, "{what}: max |fast - direct| = {err:e}");
    }
}

#[test]
fn dc_is_n() {
    for (name, n) in [("random", 100u64), ("jittered", 256), ("cmj", 77)] {
        let pts = set(name, n, 9);
        let s = periodogram(&pts, 16).unwrap();
        assert!(
            (s.get(0, 0).unwrap() - n as f64).abs() < 1e-6 * n as f64,
            "{name}"
        );
    }
}

#[test]
fn random_sampling_is_white_noise() {
    // E[P(w)] = 1 for w != 0; each periodogram value is close to exponentially distributed, and
    // P(w) = P(-w), so a radial bin of c frequencies over R sets averages about c R / 2
    // independent values: its standard error is sqrt(2 / (c R)).
    let (n, r, k) = (256u64, 200u32, 64u32);
    let s = expected_spectrum(r, k, |i| Ok(set("random", n, 1000 + i as u64))).unwrap();
    for bin in s.radial() {
        let se = (2.0 / (bin.count as f64 * r as f64)).sqrt();
        assert!(
            (bin.power - 1.0).abs() < 5.0 * se,
            "bin {}: mean {} is more than 5 standard errors ({se}) from 1",
            bin.frequency,
            bin.power
        );
        // One flat periodogram per frequency averaged over R: anisotropy near -10 log10(R).
        let expected = -10.0 * (r as f64).log10();
        if bin.count > 100 {
            assert!(
                (bin.anisotropy - expected).abs() < 1.5,
                "bin {}: anisotropy {}",
                bin.frequency,
                bin.anisotropy
            );
        }
    }
}

fn sinc(x: f64) -> f64 {
    if x == 0.0 {
        1.0
    } else {
        (std::f64::consts::PI * x).sin() / (std::f64::consts::PI * x)
    }
}

#[test]
fn jittered_matches_the_closed_form() {
    // Subr and Kautz 2013: for an s x s jittered grid, E[P(w)] = 1 - sinc^2(u/s) sinc^2(v/s) for w != 0.
    let (s, r, k) = (8u32, 1500u32, 48u32);
    let n = (s * s) as u64;
    let spec = expected_spectrum(r, k, |i| Ok(set("jittered", n, 50 + i as u64))).unwrap();
    let h = (k / 2) as i32;
    let mut worst = 0.0f64;
    let (mut sum_obs, mut sum_theory) = (0.0, 0.0);
    for v in -h..=h {
        for u in -h..=h {
            if u == 0 && v == 0 {
                continue;
            }
            let theory = 1.0 - (sinc(u as f64 / s as f64) * sinc(v as f64 / s as f64)).powi(2);
            let got = spec.get(u, v).unwrap();
            // The mean of R near-exponential values with mean `theory` has standard error
            // theory / sqrt(R); allow 6 of them plus a floor for theory ~ 0 near DC.
            let tol = 6.0 * theory / (r as f64).sqrt() + 2e-3;
            worst = worst.max((got - theory).abs() / tol);
            assert!(
                (got - theory).abs() < tol,
                "({u}, {v}): {got} vs theory {theory}"
            );
            sum_obs += got;
            sum_theory += theory;
        }
    }
    // And over the whole grid the average is far tighter.
    let m = ((2 * h + 1) * (2 * h + 1) - 1) as f64;
    assert!(
        ((sum_obs - sum_theory) / m).abs() < 0.01,
        "grid mean differs: {} vs {}",
        sum_obs / m,
        sum_theory / m
    );
    assert!(worst < 1.0);
}

#[test]
fn regular_sampling_peaks_on_its_lattice() {
    // Cell centres of an s x s grid: P = N exactly at multiples of s on both axes, 0 elsewhere.
    let s = 12i32;
    let n = (s * s) as u64;
    let spec = periodogram(&set("regular", n, 1), 60).unwrap();
    for v in -30..=30 {
        for u in -30..=30 {
            let p = spec.get(u, v).unwrap();
            if u % s == 0 && v % s == 0 {
                assert!(
                    (p - n as f64).abs() < 1e-6,
                    "({u}, {v}): {p}, expected a peak of {n}"
                );
            } else {
                assert!(p.abs() < 1e-6, "({u}, {v}): {p}, expected 0");
            }
        }
    }
}

#[test]
fn expected_spectrum_is_bit_identical_for_any_thread_count() {
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| expected_spectrum(37, 32, |i| Ok(set("cmj", 300, i as u64))).unwrap())
    };
    let (a, b, c) = (run(1), run(2), run(3));
    let bits = |s: &Spectrum| s.values().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(bits(&a), bits(&c));
}

#[test]
fn bad_input_gives_clear_errors() {
    let ok = vec![[0.5, 0.5]];
    let msg = |r: Result<Spectrum, strata_lab::Error>| r.expect_err("must fail").to_string();
    assert!(msg(periodogram(&[], 8)).contains("empty"));
    assert!(msg(periodogram(&[[f32::NAN, 0.1]], 8)).contains("[0, 1)"));
    assert!(msg(periodogram(&[[1.0, 0.1]], 8)).contains("[0, 1)"));
    assert!(msg(periodogram(&[[-0.1, 0.1]], 8)).contains("[0, 1)"));
    assert!(msg(periodogram(&ok, 0)).contains("even"));
    assert!(msg(periodogram(&ok, 7)).contains("even"));
    assert!(msg(periodogram(&ok, 1 << 20)).contains("even"));
    assert!(msg(periodogram_direct(&ok, 9)).contains("even"));
    assert!(msg(expected_spectrum(0, 8, |_| Ok(ok.clone()))).contains("realizations"));
    let uneven = expected_spectrum(3, 8, |i| Ok(vec![[0.5, 0.5]; 1 + i as usize]));
    assert!(msg(uneven).contains("same count"));
    assert!(spectrum::point_set_measures(&[]).is_err());
}

#[test]
fn point_set_measures_match_known_values() {
    // Random points: the mean nearest-neighbour distance of a Poisson process of density N is
    // 1 / (2 sqrt N), i.e. 0.465 r_max; no empty disc around DC, so nu_eff = 0.
    let sets: Vec<Vec<[f32; 2]>> = (0..8).map(|i| set("random", 2048, 77 + i)).collect();
    let m = spectrum::point_set_measures(&sets).unwrap();
    assert!(
        (m.average_min_distance.unwrap() - 0.4653).abs() < 0.01,
        "{m:?}"
    );
    assert!(m.global_min_distance.unwrap() < 0.1, "{m:?}");
    assert_eq!(m.effective_nyquist, Some(0.0));
    // Jittered sets have an emptier low band than random ones, so a larger nu_eff.
    let jit: Vec<Vec<[f32; 2]>> = (0..8).map(|i| set("jittered", 2025, 77 + i)).collect();
    let mj = spectrum::point_set_measures(&jit).unwrap();
    assert!(mj.effective_nyquist.unwrap() > 0.1, "{mj:?}");
    assert!(mj.average_min_distance.unwrap() > m.average_min_distance.unwrap() + 0.05);
}

#[test]
fn exr_reads_back_the_values_written() {
    let pts = set("jittered", 256, 2);
    let spec = periodogram(&pts, 32).unwrap();
    let path = std::env::temp_dir().join(format!("strata-{}-spectrum.exr", std::process::id()));
    strata_lab::io::write_spectrum_exr(&path, &spec).unwrap();
    let (w, h, vals) = strata_lab::io::read_exr_y(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert_eq!((w, h), (33, 33));
    // Row 0 of the image is v = +K/2.
    for row in 0..33 {
        for col in 0..33 {
            let (u, v) = (col as i32 - 16, 16 - row as i32);
            assert_eq!(
                vals[row * 33 + col],
                spec.get(u, v).unwrap() as f32,
                "({u}, {v})"
            );
        }
    }
}

#[test]
fn radial_csv_has_the_contract_columns() {
    let pts = set("random", 64, 2);
    let spec = periodogram(&pts, 16).unwrap();
    let path = std::env::temp_dir().join(format!("strata-{}-radial.csv", std::process::id()));
    strata_lab::io::write_radial_csv(&path, &spec.radial()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::remove_file(&path).ok();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("frequency,power,anisotropy"));
    let rows: Vec<_> = lines.collect();
    assert_eq!(rows.len(), 8);
    for (i, row) in rows.iter().enumerate() {
        let cols: Vec<&str> = row.split(',').collect();
        assert_eq!(cols.len(), 3);
        assert_eq!(cols[0], (i + 1).to_string());
        assert!(cols[1].parse::<f64>().unwrap() >= 0.0);
    }
}
