//! The conformance suite passes every adapter sequence, and fails every deliberately broken
//! sequence on the row that names its fault: a test that cannot fail proves nothing.

use strata::hash::{GOLDEN_GAMMA, hash_u64, hash32, mix64, stream_seed};
use strata::pixel::{PixelSampler, Sequence};
use strata::samplers::{Pmj02Stochastic, halton};
use strata::{Seed, StrataGrid};
use strata_lab::conformance::{PairStudy, Report, SequenceSource, Shuffle, Source, Suite};

fn assert_passes(report: &Report, what: &str) {
    assert!(report.passed(), "{what} should pass:\n{report}");
}

/// Asserts that the row `(test, scope)` ran and failed.
fn assert_fails(report: &Report, test: &str, scope: &str, what: &str) {
    let row = report
        .row(test, scope)
        .unwrap_or_else(|| panic!("{what}: no row {test} / {scope}"));
    assert!(
        row.cases > 0,
        "{what}: {test} / {scope} did not run:\n{report}"
    );
    assert!(
        !row.passed(),
        "{what}: {test} / {scope} should fail:\n{report}"
    );
    assert!(!report.passed());
}

fn run(name: &str) -> Report {
    Suite::default()
        .run_sequence(Sequence::by_name(name, [256, 256]).unwrap())
        .unwrap()
}

/// Runs the suite on the sequences of `Sequence::NAMES` in `range` (the list, not a list of
/// our own: a sequence cannot be added without passing), and checks that every sequence
/// whose draws promise strata had them counted.
fn the_listed_sequences_pass(range: std::ops::Range<usize>) {
    for name in &Sequence::NAMES[range] {
        let r = run(name);
        assert_passes(&r, name);
        let suite = Suite::default();
        let promises = PixelSampler::new(
            Sequence::by_name(name, [256, 256]).unwrap(),
            suite.spp,
            strata::Seed(1),
        )
        .unwrap()
        .promised_strata(suite.spp as u64);
        let counted = r.row("stratification", "per draw").unwrap().cases;
        assert_eq!(
            counted > 0,
            !promises.is_empty(),
            "{name}: {counted} strata cases"
        );
        if *name == "pmj02" {
            // every power of two up to 4096, every elementary shape, every draw of every
            // instance
            assert_eq!(counted, 91 * 4 * 128);
        }
    }
}

#[test]
fn the_first_half_of_the_sequences_pass() {
    the_listed_sequences_pass(0..Sequence::NAMES.len() / 2);
}

#[test]
fn the_second_half_of_the_sequences_pass() {
    // the Z-ordered ones: the default pixels, three inside the 256 x 256 image, share its
    // global sequence, the others fall back to their own copies; the joint ones' draws of a
    // group share an index, jointly stratified, never the same points twice
    the_listed_sequences_pass(Sequence::NAMES.len() / 2..Sequence::NAMES.len());
}

#[test]
fn pmj02_past_its_table_and_halton_at_non_powers_of_two_pass() {
    // pmj02 indices 2^16.. come from the on-demand path; Halton at 3^5 * 2 uses a mixed grid
    let suite = Suite {
        spp: 1 << 17,
        dimensions: 4,
        pixels: vec![[5, 9], [6, 9]],
        seeds: vec![Seed(3), Seed(4)],
        ..Suite::default()
    };
    assert_passes(
        &suite.run_sequence(Sequence::pmj02()).unwrap(),
        "pmj02 2^17",
    );
    let suite = Suite {
        spp: 486,
        ..Suite::default()
    };
    let r = suite.run_sequence(Sequence::halton()).unwrap();
    assert_passes(&r, "halton 486");
    assert!(
        r.row("stratification", "per draw")
            .unwrap()
            .worst_case
            .contains("2x243")
    );
}

/// A smaller suite for the broken sources (each fails by a wide margin).
fn small() -> Suite {
    Suite {
        spp: 1024,
        dimensions: 6,
        pixels: vec![[0, 0], [1, 0], [0, 1], [17, 4], [300, 200], [7, 7]],
        seeds: (1..=8).map(Seed).collect(),
        ..Suite::default()
    }
}

