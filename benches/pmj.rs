//! Progressive multi-jittered sequences: 4096 and 65536 points of each, generated from scratch
//! (a new seed per iteration), against the PCG32 baseline in the same run; and the growth of
//! the constructive pmj02's time per point from 2^12 to 2^24 points (`pmj/growth/...`), with the
//! stochastic generator (linear by construction) beside it. `STRATA_BENCH_QUICK=1` stops the
//! growth table at 2^20.
//!
//! `cargo bench --bench pmj`; `python3 tools/criterion_table.py pmj` prints medians and ratios.
//!
//! The `pmj` crate (sjb3d/pmj, whose best-candidate pmj02bn is the peer of `pmj02bn`) is not
//! on crates.io, so it cannot be a dependency here: `tools/pmj-peer/` is a separate crate
//! (not built by `cargo test` or `cargo bench`) that times the two interleaved and compares
//! their mean nearest-neighbour distances; its README says how to get the peer's source.

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use strata_lab::registry::{self, Params};

fn pmj(c: &mut Criterion) {
    for n in [4096u64, 65536] {
        let mut group = c.benchmark_group(format!("pmj/{n}"));
        group.throughput(Throughput::Elements(n));
        group
            .sample_size(20)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(3));
        let mut buf = vec![[0.0f32; 2]; n as usize];
        common::pcg32_baseline(&mut group, &mut buf);
        for name in ["pmj", "pmjbn", "pmj02", "pmj02bn", "pmj02-stochastic"] {
            if name == "pmjbn" && n > 4096 {
                continue; // about half a second per sequence; 4096 shows the cost
            }
            let mut seed = 0u64;
            group.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    seed += 1;
                    let mut s =
                        registry::build(name, &Params::new(n).seed(strata::Seed(seed))).unwrap();
                    s.fill(&mut buf);
                    black_box(&buf);
                })
            });
        }
        group.finish();
    }
    growth(c);
}

/// Time per point of whole sequences of 2^12 to 2^24 points (the elementary-interval search
/// and marking are O(log N) per point; the memory they touch is what grows).
fn growth(c: &mut Criterion) {
    let quick = std::env::var_os("STRATA_BENCH_QUICK").is_some();
    for e in [12u32, 16, 20, 22, 24] {
        if quick && e > 20 {
            break;
        }
        let n = 1u64 << e;
        let mut group = c.benchmark_group(format!("pmj/growth/2^{e}"));
        group.throughput(Throughput::Elements(n));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(100))
            .measurement_time(Duration::from_secs(if e >= 22 { 20 } else { 3 }));
        let mut buf = vec![[0.0f32; 2]; n as usize];
        for name in ["pmj02", "pmj02-stochastic"] {
            let mut seed = 0u64;
            group.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    seed += 1;
                    let mut s =
                        registry::build(name, &Params::new(n).seed(strata::Seed(seed))).unwrap();
                    s.fill(&mut buf);
                    black_box(&buf);
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, pmj);
criterion_main!(benches);
