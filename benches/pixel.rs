//! The path-tracer adapter: time per 2D value, drawn one at a time (`get_2d`) and two at a time
//! (`get_4d`), for every adapter sequence (random, padded jittered, pmj02, Sobol', Halton, the
//! lattice, Z-ordered Sobol' and pmj02), against the `sobol_burley` crate (Owen-scrambled
//! Sobol', the peer; `sample` and `sample_4d`) in the same run.
//!
//! Each iteration renders a 32 x 32 "image": for every pixel and sample index (16 spp) it starts
//! the pixel sample and draws four 2D values (dimensions 0-7), as a path tracer would.
//! `cargo bench --bench pixel`; `python3 tools/criterion_table.py pixel sobol_burley-sample`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use strata::pixel::{PixelSampler, Sequence};

const SIDE: u32 = 32;
const SPP: u32 = 16;
const PAIRS: u32 = 4;

fn pixel(c: &mut Criterion) {
    let values = (SIDE * SIDE * SPP * PAIRS) as u64;
    let mut group = c.benchmark_group("pixel/get_2d");
    group.throughput(Throughput::Elements(values));
    group
        .sample_size(30)
        .measurement_time(Duration::from_secs(3));
    for name in Sequence::NAMES {
        let sequence = Sequence::by_name_at(name, [SIDE, SIDE]).unwrap();
        let mut s = PixelSampler::new(sequence, SPP, strata::Seed(1)).unwrap();
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for y in 0..SIDE {
                    for x in 0..SIDE {
                        for i in 0..SPP as u64 {
                            s.start_pixel_sample([x, y], i, 0);
                            for _ in 0..PAIRS {
                                let v = s.get_2d();
                                acc += v.x + v.y;
                            }
                        }
                    }
                }
                black_box(acc)
            })
        });
        group.bench_function(BenchmarkId::from_parameter(format!("{name}-get_4d")), |b| {
            b.iter(|| {
                let mut acc = 0.0f32;
                for y in 0..SIDE {
                    for x in 0..SIDE {
                        for i in 0..SPP as u64 {
                            s.start_pixel_sample([x, y], i, 0);
                            for _ in 0..PAIRS / 2 {
                                let v = s.get_4d();
                                acc += v.x + v.y + v.z + v.w;
                            }
                        }
                    }
                }
                black_box(acc)
            })
        });
    }
    // The peer: one seed per pixel (its own decorrelation), dimensions 0..7 of its padded
    // Sobol'. `sample` is its scalar path (two calls per 2D value); `sample_4d` its SIMD path.
    group.bench_function(BenchmarkId::from_parameter("sobol_burley-sample"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for y in 0..SIDE {
                for x in 0..SIDE {
                    let seed = y * SIDE + x;
                    for i in 0..SPP {
                        for d in 0..PAIRS {
                            acc += sobol_burley::sample(i, 2 * d, seed)
                                + sobol_burley::sample(i, 2 * d + 1, seed);
                        }
                    }
                }
            }
            black_box(acc)
        })
    });
    group.bench_function(BenchmarkId::from_parameter("sobol_burley-sample_4d"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for y in 0..SIDE {
                for x in 0..SIDE {
                    let seed = y * SIDE + x;
                    for i in 0..SPP {
                        for set in 0..PAIRS / 2 {
                            let v = sobol_burley::sample_4d(i, set, seed);
                            acc += v[0] + v[1] + v[2] + v[3];
                        }
                    }
                }
            }
            black_box(acc)
        })
    });
    group.finish();
}

criterion_group!(benches, pixel);
criterion_main!(benches);
