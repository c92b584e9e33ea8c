//! Convergence studies: estimates over seeds and counts, variance, RMSE, slopes with bootstrap
//! intervals, generation time, and the time each sampler needs to reach an error.
//!
//! **What is timed.** The cost of a *set*: building the sampler with a new seed and filling
//! `N` points (for set generators such as Lloyd or CCVT, the whole optimisation), on one core.
//! Before timing, one untimed build pays the one-time costs (direction-number tables, lazily
//! built lookup tables); its excess over a timed set is reported as `one_time_ns`. A
//! measurement repeats sets with fresh seeds until at least [`MIN_TIMED_NS`] of work has run
//! and divides; [`TIMINGS`] such measurements give the median and the spread (min, max).

use std::time::Instant;

use rayon::prelude::*;

use super::Integrand;
use super::fit::variance;
pub use super::fit::{
    BOOTSTRAP, MAX_PROJECTED_COUNT, bootstrap_interval, count_to_reach, fit_slope, pareto_front,
    power_law_at, ratio_of_means,
};
use super::fourier::{integrand_power, predicted_variance};
use crate::registry::{CountRule, Entry, Params};
use crate::spectrum::expected_spectrum;
use crate::{Error, Result};

/// The largest count a study accepts.
pub const MAX_STUDY_COUNT: u64 = 1 << 20;

/// The largest number of seeds.
pub const MAX_SEEDS: u32 = 1 << 16;

/// The most coordinates a study holds at once (`seeds x N x D`, 4 bytes each: 1 GiB).
pub const MAX_STUDY_VALUES: u64 = 1 << 28;

/// At least this much work (nanoseconds) per timing measurement.
pub const MIN_TIMED_NS: f64 = 1e6;

/// Timing measurements per (sampler, count); their median is the reported time.
pub const TIMINGS: usize = 5;

/// How many seeds (independent estimates) per count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Seeds {
    /// The same number for every sampler.
    Fixed(u32),
    /// Per sampler, from its cost: as many as [`SEED_BUDGET_NS`] of generation at its largest
    /// count allows, rounded down to a power of two and clamped to `[min, max]`.
    Auto {
        /// Fewest seeds.
        min: u32,
        /// Most seeds.
        max: u32,
    },
}

/// The generation time per count that [`Seeds::Auto`] spends (32 ms).
pub const SEED_BUDGET_NS: f64 = 3.2e7;

impl Seeds {
    /// The default: 32 to 256 seeds by cost.
    pub const DEFAULT: Seeds = Seeds::Auto { min: 32, max: 256 };

    /// The seeds for a sampler whose set at the largest count takes `set_ns`.
    pub fn for_cost(&self, set_ns: f64) -> u32 {
        match *self {
            Seeds::Fixed(k) => k,
            Seeds::Auto { min, max } => {
                let k = (SEED_BUDGET_NS / set_ns.max(1.0)).clamp(1.0, f64::from(u32::MAX)) as u32;
                let pow2 = 1u32 << (31 - k.leading_zeros());
                pow2.clamp(min, max)
            }
        }
    }

    /// The most seeds this can give.
    pub fn max(&self) -> u32 {
        match *self {
            Seeds::Fixed(k) => k,
            Seeds::Auto { max, .. } => max,
        }
    }

    /// The fewest seeds this can give.
    pub fn min(&self) -> u32 {
        match *self {
            Seeds::Fixed(k) => k,
            Seeds::Auto { min, .. } => min,
        }
    }
}

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
    pub seeds: Seeds,
    /// Compute the spectrum-predicted variance (2D samplers and integrands).
    pub predict: bool,
}

/// One (sampler, integrand, count) of the study.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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
    /// Generation time per sample: [`set_ns`](Row::set_ns) divided by `N` (a timing, so not
    /// deterministic).
    pub ns_per_sample: f64,
    /// Generation time of one set on one core, nanoseconds: the median of [`TIMINGS`]
    /// measurements (see the module docs).
    pub set_ns: f64,
    /// The fastest of the measurements.
    pub set_ns_min: f64,
    /// The slowest of the measurements.
    pub set_ns_max: f64,
    /// The first build's excess over a timed set (one-time tables), nanoseconds, at least 0.
    pub one_time_ns: f64,
    /// Variance predicted from the expected spectrum, where made.
    pub predicted_variance: Option<f64>,
}

/// The fitted convergence of one (sampler, integrand).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
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
    /// The 95% confidence interval of the slope: 2.5% and 97.5% quantiles of the slopes of
    /// [`BOOTSTRAP`] bootstrap resamples of the seeds (see [`bootstrap_interval`]).
    pub interval: Option<(f64, f64)>,
}

