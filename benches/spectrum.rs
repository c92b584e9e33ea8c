//! The fast periodogram (non-uniform FFT) against the direct sum, in the same run, on one core:
//! N = 1024 and 16384 at K = 128, and the fast path alone at K = 512.
//!
//! `cargo bench --bench spectrum`; `python3 tools/criterion_table.py spectrum direct` prints the
//! medians with the ratio of each fast run to the direct one.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use strata_lab::registry::{self, Params};
use strata_lab::spectrum::{periodogram, periodogram_direct};

fn points(n: u64) -> Vec<[f32; 2]> {
    let mut s = registry::build("jittered", &Params::new(n).seed(strata::Seed(1))).unwrap();
    let mut v = vec![[0.0f32; 2]; n as usize];
    s.fill(&mut v);
    v
}

fn spectrum(c: &mut Criterion) {
    // One core, as the targets are stated (the direct sum is parallel over frequencies).
    // (If another benchmark already built the global pool this fails; it is then left as is.)
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global();
    {
        for n in [1024u64, 16384] {
            let pts = points(n);
            let mut group = c.benchmark_group(format!("spectrum/N{n}-K128"));
            group
                .sample_size(10)
                .warm_up_time(Duration::from_millis(200));
            group.measurement_time(Duration::from_secs(if n > 4096 { 30 } else { 5 }));
            group.bench_function(BenchmarkId::from_parameter("direct"), |b| {
                b.iter(|| black_box(periodogram_direct(&pts, 128).unwrap()))
            });
            group.bench_function(BenchmarkId::from_parameter("fast"), |b| {
                b.iter(|| black_box(periodogram(&pts, 128).unwrap()))
            });
            group.finish();
        }
        let pts = points(16384);
        let mut group = c.benchmark_group("spectrum/N16384-K512");
        group
            .sample_size(20)
            .measurement_time(Duration::from_secs(5));
        group.bench_function(BenchmarkId::from_parameter("fast"), |b| {
            b.iter(|| black_box(periodogram(&pts, 512).unwrap()))
        });
        group.finish();
    }
}

criterion_group!(benches, spectrum);
criterion_main!(benches);
