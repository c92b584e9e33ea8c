//! The speed-against-accuracy study: estimates unbiased for every sampler (t-test over seeds),
//! convergence slopes of random, jittered and pmj02 within a tolerance of the published rates,
//! the spectral variance prediction exact for random sampling, determinism, and the errors.

#![cfg(feature = "spectrum")]

use strata::analysis::Integrand;
use strata::analysis::study::{self, Config};
use strata::registry;

fn config(names: &[&str], integrands: &[Integrand], min_n: u64, max_n: u64, seeds: u32) -> Config {
    Config {
        samplers: names.iter().map(|n| registry::find(n).unwrap()).collect(),
        integrands: integrands.to_vec(),
        min_n,
        max_n,
        seeds,
        predict: false,
    }
}

#[test]
fn every_sampler_is_unbiased() {
    // regular sampling is deterministic and biased by design; every other pattern is a random
    // point set whose points are (marginally) uniform, so its estimates average the integral.
    for entry in registry::entries().iter().filter(|e| e.name != "regular") {
        let n = entry.counts.nearest(64);
        let seeds = if entry.expensive { 48 } else { 160 };
        let c = Config {
            samplers: vec![entry],
            ..config(
                &[],
                &[Integrand::Disk, Integrand::Gaussian, Integrand::Ball4d],
                n,
                n,
                seeds,
            )
        };
        let (rows, _) = study::run(&c, &|_, _| {}).unwrap();
        for r in rows {
            let se = (r.variance / r.seeds as f64).sqrt();
            let t = (r.mean - r.integrand.exact()) / se.max(1e-300);
            assert!(
                t.abs() < 4.5,
                "{} on {} (N={}): mean {} vs {}, t = {t:.2}",
                r.sampler,
                r.integrand.name(),
                r.n,
                r.mean,
                r.integrand.exact()
            );
        }
    }
}

#[test]
fn convergence_slopes_match_the_published_rates() {
    let c = config(
        &["random", "jittered", "pmj02"],
        &[Integrand::Disk, Integrand::Gaussian],
        16,
        1024,
        64,
    );
    let (_, slopes) = study::run(&c, &|_, _| {}).unwrap();
    for s in slopes {
        let (slope, expected) = (s.slope.unwrap(), s.expected.unwrap());
        assert!(
            (slope - expected).abs() < 0.3,
            "{} on {}: slope {slope:.2}, published {expected}",
            s.sampler,
            s.integrand.name()
        );
    }
}

#[test]
fn the_spectral_prediction_is_exact_for_random_sampling() {
    let mut c = config(
        &["random"],
        &[Integrand::Disk, Integrand::Bilinear],
        256,
        256,
        256,
    );
    c.predict = true;
    let (rows, _) = study::run(&c, &|_, _| {}).unwrap();
    for r in rows {
        let truth = r.integrand.variance() / r.n as f64;
        let predicted = r.predicted_variance.unwrap();
        // the prediction uses the measured expected spectrum: within a few percent of sigma^2/N
        assert!(
            (predicted / truth - 1.0).abs() < 0.1,
            "{}: predicted {predicted}, sigma^2/N {truth}",
            r.integrand.name()
        );
        // the measured variance of 256 estimates: relative standard error sqrt(2/255) = 9%
        assert!(
            (r.variance / truth - 1.0).abs() < 0.3,
            "{}: measured {}, sigma^2/N {truth}",
            r.integrand.name(),
            r.variance
        );
    }
}

#[test]
fn the_study_is_bit_identical_for_any_thread_count() {
    let c = config(
        &["cmj", "sobol", "latin"],
        &[Integrand::Disk, Integrand::Gaussian4d],
        16,
        64,
        8,
    );
    let run = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let (rows, slopes) = study::run(&c, &|_, _| {}).unwrap();
                let bits: Vec<u64> = rows
                    .iter()
                    .flat_map(|r| [r.mean.to_bits(), r.variance.to_bits(), r.rmse.to_bits()])
                    .collect();
                (
                    bits,
                    slopes
                        .iter()
                        .map(|s| s.slope.map(f64::to_bits))
                        .collect::<Vec<_>>(),
                )
            })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn bad_requests_say_what_is_allowed() {
    let msg = |c: Config| study::run(&c, &|_, _| {}).unwrap_err().to_string();
    assert!(msg(config(&["random"], &[Integrand::Disk], 100, 10, 8)).contains("min-n <= max-n"));
    assert!(msg(config(&["random"], &[Integrand::Disk], 16, 64, 1)).contains("seeds"));
    assert!(msg(config(&["random"], &[Integrand::Disk], 16, 64, 0)).contains("seeds"));
    assert!(msg(config(&["jittered"], &[Integrand::Disk], 17, 24, 8)).contains("no allowed count"));
    assert!(msg(config(&[], &[Integrand::Disk], 16, 64, 8)).contains("at least one sampler"));
    assert!(
        Integrand::by_name("sphere")
            .unwrap_err()
            .to_string()
            .contains("disk")
    );
}
