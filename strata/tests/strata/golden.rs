//! Golden digests: the values of every sampler of this crate and of every path-tracer sequence
//! are pinned.
//!
//! A 64-bit digest of the first values of every sampler (2D, and 5D where it has D dimensions,
//! and the bulk `fill` path at 13 dimensions) and of every adapter sequence (three pixels,
//! dimensions 0-31, indices at the start, across `2^16` and across `2^32`; once more under the
//! nested padding) and of the stateless functions a renderer keeps (the blue-noise mask,
//! `warp::pick` and `pick_u32`, the scrambles, Halton's radical inverse) is compared with
//! `strata/tests/golden.txt`. The samplers are built as the lab's registry builds them (seed 1, the
//! count its rule allows nearest to 2048, or to 819 for 5D), so that the lab's golden file
//! repeats these lines and a lab test checks that the two files agree. A refactor must leave
//! every digest as it is; a deliberate change of values is announced in `CHANGELOG.md` under
//! "value-breaking" and blessed with `STRATA_BLESS=1 cargo test -p strata-sampling --test
//! strata golden`. CI also runs this test with the SIMD lane types compiled out
//! (the `portable` feature), so the same digests hold without SIMD.

use std::path::Path;

use strata::counts::CountRule;
use strata::pixel::frames::BlueNoiseMask;
use strata::pixel::warp;
use strata::samplers::halton;
use strata::samplers::{
    Cmj, Fibonacci, Halton, HaltonNd, Jittered, LatinHypercube, Lattice, LatticeNd, MultiJittered,
    NRooks, Pmj02Stochastic, Random, RandomNd, Regular, Sobol, SobolNd, UncorrelatedJitter,
};
use strata::{Padding, PixelSampler, Sampler, SamplerNd, Seed, Sequence};
use strata::{hash, scramble};

/// A 64-bit digest of a stream of 32-bit words (each folded in with SplitMix64's finalizer).
#[derive(Default)]
struct Digest(u64);

impl Digest {
    fn push(&mut self, bits: u32) {
        self.0 = strata::hash::mix64(self.0 ^ bits as u64).wrapping_add(0x9e37_79b9_7f4a_7c15);
    }
    fn floats(&mut self, v: &[f32]) {
        v.iter().for_each(|x| self.push(x.to_bits()));
    }
}

/// The values digested per sampler (about 4096).
const VALUES: u64 = 4096;

type Two = Box<dyn Sampler>;
type Nd = Box<dyn SamplerNd>;

/// A sampler of this crate as the registry builds it: its name, its count rule, the 2D form
/// for a count, and the D-dimensional form for a count and `D` (`None` for 2D-only ones).
struct Case {
    name: &'static str,
    counts: CountRule,
    two: fn(u64) -> Two,
    nd: Option<fn(u64, u32) -> strata::Result<Nd>>,
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "random",
            counts: CountRule::Any,
            two: |_| Box::new(Random::new(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(RandomNd::new(d, Seed(1))?))),
        },
        Case {
            name: "regular",
            counts: CountRule::Square,
            two: |n| Box::new(Regular::new(n).unwrap()),
            nd: None,
        },
        Case {
            name: "jittered",
            counts: CountRule::Square,
            two: |n| Box::new(Jittered::new(n, Seed(1)).unwrap()),
            nd: None,
        },
        Case {
            name: "nrooks",
            counts: CountRule::Any,
            two: |n| Box::new(NRooks::new(n, Seed(1)).unwrap()),
            nd: None,
        },
        Case {
            name: "multijittered",
            counts: CountRule::Square,
            two: |n| Box::new(MultiJittered::new(n, Seed(1)).unwrap()),
            nd: None,
        },
        Case {
            name: "cmj",
            counts: CountRule::Any,
            two: |n| Box::new(Cmj::new(n, Seed(1)).unwrap()),
            nd: None,
        },
        Case {
            name: "pmj02-stochastic",
            counts: CountRule::Any,
            two: |_| Box::new(Pmj02Stochastic::new(Seed(1))),
            nd: None,
        },
        Case {
            name: "sobol",
            counts: CountRule::Any,
            two: |_| Box::new(Sobol::new(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(SobolNd::new(d, Seed(1))?))),
        },
        Case {
            name: "sobol12",
            counts: CountRule::Any,
            two: |_| Box::new(Sobol::one_two(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(SobolNd::one_two(d, Seed(1))?))),
        },
        Case {
            name: "faure4",
            counts: CountRule::Any,
            two: |_| Box::new(Sobol::faure4(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(SobolNd::faure4(d, Seed(1))?))),
        },
        Case {
            name: "halton",
            counts: CountRule::Any,
            two: |_| Box::new(Halton::new(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(HaltonNd::new(d, Seed(1))?))),
        },
        Case {
            name: "lattice",
            counts: CountRule::Any,
            two: |_| Box::new(Lattice::new(Seed(1))),
            nd: Some(|_, d| Ok(Box::new(LatticeNd::new(d, Seed(1))?))),
        },
        Case {
            name: "fibonacci",
            counts: CountRule::Fibonacci,
            two: |n| Box::new(Fibonacci::new(n, Seed(1)).unwrap()),
            nd: None,
        },
        Case {
            name: "latin",
            counts: CountRule::Any,
            two: |n| Box::new(LatinHypercube::new(n, 2, Seed(1)).unwrap()),
            nd: Some(|n, d| Ok(Box::new(LatinHypercube::new(n, d, Seed(1))?))),
        },
        Case {
            name: "uncorrelated",
            counts: CountRule::Square,
            two: |n| Box::new(UncorrelatedJitter::new(n, 2, Seed(1)).unwrap()),
            nd: Some(|n, d| Ok(Box::new(UncorrelatedJitter::new(n, d, Seed(1))?))),
        },
    ]
}

