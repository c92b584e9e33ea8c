//! Golden digests: the values of every sampler of the registry are pinned.
//!
//! A 64-bit digest of the first values of every registry entry (2D, and 5D where it has D
//! dimensions, and the bulk `fill` path at 13) is compared with `tests/lab/golden.txt`. The
//! renderer crate pins its own samplers the same way (and the path-tracer sequences) in
//! `strata/tests/golden.txt`: the lines of its samplers must be the same in both files (a test
//! below). A refactor must leave every digest as it is; a deliberate change of values is
//! announced in `CHANGELOG.md` under "value-breaking" (the section of the crate that owns the
//! sampler) and blessed with `STRATA_BLESS=1 cargo test -p strata-lab --test lab golden`. CI
//! also runs this test with the renderer's crate's SIMD lane types compiled out (its `portable`
//! feature), so the same digests hold without SIMD.

use std::path::Path;

use strata_lab::registry::{self, Params};

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
        let mut s = registry::build(e.name, &Params::new(n).seed(strata::Seed(1)))
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
        let mut d = Digest::default();
        for _ in 0..n {
            d.floats(&s.next_sample());
        }
        out.push((e.name.to_string(), d.0));
        if e.has_dimensions() {
            let n = e.counts.nearest(VALUES / 5);
            // five dimensions, or four for a sampler that has no more (`faure4`)
            let (dims, built) =
                match registry::build_nd(e.name, &Params::new(n).seed(strata::Seed(1)), 5) {
                    Ok(s) => (5, s),
                    Err(_) => (
                        4,
                        registry::build_nd(e.name, &Params::new(n).seed(strata::Seed(1)), 4)
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
            if let Ok(mut s) =
                registry::build_nd(e.name, &Params::new(n).seed(strata::Seed(1)), dims)
            {
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

/// The digests of the blue-noise masks the lab makes (seed 1; the renderer crate pinned the
/// same digests while the fill was its own).
fn mask_digests() -> Vec<(String, u64)> {
    [4u32, 16, 64]
        .map(|side| {
            let mut d = Digest::default();
            let ranks =
                strata_lab::samplers::mask::void_and_cluster(side, strata::Seed(1)).unwrap();
            ranks.iter().for_each(|&r| d.push(r as u32));
            (format!("mask void_and_cluster {side}"), d.0)
        })
        .into()
}

#[test]
fn every_sampler_gives_its_pinned_values() {
    let mut digests = sampler_digests();
    digests.extend(mask_digests());
    let text: String = digests
        .iter()
        .map(|(name, d)| format!("{d:016x} {name}\n"))
        .collect();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/lab/golden.txt");
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
         STRATA_BLESS=1 cargo test -p strata-lab --test lab golden):\n{}",
        changed.join("\n")
    );
}

#[test]
fn the_renderer_crate_pins_its_samplers_with_the_same_digests() {
    // one value per line in both files: a renderer sampler's line here is its line there
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let read = |p: &str| std::fs::read_to_string(root.join(p)).unwrap();
    let (lab, renderer) = (
        read("tests/lab/golden.txt"),
        read("strata/tests/golden.txt"),
    );
    let lab: std::collections::HashMap<&str, &str> = lab
        .lines()
        .map(|l| {
            let (digest, name) = l.split_once(' ').unwrap();
            (name, digest)
        })
        .collect();
    let mut compared = 0;
    for line in renderer.lines() {
        let (digest, name) = line.split_once(' ').unwrap();
        // the sequences and the stateless functions are the renderer crate's alone
        if name.starts_with("pixel ") || name.starts_with("fn ") {
            continue;
        }
        assert_eq!(
            lab.get(name),
            Some(&digest),
            "{name}: the two golden files disagree"
        );
        compared += 1;
    }
    // every renderer sampler, 2D and D-dimensional forms
    assert_eq!(compared, 30);
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