/// The key of a draw, as the adapter derives it.
fn stream(seed: Seed, pixel: [u32; 2], dim: u32) -> u64 {
    let key = stream_seed((pixel[0] as u64) << 32 | pixel[1] as u64, seed.0);
    mix64(key ^ (dim as u64).wrapping_mul(GOLDEN_GAMMA))
}

fn unit(bits: u32) -> f32 {
    (bits >> 8) as f32 / 16_777_216.0
}

#[test]
fn the_former_pmj02_padding_fails_across_draws() {
    // Before the fix: one shared table, the index XOR-ed and the values digitally shifted per
    // draw. Both keep sample i of every draw in corresponding strata.
    let mut s = Pmj02Stochastic::new(strata::Seed(0x706d_6a30_3200));
    s.reserve(1 << 16);
    let table = s.generated().to_vec();
    let source = move |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        let st = stream(seed, pixel, dim & !1);
        let p = table[(index as u32 ^ (st as u32 & 0xffff)) as usize];
        let shift = mix64(st);
        let k = (dim & 1) as usize;
        unit(p[k] ^ (shift >> (32 * k)) as u32)
    };
    let r = small().run(&source).unwrap();
    assert_fails(&r, "chi-square", "across draws", "XOR-shuffled pmj02");
    assert_fails(&r, "products", "across draws", "XOR-shuffled pmj02");
    assert_fails(
        &r,
        "variance over seeds",
        "across draws",
        "XOR-shuffled pmj02",
    );
}

#[test]
fn the_former_halton_padding_fails_across_draws() {
    // Before the fix: every draw the radical inverses of the same index in bases 2 and 3,
    // digit-scrambled per draw: the digits tie every draw to every other.
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        halton::scrambled_radical_inverse(
            index,
            dim & 1,
            strata::Seed(stream(seed, pixel, dim & !1)),
        )
        .unwrap()
    };
    let r = small().run(&source).unwrap();
    assert_fails(&r, "chi-square", "across draws", "former Halton");
}

#[test]
fn draws_that_share_their_values_fail() {
    // padding forgotten: every draw reads the same stream
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        let h = hash_u64(index, stream(seed, pixel, 0));
        unit((h >> (32 * (dim & 1))) as u32)
    };
    let r = small().run(&source).unwrap();
    assert_fails(&r, "products", "across draws", "shared draws");
    assert_fails(&r, "chi-square", "across draws", "shared draws");
}

#[test]
fn correlations_of_opposite_sign_in_different_pixels_do_not_cancel() {
    // The old test's blind spot: dimension 2 copies dimension 0 in some pixels and mirrors it
    // in others. A correlation averaged over pixels is about 0; every pixel is broken.
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        let draw = |d: u32| {
            let h = hash_u64(index, stream(seed, pixel, d & !1));
            unit((h >> (32 * (d & 1))) as u32)
        };
        match dim {
            2 if (pixel[0] + pixel[1]).is_multiple_of(2) => draw(0),
            2 => 1.0 - draw(0) - f32::EPSILON / 2.0,
            _ => draw(dim),
        }
    };
    let r = small().run(&source).unwrap();
    assert_fails(&r, "products", "across draws", "mirrored draws");
    let worst = r.row("products", "across draws").unwrap();
    assert!(
        worst.worst_case.contains("dims 0,2"),
        "{}",
        worst.worst_case
    );
}