/// The digests of every sampler of this crate, by name (`NAME`, `NAME --dims 5`, `NAME --dims
/// 13 fill`), as the lab's golden test writes them.
fn sampler_digests() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for c in cases() {
        let n = c.counts.nearest(VALUES / 2);
        let mut s = (c.two)(n);
        assert_eq!(Sampler::name(&*s), c.name);
        let mut d = Digest::default();
        for _ in 0..n {
            d.floats(&s.next_sample());
        }
        out.push((c.name.to_string(), d.0));
        let Some(nd) = c.nd else { continue };
        let n = c.counts.nearest(VALUES / 5);
        // five dimensions, or four for a sampler that has no more (`faure4`)
        let (dims, mut s) = match nd(n, 5) {
            Ok(s) => (5, s),
            Err(_) => (4, nd(n, 4).unwrap()),
        };
        let mut d = Digest::default();
        let mut p = vec![0f32; dims];
        for _ in 0..n {
            s.next_point(&mut p);
            d.floats(&p);
        }
        out.push((format!("{} --dims {dims}", c.name), d.0));
        // the bulk path (SIMD lanes in Sobol': 8 with AVX2, 4 with SSE2, and the tail)
        let dims = 13;
        if let Ok(mut s) = nd(n, dims) {
            let mut v = vec![0f32; n as usize * dims as usize];
            s.fill(&mut v);
            let mut d = Digest::default();
            d.floats(&v);
            out.push((format!("{} --dims {dims} fill", c.name), d.0));
        }
    }
    out
}

/// The digests of every adapter sequence.
fn sequence_digests() -> Vec<(String, u64)> {
    let indices: Vec<u64> = (0..64)
        .chain(65_530..65_542)
        .chain((1u64 << 32) - 6..(1u64 << 32) + 6)
        .collect();
    Sequence::NAMES
        .iter()
        .map(|&name| {
            let seq = Sequence::by_name(name, [64, 64]).unwrap();
            let s = PixelSampler::new(seq, 16, Seed(1)).unwrap();
            let mut d = Digest::default();
            for pixel in [[0u32, 0], [1, 0], [37, 11]] {
                for &i in &indices {
                    for dim in (0..32).step_by(2) {
                        d.floats(&s.sample_2d(pixel, i, dim));
                    }
                    d.floats(&[s.sample_1d(pixel, i, 31)]);
                }
            }
            (format!("pixel {name}"), d.0)
        })
        .collect()
}

