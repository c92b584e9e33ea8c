//! Fitting the measurements of a study: power laws by log-log least squares (the slope of a
//! convergence plot, the count at which a fitted error reaches a target, a fitted time at a
//! count), bootstrap intervals of a slope over seeds, the unbiased variance of estimates, the
//! ratio of two means with its standard error, and the Pareto front of cost against error. Pure functions of their inputs; `study` runs the
//! measurements and re-exports these.

/// Bootstrap resamples for the slopes' confidence intervals.
pub const BOOTSTRAP: usize = 400;

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

/// The unbiased variance of `values` (shifted by the first value, for accuracy).
pub(crate) fn variance(values: impl Iterator<Item = f64> + Clone) -> f64 {
    let k = values.clone().count() as f64;
    let mut it = values;
    let Some(e0) = it.clone().next() else {
        return 0.0;
    };
    let (s1, s2) = it.by_ref().fold((0.0, 0.0), |(a, b), e| {
        (a + (e - e0), b + (e - e0) * (e - e0))
    });
    ((s2 - s1 * s1 / k) / (k - 1.0)).max(0.0)
}

/// The ratio of the means of two figures measured with the same seeds (`a[k]` and `b[k]` with
/// seed `k`, as a sampler's and a baseline's error measures in one run), and its standard
/// error by the delta method: `r = mean(a) / mean(b)`, and the standard deviation of
/// `a[k] - r b[k]` over `sqrt(K) mean(b)` (pairing the seeds removes what they share). `None`
/// with fewer than two seeds, slices of different lengths, a mean of `b` that is not positive
/// or a value that is not finite.
pub fn ratio_of_means(a: &[f64], b: &[f64]) -> Option<(f64, f64)> {
    let k = a.len();
    if k < 2 || b.len() != k || a.iter().chain(b).any(|x| !x.is_finite()) {
        return None;
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / k as f64;
    let mb = mean(b);
    if mb <= 0.0 {
        return None;
    }
    let r = mean(a) / mb;
    let se = (variance(a.iter().zip(b).map(|(x, y)| x - r * y)) / k as f64).sqrt() / mb;
    Some((r, se))
}

/// The 95% bootstrap interval of the slope of `log variance` against `log N`: each resample
/// draws seeds with replacement, the same seeds at every count (estimates of one seed at
/// different counts can be correlated: a progressive sequence's small set is a prefix of its
/// large one), and refits the slope. `None` when the counts have different numbers of
/// estimates or fewer than 90% of the resamples give a slope.
pub fn bootstrap_interval(series: &[(f64, &[f64])], key: u64) -> Option<(f64, f64)> {
    let k = series.first()?.1.len();
    if k == 0 || series.iter().any(|s| s.1.len() != k) {
        return None;
    }
    let mut slopes = Vec::with_capacity(BOOTSTRAP);
    let mut picks = vec![0usize; k];
    for b in 0..BOOTSTRAP as u64 {
        for (j, p) in picks.iter_mut().enumerate() {
            let r = strata::hash::hash_u64(b * k as u64 + j as u64, key);
            *p = ((u128::from(r) * k as u128) >> 64) as usize;
        }
        let pts: Vec<(f64, f64)> = series
            .iter()
            .map(|&(n, est)| (n, variance(picks.iter().map(|&i| est[i]))))
            .collect();
        if let Some(s) = fit_slope(&pts) {
            slopes.push(s);
        }
    }
    if slopes.len() * 10 < BOOTSTRAP * 9 {
        return None;
    }
    slopes.sort_by(f64::total_cmp);
    let q = |p: f64| slopes[((slopes.len() - 1) as f64 * p).round() as usize];
    Some((q(0.025), q(0.975)))
}

/// The least-squares line `log y = a + b log x` over the pairs with `x, y > 0`: `(a, b)`.
fn fit_line(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let b = fit_slope(points)?;
    let p: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = p.len() as f64;
    let (mx, my) = (
        p.iter().map(|q| q.0).sum::<f64>() / n,
        p.iter().map(|q| q.1).sum::<f64>() / n,
    );
    Some((my - b * mx, b))
}

/// The largest count [`time_to_error`](super::study::time_to_error) considers (beyond it a target counts as out of reach).
pub const MAX_PROJECTED_COUNT: f64 = 1e12;

/// The count at which the power law fitted to `(count, error)` pairs (log-log least squares)
/// falls to `target`: `None` when the fitted error does not fall with the count (exponent
/// above -0.05), fewer than two pairs are usable, or the count would exceed
/// [`MAX_PROJECTED_COUNT`]. At least 1.
pub fn count_to_reach(errors: &[(f64, f64)], target: f64) -> Option<f64> {
    let (a, b) = fit_line(errors)?;
    if b > -0.05 || target <= 0.0 {
        return None;
    }
    let n = ((target.ln() - a) / b).exp().max(1.0);
    (n.is_finite() && n <= MAX_PROJECTED_COUNT).then_some(n)
}

/// The indices of the points `(cost, error)` that no other point beats on both axes (lower or
/// equal cost and error, one strictly lower), by increasing cost: the Pareto front.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].0.is_finite() && points[i].1.is_finite())
        .collect();
    order.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[a].1.total_cmp(&points[b].1))
    });
    let mut best = f64::INFINITY;
    order
        .into_iter()
        .filter(|&i| {
            let keep = points[i].1 < best;
            best = best.min(points[i].1);
            keep
        })
        .collect()
}