/// The cost of reaching an error: one row of `time_to_error.csv`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct TimeToError {
    /// Integrand.
    pub integrand: Integrand,
    /// Target RMSE relative to the integral.
    pub target: f64,
    /// Sampler name.
    pub sampler: &'static str,
    /// The smallest allowed count whose fitted RMSE is at most the target.
    pub n: u64,
    /// The fitted generation time of a set of `n`, nanoseconds.
    pub ns: f64,
    /// True when `n` lies outside the measured counts (the power laws are extrapolated).
    pub extrapolated: bool,
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
    if config.seeds.min() < 2
        || config.seeds.max() > MAX_SEEDS
        || config.seeds.min() > config.seeds.max()
    {
        return Err(Error::input(
            "study::check",
            format!(
                "{:?}: seeds must be 2 to {MAX_SEEDS} (a variance needs two estimates), the fewest no more than the most",
                config.seeds
            ),
        ));
    }
    let dims = config
        .integrands
        .iter()
        .map(|f| f.dimensions())
        .max()
        .unwrap_or(2) as u64;
    if config.seeds.max() as u64 * config.max_n * dims > MAX_STUDY_VALUES {
        return Err(Error::input(
            "study::check",
            format!(
                "{} seeds of {} points in {dims} dimensions would hold more than {MAX_STUDY_VALUES} coordinates; use fewer seeds or a smaller max-n",
                config.seeds.max(),
                config.max_n
            ),
        ));
    }
    // every sampler must serve at least one integrand: a 2D one, or one in as many
    // dimensions as it has (else it would give no rows, silently)
    for e in &config.samplers {
        if !config
            .integrands
            .iter()
            .any(|f| f.dimensions() == 2 || e.has_dimensions())
        {
            let names: Vec<&str> = config.integrands.iter().map(|f| f.name()).collect();
            let can: Vec<&str> = crate::registry::entries()
                .iter()
                .filter(|x| x.has_dimensions())
                .map(|x| x.name)
                .collect();
            return Err(Error::input(
                "study::check",
                format!(
                    "{} has 2 dimensions and cannot serve {} (more dimensions); samplers that \
                     can: {}; or add a 2D integrand",
                    e.name,
                    names.join(", "),
                    can.join(", ")
                ),
            ));
        }
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
fn realization(entry: &Entry, n: u64, seed: u64, dims: u32) -> Result<Vec<f32>> {
    let params = Params::new(n).seed(strata::Seed(seed));
    Ok(if dims == 2 {
        let mut s = entry.build(&params)?;
        let mut pts = vec![[0.0; 2]; n as usize];
        s.fill(&mut pts);
        pts.iter().flat_map(|p| *p).collect()
    } else {
        let mut s = entry.build_nd(&params, dims)?;
        let mut v = vec![0f32; n as usize * dims as usize];
        s.fill(&mut v);
        v
    })
}

/// The timing of one (sampler, count), nanoseconds per set.
#[derive(Clone, Copy, Debug)]
struct Timing {
    median: f64,
    min: f64,
    max: f64,
    one_time: f64,
}

/// Times sets of `n` (see the module docs). Seeds from `1 << 40` up, apart from the study's.
fn time_sets(entry: &Entry, n: u64, dims: u32) -> Result<Timing> {
    let mut seed = 1u64 << 40;
    let start = Instant::now();
    std::hint::black_box(realization(entry, n, seed, dims)?);
    let first = start.elapsed().as_nanos() as f64;
    let mut per_set = Vec::with_capacity(TIMINGS);
    // slow sets (over 0.1 s) get 3 measurements of one set each
    let runs = if first > 1e8 { 3 } else { TIMINGS };
    for _ in 0..runs {
        let start = Instant::now();
        let mut sets = 0u32;
        loop {
            seed += 1;
            std::hint::black_box(realization(entry, n, seed, dims)?);
            sets += 1;
            if start.elapsed().as_nanos() as f64 >= MIN_TIMED_NS {
                break;
            }
        }
        per_set.push(start.elapsed().as_nanos() as f64 / f64::from(sets));
    }
    per_set.sort_by(f64::total_cmp);
    let median = per_set[per_set.len() / 2];
    Ok(Timing {
        median,
        min: per_set[0],
        max: per_set[per_set.len() - 1],
        one_time: (first - median).max(0.0),
    })
}

/// Runs the study: one row per (sampler, integrand, count), and the slopes with their
/// bootstrap intervals. `progress(sampler, n)` is called after each count.
pub fn run(
    config: &Config,
    progress: &(dyn Fn(&str, u64) + Sync),
) -> Result<(Vec<Row>, Vec<Slope>)> {
    check(config)?;
    let mut acc = Measured::default();
    for entry in &config.samplers {
        study_sampler(config, entry, &mut acc, progress)?;
    }
    let slopes = fit_slopes(config, &acc);
    Ok((acc.rows, slopes))
}

/// What a study has measured so far: its rows, the estimates behind each row (for the
/// bootstrap), and the integrands' power spectra computed so far (by resolution).
#[derive(Default)]
struct Measured {
    rows: Vec<Row>,
    estimates_of: Vec<Vec<f64>>,
    powers: Vec<(Integrand, u32, Vec<f64>)>,
}

/// One sampler at every count: the set times first (largest count first: it decides the
/// number of seeds), then the estimates.
fn study_sampler(
    config: &Config,
    entry: &'static Entry,
    acc: &mut Measured,
    progress: &(dyn Fn(&str, u64) + Sync),
) -> Result<()> {
    let integrands: Vec<Integrand> = config
        .integrands
        .iter()
        .copied()
        .filter(|f| f.dimensions() == 2 || entry.has_dimensions())
        .collect();
    if integrands.is_empty() {
        return Ok(());
    }
    let wanted = integrands.iter().map(|f| f.dimensions()).max().unwrap_or(2);
    let counts = counts_for(entry.counts, config.min_n, config.max_n);
    let dims_at = |n: u64| {
        if wanted > 2 && entry.build_nd(&Params::new(n), wanted).is_err() {
            2
        } else {
            wanted
        }
    };
    let mut timings = Vec::with_capacity(counts.len());
    for &n in counts.iter().rev() {
        timings.push(time_sets(entry, n, dims_at(n))?);
    }
    timings.reverse();
    let seeds = config
        .seeds
        .for_cost(timings.last().map_or(0.0, |t| t.median));
    for (&n, timing) in counts.iter().zip(&timings) {
        let dims = dims_at(n);
        let at = Count {
            entry,
            n,
            dims,
            seeds,
            timing,
        };
        let integrands: Vec<Integrand> = integrands
            .iter()
            .copied()
            .filter(|f| f.dimensions() <= dims)
            .collect();
        study_count(config, &at, &integrands, acc)?;
        progress(entry.name, n);
    }
    Ok(())
}

/// A sampler at one count: its dimensions there, the seeds and the set times.
struct Count<'a> {
    entry: &'static Entry,
    n: u64,
    dims: u32,
    seeds: u32,
    timing: &'a Timing,
}