/// The digests of every sequence under the nested padding (the default's are above).
fn nested_digests() -> Vec<(String, u64)> {
    Sequence::NAMES
        .iter()
        .map(|&name| {
            let seq = Sequence::by_name(name, [64, 64]).unwrap();
            let s = PixelSampler::new(seq, 16, Seed(1))
                .unwrap()
                .with_padding(Padding::Nested);
            let mut d = Digest::default();
            for pixel in [[0u32, 0], [37, 11]] {
                for i in (0..64).chain((1u64 << 32) - 3..(1u64 << 32) + 3) {
                    for dim in (0..16).step_by(2) {
                        d.floats(&s.sample_2d(pixel, i, dim));
                    }
                }
            }
            (format!("pixel {name} nested"), d.0)
        })
        .collect()
}

/// The digests of the stateless functions whose values a renderer keeps: the built-in
/// blue-noise mask, the index picks, the scrambles and permutations, Halton's radical inverse.
fn function_digests() -> Vec<(String, u64)> {
    let mut out = Vec::new();
    let mask = BlueNoiseMask::builtin();
    let mut d = Digest::default();
    for y in 0..mask.side() {
        for x in 0..mask.side() {
            d.push(mask.rank([x, y]));
        }
    }
    out.push(("fn BlueNoiseMask builtin".into(), d.0));
    let words: Vec<u32> = (0..4096u32)
        .map(|i| strata::hash::mix64(i as u64) as u32)
        .chain([0, 1, u32::MAX - 1, u32::MAX])
        .collect();
    let counts = [1u32, 2, 3, 7, 1000, (1 << 24) - 1, 1 << 24, u32::MAX];
    let mut d = Digest::default();
    for &n in &counts {
        for &w in &words {
            let (i, r) = warp::pick((w >> 8) as f32 / (1u32 << 24) as f32, n);
            d.push(i);
            d.floats(&[r]);
        }
    }
    out.push(("fn warp::pick".to_string(), d.0));
    let mut d = Digest::default();
    for &n in &counts {
        for &w in &words {
            let (i, r) = warp::pick_u32(w, n);
            d.push(i);
            d.floats(&[r]);
        }
    }
    out.push(("fn warp::pick_u32".to_string(), d.0));
    let mut d = Digest::default();
    for &w in &words {
        d.push(scramble::owen_scramble(w, 0x1234_5678));
        d.push(scramble::owen_scramble_rev(w, 0x9abc_def0));
        d.push(hash::permute(w % 1000, 1000, 7));
        d.push(hash::permute(w, u32::MAX, 7));
    }
    out.push(("fn scramble and permute".to_string(), d.0));
    let mut d = Digest::default();
    for dim in [0u32, 1, 2, 10, 100, 999] {
        for i in (0..256u64).chain([u32::MAX as u64, u64::MAX]) {
            d.floats(&[halton::scrambled_radical_inverse(i, dim, strata::Seed(1)).unwrap()]);
        }
    }
    out.push(("fn halton::scrambled_radical_inverse".to_string(), d.0));
    out
}

#[test]
fn every_sampler_and_sequence_gives_its_pinned_values() {
    let mut digests = sampler_digests();
    digests.extend(sequence_digests());
    digests.extend(nested_digests());
    digests.extend(function_digests());
    let text: String = digests
        .iter()
        .map(|(name, d)| format!("{d:016x} {name}\n"))
        .collect();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden.txt");
    if std::env::var_os("STRATA_BLESS").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let want = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (STRATA_BLESS=1 writes it)", path.display()));
    let changed: Vec<String> = text
        .lines()
        .zip(want.lines())
        .filter(|(a, b)| a != b)
        .map(|(a, b)| format!("  now {a}\n  was {b}"))
        .collect();
    assert!(
        changed.is_empty() && text.lines().count() == want.lines().count(),
        "values changed (a deliberate change goes into CHANGELOG.md under value-breaking, then \
         STRATA_BLESS=1 cargo test -p strata-sampling --test strata golden):\n{}",
        changed.join("\n")
    );
}

#[test]
fn the_digest_sees_one_changed_bit() {
    // the test above can fail: one flipped bit in one value changes the digest
    let mut a = Digest::default();
    let mut b = Digest::default();
    a.floats(&[0.25, 0.5, 0.75]);
    b.floats(&[0.25, f32::from_bits(0.5f32.to_bits() ^ 1), 0.75]);
    assert_ne!(a.0, b.0);
}
