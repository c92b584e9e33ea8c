//! Blue noise, in one run: dart throwing (exact count) and Bridson against the `fast_poisson`
//! crate (Bridson's algorithm, non-periodic) at the same N and radius; one Lloyd iteration on
//! 4096 points; a whole CCVT optimisation of 1024 sites.
//!
//! `cargo bench --bench blue_noise`; `python3 tools/criterion_table.py blue_noise fast_poisson`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use strata_lab::samplers::{Bridson, Ccvt, DartThrowing, SetGenerator, poisson};
use strata_lab::spectrum::relative_radius_max;

fn poisson_disk(c: &mut Criterion) {
    for n in [1024u64, 4096] {
        let r = 0.7 * relative_radius_max(n as usize);
        let mut group = c.benchmark_group(format!("blue_noise/poisson-N{n}-rho0.7"));
        group
            .sample_size(20)
            .measurement_time(Duration::from_secs(3));
        let mut key = 0u64;
        group.bench_function(BenchmarkId::from_parameter("fast_poisson"), |b| {
            b.iter(|| {
                key += 1;
                black_box(
                    fast_poisson::Poisson2D::new()
                        .with_dimensions([1.0, 1.0], r)
                        .with_seed(key)
                        .generate(),
                )
            })
        });
        group.bench_function(BenchmarkId::from_parameter("bridson-raw"), |b| {
            b.iter(|| {
                key += 1;
                black_box(poisson::bridson(r, key).unwrap())
            })
        });
        let bridson = Bridson::new(n, 0.7).unwrap();
        group.bench_function(BenchmarkId::from_parameter("bridson-exact-N"), |b| {
            b.iter(|| {
                key += 1;
                black_box(bridson.generate(key).unwrap())
            })
        });
        let dart = DartThrowing::new(n, 0.7).unwrap();
        group.bench_function(BenchmarkId::from_parameter("poisson-exact-N"), |b| {
            b.iter(|| {
                key += 1;
                black_box(dart.generate(key).unwrap())
            })
        });
        group.finish();
    }
}

fn lloyd(c: &mut Criterion) {
    use strata_lab::samplers::lloyd::relax;
    let mut group = c.benchmark_group("blue_noise/lloyd-N4096");
    group
        .sample_size(30)
        .measurement_time(Duration::from_secs(3));
    // random points, relaxed a few times (a typical mid-relaxation state)
    let mut h = 7u64;
    let mut pts: Vec<[f64; 2]> = (0..4096)
        .map(|_| {
            h = strata::hash::mix64(h + 1);
            let a = (h >> 11) as f64 / (1u64 << 53) as f64;
            h = strata::hash::mix64(h + 1);
            [a, (h >> 11) as f64 / (1u64 << 53) as f64]
        })
        .collect();
    relax(&mut pts, 5).unwrap();
    group.bench_function(BenchmarkId::from_parameter("one-iteration"), |b| {
        b.iter(|| {
            let mut p = pts.clone();
            black_box(relax(&mut p, 1).unwrap())
        })
    });
    group.finish();
}

fn ccvt(c: &mut Criterion) {
    let mut group = c.benchmark_group("blue_noise/ccvt-N1024");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    let g = Ccvt::new(1024, 200).unwrap();
    let mut key = 0u64;
    group.bench_function(BenchmarkId::from_parameter("optimize-256-per-site"), |b| {
        b.iter(|| {
            key += 1;
            black_box(g.generate(key).unwrap())
        })
    });
    group.finish();
}

criterion_group!(benches, poisson_disk, lloyd, ccvt);
criterion_main!(benches);
