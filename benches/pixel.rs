//! The path-tracer adapter against `sobol_burley` (Owen-scrambled Sobol', the crate a renderer
//! would pick instead), in one run, single thread, every sequence with the default padding.
//!
//! * `pixel/get_2d`: a 32 x 32 "image" at 16 spp, four 2D values (dimensions 0-7) per pixel
//!   sample, as a path tracer asks for them: every adapter sequence by `get_2d` and by
//!   `get_4d` (a sampler made per image, as a renderer makes it), `sobol` and `zsobol` with the
//!   nested padding, and the peer's `sample_4d` with a per-pixel seed (two calls per pixel
//!   sample) and its scalar `sample`. Time per 2D value.
//! * `pixel/one-pixel-4096` and `pixel/one-pixel-65536`: one pixel at 4096 and 65536 samples,
//!   four 2D values per sample (the cost of a draw deep into a pixel's sequence), every
//!   sequence the kernel draws beside the peer's `sample_4d`.
//! * `pixel/one-spp-pass`: a 128 x 128 image at one sample per pixel, four 2D values per
//!   sample (a viewport's progressive pass: the pixel's setup is paid by every sample), the
//!   kernel's sequences beside the peer's `sample_4d`.
//! * `pixel/one-value`: one value per call, `sobol::owen_scrambled(index, dim, seed)` against
//!   `sobol_burley::sample(index, dim, seed)` over dimensions 0-31: time per value.
//! * `pixel/whole-point`: a 4D point of a research sequence per call, `SobolNd::fill` against
//!   `sample_4d`: time per point; `pixel/construct`: `SobolNd::new` at 8 dimensions.
//!
//! `cargo bench --bench pixel`; `python3 tools/criterion_table.py pixel sobol_burley-sample_4d`.

use std::hint::black_box;
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{
    BenchmarkGroup, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main,
};
use strata::pixel::{Padding, PixelSampler, Sequence};
use strata::samplers::{SobolNd, sobol};
use strata::{SamplerNd, Seed};

/// `side x side` pixels, `spp` samples each, `pairs` 2D values per sample.
#[derive(Clone, Copy)]
struct Shape {
    side: u32,
    spp: u32,
    pairs: u32,
}

impl Shape {
    fn values(&self) -> u64 {
        (self.side * self.side * self.spp * self.pairs) as u64
    }
}

fn get_2d(s: &mut PixelSampler, shape: Shape) -> f32 {
    let mut acc = 0.0f32;
    for y in 0..shape.side {
        for x in 0..shape.side {
            for i in 0..shape.spp as u64 {
                s.start_pixel_sample([x, y], i, 0);
                for _ in 0..shape.pairs {
                    let v = s.get_2d();
                    acc += v[0] + v[1];
                }
            }
        }
    }
    acc
}

fn get_4d(s: &mut PixelSampler, shape: Shape) -> f32 {
    let mut acc = 0.0f32;
    for y in 0..shape.side {
        for x in 0..shape.side {
            for i in 0..shape.spp as u64 {
                s.start_pixel_sample([x, y], i, 0);
                for _ in 0..shape.pairs / 2 {
                    let v = s.get_4d();
                    acc += v[0] + v[1] + v[2] + v[3];
                }
            }
        }
    }
    acc
}

/// The peer as a renderer uses it: one seed per pixel (its own decorrelation), dimensions
/// `0..2 pairs` of its padded Sobol', four at a time.
fn peer_4d(shape: Shape) -> f32 {
    let mut acc = 0.0f32;
    for y in 0..shape.side {
        for x in 0..shape.side {
            let seed = y * shape.side + x;
            for i in 0..shape.spp {
                for set in 0..shape.pairs / 2 {
                    let v = sobol_burley::sample_4d(i, set, seed);
                    acc += v[0] + v[1] + v[2] + v[3];
                }
            }
        }
    }
    acc
}

fn peer_scalar(shape: Shape) -> f32 {
    let mut acc = 0.0f32;
    for y in 0..shape.side {
        for x in 0..shape.side {
            let seed = y * shape.side + x;
            for i in 0..shape.spp {
                for d in 0..shape.pairs {
                    acc += sobol_burley::sample(i, 2 * d, seed)
                        + sobol_burley::sample(i, 2 * d + 1, seed);
                }
            }
        }
    }
    acc
}

fn group<'a>(c: &'a mut Criterion, name: &str, elements: u64) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(elements));
    g.sample_size(30)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1));
    g
}

