//! D-dimensional samplers: time per point at D = 5 and D = 16, N = 4096 points per set
//! (Bose with q = 64, Bush with q = 16 and strength 3), with random points as the baseline, and
//! `halton-before`: the crate's previous scrambled Halton (a Kensler permutation drawn per
//! digit, 64-bit division, digits to `2^-32`), kept here as the reference its replacement is
//! measured against in the same run.
//!
//! `cargo bench --bench high_dim`; `python3 tools/criterion_table.py high_dim random`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use strata::float::{f32_in_stratum, unit_f32_from_u32};
use strata::hash::{GOLDEN_GAMMA, Permutation, hash32, mix64, stream_seed};
use strata::samplers::halton::PRIMES;
use strata::scramble::owen_scramble;
use strata_lab::registry::{self, Params};

/// The previous scrambled radical inverse (until the Halton speed work): per digit, a node hash
/// and a Kensler permutation of the base, 64-bit division, digits to `2^-32`.
fn halton_before(dim: usize, index: u64, seed: u64) -> f32 {
    const HALTON_DIGITS: u64 = 0x4a17; // the stream id of the Halton digits
    let base = PRIMES[dim] as u64;
    let key = stream_seed(HALTON_DIGITS + dim as u64, seed);
    if base == 2 {
        let bits = (index as u32).reverse_bits();
        return unit_f32_from_u32(owen_scramble(bits, hash32(key as u32, (key >> 32) as u32)));
    }
    let mut a = index;
    let (mut reversed, mut scale, mut coarse, mut level) = (0u64, 1u64, 1u64, 0u64);
    while scale < 1 << 32 {
        let digit = (a % base) as u32;
        a /= base;
        let node = mix64(key ^ reversed ^ level.wrapping_mul(GOLDEN_GAMMA));
        let perm = Permutation::new(base as u32, (node >> 32) as u32).expect("base >= 2");
        level += 1;
        reversed = reversed * base + perm.apply(digit) as u64;
        scale *= base;
        if scale <= 1 << 23 {
            coarse = scale;
        }
    }
    let fine = scale / coarse;
    f32_in_stratum(
        reversed / fine,
        coarse,
        (reversed % fine) as f64 / fine as f64,
    )
}

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
            let mut s = registry::build_nd(name, &Params::new(n).seed(strata::Seed(1)), d).unwrap();
            group.bench_function(BenchmarkId::from_parameter(name), |b| {
                b.iter(|| {
                    s.fill(&mut buf);
                    black_box(&buf);
                })
            });
        }
        let mut next = 0u64;
        group.bench_function(BenchmarkId::from_parameter("halton-before"), |b| {
            b.iter(|| {
                for p in buf.chunks_exact_mut(d as usize) {
                    for (k, o) in p.iter_mut().enumerate() {
                        *o = halton_before(k, next, 1);
                    }
                    next += 1;
                }
                black_box(&buf);
            })
        });
        group.finish();
    }
}

criterion_group!(benches, high_dim);
criterion_main!(benches);
