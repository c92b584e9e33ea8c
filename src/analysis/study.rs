//! Convergence studies: estimates over seeds and counts, variance, RMSE, slopes, time.

use std::time::Instant;

use rayon::prelude::*;

use super::Integrand;
use super::fourier::{integrand_power, predicted_variance};
use crate::error::{Error, Result};
use crate::registry::{CountRule, Entry, Params};
use crate::sampler::Point2;
use crate::spectrum::expected_spectrum;

/// The largest count a study accepts.
pub const MAX_STUDY_COUNT: u64 = 1 << 20;

/// The largest number of seeds.
pub const MAX_SEEDS: u32 = 1 << 16;

/// The most coordinates a study holds at once (`seeds x N x D`, 4 bytes each: 1 GiB).
pub const MAX_STUDY_VALUES: u64 = 1 << 28;

/// What to study.
#[derive(Clone, Debug)]
pub struct Config {
    /// The samplers (2D ones are used for 2D integrands, D-dimensional ones for all).
    pub samplers: Vec<&'static Entry>,
    /// The integrands.
    pub integrands: Vec<Integrand>,
    /// Smallest count.
    pub min_n: u64,
    /// Largest count.
    pub max_n: u64,
    /// Seeds per count (at least 2, for a variance).
    pub seeds: u32,
    /// Compute the spectrum-predicted variance (2D samplers and integrands).
    pub predict: bool,
}

/// One (sampler, integrand, count) of the study.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Sampler name.
    pub sampler: &'static str,
    /// Integrand.
    pub integrand: Integrand,
    /// Points per estimate.
    pub n: u64,
    /// Seeds.
    pub seeds: u32,
    /// Mean of the estimates.
    pub mean: f64,
    /// Unbiased sample variance of the estimates.
    pub variance: f64,
    /// Root mean squared error against the exact value.
    pub rmse: f64,
    /// Generation time per sample: the fastest of a few generations of one set, on one core,
    /// divided by `N` (nanoseconds; a timing, so not deterministic).
    pub ns_per_sample: f64,
    /// Variance predicted from the expected spectrum, where made.
    pub predicted_variance: Option<f64>,
}

/// The fitted convergence of one (sampler, integrand).
#[derive(Clone, Debug, PartialEq)]
pub struct Slope {
    /// Sampler name.
    pub sampler: &'static str,
    /// Integrand.
    pub integrand: Integrand,
    /// Least-squares slope of `log variance` against `log N` (`None` with fewer than two counts
    /// of nonzero variance).
    pub slope: Option<f64>,
    /// The published rate for the pattern class, where there is one.
    pub expected: Option<f64>,
}

/// The counts a sampler is studied at: powers of two in `[min, max]` (plus `min` and `max`),
/// each moved to the sampler's nearest allowed count, kept when still in range.
pub fn counts_for(rule: CountRule, min: u64, max: u64) -> Vec<u64> {
    let mut targets: Vec<u64> = (0..64)
        .map(|k| 1u64 << k)
        .filter(|&c| c >= min && c <= max)
        .collect();
    targets.extend([min, max]);
    let mut counts: Vec<u64> = targets
        .into_iter()
        .map(|c| rule.nearest(c))
        .filter(|&c| c >= min && c <= max && rule.allows(c))
        .collect();
    counts.sort_unstable();
    counts.dedup();
    counts
}