#[test]
fn a_weak_correlation_in_one_pair_of_draws_is_caught() {
    // One draw in ten of dimension 4 repeats dimension 1: a correlation of 0.1, in one pair.
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        let draw = |d: u32| {
            let h = hash_u64(index, stream(seed, pixel, d & !1));
            unit((h >> (32 * (d & 1))) as u32)
        };
        if dim == 4 && hash_u64(index, stream(seed, pixel, 99)).is_multiple_of(10) {
            draw(1)
        } else {
            draw(dim)
        }
    };
    let suite = Suite {
        spp: 4096,
        ..small()
    };
    let r = suite.run(&source).unwrap();
    assert_fails(&r, "chi-square", "across draws", "weak correlation");
    assert!(
        r.row("chi-square", "across draws")
            .unwrap()
            .worst_case
            .contains("dims 1,4")
    );
    // and only that pair: no other row fails
    assert_eq!(r.failures().count(), 1, "{r}");
}

#[test]
fn pixels_and_seeds_that_share_their_values_fail() {
    let pixel_blind = |_pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        unit(hash_u64(index, stream(seed, [0, 0], dim)) as u32)
    };
    let r = small().run(&pixel_blind).unwrap();
    assert_fails(&r, "chi-square", "across pixels", "pixel-blind");
    assert!(r.row("chi-square", "across seeds").unwrap().passed());

    let seed_blind = |pixel: [u32; 2], index: u64, dim: u32, _seed: Seed| {
        unit(hash_u64(index, stream(Seed(0), pixel, dim)) as u32)
    };
    let r = small().run(&seed_blind).unwrap();
    assert_fails(&r, "chi-square", "across seeds", "seed-blind");
    assert!(r.row("chi-square", "across pixels").unwrap().passed());
}

#[test]
fn a_biased_sequence_fails_the_mean_tests() {
    // values pulled towards 0 by 5% at most: a bias, not a correlation
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        let u = unit(hash_u64(index, stream(seed, pixel, dim)) as u32);
        u * (1.0 - 0.05 * u)
    };
    let suite = Suite {
        spp: 4096,
        seeds: (1..=16).map(Seed).collect(),
        ..small()
    };
    let r = suite.run(&source).unwrap();
    for scope in ["within draws", "across draws"] {
        assert_fails(&r, "t-test over seeds", scope, "biased");
        assert_fails(&r, "variance over seeds", scope, "biased");
        assert_fails(&r, "integrands", scope, "biased");
    }
}

/// Independent values that claim to be (0,m,2)-nets.
struct FalsePromise;

impl Source for FalsePromise {
    fn value(&self, pixel: [u32; 2], index: u64, dim: u32, seed: Seed) -> f32 {
        unit(hash_u64(index, stream(seed, pixel, dim)) as u32)
    }

    fn promised_strata(&self, n: u64) -> Vec<StrataGrid> {
        if n.is_power_of_two() {
            vec![StrataGrid {
                columns: n as u32,
                rows: 1,
            }]
        } else {
            Vec::new()
        }
    }
}

#[test]
fn a_broken_promise_of_stratification_fails() {
    let r = small().run(&FalsePromise).unwrap();
    assert_fails(&r, "stratification", "per draw", "false promise");
    // everything else about independent values is fine
    assert_eq!(r.failures().count(), 1, "{r}");
}

#[test]
fn a_renderers_own_closure_can_be_checked() {
    // a renderer that keeps one sampler per seed, behind a closure
    let samplers: Vec<_> = (1..=4u64)
        .map(|s| PixelSampler::new(Sequence::pmj02(), 256, strata::Seed(s)).unwrap())
        .collect();
    let suite = Suite {
        spp: 256,
        dimensions: 6,
        pixels: vec![[0, 0], [1, 1], [9, 2]],
        seeds: (1..=4).map(Seed).collect(),
        ..Suite::default()
    };
    let r = suite
        .run(&|pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
            samplers[seed.0 as usize - 1].sample_2d(pixel, index, dim & !1)[(dim & 1) as usize]
        })
        .unwrap();
    assert_passes(&r, "closure over pmj02");
    // values outside [0, 1) are refused, not tested
    let e = suite
        .run(&|_: [u32; 2], _: u64, _: u32, _: Seed| 1.0f32)
        .unwrap_err();
    assert!(e.to_string().contains("outside [0, 1)"), "{e}");
}