/// The sets of one count, the spectrum predicting their variance (if asked), and a row per
/// integrand.
fn study_count(
    config: &Config,
    at: &Count<'_>,
    integrands: &[Integrand],
    acc: &mut Measured,
) -> Result<()> {
    let (n, dims, seeds) = (at.n, at.dims, at.seeds);
    let sets: Vec<Vec<f32>> = (0..u64::from(seeds))
        .into_par_iter()
        .map(|s| realization(at.entry, n, s, dims))
        .collect::<Result<_>>()?;
    let spectrum = if config.predict && integrands.iter().any(|f| f.dimensions() == 2) {
        // the prediction averages at most 32 realizations: the spectrum converges
        // much faster than the slopes need seeds
        let k = ((4.0 * (n as f64).sqrt()) as u32 / 2 * 2).clamp(32, 256);
        let spectrum = expected_spectrum(seeds.min(32), k, |r| {
            Ok(sets[r as usize]
                .chunks_exact(dims as usize)
                .map(|c| [c[0], c[1]])
                .collect())
        })?;
        Some((k, spectrum))
    } else {
        None
    };
    for &f in integrands {
        let estimates: Vec<f64> = sets.par_iter().map(|v| f.estimate(v, dims)).collect();
        let predicted = match (&spectrum, f.dimensions()) {
            (Some((res, spec)), 2) => {
                let power = match acc.powers.iter().find(|p| p.0 == f && p.1 == *res) {
                    Some(p) => &p.2,
                    None => {
                        acc.powers.push((f, *res, integrand_power(f, *res)));
                        &acc.powers.last().expect("pushed").2
                    }
                };
                Some(predicted_variance(f, power, spec, n as usize))
            }
            _ => None,
        };
        acc.rows.push(row(at, f, &estimates, predicted));
        acc.estimates_of.push(estimates);
    }
    Ok(())
}

/// The statistics of a row: the estimates of one integrand over seeds, summarised.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Summary {
    /// Mean of the estimates.
    pub mean: f64,
    /// Unbiased sample variance of the estimates (0 for fewer than two).
    pub variance: f64,
    /// Root mean squared error against the integrand's exact value.
    pub rmse: f64,
}