/// Least-squares slope of `log y` against `log x` over the pairs with `y > 0`.
pub fn fit_slope(points: &[(f64, f64)]) -> Option<f64> {
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if p.len() < 2 {
        return None;
    }
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    let sxx: f64 = p.iter().map(|q| (q.0 - mx).powi(2)).sum();
    let sxy: f64 = p.iter().map(|q| (q.0 - mx) * (q.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Checks a configuration; the error says what is allowed.
pub fn check(config: &Config) -> Result<()> {
    if config.samplers.is_empty() || config.integrands.is_empty() {
        return Err(Error::input(
            "study::check",
            "at least one sampler and one integrand are needed",
        ));
    }
    if config.min_n == 0 || config.min_n > config.max_n || config.max_n > MAX_STUDY_COUNT {
        return Err(Error::input(
            "study::check",
            format!(
                "min-n = {} and max-n = {}: allowed 1 <= min-n <= max-n <= {MAX_STUDY_COUNT}",
                config.min_n, config.max_n
            ),
        ));
    }
    if config.seeds < 2 || config.seeds > MAX_SEEDS {
        return Err(Error::parameter(
            "study::check",
            "seeds",
            config.seeds,
            format!("2 to {MAX_SEEDS} (a variance needs two estimates)"),
        ));
    }
    let dims = config
        .integrands
        .iter()
        .map(|f| f.dimensions())
        .max()
        .unwrap_or(2) as u64;
    if config.seeds as u64 * config.max_n * dims > MAX_STUDY_VALUES {
        return Err(Error::input(
            "study::check",
            format!(
                "{} seeds of {} points in {dims} dimensions would hold more than {MAX_STUDY_VALUES} coordinates; use fewer seeds or a smaller max-n",
                config.seeds, config.max_n
            ),
        ));
    }
    for e in &config.samplers {
        if counts_for(e.counts, config.min_n, config.max_n).is_empty() {
            return Err(Error::input(
                "study::check",
                format!(
                    "{} has no allowed count between {} and {} (it takes {}; nearest: {})",
                    e.name,
                    config.min_n,
                    config.max_n,
                    e.counts,
                    e.counts.nearest(config.min_n)
                ),
            ));
        }
    }
    Ok(())
}

/// One realization: the points (flat, `dims` per point) and the time it took.
fn realization(entry: &Entry, n: u64, seed: u64, dims: u32) -> Result<(Vec<f32>, f64)> {
    let params = Params::new(n).seed(seed);
    let start = Instant::now();
    let values = if dims == 2 {
        let mut s = entry.build(&params)?;
        let mut pts = vec![Point2::ZERO; n as usize];
        s.fill(&mut pts);
        pts.iter().flat_map(|p| [p.x, p.y]).collect()
    } else {
        let mut s = entry.build_nd(&params, dims)?;
        let mut v = vec![0f32; n as usize * dims as usize];
        s.fill(&mut v);
        v
    };
    Ok((values, start.elapsed().as_nanos() as f64))
}

/// Runs the study. `progress(sampler, n)` is called after each count of each sampler.
pub fn run(
    config: &Config,
    progress: &(dyn Fn(&str, u64) + Sync),
) -> Result<(Vec<Row>, Vec<Slope>)> {
    check(config)?;
    let mut rows = Vec::new();
    let mut powers: Vec<(Integrand, u32, Vec<f64>)> = Vec::new();
    for entry in &config.samplers {
        // the integrands this sampler can evaluate: 2D always; D-dimensional if it has them
        let integrands: Vec<Integrand> = config
            .integrands
            .iter()
            .copied()
            .filter(|f| f.dimensions() == 2 || entry.has_dimensions())
            .collect();
        if integrands.is_empty() {
            continue;
        }
        let wanted = integrands.iter().map(|f| f.dimensions()).max().unwrap_or(2);
        for n in counts_for(entry.counts, config.min_n, config.max_n) {
            // a construction may not reach D dimensions at every count (an orthogonal array
            // over q symbols has at most q or q + 1 columns): then only the 2D integrands
            let dims = if wanted > 2 && entry.build_nd(&Params::new(n), wanted).is_err() {
                2
            } else {
                wanted
            };
            let integrands: Vec<Integrand> = integrands
                .iter()
                .copied()
                .filter(|f| f.dimensions() <= dims)
                .collect();
            let sets: Vec<(Vec<f32>, f64)> = (0..config.seeds as u64)
                .into_par_iter()
                .map(|s| realization(entry, n, s, dims))
                .collect::<Result<_>>()?;
            // Time generation on its own, one core, not under the parallel run's contention: the
            // fastest of up to 7 generations (one when a set takes over 20 ms).
            let mut best = f64::INFINITY;
            for s in 0..7u64.min(config.seeds as u64) {
                best = best.min(realization(entry, n, s, dims)?.1);
                if best > 2e7 {
                    break;
                }
            }
            let ns_per_sample = best / n as f64;
            // the 2D spectrum of the first two dimensions, for the predictions
            let spectrum = if config.predict && integrands.iter().any(|f| f.dimensions() == 2) {
                let k = ((4.0 * (n as f64).sqrt()) as u32 / 2 * 2).clamp(32, 256);
                // each set's first two dimensions, converted as the realizations are needed
                let spectrum = expected_spectrum(config.seeds, k, |r| {
                    Ok(sets[r as usize]
                        .0
                        .chunks_exact(dims as usize)
                        .map(|c| Point2::new(c[0], c[1]))
                        .collect())
                })?;
                Some((k, spectrum))
            } else {
                None
            };
            for &f in &integrands {
                let estimates: Vec<f64> = sets
                    .par_iter()
                    .map(|(v, _)| {
                        v.chunks_exact(dims as usize)
                            .map(|p| f.eval(p))
                            .sum::<f64>()
                            / n as f64
                    })
                    .collect();
                let k = estimates.len() as f64;
                let mean = estimates.iter().sum::<f64>() / k;
                // shifted by the first estimate, so that identical estimates (a deterministic
                // pattern) give exactly zero rather than rounding noise
                let e0 = estimates[0];
                let (s1, s2) = estimates.iter().fold((0.0, 0.0), |(a, b), e| {
                    (a + (e - e0), b + (e - e0) * (e - e0))
                });
                let variance = ((s2 - s1 * s1 / k) / (k - 1.0)).max(0.0);
                let exact = f.exact();
                let rmse = (estimates.iter().map(|e| (e - exact).powi(2)).sum::<f64>() / k).sqrt();
                let predicted = match (&spectrum, f.dimensions()) {
                    (Some((res, spec)), 2) => {
                        let power = match powers.iter().find(|p| p.0 == f && p.1 == *res) {
                            Some(p) => &p.2,
                            None => {
                                powers.push((f, *res, integrand_power(f, *res)));
                                &powers.last().expect("pushed").2
                            }
                        };
                        Some(predicted_variance(f, power, spec, n as usize))
                    }
                    _ => None,
                };
                rows.push(Row {
                    sampler: entry.name,
                    integrand: f,
                    n,
                    seeds: config.seeds,
                    mean,
                    variance,
                    rmse,
                    ns_per_sample,
                    predicted_variance: predicted,
                });
            }
            progress(entry.name, n);
        }
    }
    let mut slopes = Vec::new();
    for entry in &config.samplers {
        for &f in &config.integrands {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.sampler == entry.name && r.integrand == f)
                .map(|r| (r.n as f64, r.variance))
                .collect();
            if pts.is_empty() {
                continue;
            }
            slopes.push(Slope {
                sampler: entry.name,
                integrand: f,
                slope: fit_slope(&pts),
                expected: entry.rates.on(f),
            });
        }
    }
    Ok((rows, slopes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slopes_of_exact_power_laws() {
        let pts: Vec<(f64, f64)> = [16.0, 64.0, 256.0, 1024.0]
            .iter()
            .map(|&n: &f64| (n, 3.0 * n.powf(-1.5)))
            .collect();
        assert!((fit_slope(&pts).unwrap() + 1.5).abs() < 1e-12);
        assert_eq!(fit_slope(&[(4.0, 1.0)]), None);
        assert_eq!(fit_slope(&[(4.0, 0.0), (8.0, 0.0)]), None);
    }

    #[test]
    fn counts_follow_the_rules() {
        assert_eq!(counts_for(CountRule::Any, 16, 128), vec![16, 32, 64, 128]);
        assert_eq!(
            counts_for(CountRule::Square, 16, 300),
            vec![16, 36, 64, 121, 256, 289]
        );
        assert!(counts_for(CountRule::Square, 17, 24).is_empty());
    }
}
