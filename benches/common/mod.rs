//! Shared by the benchmarks: the baseline every generator is compared with.

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, BenchmarkId};
use rand::Rng;
use rand_pcg::Pcg32;
use std::hint::black_box;
use strata::float::unit_f32_from_u32;

/// Benchmarks `baseline-pcg32`: filling `buf` with points of two uniform numbers from PCG32
/// each, the cheapest honest way to make random 2D points.
pub fn pcg32_baseline(group: &mut BenchmarkGroup<'_, WallTime>, buf: &mut [[f32; 2]]) {
    let mut rng = Pcg32::new(0xcafe_f00d_d15e_a5e5, 0x0a02_bdbf_7bb3_c0a7);
    group.bench_function(BenchmarkId::from_parameter("baseline-pcg32"), |b| {
        b.iter(|| {
            for p in buf.iter_mut() {
                *p = [
                    unit_f32_from_u32(rng.next_u32()),
                    unit_f32_from_u32(rng.next_u32()),
                ];
            }
            black_box(&*buf);
        })
    });
}