#[test]
fn independent_values_pass_at_small_counts() {
    // Pearson's statistic on 31 x 31 cells is far from its chi-square law with a few points
    // per cell; the grid shrinks with the count. This case failed at 1e-40 on 31 x 31.
    let source = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        unit(hash_u64(index, stream(seed, pixel, dim)) as u32)
    };
    let suite = Suite {
        spp: 16,
        dimensions: 14,
        pixels: vec![[3274, 2305]],
        seeds: vec![Seed(1044)],
        ..Suite::default()
    };
    let r = suite.run(&source).unwrap();
    assert_passes(&r, "independent values at 16 samples");
    assert_eq!(r.chi_square_side, 2);
    for spp in [32, 64, 128] {
        let suite = Suite { spp, ..small() };
        assert_passes(&suite.run(&source).unwrap(), "independent values");
    }
}

/// A smaller pair study for `cargo test` (49,600 pairs; the full one is `--ignored`).
fn small_pairs() -> PairStudy {
    PairStudy {
        pixels: 100,
        draws: 32,
        ..PairStudy::default()
    }
}

#[test]
fn the_shipped_shuffle_pairs_draws_as_chance_does_on_a_small_study() {
    let source = SequenceSource::new(Sequence::sobol(), 4096).unwrap();
    let r = small_pairs().run(&source).unwrap();
    assert_eq!(r.pairs, 100 * 32 * 31 / 2);
    assert!(r.passed(), "sobol: {r}");
    // the shipped shuffle in the study is the adapter's index shuffle: the same statistics as
    // the sequence under the nested padding (the default's shells reorder the index further)
    let nested = SequenceSource::new(Sequence::sobol(), 4096)
        .unwrap()
        .with_padding(strata::Padding::Nested);
    let n = small_pairs().run(&nested).unwrap();
    assert!(n.passed(), "sobol nested: {n}");
    assert_eq!(small_pairs().run(&Shuffle::Shipped).unwrap(), n);
    assert_ne!(n, r, "the shells padding changes the pairs");
}

/// The full study (786,240 pairs): every sequence of the list passes, and one plain round of
/// the hash, the counterexample, fails (it has a case above the bound at every seed tried).
#[test]
#[ignore = "about 70 s in the test profile, 30 s in release: .ci/run runs it"]
fn the_pair_test_passes_every_sequence_and_fails_one_plain_round() {
    let study = PairStudy::default();
    // every sequence of the list
    for name in Sequence::NAMES {
        let source =
            SequenceSource::new(Sequence::by_name(name, [256, 256]).unwrap(), 4096).unwrap();
        let r = study.run(&source).unwrap();
        assert_eq!(r.pairs, 786_240);
        assert!(r.passed(), "{name}: {r}");
    }
    let r = study.run(&Shuffle::PlainRound).unwrap();
    assert!(!r.passed(), "one plain round should fail: {r}");
    assert!(study.run(&Shuffle::TwoRounds).unwrap().passed());
    // independent values keyed by XOR-ing the index with the draw's key (the first version of
    // the 32-bit `random`, which failed at each of 8 seeds): two draws whose keys differ by
    // less than the sample count read each other's hash inputs in another order
    let xor_keyed = |pixel: [u32; 2], index: u64, dim: u32, seed: Seed| {
        // the image's key words, as the shader receives them
        let k = strata::PixelSampler::new(Sequence::random(), 1, seed)
            .unwrap()
            .gpu_parameters()
            .unwrap()
            .key;
        let p = k.map(|k| hash32(pixel[0], hash32(pixel[1], k)));
        let x = (dim & !1 ^ p[0]).wrapping_mul(0x7feb_352d);
        let h = x ^ (x >> 15);
        unit(hash32(index as u32, h ^ p[2 + (dim & 1) as usize]))
    };
    let r = study.run(&xor_keyed).unwrap();
    assert!(!r.passed(), "XOR-keyed random values should fail: {r}");
}
