//! Blue noise: minimum distances checked pair by pair (toroidal), exact counts, Lloyd's energy
//! and centroids, CCVT's capacities and areas, best candidate's spacing, and the errors.

use crate::common::torus_distance_squared;
use strata_lab::registry::{self, Params};
use strata_lab::samplers::{Bridson, Ccvt, DartThrowing, SetGenerator};
use strata_lab::spectrum::relative_radius_max;

fn set(name: &str, n: u64, seed: u64, rho: Option<f64>) -> Vec<[f32; 2]> {
    let mut p = Params::new(n).seed(strata::Seed(seed));
    if let Some(v) = rho {
        p.set("radius", v);
    }
    let mut s = registry::build(name, &p).unwrap();
    crate::common::take(s.as_mut(), n as usize)
}

/// The smallest toroidal distance between two points, by brute force over all pairs.
fn min_distance(pts: &[[f32; 2]]) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..pts.len() {
        for j in 0..i {
            let d = torus_distance_squared(
                [pts[i][0] as f64, pts[i][1] as f64],
                [pts[j][0] as f64, pts[j][1] as f64],
            );
            best = best.min(d);
        }
    }
    best.sqrt()
}

fn in_unit_square(pts: &[[f32; 2]]) -> bool {
    pts.iter()
        .all(|p| (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]))
}

#[test]
fn poisson_and_bridson_keep_the_radius_and_the_count() {
    for name in ["poisson", "bridson"] {
        for (n, rho) in [(64u64, 0.3), (500, 0.5), (1000, 0.7), (777, 0.76)] {
            for seed in [1u64, 2, 3] {
                let pts = set(name, n, seed, Some(rho));
                assert_eq!(pts.len(), n as usize);
                assert!(in_unit_square(&pts));
                let d = min_distance(&pts);
                let r = rho * relative_radius_max(n as usize);
                assert!(
                    d >= r,
                    "{name} n={n} rho={rho} seed={seed}: two points {d} apart, radius {r}"
                );
            }
        }
    }
}

#[test]
fn every_block_is_its_own_poisson_set() {
    let mut p = Params::new(300).seed(strata::Seed(9));
    p.set("radius", 0.7);
    let mut s = registry::build("poisson", &p).unwrap();
    let a = crate::common::take(s.as_mut(), 300);
    let b = crate::common::take(s.as_mut(), 300);
    assert_ne!(a, b);
    let r = 0.7 * relative_radius_max(300);
    assert!(min_distance(&a) >= r && min_distance(&b) >= r);
}

#[test]
fn dart_throwing_reports_saturation_instead_of_hanging() {
    // rho = 0.77 sits at random sequential adsorption's jamming limit: some seeds cannot place
    // all points; those must fail with a clear error after bounded work, the others succeed.
    let g = DartThrowing::new(256, 0.775).unwrap();
    let results: Vec<_> = (0..12u64).map(|k| g.generate(k)).collect();
    for r in &results {
        match r {
            Ok(p) => assert_eq!(p.len(), 256),
            Err(e) => assert!(e.to_string().contains("saturated"), "{e}"),
        }
    }
    assert!(
        results.iter().any(|r| r.is_err()),
        "0.775 should saturate for some seeds"
    );
}

#[test]
fn radii_beyond_reach_are_refused_at_once() {
    // the constructors validate before any generation, so a refusal does no work
    for rho in [0.0, -0.1, 1.0, 1.5, 0.79, 0.95, f64::NAN] {
        let e = DartThrowing::new(1000, rho).expect_err("invalid radius");
        assert!(e.to_string().contains("radius"), "{e}");
        assert!(Bridson::new(1000, rho).is_err());
    }
    assert!(DartThrowing::new(0, 0.5).is_err());
    let huge = DartThrowing::new(1 << 40, 0.5).expect_err("too many points");
    assert!(huge.to_string().contains("between 1 and"), "{huge}");
}

