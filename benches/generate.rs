//! Time per 2D point of every registered sampler at N = 256, 4096 and 65536, against a baseline
//! measured in the same run: two uniform numbers from PCG32 per point.
//!
//! `cargo bench --bench generate`; `python3 tools/criterion_table.py generate` prints the medians
//! and the ratios to the baseline.

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use strata_lab::registry::{self, Params};

const COUNTS: [u64; 3] = [256, 4096, 65536];

fn generate(c: &mut Criterion) {
    for n in COUNTS {
        let mut group = c.benchmark_group(format!("generate/{n}"));
        group.throughput(Throughput::Elements(n));
        let mut buf = vec![[0.0f32; 2]; n as usize];
        common::pcg32_baseline(&mut group, &mut buf);

        for entry in registry::entries() {
            if !entry.counts.allows(n) {
                continue;
            }
            let mut sampler = entry
                .build(&Params::new(n).seed(strata::Seed(1)))
                .expect("valid count");
            group.bench_function(BenchmarkId::from_parameter(entry.name), |b| {
                // Each iteration generates one set of n (a new block for fixed-count samplers).
                b.iter(|| {
                    sampler.fill(&mut buf);
                    black_box(&buf);
                })
            });
        }
        group.finish();
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(40)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = generate
}
criterion_main!(benches);