/// The power law fitted to `(count, value)` pairs (log-log least squares), at `count`.
pub fn power_law_at(pairs: &[(f64, f64)], count: f64) -> Option<f64> {
    let (a, b) = fit_line(pairs)?;
    Some((a + b * count.ln()).exp())
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
    fn a_ratios_standard_error_matches_its_spread_over_repeated_runs() {
        // by hand: a = 1..4, b = 1: r = 2.5, a - r b = -1.5 .. 1.5, variance 5/3, so the
        // standard error is sqrt(5/3 / 4)
        let (r, se) = ratio_of_means(&[1.0, 2.0, 3.0, 4.0], &[1.0; 4]).unwrap();
        assert!((r - 2.5).abs() < 1e-12 && (se - (5.0f64 / 12.0).sqrt()).abs() < 1e-12);
        assert_eq!(ratio_of_means(&[1.0], &[1.0]), None);
        assert_eq!(ratio_of_means(&[1.0, 2.0], &[1.0]), None);
        assert_eq!(ratio_of_means(&[1.0, 2.0], &[0.0, 0.0]), None);
        assert_eq!(ratio_of_means(&[1.0, f64::NAN], &[1.0, 1.0]), None);
        // runs of 64 paired seeds: b = 1 + u, a = 0.9 b + 0.2 v (u, v uniform): the mean of
        // the standard errors is the spread of the ratios over 2,000 runs, within 10% (the
        // spread's own relative error is about 1.6%)
        let uniform =
            |i: u64, key: u64| (strata::hash::hash_u64(i, key) >> 11) as f64 / 2f64.powi(53);
        let (runs, k) = (2000u64, 64u64);
        let (mut ratios, mut ses) = (Vec::new(), Vec::new());
        for run in 0..runs {
            let b: Vec<f64> = (0..k).map(|j| 1.0 + uniform(run * k + j, 1)).collect();
            let a: Vec<f64> = (0..k)
                .map(|j| 0.9 * b[j as usize] + 0.2 * uniform(run * k + j, 2))
                .collect();
            let (r, se) = ratio_of_means(&a, &b).unwrap();
            ratios.push(r);
            ses.push(se);
        }
        let spread = variance(ratios.iter().copied()).sqrt();
        let mean_se = ses.iter().sum::<f64>() / runs as f64;
        assert!(
            (mean_se / spread - 1.0).abs() < 0.1,
            "standard error {mean_se} against the ratios' spread {spread}"
        );
    }

    #[test]
    fn the_pareto_front_keeps_the_undominated() {
        let p = [
            (1.0, 5.0),
            (2.0, 3.0),
            (2.5, 4.0),
            (3.0, 1.0),
            (0.5, 9.0),
            (3.0, 2.0),
        ];
        assert_eq!(pareto_front(&p), vec![4, 0, 1, 3]);
        // a projected count: error 1/n, so 1e-2 needs n = 100; no fall, no count
        let e: Vec<(f64, f64)> = [10.0, 20.0, 40.0]
            .iter()
            .map(|&n: &f64| (n, 1.0 / n))
            .collect();
        assert!((count_to_reach(&e, 1e-2).unwrap() - 100.0).abs() < 1e-9);
        assert_eq!(count_to_reach(&[(10.0, 1.0), (20.0, 1.0)], 0.5), None);
        assert!((power_law_at(&e, 80.0).unwrap() - 1.0 / 80.0).abs() < 1e-12);
    }
}
