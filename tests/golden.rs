//! Golden digests: the values of every sampler and every path-tracer sequence are pinned.
//!
//! A 64-bit digest of the first values of every registry entry (2D, and 5D where it has D
//! dimensions) and of every adapter sequence (three pixels, dimensions 0-31, indices at the
//! start, across `2^16` and across `2^32`) is compared with `tests/golden.txt`. A refactor must
//! leave every digest as it is; a deliberate change of values is announced in `CHANGELOG.md`
//! under "value-breaking" and blessed with `STRATA_BLESS=1 cargo test --test golden`.
//! `.ci/run` also runs this test with the SIMD lane types compiled out
//! (`RUSTFLAGS="--cfg strata_portable"`), so the same digests hold without SIMD.

use std::path::Path;

use strata::registry::{self, Params};
use strata::{PixelSampler, Seed, Sequence};

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

/// The values digested per registry entry (about 4096).
const VALUES: u64 = 4096;

/// The digests of every registry entry, by name (`NAME` and `NAME --dims 5`).
fn sampler_digests() -> Vec<(String, u64)> {
    let entries = registry::entries();
    let work = |e: &registry::Entry| {
        let mut out = Vec::new();
        let n = e.counts.nearest(VALUES / 2);
        let mut s = registry::build(e.name, &Params::new(n).seed(1))
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
        let mut d = Digest::default();
        for _ in 0..n {
            let p = s.next_sample();
            d.floats(&[p.x, p.y]);
        }
        out.push((e.name.to_string(), d.0));
        if e.has_dimensions() {
            let n = e.counts.nearest(VALUES / 5);
            // five dimensions, or four for a sampler that has no more (`faure4`)
            let (dims, built) = match registry::build_nd(e.name, &Params::new(n).seed(1), 5) {
                Ok(s) => (5, s),
                Err(_) => (
                    4,
                    registry::build_nd(e.name, &Params::new(n).seed(1), 4)
                        .unwrap_or_else(|err| panic!("{} --dims 4: {err}", e.name)),
                ),
            };
            let mut s = built;
            let mut d = Digest::default();
            let mut p = vec![0f32; dims];
            for _ in 0..n {
                s.next_point(&mut p);
                d.floats(&p);
            }
            out.push((format!("{} --dims {dims}", e.name), d.0));
            // the bulk path (SIMD lanes in Sobol': 8 with AVX2, 4 with SSE2, and the tail)
            let dims = 13;
            if let Ok(mut s) = registry::build_nd(e.name, &Params::new(n).seed(1), dims) {
                let mut v = vec![0f32; n as usize * dims as usize];
                s.fill(&mut v);
                let mut d = Digest::default();
                d.floats(&v);
                out.push((format!("{} --dims {dims} fill", e.name), d.0));
            }
        }
        out
    };
    // the expensive relaxations run on the other core
    let half = entries.len() / 2;
    let (a, b) = entries.split_at(half);
    std::thread::scope(|sc| {
        let h = sc.spawn(|| a.iter().flat_map(work).collect::<Vec<_>>());
        let mut rest: Vec<_> = b.iter().flat_map(work).collect();
        let mut out = h.join().expect("the other half");
        out.append(&mut rest);
        out
    })
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
            let seq = Sequence::by_name_at(name, [64, 64]).unwrap();
            let s = PixelSampler::new(seq, 16, Seed(1)).unwrap();
            let mut d = Digest::default();
            for pixel in [[0u32, 0], [1, 0], [37, 11]] {
                for &i in &indices {
                    for dim in (0..32).step_by(2) {
                        let v = s.sample_2d(pixel, i, dim);
                        d.floats(&[v.x, v.y]);
                    }
                    d.floats(&[s.sample_1d(pixel, i, 31)]);
                }
            }
            (format!("pixel {name}"), d.0)
        })
        .collect()
}

#[test]
fn every_sampler_and_sequence_gives_its_pinned_values() {
    let mut digests = sampler_digests();
    digests.extend(sequence_digests());
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
         STRATA_BLESS=1 cargo test --test golden):\n{}",
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