#[test]
fn lloyd_energy_never_rises_and_points_end_near_their_centroids() {
    use strata_lab::samplers::lloyd::{DEFAULT_ITERATIONS, TOLERANCE, relax_until, voronoi_cells};
    for (n, seed) in [(100usize, 1u64), (500, 2), (1024, 3)] {
        let mut pts: Vec<[f64; 2]> = set("random", n as u64, seed, None)
            .iter()
            .map(|p| [p[0] as f64, p[1] as f64])
            .collect();
        // cells tile the torus
        let cells = voronoi_cells(&pts).unwrap();
        let area: f64 = cells.iter().map(|c| c.unwrap().area).sum();
        assert!((area - 1.0).abs() < 1e-9, "cells cover {area}");
        let steps = relax_until(&mut pts, TOLERANCE, DEFAULT_ITERATIONS).unwrap();
        for w in steps.windows(2) {
            assert!(
                w[1].energy <= w[0].energy * (1.0 + 1e-12),
                "n={n}: energy rose {} -> {}",
                w[0].energy,
                w[1].energy
            );
        }
        // stopped by convergence, not by the cap
        let last = steps.last().unwrap();
        assert!(
            last.mean_offset < TOLERANCE && steps.len() < DEFAULT_ITERATIONS as usize,
            "n={n}: after {} steps, points are {} r_max from their centroids",
            steps.len(),
            last.mean_offset
        );
        assert!(
            steps[..steps.len() - 1]
                .iter()
                .all(|s| s.mean_offset >= TOLERANCE)
        );
        assert!(
            pts.iter()
                .all(|p| (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1]))
        );
    }
}

#[test]
fn converged_lloyd_reaches_the_published_spacing() {
    // A converged CVT of 1024 points has a spacing rho (minimum distance / r_max) of about
    // 0.795 on average (0.76 after the old fixed 64 iterations). The minimum of one set
    // varies by +-0.02 between seeds, so the published figure is checked on the mean of 4
    // seeds and each seed against a floor the old 64 iterations miss on average.
    let rhos: Vec<f64> = (1u64..=4)
        .map(|seed| min_distance(&set("lloyd", 1024, seed, None)) / relative_radius_max(1024))
        .collect();
    for (i, rho) in rhos.iter().enumerate() {
        assert!(*rho >= 0.75, "seed {}: rho {rho}", i + 1);
    }
    let mean = rhos.iter().sum::<f64>() / rhos.len() as f64;
    assert!(mean >= 0.79, "mean rho {mean} over seeds 1-4: {rhos:?}");
}

#[test]
fn lloyd_separates_coincident_points() {
    use strata_lab::samplers::lloyd::relax;
    let mut pts = vec![[0.25, 0.25]; 5];
    pts.extend([[0.7, 0.1], [0.1, 0.8], [0.6, 0.6]]);
    pts.push([0.6, 0.6]);
    relax(&mut pts, 30).unwrap();
    for i in 0..pts.len() {
        for j in 0..i {
            assert!(
                torus_distance_squared(pts[i], pts[j]) > 1e-6,
                "{i} and {j} still coincide: {:?}",
                pts[i]
            );
        }
    }
    let mut single = vec![[0.3, 0.3]];
    relax(&mut single, 3).unwrap();
}

#[test]
fn ccvt_sites_own_equal_shares() {
    let c = Ccvt::with_capacity(200, 200, 128).unwrap();
    let r = c.optimize(5);
    assert!(r.converged, "no stable state after {} passes", r.passes);
    assert_eq!(r.points.len(), 200 * 128);
    for w in r.energy.windows(2) {
        assert!(w[1] <= w[0] + 1e-12, "energy rose {} -> {}", w[0], w[1]);
    }
    // The capacity constraint: each site's Voronoi region, estimated with independent
    // uniform probes, holds about 1/N of the torus.
    let nearest = |p: [f64; 2]| {
        (0..r.sites.len())
            .min_by(|&i, &j| {
                torus_distance_squared(p, r.sites[i])
                    .total_cmp(&torus_distance_squared(p, r.sites[j]))
            })
            .unwrap()
    };
    let probes = 200_000u64;
    let mut counts = vec![0u32; 200];
    let mut h = 42u64;
    for _ in 0..probes {
        h = strata::hash::mix64(h);
        let a = (h >> 11) as f64 / (1u64 << 53) as f64;
        h = strata::hash::mix64(h);
        let b = (h >> 11) as f64 / (1u64 << 53) as f64;
        counts[nearest([a, b])] += 1;
    }
    let mean = probes as f64 / 200.0;
    let worst = counts
        .iter()
        .map(|&c| (c as f64 / mean - 1.0).abs())
        .fold(0.0, f64::max);
    // Binomial noise alone is about 3.5% per site here; random points' cells vary by 50%.
    assert!(
        worst < 0.25,
        "a site's Voronoi area is off by {:.1}%",
        worst * 100.0
    );
}