/// The sequences a shape times: every one, or the kernel's only.
fn sequences(shape: Shape, kernel_only: bool) -> Vec<(&'static str, Sequence)> {
    Sequence::NAMES
        .iter()
        .map(|&name| {
            (
                name,
                Sequence::by_name(name, [shape.side, shape.side]).unwrap(),
            )
        })
        .filter(|(_, s)| !kernel_only || s.runs_on_gpu())
        .collect()
}

/// Every sequence (or the kernel's only) by `get_2d` and `get_4d` beside the peer; with every
/// sequence, also the nested padding and the peer's scalar `sample`.
fn adapter_group(c: &mut Criterion, label: &str, shape: Shape, kernel_only: bool) {
    let mut g = group(c, label, shape.values());
    for (name, sequence) in sequences(shape, kernel_only) {
        let mut s = PixelSampler::new(sequence, shape.spp, Seed(1)).unwrap();
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| black_box(get_2d(&mut s, shape)))
        });
        g.bench_function(BenchmarkId::from_parameter(format!("{name}-get_4d")), |b| {
            b.iter(|| black_box(get_4d(&mut s, shape)))
        });
    }
    if !kernel_only {
        // the nested padding alone, for the record
        for name in ["sobol", "zsobol"] {
            let sequence = Sequence::by_name(name, [shape.side, shape.side]).unwrap();
            let mut s = PixelSampler::new(sequence, shape.spp, Seed(1))
                .unwrap()
                .with_padding(Padding::Nested);
            g.bench_function(BenchmarkId::from_parameter(format!("{name}-nested")), |b| {
                b.iter(|| black_box(get_2d(&mut s, shape)))
            });
        }
        g.bench_function(BenchmarkId::from_parameter("sobol_burley-sample"), |b| {
            b.iter(|| black_box(peer_scalar(shape)))
        });
    }
    g.bench_function(BenchmarkId::from_parameter("sobol_burley-sample_4d"), |b| {
        b.iter(|| black_box(peer_4d(shape)))
    });
    g.finish();
}

fn pixel(c: &mut Criterion) {
    let image = Shape {
        side: 32,
        spp: 16,
        pairs: 4,
    };
    adapter_group(c, "pixel/get_2d", image, false);
    for spp in [4096, 65536] {
        let shape = Shape {
            side: 1,
            spp,
            pairs: 4,
        };
        adapter_group(c, &format!("pixel/one-pixel-{spp}"), shape, true);
    }
    let pass = Shape {
        side: 128,
        spp: 1,
        pairs: 4,
    };
    adapter_group(c, "pixel/one-spp-pass", pass, true);

    // one value per call: 4096 indices x 32 dimensions, one seed per index block
    let mut g = group(c, "pixel/one-value", 4096 * 32);
    g.bench_function(BenchmarkId::from_parameter("owen_scrambled"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..4096u32 {
                for d in 0..32 {
                    acc += sobol::owen_scrambled(i, d, Seed((i >> 4) as u64)).unwrap_or(0.0);
                }
            }
            black_box(acc)
        })
    });
    g.bench_function(BenchmarkId::from_parameter("sobol_burley-sample"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..4096u32 {
                for d in 0..32 {
                    acc += sobol_burley::sample(i, d, i >> 4);
                }
            }
            black_box(acc)
        })
    });
    g.finish();

    // whole points: 65536 4D points of one sequence
    let mut g = group(c, "pixel/whole-point", 65536);
    let mut nd = SobolNd::new(4, Seed(3)).unwrap();
    let mut buf = vec![0f32; 65536 * 4];
    g.bench_function(BenchmarkId::from_parameter("SobolNd-fill"), |b| {
        b.iter(|| {
            nd.fill(&mut buf);
            black_box(buf[12345])
        })
    });
    g.bench_function(BenchmarkId::from_parameter("sobol_burley-sample_4d"), |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for i in 0..65536u32 {
                let v = sobol_burley::sample_4d(i, 0, 3);
                acc += v[0] + v[1] + v[2] + v[3];
            }
            black_box(acc)
        })
    });
    g.finish();

    // construction: what a sampler of 8 dimensions costs before its first point
    let mut g = group(c, "pixel/construct", 1);
    g.bench_function(BenchmarkId::from_parameter("SobolNd-new-8"), |b| {
        b.iter(|| black_box(SobolNd::new(8, Seed(3)).unwrap()))
    });
    g.finish();
}

criterion_group!(benches, pixel);
criterion_main!(benches);
