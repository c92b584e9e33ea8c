//! Time per 2D point of every registered sampler at N = 256, 4096 and 65536, against a baseline
//! measured in the same run: two uniform numbers from PCG32 per point.
//!
//! `cargo bench --bench generate`; `python3 tools/criterion_table.py generate` prints the medians
//! and the ratios to the baseline.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec2;
use rand::Rng;
use rand_pcg::Pcg32;
use strata::registry::{self, Params};
use strata::sampler::unit_f32_from_u32;

const COUNTS: [u64; 3] = [256, 4096, 65536];

fn generate(c: &mut Criterion) {
    for n in COUNTS {
        let mut group = c.benchmark_group(format!("generate/{n}"));
        group.throughput(Throughput::Elements(n));
        let mut buf = vec![Vec2::ZERO; n as usize];

        let mut rng = Pcg32::new(0xcafe_f00d_d15e_a5e5, 0x0a02_bdbf_7bb3_c0a7);
        group.bench_function(BenchmarkId::from_parameter("baseline-pcg32"), |b| {
            b.iter(|| {
                for p in buf.iter_mut() {
                    *p = Vec2::new(
                        unit_f32_from_u32(rng.next_u32()),
                        unit_f32_from_u32(rng.next_u32()),
                    );
                }
                black_box(&buf);
            })
        });

        for entry in registry::entries() {
            if !entry.counts.allows(n) {
                continue;
            }
            let mut sampler = entry.build(&Params::new(n).seed(1)).expect("valid count");
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
