//! The speed-against-accuracy study: estimates unbiased for every sampler (t-test over seeds),
//! convergence slopes of random, jittered and pmj02 within a tolerance of the published rates,
//! the spectral variance prediction exact for random sampling, bootstrap intervals that hold the
//! rates and separate the classes, the time to reach an error, determinism, and the errors.

use strata_lab::analysis::Integrand;
use strata_lab::analysis::study::{self, Config, Seeds};
use strata_lab::registry;

fn config(names: &[&str], integrands: &[Integrand], min_n: u64, max_n: u64, seeds: u32) -> Config {
    Config {
        samplers: names.iter().map(|n| registry::find(n).unwrap()).collect(),
        integrands: integrands.to_vec(),
        min_n,
        max_n,
        seeds: Seeds::Fixed(seeds),
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
fn slope_intervals_hold_the_rates_and_separate_the_classes() {
    // 128 seeds, 16..1024: random (-1) and jittered on the smooth Gaussian (-2)
    let c = config(
        &["random", "jittered"],
        &[Integrand::Gaussian],
        16,
        1024,
        128,
    );
    let (rows, slopes) = study::run(&c, &|_, _| {}).unwrap();
    let of = |name: &str| {
        slopes
            .iter()
            .find(|s| s.sampler == name)
            .and_then(|s| s.interval)
            .unwrap()
    };
    let (r, j) = (of("random"), of("jittered"));
    // the published rates within the intervals widened by 0.1 (one fixed set of seeds can be
    // unlucky; the coverage itself is checked below on independent data)
    assert!(
        r.0 - 0.1 < -1.0 && -1.0 < r.1 + 0.1,
        "random's interval {r:?} far from -1"
    );
    assert!(
        j.0 - 0.1 < -2.0 && -2.0 < j.1 + 0.1,
        "jittered's interval {j:?} far from -2"
    );
    assert!(
        j.1 < r.0,
        "the intervals overlap: jittered {j:?}, random {r:?}"
    );
    // and they are not wide by construction: each under 0.3
    assert!(r.1 - r.0 < 0.3 && j.1 - j.0 < 0.3, "{r:?} {j:?}");
    // The interval of a series made to fall as N^-2 holds -2 and not -1: the bootstrap
    // follows the data (a fixed interval around -1 would fail here).
    let est: Vec<Vec<f64>> = [16.0f64, 64.0, 256.0, 1024.0]
        .iter()
        .map(|&n| (0..64).map(|k| ((k * 37 % 64) as f64 - 31.5) / n).collect())
        .collect();
    let series: Vec<(f64, &[f64])> = [16.0, 64.0, 256.0, 1024.0]
        .iter()
        .zip(&est)
        .map(|(&n, e)| (n, e.as_slice()))
        .collect();
    let (lo, hi) = study::bootstrap_interval(&series, 9).unwrap();
    assert!(lo < -2.0 && -2.0 < hi && hi < -1.5, "[{lo}, {hi}]");

    // Time to an error: random needs N = sigma^2 / (target I)^2 points (its variance is
    // sigma^2 / N exactly); jittered, converging faster, fewer. The target is chosen inside
    // the measured counts (N = 500), where the fit interpolates.
    let f = Integrand::Gaussian;
    let target = (f.variance() / 500.0).sqrt() / f.exact();
    let tte = study::time_to_error(&rows, &c.samplers, &[target]);
    let n_of = |name: &str| tte.iter().find(|t| t.sampler == name).unwrap();
    let expected = 500.0;
    let random = n_of("random");
    assert!(
        (random.n as f64 / expected - 1.0).abs() < 0.3,
        "random needs {} points, sigma^2 / (target I)^2 = {expected}",
        random.n
    );
    assert!(random.extrapolated == (random.n > 1024));
    let jittered = n_of("jittered");
    assert!(
        jittered.n < random.n / 4,
        "jittered {} vs random {}",
        jittered.n,
        random.n
    );
    assert!(
        jittered.n.isqrt().pow(2) == jittered.n,
        "{} is not a count jittered takes",
        jittered.n
    );
    assert!(tte[0].ns <= tte[1].ns, "not sorted cheapest first");
    // every row's timing is a median inside its measured range
    for r in &rows {
        assert!(
            r.set_ns_min <= r.set_ns && r.set_ns <= r.set_ns_max,
            "{r:?}"
        );
    }
}

#[test]
fn bootstrap_intervals_cover_the_true_slope_95_percent_of_the_time() {
    // 300 independent synthetic studies of a progressive i.i.d. sequence (the estimate at N is
    // the mean of a seed's first N values, so counts share points as a progressive sampler's
    // do): variance exactly sigma^2 / N, slope -1. A 95% interval covers -1 in 95% of them;
    // the check accepts 89% to 99.5% (binomial false alarm about 1e-4 each side).
    let counts = [16usize, 32, 64, 128, 256, 512, 1024];
    let mut covered = 0;
    let studies = 300u64;
    for d in 0..studies {
        let est: Vec<Vec<f64>> = {
            let mut per_count = vec![Vec::with_capacity(64); counts.len()];
            for seed in 0..64u64 {
                let mut sum = 0.0;
                let mut k = 0;
                for i in 0..1024u64 {
                    let h = strata::hash::hash_u64(i, d * 1_000_003 + seed);
                    sum += (h >> 11) as f64 / (1u64 << 53) as f64;
                    if Some(&(i as usize + 1)) == counts.get(k) {
                        per_count[k].push(sum / (i + 1) as f64);
                        k += 1;
                    }
                }
            }
            per_count
        };
        let series: Vec<(f64, &[f64])> = counts
            .iter()
            .zip(&est)
            .map(|(&n, e)| (n as f64, e.as_slice()))
            .collect();
        let (lo, hi) = study::bootstrap_interval(&series, d).unwrap();
        if lo < -1.0 && -1.0 < hi {
            covered += 1;
        }
    }
    let rate = covered as f64 / studies as f64;
    assert!((0.89..=0.995).contains(&rate), "coverage {rate}");
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
    let mut c = config(&["random"], &[Integrand::Disk], 16, 64, 8);
    c.seeds = Seeds::Auto { min: 64, max: 32 };
    assert!(msg(c).contains("seeds"));
    assert!(msg(config(&["jittered"], &[Integrand::Disk], 17, 24, 8)).contains("no allowed count"));
    assert!(msg(config(&[], &[Integrand::Disk], 16, 64, 8)).contains("at least one sampler"));
    assert!(
        Integrand::by_name("sphere")
            .unwrap_err()
            .to_string()
            .contains("disk")
    );
}