impl Summary {
    /// The statistics of `estimates` of `f` (in the order of their seeds: the sums run in
    /// that order, so a study split over machines and gathered by seed gives the same bits).
    pub fn of(f: Integrand, estimates: &[f64]) -> Self {
        let k = estimates.len() as f64;
        let exact = f.exact();
        Summary {
            mean: estimates.iter().sum::<f64>() / k,
            variance: variance(estimates.iter().copied()),
            rmse: (estimates.iter().map(|e| (e - exact).powi(2)).sum::<f64>() / k).sqrt(),
        }
    }
}

/// The row of one integrand at one count, from its estimates.
fn row(at: &Count<'_>, f: Integrand, estimates: &[f64], predicted: Option<f64>) -> Row {
    let Summary {
        mean,
        variance,
        rmse,
    } = Summary::of(f, estimates);
    let timing = at.timing;
    Row {
        sampler: at.entry.name,
        integrand: f,
        n: at.n,
        seeds: at.seeds,
        mean,
        variance,
        rmse,
        ns_per_sample: timing.median / at.n as f64,
        set_ns: timing.median,
        set_ns_min: timing.min,
        set_ns_max: timing.max,
        one_time_ns: timing.one_time,
        predicted_variance: predicted,
    }
}

/// The slope of each (sampler, integrand), with its bootstrap interval.
fn fit_slopes(config: &Config, acc: &Measured) -> Vec<Slope> {
    let rows = &acc.rows;
    let mut slopes = Vec::new();
    for entry in &config.samplers {
        for &f in &config.integrands {
            let idx: Vec<usize> = (0..rows.len())
                .filter(|&i| rows[i].sampler == entry.name && rows[i].integrand == f)
                .collect();
            if idx.is_empty() {
                continue;
            }
            let pts: Vec<(f64, f64)> = idx
                .iter()
                .map(|&i| (rows[i].n as f64, rows[i].variance))
                .collect();
            let series: Vec<(f64, &[f64])> = idx
                .iter()
                .map(|&i| (rows[i].n as f64, acc.estimates_of[i].as_slice()))
                .collect();
            slopes.push(Slope {
                sampler: entry.name,
                integrand: f,
                slope: fit_slope(&pts),
                expected: entry.rates.on(f),
                interval: bootstrap_interval(&series, strata::hash::hash_u64(0x5107, f as u64)),
            });
        }
    }
    slopes
}

/// For each integrand, target (RMSE relative to the integral) and sampler: the smallest
/// allowed count whose RMSE, on the power law fitted to the measured RMSEs, is at most the
/// target, and the time of a set of that count on the power law fitted to the measured set
/// times. Samplers whose RMSE does not fall with `N` (fitted exponent above -0.05), or would
/// need more than [`MAX_PROJECTED_COUNT`] points, get no row; nor do deterministic patterns
/// (zero variance at every count, such as `regular`), whose error follows how the grid meets
/// the integrand rather than a power law. Rows are sorted by integrand,
/// target, then time (cheapest first).
pub fn time_to_error(rows: &[Row], samplers: &[&Entry], targets: &[f64]) -> Vec<TimeToError> {
    let mut out = Vec::new();
    let mut integrands: Vec<Integrand> = rows.iter().map(|r| r.integrand).collect();
    integrands.dedup();
    integrands.sort_by_key(|f| *f as u8);
    integrands.dedup();
    for f in integrands {
        for &target in targets {
            let mut block = Vec::new();
            for e in samplers {
                let mine: Vec<&Row> = rows
                    .iter()
                    .filter(|r| r.sampler == e.name && r.integrand == f)
                    .collect();
                if mine.iter().all(|r| r.variance == 0.0) {
                    continue; // deterministic: the error follows the grid's alignment, no law
                }
                let err: Vec<(f64, f64)> = mine.iter().map(|r| (r.n as f64, r.rmse)).collect();
                let time: Vec<(f64, f64)> = mine.iter().map(|r| (r.n as f64, r.set_ns)).collect();
                let Some(n_star) = count_to_reach(&err, target * f.exact().abs()) else {
                    continue;
                };
                let want = n_star.ceil() as u64;
                let n = if e.counts.allows(want) {
                    want
                } else {
                    match e
                        .counts
                        .counts_between(want, want.saturating_mul(4).saturating_add(64))
                        .next()
                    {
                        Some(c) => c,
                        None => continue,
                    }
                };
                let Some(ns) = power_law_at(&time, n as f64) else {
                    continue;
                };
                let (lo, hi) = mine
                    .iter()
                    .fold((u64::MAX, 0), |(l, h), r| (l.min(r.n), h.max(r.n)));
                block.push(TimeToError {
                    integrand: f,
                    target,
                    sampler: e.name,
                    n,
                    ns,
                    extrapolated: n < lo || n > hi,
                });
            }
            block.sort_by(|x, y| x.ns.total_cmp(&y.ns));
            out.extend(block);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

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
