//! D-dimensional samplers: time per point at D = 5 and D = 16, N = 4096 points per set
//! (Bose with q = 64, Bush with q = 16 and strength 3), with random points as the baseline.
//!
//! `cargo bench --bench high_dim`; `python3 tools/criterion_table.py high_dim random`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use strata::registry::{self, Params};

fn high_dim(c: &mut Criterion) {
    let n = 4096u64;
    for d in [5u32, 16] {
        let mut group = c.benchmark_group(format!("high_dim/D{d}"));
        group.throughput(Throughput::Elements(n));
        group
            .sample_size(20)
            .measurement_time(Duration::from_secs(2));
        let mut buf = vec![0f32; n as usize * d as usize];
        // every sampler with D-dimensional points
        for name in registry::entries()
            .iter()
            .filter(|e| e.has_dimensions())
            .map(|e| e.name)
        {
            let mut s = registry::build_nd(name, &Params::new(n).seed(1), d).unwrap();
            group.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    s.fill(&mut buf);
                    black_box(&buf);
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, high_dim);
criterion_main!(benches);