#[test]
fn blue_noise_sets_are_well_spaced() {
    // Relative to r_max(N): random points get close to 0; these keep a real gap.
    for (name, floor) in [
        ("ccvt", 0.5),
        ("best-candidate", 0.3),
        ("poisson", 0.7),
        ("bridson", 0.7),
    ] {
        let n = 256;
        let pts = set(name, n, 4, None);
        assert!(in_unit_square(&pts));
        let d = min_distance(&pts) / relative_radius_max(n as usize);
        assert!(d >= floor, "{name}: minimum distance {d} r_max");
    }
    {
        let pts = set("lloyd", 256, 4, None);
        assert!(min_distance(&pts) / relative_radius_max(256) > 0.5);
    }
}

#[test]
fn best_candidate_is_progressive() {
    let mut p = Params::new(1).seed(strata::Seed(1));
    p.set("candidates", (2) as f64);
    let mut s = registry::build("best-candidate", &p).unwrap();
    let pts = crate::common::take(s.as_mut(), 512);
    for m in [16usize, 64, 256, 512] {
        let d = min_distance(&pts[..m]) / relative_radius_max(m);
        assert!(d > 0.3, "prefix {m}: minimum distance {d} r_max");
    }
}

#[test]
fn iteration_counts_are_checked() {
    assert!(Ccvt::new(100, 0).is_err());
    assert!(Ccvt::new(100, 1_000_000).is_err());
    assert!(Ccvt::new(0, 10).is_err());
    assert!(Ccvt::new(1 << 20, 10).is_err());
    {
        assert!(strata_lab::samplers::Lloyd::new(100, 1_000_000).is_err());
        assert!(strata_lab::samplers::Lloyd::new(0, 10).is_err());
    }
    let mut p = Params::new(100);
    p.set("iterations", (5) as f64);
    assert!(
        registry::build("poisson", &p).is_err(),
        "poisson takes no iterations"
    );
}

/// Mean over `seeds` of (per-set minimum distance, per-set mean nearest-neighbour distance),
/// both relative to `r_max`.
fn spacing(
    name: &str,
    n: u64,
    iterations: Option<u32>,
    seeds: std::ops::RangeInclusive<u64>,
) -> [f64; 2] {
    let k = seeds.clone().count() as f64;
    let r = relative_radius_max(n as usize);
    let mut sum = [0.0; 2];
    for seed in seeds {
        let mut p = Params::new(n).seed(strata::Seed(seed));
        if let Some(v) = iterations {
            p.set("iterations", v as f64);
        }
        let mut s = registry::build(name, &p).unwrap();
        let pts = crate::common::take(s.as_mut(), n as usize);
        if name == "net02bn" {
            assert!(
                crate::common::is_net(&pts),
                "{name} n={n} seed={seed} is not a (0,m,2)-net"
            );
        }
        let d = strata_lab::spectrum::nearest_neighbour_distances(&pts).unwrap();
        sum[0] += d.iter().copied().fold(f64::INFINITY, f64::min) / r;
        sum[1] += d.iter().sum::<f64>() / d.len() as f64 / r;
    }
    [sum[0] / k, sum[1] / k]
}

#[test]
fn net02bn_is_a_net_and_bluer_than_pmj02() {
    // Each set is checked as a net (every elementary interval of area 1/N holds one point),
    // at every m up to 10 and for 4 seeds at 1024.
    for m in 0..=10u32 {
        for seed in [1u64, 2] {
            let pts = set("net02bn", 1 << m, seed, None);
            assert!(crate::common::is_net(&pts), "m={m} seed={seed}");
        }
    }
    // The targets against pmj02 (4 seeds at 1024 points, each a net): mean nearest-neighbour
    // distance >= 1.15x, minimum distance >= 1.3x. Measured: 1.37x and 5x.
    let pmj02 = spacing("pmj02", 1024, None, 1..=4);
    let bn = spacing("net02bn", 1024, None, 1..=4);
    assert!(
        bn[1] >= 1.15 * pmj02[1],
        "mean NN {} vs pmj02 {}",
        bn[1],
        pmj02[1]
    );
    assert!(
        bn[0] >= 1.3 * pmj02[0],
        "min distance {} vs pmj02 {}",
        bn[0],
        pmj02[0]
    );
    // The check can fail: without the swaps (0 sweeps: the scrambled Sobol' net it starts
    // from), the same comparison does not pass.
    let start = spacing("net02bn", 1024, Some(0), 1..=4);
    assert!(
        start[1] < 1.15 * pmj02[1],
        "unoptimised mean NN {} vs {}",
        start[1],
        pmj02[1]
    );
}
