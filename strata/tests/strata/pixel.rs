//! The path-tracer adapter: values in [0,1), order independence (pbrt-v4's revisit test),
//! per-pixel stratification, padding decorrelation, index limits; and Sobol' direction
//! numbers checked against an independent implementation.

use crate::common::{cell, is_net, is_net_fixed};
use strata::pixel::{Padding, PixelSampler, Sequence};

fn all() -> Vec<Sequence> {
    Sequence::NAMES
        .iter()
        .map(|n| Sequence::by_name(n, [256, 256]).unwrap())
        .collect()
}

#[test]
fn values_stay_in_the_unit_interval_everywhere() {
    for seq in all() {
        let s = PixelSampler::new(seq.clone(), 16, strata::Seed(u64::MAX)).unwrap();
        for pixel in [[0u32, 0], [u32::MAX, u32::MAX], [12345, 0]] {
            for index in [
                0u64,
                1,
                15,
                16,
                65535,
                65536,
                (1 << 32) - 1,
                1 << 32,
                u64::MAX,
            ] {
                for dim in [0u32, 1, 2, 7, 1000, u32::MAX - 3, u32::MAX - 1, u32::MAX] {
                    let v = s.sample_2d(pixel, index, dim);
                    let w = s.sample_1d(pixel, index, dim);
                    let q = s.sample_4d(pixel, index, dim);
                    for x in [v[0], v[1], w, q[0], q[1], q[2], q[3]] {
                        assert!(
                            (0.0..1.0).contains(&x),
                            "{}: {x} at {pixel:?} {index} {dim}",
                            seq.name()
                        );
                    }
                    // the 32-bit values are the floats' source, where the kernel has them
                    if let Some(u) = s.sample_2d_u32(pixel, index, dim) {
                        let f = u.map(strata::float::unit_f32_from_u32);
                        assert_eq!([v[0], v[1]], f, "{}", seq.name());
                    } else {
                        assert!(!seq.runs_on_gpu(), "{}", seq.name());
                    }
                }
            }
        }
    }
}

#[test]
fn revisiting_a_pixel_in_any_order_gives_the_same_bits() {
    for seq in all() {
        let mut s = PixelSampler::new(seq.clone(), 16, strata::Seed(3)).unwrap();
        let draw = |s: &mut PixelSampler, i: u64| {
            s.start_pixel_sample([1, 5], i, 0);
            let mut v = Vec::new();
            for _ in 0..4 {
                let a = s.get_2d();
                v.extend([a[0].to_bits(), a[1].to_bits(), s.get_1d().to_bits()]);
            }
            v
        };
        let forward: Vec<Vec<u32>> = (0..16).map(|i| draw(&mut s, i)).collect();
        // another pixel in between, then the samples in reverse order, from a clone
        s.start_pixel_sample([0, 6], 10, 0);
        let _ = (s.get_2d(), s.get_1d());
        let mut t = s.clone();
        for i in (0..16).rev() {
            assert_eq!(
                draw(&mut t, i),
                forward[i as usize],
                "{}: sample {i}",
                seq.name()
            );
        }
        // and the stateless form agrees with get_2d / get_1d
        t.start_pixel_sample([1, 5], 9, 0);
        let a = t.get_2d();
        let b = t.get_1d();
        assert_eq!(t.sample_2d([1, 5], 9, 0), a);
        assert_eq!(t.sample_1d([1, 5], 9, 2), b);
    }
}

#[test]
fn each_pixel_gets_a_stratified_set_in_every_draw() {
    for name in ["pmj02", "sobol"] {
        for spp in [4u32, 16, 64, 256] {
            let s = PixelSampler::new(
                Sequence::by_name(name, [256, 256]).unwrap(),
                spp,
                strata::Seed(11),
            )
            .unwrap();
            for pixel in [[0u32, 0], [7, 3], [1000, 999]] {
                for dim in [0u32, 2, 9] {
                    let pts: Vec<_> = (0..spp as u64)
                        .map(|i| s.sample_2d(pixel, i, dim))
                        .collect();
                    assert!(
                        is_net(&pts),
                        "{name}: pixel {pixel:?} dim {dim} spp {spp} is not a (0,m,2)-net"
                    );
                }
            }
        }
    }
    // jittered: one point per cell of s x s
    let s = PixelSampler::new(Sequence::jittered(), 49, strata::Seed(2)).unwrap();
    for dim in [0u32, 4] {
        let pts: Vec<_> = (0..49u64).map(|i| s.sample_2d([3, 4], i, dim)).collect();
        crate::common::assert_one_per_cell(&pts, 7, 7, &format!("jittered dim {dim}"));
    }
}

// Independence of draws, pixels and seeds is tested per pixel and per pair of dimensions by
// the conformance suite (tests/conformance.rs), which also fails the former, tied padding.

#[test]
fn halton_blocks_are_stratified_on_their_grid_in_every_draw() {
    // spp 100: blocks of 108 = 2^2 3^3, one point per cell of 4 x 27
    let s = PixelSampler::new(Sequence::halton(), 100, strata::Seed(4)).unwrap();
    assert_eq!(s.sequence().round_count(100), 108);
    for pixel in [[0u32, 0], [9, 4]] {
        for dim in [0u32, 2, 11] {
            for block in [0u64, 1, 7] {
                let pts: Vec<_> = (0..108u64)
                    .map(|i| s.sample_2d(pixel, 108 * block + i, dim))
                    .collect();
                crate::common::assert_one_per_cell(&pts, 4, 27, &format!("halton dim {dim}"));
            }
        }
    }
}

#[test]
fn past_two_to_the_32_the_draws_stay_stratified() {
    for name in ["pmj02", "sobol"] {
        let s = PixelSampler::new(
            Sequence::by_name(name, [256, 256]).unwrap(),
            256,
            strata::Seed(8),
        )
        .unwrap();
        for start in [1u64 << 32, 5 << 32] {
            let pts: Vec<_> = (0..256u64)
                .map(|i| s.sample_2d([3, 3], start + i, 4))
                .collect();
            assert!(is_net(&pts), "{name} at {start}");
        }
    }
}

#[test]
fn progressive_sequences_ignore_the_samples_per_pixel() {
    for name in ["random", "pmj02", "sobol"] {
        let a = PixelSampler::new(
            Sequence::by_name(name, [256, 256]).unwrap(),
            16,
            strata::Seed(2),
        )
        .unwrap();
        let b = PixelSampler::new(
            Sequence::by_name(name, [256, 256]).unwrap(),
            1000,
            strata::Seed(2),
        )
        .unwrap();
        for i in [0u64, 5, 999, 70_000] {
            assert_eq!(
                a.sample_2d([1, 2], i, 6),
                b.sample_2d([1, 2], i, 6),
                "{name}"
            );
        }
    }
}

#[test]
fn bounces_start_at_fixed_dimensions() {
    let mut s = PixelSampler::new(Sequence::sobol(), 16, strata::Seed(1)).unwrap();
    s.start_pixel_sample([4, 4], 3, 0);
    assert_eq!(s.dimension(), 0);
    let _ = s.get_pixel_2d();
    let _ = s.get_1d();
    assert_eq!(s.dimension(), 3);
    // bounce 2 of the default layout: 8 + 2 * 8, whatever came before
    s.start_bounce(2);
    assert_eq!(s.dimension(), 24);
    assert_eq!(s.get_2d(), s.sample_2d([4, 4], 3, 24));
    s.set_dimension(7);
    assert_eq!(s.get_1d(), s.sample_1d([4, 4], 3, 7));
    let layout = strata::pixel::DimensionLayout {
        camera: 5,
        per_bounce: 6,
    };
    let mut t = s.clone().with_layout(layout).unwrap();
    // a layout with no dimension per bounce is refused (was: every bounce at one dimension)
    let none = strata::pixel::DimensionLayout {
        camera: 5,
        per_bounce: 0,
    };
    assert!(s.clone().with_layout(none).is_err());
    t.start_bounce(3);
    assert_eq!(t.dimension(), 23);
    // saturates instead of wrapping
    t.start_bounce(u32::MAX);
    assert_eq!(t.dimension(), u32::MAX);
}

#[test]
fn the_rand_bridge_hands_out_successive_dimensions() {
    use rand::{Rng, RngExt};
    for seq in all() {
        let mut s = PixelSampler::new(seq.clone(), 16, strata::Seed(5)).unwrap();
        s.start_pixel_sample([2, 7], 9, 4);
        let mut bytes = [0u8; 12];
        let (a, b, c, d) = {
            let mut rng = s.rng();
            let a: f32 = rng.random();
            let b = rng.next_u64();
            let c = rng.next_u32();
            let d: f64 = rng.random();
            rng.fill_bytes(&mut bytes);
            (a, b, c, d)
        };
        // one dimension per word; the value's top 24 bits on top: f32 is the sequence's value
        // rounded down to a multiple of 2^-24 (exactly it for the nets)
        let top24 = |v: f32| (v * 16_777_216.0) as u32 as f32 / 16_777_216.0;
        assert_eq!(a, top24(s.sample_1d([2, 7], 9, 4)), "{}", seq.name());
        assert_eq!(
            (b >> 40) as f32 / 16_777_216.0,
            top24(s.sample_1d([2, 7], 9, 5))
        );
        assert_eq!(
            (c >> 8) as f32 / 16_777_216.0,
            top24(s.sample_1d([2, 7], 9, 6))
        );
        // (an f64's top 24 bits, truncated: `as f32` would round to nearest)
        assert_eq!(
            (d * 16_777_216.0) as u32 as f32 / 16_777_216.0,
            top24(s.sample_1d([2, 7], 9, 7))
        );
        assert_eq!(s.dimension(), 4 + 4 + 2);
        assert!(bytes.iter().any(|&x| x != 0));
    }
}

#[test]
fn indices_past_two_to_the_32_start_a_fresh_copy() {
    for seq in all() {
        let s = PixelSampler::new(seq.clone(), 16, strata::Seed(1)).unwrap();
        let a = s.sample_2d([2, 2], 3, 0);
        let b = s.sample_2d([2, 2], (1 << 32) + 3, 0);
        assert_ne!(a, b, "{}", seq.name());
        assert_eq!(b, s.sample_2d([2, 2], (1 << 32) + 3, 0));
    }
}

#[test]
fn bad_counts_are_refused() {
    let e = PixelSampler::new(Sequence::jittered(), 10, strata::Seed(1)).unwrap_err();
    assert!(e.to_string().contains("9 or 16"), "{e}");
    assert!(PixelSampler::new(Sequence::sobol(), 0, strata::Seed(1)).is_err());
    assert!(
        Sequence::by_name("cmj", [256, 256])
            .unwrap_err()
            .to_string()
            .contains("sobol")
    );
    let s = PixelSampler::new(Sequence::pmj02(), 10, strata::Seed(1)).unwrap();
    assert_eq!(s.sequence().round_count(10), 16);
    assert_eq!(
        PixelSampler::new(Sequence::jittered(), 9, strata::Seed(1))
            .unwrap()
            .sequence()
            .round_count(10),
        16
    );
}

#[test]
fn the_adapter_is_cheap_to_clone_and_thread_safe() {
    fn send_sync<T: Send + Sync + Clone>() {}
    send_sync::<PixelSampler>();
    let s = PixelSampler::new(Sequence::pmj02(), 16, strata::Seed(1)).unwrap();
    let clones: Vec<_> = (0..8).map(|_| s.clone()).collect();
    std::thread::scope(|scope| {
        for c in clones {
            scope.spawn(move || {
                assert_eq!(
                    c.sample_2d([1, 1], 1, 0),
                    PixelSampler::new(Sequence::pmj02(), 16, strata::Seed(1))
                        .unwrap()
                        .sample_2d([1, 1], 1, 0)
                );
            });
        }
    });
}

#[test]
fn sobol_direction_numbers_match_an_independent_implementation() {
    // sobol_burley builds its tables from the same Joe-Kuo file with its own code; its
    // `sobol_rev` is the plain (unscrambled) Sobol' value in bit-reversed form.
    use strata::samplers::sobol::{MAX_DIMENSIONS, sobol_u32};
    assert_eq!(MAX_DIMENSIONS, 1000);
    for dim in 0..256u32 {
        for i in (0u32..1 << 16).step_by(251).chain([1, 2, 3, 65535]) {
            let theirs = sobol_burley::parts::sobol_rev(i.reverse_bits(), dim).reverse_bits();
            assert_eq!(
                sobol_u32(i, dim),
                Some(theirs),
                "dimension {dim}, index {i}"
            );
        }
    }
}

#[test]
#[cfg(debug_assertions)]
#[should_panic(expected = "past the budget of this bounce")]
fn a_bounce_that_overruns_its_budget_is_caught_in_debug_builds() {
    let mut s = PixelSampler::new(Sequence::sobol(), 16, strata::Seed(1)).unwrap();
    s.start_pixel_sample([0, 0], 0, 0);
    s.start_bounce(0); // dimensions 8..16
    for _ in 0..5 {
        let _ = s.get_2d(); // the fifth pair takes 16-17: bounce 1's
    }
}

#[test]
fn z_ordered_sequences_need_a_resolution_and_fall_back_outside_it() {
    assert!(Sequence::zsobol(0, 10).is_err());
    assert!(Sequence::zpmj02(10, 1 << 17).is_err());
    let e = Sequence::zsobol(0, 4).unwrap_err().to_string();
    assert!(e.contains("width") && e.contains("1 to 65536"), "{e}");
    // by name: the default resolution
    assert_eq!(
        Sequence::by_name("zsobol", [256, 256]).unwrap().name(),
        Sequence::zsobol(256, 256).unwrap().name()
    );
    for seq in [
        Sequence::zsobol(20, 12).unwrap(),
        Sequence::zpmj02(20, 12).unwrap(),
    ] {
        let s = PixelSampler::new(seq.clone(), 16, strata::Seed(4)).unwrap();
        // inside: every pixel's block is a net at every power of two
        for pixel in [[0u32, 0], [19, 11], [7, 5]] {
            for n in [4u64, 16] {
                for dim in [0u32, 2, 9] {
                    let pts: Vec<_> = (0..n).map(|i| s.sample_2d(pixel, i, dim)).collect();
                    assert!(is_net(&pts), "{} {pixel:?} n {n} dim {dim}", seq.name());
                }
            }
        }
        // past the block (indices >= 16) and outside the image: independent values, no panic
        for (pixel, index) in [
            ([3u32, 3], 16u64),
            ([3, 3], u64::MAX),
            ([20, 0], 0),
            ([u32::MAX, 5], 3),
        ] {
            let v = s.sample_2d(pixel, index, 6);
            assert!((0.0..1.0).contains(&v[0]) && (0.0..1.0).contains(&v[1]));
        }
        // neighbouring pixels take complementary blocks: a 2 x 2 tile at 4 spp is a 16-point net
        // in dims 2-3 for some aligned tile (the scrambled Z curve keeps aligned tiles together)
        let tile: Vec<_> = [[8u32, 4], [9, 4], [8, 5], [9, 5]]
            .iter()
            .flat_map(|&p| (0..16u64).map(move |i| (p, i)))
            .map(|(p, i)| s.sample_2d(p, i, 2))
            .collect();
        assert!(is_net(&tile), "{}: the 2 x 2 tile is not a net", seq.name());
    }
}

#[test]
fn the_lattice_is_stratified_in_both_axes_at_every_power_of_two() {
    let s = PixelSampler::new(Sequence::lattice(), 64, strata::Seed(2)).unwrap();
    for dim in [0u32, 6] {
        for n in [8u64, 64, 256] {
            let pts: Vec<_> = (0..n).map(|i| s.sample_2d([5, 1], i, dim)).collect();
            crate::common::assert_one_per_cell(&pts, n as u32, 1, "lattice x");
            crate::common::assert_one_per_cell(&pts, 1, n as u32, "lattice y");
        }
    }
}

#[test]
fn four_dimensions_at_once_are_two_draws_of_two() {
    // get_4d's lane-parallel path against two scalar get_2d, bit for bit: every sequence, pixels
    // inside and outside the Z resolution, the pmj02 table and its on-demand continuation past
    // 2^16, and a later block of 2^32 samples
    for seq in all() {
        let mut a = PixelSampler::new(seq.clone(), 16, strata::Seed(9)).unwrap();
        let mut b = a.clone();
        for pixel in [[0u32, 0], [5, 3], [63, 63], [300, 2]] {
            for index in [0u64, 1, 15, 1000, 65_535, 65_536, 200_000, (1 << 32) + 3] {
                for dim in [0u32, 2, 7] {
                    a.start_pixel_sample(pixel, index, dim);
                    b.start_pixel_sample(pixel, index, dim);
                    let v = a.get_4d();
                    let (p, q) = (b.get_2d(), b.get_2d());
                    let (name, bits) = (seq.name(), |x: f32| x.to_bits());
                    assert_eq!(
                        v.map(bits),
                        [p[0], p[1], q[0], q[1]].map(bits),
                        "{name} pixel {pixel:?} index {index} dim {dim}"
                    );
                    assert_eq!(a.dimension(), b.dimension());
                    assert_eq!(v, a.sample_4d(pixel, index, dim));
                }
            }
        }
    }
}

#[test]
fn stateful_draws_equal_the_stateless_ones_across_pixels_samples_and_dims() {
    // the sampler caches per draw below dimension 64 a Z-ordered pixel's place and the shells'
    // keys, and per row the pixel keys' first half: the caches must follow changes of pixel,
    // row, shell and epoch (and hold within one: samples 5 and 6 share a shell, pixels 3 and 8
    // a row), and draws past 64 dimensions, get_4d and get_1d must agree
    for seq in all() {
        let mut s = PixelSampler::new(seq.clone(), 16, strata::Seed(11)).unwrap();
        // the stateless draws of a sampler that starts no sample (they would read `s`'s own
        // pixel state, cache and all, where it has the pixel)
        let r = s.clone();
        for (pixel, index) in [
            ([3, 4], 0u64),
            ([3, 4], 5),
            ([3, 4], 6),
            ([9, 1], 6),
            ([9, 1], 5),
            ([3, 4], 15),
            ([3, 4], 16),
            ([8, 4], 17),
            ([8, 4], (1 << 32) + 17),
            ([8, 4], 18),
        ] {
            s.start_pixel_sample(pixel, index, 0);
            let mut dim = 0;
            while dim < 80 {
                let a = s.get_2d();
                assert_eq!(a, r.sample_2d(pixel, index, dim), "{} 2d {dim}", seq.name());
                let q = s.get_4d();
                assert_eq!(
                    q,
                    r.sample_4d(pixel, index, dim + 2),
                    "{} 4d {dim}",
                    seq.name()
                );
                let x = s.get_1d();
                assert_eq!(
                    x,
                    r.sample_1d(pixel, index, dim + 6),
                    "{} 1d {dim}",
                    seq.name()
                );
                dim += 7;
            }
        }
    }
}

#[test]
fn any_order_of_draws_gives_the_stateless_values() {
    // get_2d at a multiple of 4 computes the next pair too and keeps it: a renderer's mix of
    // 1D, 2D and 4D draws, jumps between dimensions and new samples (of the same pixel and of
    // others, under both paddings) must still see exactly the stateless values
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |n: u64| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) % n
    };
    // (the Z-ordered sequences over a 3 x 2 image: x = 3 is outside it)
    for seq in Sequence::NAMES
        .iter()
        .map(|n| Sequence::by_name(n, [3, 2]).unwrap())
    {
        for padding in [
            strata::Padding::Nested,
            strata::Padding::Uniform,
            strata::Padding::Shells,
        ] {
            let mut s = PixelSampler::new(seq.clone(), 16, strata::Seed(5))
                .unwrap()
                .with_padding(padding);
            let (mut pixel, mut index) = ([0u32, 0], 0u64);
            for step in 0..4000 {
                let name = format!("{} {padding:?} step {step}", seq.name());
                match next(8) {
                    0 => {
                        pixel = [next(4) as u32, next(2) as u32];
                        index = next(20);
                        s.start_pixel_sample(pixel, index, next(9) as u32);
                    }
                    1 => s.set_dimension(next(12) as u32),
                    2 => {
                        let dim = s.dimension();
                        assert_eq!(
                            s.get_1d(),
                            s.sample_1d(pixel, index, dim),
                            "{name} 1d {dim}"
                        );
                    }
                    3 => {
                        let dim = s.dimension();
                        assert_eq!(
                            s.get_4d(),
                            s.sample_4d(pixel, index, dim),
                            "{name} 4d {dim}"
                        );
                    }
                    _ => {
                        let dim = s.dimension();
                        assert_eq!(
                            s.get_2d(),
                            s.sample_2d(pixel, index, dim),
                            "{name} 2d {dim}"
                        );
                    }
                }
                if s.dimension() > 40 {
                    s.set_dimension(0);
                }
            }
        }
    }
}

#[test]
fn uniform_padding_keeps_each_block_and_reorders_it_per_draw() {
    use strata::Padding;
    for name in ["sobol", "pmj02", "lattice", "zsobol", "zpmj02"] {
        let seq = Sequence::by_name(name, [16, 16]).unwrap();
        let nested = PixelSampler::new(seq.clone(), 16, strata::Seed(5))
            .unwrap()
            .with_padding(Padding::Nested);
        let uniform = nested.clone().with_padding(Padding::Uniform);
        let shells = nested.clone().with_padding(Padding::Shells);
        assert_eq!(uniform.padding(), Padding::Uniform);
        let mut reordered = 0;
        for pixel in [[0u32, 0], [3, 9]] {
            for block in [0u64, 1, 7] {
                for dim in [0u32, 2, 10, 70] {
                    let draw = |s: &PixelSampler| -> Vec<[f32; 2]> {
                        (0..16)
                            .map(|i| s.sample_2d(pixel, block * 16 + i, dim))
                            .collect()
                    };
                    let bits = |v: &[[f32; 2]]| -> Vec<[u32; 2]> {
                        let mut b: Vec<[u32; 2]> = v.iter().map(|p| p.map(f32::to_bits)).collect();
                        b.sort();
                        b
                    };
                    let (a, b) = (draw(&shells), draw(&uniform));
                    // each whole block is a net (the lattice: one point per 1/16 on each axis)
                    if name == "lattice" {
                        for axis in 0..2 {
                            let mut cells: Vec<usize> =
                                b.iter().map(|p| (p[axis] * 16.0) as usize).collect();
                            cells.sort();
                            assert_eq!(cells, (0..16).collect::<Vec<_>>(), "{name} {block}");
                        }
                    } else {
                        assert!(is_net(&b), "{name} {pixel:?} block {block} dim {dim}");
                    }
                    // the blocks that are whole shells hold the shells' points, in another order
                    if block < 2 {
                        assert_eq!(bits(&a), bits(&b), "{name} {pixel:?} block {block}");
                        reordered += (a != b) as u32;
                    }
                    // stateful draws agree with the stateless ones
                    let mut t = uniform.clone();
                    t.start_pixel_sample(pixel, block * 16 + 3, dim);
                    assert_eq!(t.get_2d(), uniform.sample_2d(pixel, block * 16 + 3, dim));
                    t.start_pixel_sample(pixel, block * 16 + 3, dim);
                    assert_eq!(t.get_4d(), uniform.sample_4d(pixel, block * 16 + 3, dim));
                }
            }
        }
        assert!(
            reordered >= 14,
            "{name}: only {reordered} of 16 blocks reordered"
        );
        // whole blocks keep their promise, prefixes do not; the shader has no uniform padding
        assert!(!uniform.promised_strata(16).is_empty(), "{name}");
        assert!(uniform.promised_strata(8).is_empty(), "{name}");
        assert!(!nested.promised_strata(8).is_empty(), "{name}");
        assert!(uniform.gpu_parameters().is_err() && nested.gpu_parameters().is_ok());
    }
    // the sequences that already pad by whole blocks are unchanged by it
    for name in ["random", "jittered", "halton"] {
        let s = PixelSampler::new(
            Sequence::by_name(name, [256, 256]).unwrap(),
            16,
            strata::Seed(5),
        )
        .unwrap();
        let u = s.clone().with_padding(Padding::Uniform);
        assert_eq!(
            s.sample_2d([1, 2], 5, 4),
            u.sample_2d([1, 2], 5, 4),
            "{name}"
        );
    }
}

#[test]
fn zjoint_in_groups_of_two_is_zsobol() {
    // with groups of two dimensions every draw is its own group: the same bits as zsobol at
    // every even dimension (inside the image, outside it, past the pixel's block, both paddings)
    let zsobol = Sequence::zsobol(5, 3).unwrap();
    let joint = Sequence::by_name("zjoint-2", [5, 3]).unwrap();
    assert_eq!(joint.group(), 2);
    for padding in [
        strata::Padding::Nested,
        strata::Padding::Uniform,
        strata::Padding::Shells,
    ] {
        let a = PixelSampler::new(zsobol.clone(), 16, strata::Seed(3))
            .unwrap()
            .with_padding(padding);
        let b = PixelSampler::new(joint.clone(), 16, strata::Seed(3))
            .unwrap()
            .with_padding(padding);
        for pixel in [[0u32, 0], [4, 2], [2, 1], [7, 1]] {
            for index in [0u64, 5, 15, 16, 40, (1 << 32) + 1] {
                for dim in (0..40).step_by(2) {
                    assert_eq!(
                        a.sample_2d(pixel, index, dim),
                        b.sample_2d(pixel, index, dim),
                        "{padding:?} {pixel:?} {index} {dim}"
                    );
                }
            }
        }
    }
}

#[test]
fn zjoint_stratifies_the_draws_of_a_group_jointly() {
    // a pixel's 64 samples: the first coordinates of two draws of one group are a projection
    // of one aligned block of the multi-dimensional Sobol' sequence, a (t, 6, 2)-net with that
    // projection's t-value in every pixel; zsobol's draws are independent, their projection as
    // coarse as chance makes it; and two draws of different groups are independent in zjoint too
    let t_of = |seq: &Sequence, pixel: [u32; 2], da: u32, db: u32| {
        let s = PixelSampler::new(seq.clone(), 64, strata::Seed(17)).unwrap();
        let pts: Vec<Vec<f32>> = (0..64)
            .map(|i| vec![s.sample_1d(pixel, i, da), s.sample_1d(pixel, i, db)])
            .collect();
        t_value(&pts, 6, 2)
    };
    let joint = Sequence::by_name("zjoint", [8, 8]).unwrap();
    let zsobol = Sequence::zsobol(8, 8).unwrap();
    let pixels: Vec<[u32; 2]> = (0..16).map(|k| [k % 8, k / 2 % 8]).collect();
    for (da, db) in [(0u32, 2u32), (0, 4), (1, 3), (2, 6), (3, 5)] {
        let tj: Vec<u32> = pixels.iter().map(|&p| t_of(&joint, p, da, db)).collect();
        let tz: Vec<u32> = pixels.iter().map(|&p| t_of(&zsobol, p, da, db)).collect();
        let tx: Vec<u32> = pixels
            .iter()
            .map(|&p| t_of(&joint, p, da, db + 8))
            .collect();
        // the projection's own t-value (0 to 2 for these pairs of Sobol' dimensions 0-6)
        assert!(
            tj.iter().all(|&t| t == tj[0] && t <= 2),
            "dims {da},{db}: zjoint {tj:?}"
        );
        // independent draws: no pixel's pair is that fine (t >= 3 here, fixed seed)
        assert!(tz.iter().all(|&t| t >= 3), "dims {da},{db}: zsobol {tz:?}");
        assert!(
            tx.iter().all(|&t| t >= 3),
            "dims {da},{db}+8: zjoint {tx:?}"
        );
    }
}

/// The t-value in base `b` (2 or 4) of `b^k` points of `s` dimensions (values in `[0, 1)`),
/// counted: the smallest `t` for which every base-`b` elementary box of volume `b^(t - k)` holds
/// `b^t` points.
fn t_value(points: &[Vec<f32>], k: u32, b: u32) -> u32 {
    let bits = b.trailing_zeros();
    let s = points[0].len();
    (0..=k)
        .find(|&t| {
            let rho = k - t;
            let mut parts = vec![0u32; s];
            loop {
                if parts.iter().sum::<u32>() == rho {
                    let mut counts = std::collections::HashMap::new();
                    for p in points {
                        let cell: Vec<u32> = p
                            .iter()
                            .zip(&parts)
                            .map(|(&v, &d)| (v as f64 * (b as f64).powi(d as i32)) as u32)
                            .collect();
                        *counts.entry(cell).or_insert(0u32) += 1;
                    }
                    if counts.len() as u64 != 1u64 << (bits * rho)
                        || counts.values().any(|&c| c != 1 << (bits * t))
                    {
                        return false;
                    }
                }
                let mut q = 0;
                while q < s && parts[q] == rho {
                    parts[q] = 0;
                    q += 1;
                }
                if q == s {
                    return true;
                }
                parts[q] += 1;
            }
        })
        .unwrap()
}

#[test]
fn zquad_makes_each_group_of_four_dimensions_a_base4_net_per_pixel() {
    // a pixel's 4^k samples of one group's four dimensions (draws at 0 and 2, their two
    // coordinates each) are an aligned block of the base-4 (0,4)-sequence under Owen
    // scrambling: a (0,k,4)-net in base 4 in every pixel, at every prefix 4^k of its block,
    // inside the image and outside it; zsobol's independent draws are not, nor are four
    // dimensions from two groups of zquad
    let quad = Sequence::zquad(8, 8).unwrap();
    let zsobol = Sequence::zsobol(8, 8).unwrap();
    let draws = |seq: &Sequence, pixel: [u32; 2], n: u64, dims: [u32; 2]| -> Vec<Vec<f32>> {
        let s = PixelSampler::new(seq.clone(), 256, strata::Seed(23)).unwrap();
        (0..n)
            .map(|i| {
                let (p, q) = (
                    s.sample_2d(pixel, i, dims[0]),
                    s.sample_2d(pixel, i, dims[1]),
                );
                vec![p[0], p[1], q[0], q[1]]
            })
            .collect()
    };
    for pixel in [[0u32, 0], [3, 5], [7, 7], [9, 2]] {
        for k in 1..=4u32 {
            let n = 1u64 << (2 * k);
            for group in [0u32, 4, 16] {
                let t = t_value(&draws(&quad, pixel, n, [group, group + 2]), k, 4);
                assert_eq!(t, 0, "zquad {pixel:?} 4^{k} group at {group}");
            }
        }
        // 256 samples: independent draws, or draws of two groups, are far from a (0,4,4)-net
        assert!(t_value(&draws(&zsobol, pixel, 256, [0, 2]), 4, 4) >= 2);
        assert!(t_value(&draws(&quad, pixel, 256, [2, 4]), 4, 4) >= 2);
    }
}

#[test]
fn a_filled_pixel_sample_is_the_stateless_draws() {
    // `fill_sample` is the row layout of `points --pixel`, the Python binding and the
    // conformance suite: pairs from `get_2d`, a last `get_1d` for an odd width, from any
    // starting dimension; every value must be the stateless draw at its dimension
    for seq in Sequence::NAMES
        .iter()
        .map(|n| Sequence::by_name(n, [3, 2]).unwrap())
    {
        for padding in [
            strata::Padding::Nested,
            strata::Padding::Uniform,
            strata::Padding::Shells,
        ] {
            let mut s = PixelSampler::new(seq.clone(), 16, strata::Seed(9))
                .unwrap()
                .with_padding(padding);
            for (pixel, index) in [
                ([0u32, 0], 0u64),
                ([2, 1], 13),
                ([3, 0], 5),
                ([1, 1], 1 << 32),
            ] {
                for first in [0u32, 1, 3, 8] {
                    for width in 0..=11usize {
                        let name = format!(
                            "{} {padding:?} {pixel:?} {index} {first}+{width}",
                            seq.name()
                        );
                        // (a draw of another sample first: nothing of it may leak in)
                        s.start_pixel_sample([1, 0], 3, 2);
                        let _ = s.get_2d();
                        let mut row = vec![f32::NAN; width];
                        s.fill_sample(pixel, index, first, &mut row);
                        for (k, &v) in row.iter().enumerate() {
                            let dim = first + k as u32;
                            let want = if k % 2 == 0 && k + 1 == width {
                                s.sample_1d(pixel, index, dim)
                            } else {
                                s.sample_2d(pixel, index, first + (k as u32 & !1))[k % 2]
                            };
                            assert_eq!(v.to_bits(), want.to_bits(), "{name} dim {dim}");
                            // the first coordinate of the 2D draw, too
                            if k % 2 == 0 {
                                assert_eq!(v, s.sample_2d(pixel, index, dim)[0], "{name} {dim}");
                            }
                        }
                        assert_eq!(s.dimension(), first + width as u32, "{name}");
                    }
                }
            }
        }
    }
}

// The second hostile pass (issue 38): values at the edges of the library.

#[test]
fn the_last_dimension_is_a_dimension_like_any_other() {
    // N3: a fresh sampler at dimension 2^32 - 1 gave a stale cached value (the "no cached
    // pair" mark was that dimension), 0.0 for every pixel
    for name in Sequence::NAMES {
        let seq = Sequence::by_name(name, [8, 8]).unwrap();
        let spp = if *name == "jittered" { 16 } else { 8 };
        let mut s = PixelSampler::new(seq, spp, strata::Seed(3)).unwrap();
        for (pixel, index) in [([0u32, 0], 0u64), ([5, 2], 3), ([7, 7], 1 << 33)] {
            s.start_pixel_sample(pixel, index, u32::MAX);
            let v = s.get_1d();
            assert_eq!(v, s.sample_1d(pixel, index, u32::MAX), "{name} {pixel:?}");
            // and after a pair computed ahead (dimension 2^32 - 4 computes 2^32 - 2 too)
            s.start_pixel_sample(pixel, index, u32::MAX - 3);
            s.get_2d();
            s.set_dimension(u32::MAX);
            assert_eq!(s.get_1d(), s.sample_1d(pixel, index, u32::MAX), "{name}");
        }
        // a bounce whose start saturates at the last dimension draws it, not a stale value
        s.start_pixel_sample([1, 1], 0, 0);
        s.start_bounce(600_000_000);
        assert_eq!(s.dimension(), u32::MAX);
        assert_eq!(s.get_1d(), s.sample_1d([1, 1], 0, u32::MAX), "{name}");
    }
}

#[test]
#[cfg(debug_assertions)] // it checks the debug budget
fn no_bounce_open_means_no_budget_to_check() {
    // N5: a debug build panicked at the last dimensions when no bounce was open (the "no
    // limit" value was checked as an end); the tests run with debug assertions
    let mut s = PixelSampler::new(Sequence::sobol(), 16, strata::Seed(1)).unwrap();
    s.start_pixel_sample([0, 0], 0, u32::MAX - 3);
    let [a, b, c, d] = s.get_4d();
    assert!([a, b, c, d].iter().all(|v| (0.0..1.0).contains(v)));
    s.start_pixel_sample([0, 0], 0, u32::MAX);
    let v = s.get_1d();
    assert!((0.0..1.0).contains(&v));
    // inside a bounce the budget is still checked
    let caught = std::panic::catch_unwind(|| {
        let mut s = PixelSampler::new(Sequence::sobol(), 16, strata::Seed(1)).unwrap();
        s.start_pixel_sample([0, 0], 0, 0);
        s.start_bounce(0);
        for _ in 0..5 {
            s.get_2d(); // the fifth pair is past the 8 dimensions of the bounce
        }
    });
    assert!(caught.is_err());
}

#[test]
fn permutations_past_two_to_the_31_are_bijections() {
    // N4: Kensler's final rotation added in 32 bits: past 2^31 two indices met
    use strata::hash::Permutation;
    let p = Permutation::new(65535 * 65535, 0x9e37_79b9).unwrap();
    let (a, b) = (p.apply(3_112_325), p.apply(3_374_643));
    assert_ne!(a, b, "both map to {a}");
    // a window of indices whose rotation crosses 2^32, all distinct and in range
    for (len, key) in [
        (u32::MAX, 7u32),
        (65535 * 65535, 0x9e37_79b9),
        ((1 << 31) + 5, 1),
    ] {
        let p = Permutation::new(len, key).unwrap();
        let mut seen: Vec<u32> = (0..1u32 << 20).map(|i| p.apply(i)).collect();
        assert!(seen.iter().all(|&v| v < len));
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), 1 << 20, "len {len}");
    }
    // and jittered sets of more than 2^31 samples keep one sample per cell
    let s = PixelSampler::new(Sequence::jittered(), 65535 * 65535, strata::Seed(9)).unwrap();
    let cells: Vec<(u32, u32)> = [3_112_325u64, 3_374_643]
        .iter()
        .map(|&i| {
            let v = s.sample_2d([0, 0], i, 0);
            ((v[0] * 65535.0) as u32, (v[1] * 65535.0) as u32)
        })
        .collect();
    assert_ne!(cells[0], cells[1]);
}

#[test]
fn listing_every_count_of_a_rule_allocates_nothing_up_front() {
    // N24: counts_between(1, u64::MAX) tried to collect 2^31 counts (16 GiB)
    use strata::counts::CountRule;
    let mut all = CountRule::Any.counts_between(1, u64::MAX);
    assert_eq!(all.next(), Some(1));
    assert_eq!(all.last(), Some(strata::counts::MAX_FIXED_COUNT));
    assert_eq!(
        CountRule::Square.counts_between(1, u64::MAX).count(),
        46_340
    );
}

/// Over `pixels` pixels at 16 samples, the mean number of cells of a 4 x 4 grid that the
/// first coordinates of the draws at dimensions 2 and 4 occupy together (the issue-39 lead:
/// a uniformly random pairing of two stratified sets gives 11.65 on average), and in how many
/// pixels that number is odd.
fn occupied_cells(sequence: Sequence, padding: strata::Padding, pixels: u32) -> (f64, usize) {
    let s = PixelSampler::new(sequence, 16, strata::Seed(7))
        .unwrap()
        .with_padding(padding);
    let (mut total, mut odd) = (0usize, 0usize);
    for p in 0..pixels {
        let pixel = [p % 37, p / 37];
        let mut cells = [false; 16];
        for i in 0..16u64 {
            let (a, b) = (s.sample_1d(pixel, i, 2), s.sample_1d(pixel, i, 4));
            cells[(a * 4.0) as usize * 4 + (b * 4.0) as usize] = true;
        }
        let n = cells.iter().filter(|&&c| c).count();
        total += n;
        odd += n % 2;
    }
    (total as f64 / pixels as f64, odd)
}

#[test]
fn shell_padding_keeps_every_prefix_a_net_and_pairs_draws_at_random() {
    use strata::Padding;
    // every power-of-two prefix of every draw is the net it was under the nested padding
    for seq in [
        Sequence::sobol(),
        Sequence::pmj02(),
        Sequence::zsobol(16, 16).unwrap(),
    ] {
        let s = PixelSampler::new(seq.clone(), 64, strata::Seed(3))
            .unwrap()
            .with_padding(Padding::Shells);
        for pixel in [[0u32, 0], [5, 9]] {
            for dim in [0u32, 2, 6, 10] {
                for m in 0..=6u32 {
                    let pts: Vec<[f32; 2]> =
                        (0..1u64 << m).map(|i| s.sample_2d(pixel, i, dim)).collect();
                    assert!(is_net(&pts), "{seq:?} pixel {pixel:?} dim {dim}: 2^{m}");
                }
            }
        }
    }
    // and two draws meet more at random than under the nested padding, which keeps sibling
    // samples together (only even counts: about 10.9 cells). Not as at random as a uniform
    // permutation of all 16 (11.65; `Uniform` gives it, and loses the prefixes): shells keep
    // samples 0 and 1 where they are and pair each shell only with itself (about 11.25).
    // 450 pixels: standard errors near 0.06.
    let (shells, shells_odd) = occupied_cells(Sequence::sobol(), Padding::Shells, 450);
    let (nested, nested_odd) = occupied_cells(Sequence::sobol(), Padding::Nested, 450);
    let (uniform, _) = occupied_cells(Sequence::sobol(), Padding::Uniform, 450);
    assert_eq!(nested_odd, 0, "nested: {nested}");
    assert!(nested < 11.1, "nested: {nested}");
    assert!(
        shells > nested + 0.2 && shells_odd > 100,
        "shells: {shells} ({shells_odd} odd)"
    );
    assert!((uniform - 11.65).abs() < 0.3, "uniform: {uniform}");
}

/// The chi-square bound at a false-alarm rate of `1e-9` for `df` degrees of freedom
/// (Wilson-Hilferty: within 1% of the exact quantile from `df = 3` on).
fn chi_square_bound(df: f64) -> f64 {
    let (z, a) = (5.998, 2.0 / (9.0 * df));
    df * (1.0 - a + z * a.sqrt()).powi(3)
}

/// The Z-ordered sequences on a 64 x 64 image, at `spp` samples per pixel.
fn z_ordered(spp: u32) -> Vec<PixelSampler> {
    Sequence::NAMES
        .iter()
        .map(|n| Sequence::by_name(n, [64, 64]).unwrap())
        .filter(|s| s.resolution().is_some())
        .map(|s| PixelSampler::new(s, spp, strata::Seed(11)).unwrap())
        .collect()
}

#[test]
fn z_ordered_draws_put_each_sample_of_a_pixel_in_any_stratum() {
    // Sample i of a pixel, in one coordinate of one draw, across the 4096 pixels of the image:
    // its stratum among spp must be spread over all spp of them (a chi-square test of
    // uniformity per sequence, count, draw, sample and coordinate, false alarm 1e-9 each). A
    // padding that leaves samples 0 and 1 of every pixel's block in place puts them in the same
    // strata in every pixel, under the image's shared value scramble: every pixel then errs the
    // same way, a red error. Stateful and stateless draws are the same values (tested above).
    let pixels: Vec<[u32; 2]> = (0..64 * 64).map(|k| [k % 64, k / 64]).collect();
    for spp in [4u32, 16] {
        let bound = chi_square_bound(spp as f64 - 1.0);
        let expected = pixels.len() as f64 / spp as f64;
        let samplers = z_ordered(spp);
        assert!(samplers.len() >= 5);
        for s in &samplers {
            for dim in [0u32, 2, 3, 8, 9, 13] {
                for i in 0..spp as u64 {
                    for axis in 0..2 {
                        let mut hist = vec![0u32; spp as usize];
                        for &p in &pixels {
                            hist[cell(s.sample_2d(p, i, dim)[axis], spp)] += 1;
                        }
                        let chi: f64 = hist
                            .iter()
                            .map(|&c| (c as f64 - expected).powi(2) / expected)
                            .sum();
                        assert!(
                            chi < bound,
                            "{} at {spp} spp: sample {i} of dimension {} in strata {hist:?}",
                            s.sequence().name(),
                            dim + axis as u32
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn z_ordered_draws_pair_their_samples_differently_from_pixel_to_pixel() {
    // At 4 samples per pixel, the strata of a pixel's samples in one draw's first coordinate
    // against another draw's: a permutation of 4. Across the 4096 pixels no permutation may be
    // taken by more than a third of them (a nested shuffle draws them from a group of 8: about
    // an eighth each); the same pairing in every pixel, under the image's shared value
    // scramble, makes every pixel's error of an integrand of two draws the same (red).
    let pixels: Vec<[u32; 2]> = (0..64 * 64).map(|k| [k % 64, k / 64]).collect();
    for s in &z_ordered(4) {
        for (d1, d2) in [(0u32, 2u32), (0, 8), (2, 9), (8, 10), (9, 13)] {
            let mut taken = std::collections::HashMap::new();
            for &p in &pixels {
                let mut pairing = [0u8; 4];
                for i in 0..4 {
                    let a = cell(s.sample_2d(p, i, d1)[0], 4);
                    pairing[a] = cell(s.sample_2d(p, i, d2)[0], 4) as u8;
                }
                *taken.entry(pairing).or_insert(0u32) += 1;
            }
            let most = *taken.values().max().unwrap();
            assert!(
                most * 3 <= pixels.len() as u32,
                "{}: dimensions {d1} and {d2} pair the same way in {most} of {} pixels ({} pairings)",
                s.sequence().name(),
                pixels.len(),
                taken.len()
            );
        }
    }
}

#[test]
fn no_promise_names_a_grid_finer_than_f32_can_fill() {
    // an f32 in [1/2, 1) is a multiple of 2^-24: a grid of 2^25 columns has columns near 1
    // that no value reaches (was promised by every net and by the pixel sequences)
    let fine = |grids: &[strata::StrataGrid]| {
        grids
            .iter()
            .any(|g| g.columns > 1 << 24 || g.rows > 1 << 24)
    };
    for seq in all() {
        let spp = seq.round_count(1 << 25);
        let s = PixelSampler::new(seq.clone(), spp, strata::Seed(1)).unwrap();
        for n in [1u64 << 24, 1 << 25, 1 << 31] {
            assert!(!fine(&s.promised_strata(n)), "{} at {n}", seq.name());
        }
    }
    use strata::Sampler;
    use strata::samplers::{Halton, NRooks, Pmj02Stochastic, Sobol};
    assert!(!fine(&Sobol::new(strata::Seed(1)).strata(1 << 25)));
    assert!(!fine(
        &Pmj02Stochastic::new(strata::Seed(1)).strata(1 << 25)
    ));
    assert!(!fine(&Halton::new(strata::Seed(1)).strata(1 << 25)));
    let rooks = NRooks::new((1 << 24) + 1, strata::Seed(1)).unwrap();
    assert!(!fine(&rooks.strata((1 << 24) + 1)));
    // the coarser grids stay promised
    assert!(!Sobol::new(strata::Seed(1)).strata(1 << 25).is_empty());
}

#[test]
fn the_padding_changes_every_group_of_every_padded_sequence() {
    // A11: the docs said the joint sequences' first group kept its values under the padding;
    // every group of them changes (as the CHANGELOG now lists), and `random`, `jittered` and
    // `halton` do not change at all
    for seq in all() {
        let shells = PixelSampler::new(seq.clone(), 16, strata::Seed(3)).unwrap();
        let nested = shells.clone().with_padding(Padding::Nested);
        for dim in [0u32, 2, 8, 16] {
            let changed = (0..16u64)
                .filter(|&i| shells.sample_2d([5, 9], i, dim) != nested.sample_2d([5, 9], i, dim))
                .count();
            match seq.name() {
                "random" | "jittered" | "halton" => {
                    assert_eq!(changed, 0, "{} at {dim}", seq.name())
                }
                // samples 0 and 1 stay; at least half the rest move
                name => assert!(changed >= 7, "{name} at {dim}: {changed} of 16 changed"),
            }
        }
    }
}

#[test]
fn sobolbn_wraps_its_table_and_keeps_every_prefix_a_net_past_the_ranks() {
    let s = PixelSampler::new(Sequence::sobolbn(), 1, strata::Seed(5)).unwrap();
    let side = strata::pixel::BlueNoiseTable::builtin().side();
    let fixed = |p: [u32; 2], range: std::ops::Range<u64>, dim: u32| -> Vec<[u32; 2]> {
        range.map(|i| s.sample_2d_u32(p, i, dim).unwrap()).collect()
    };
    for dim in [0u32, 2, 9] {
        // an image larger than the table: a pixel and its copy one side away read one entry,
        // so that their first 2^m samples are the same set (each pixel pads its own order)
        for m in [0u32, 2, 6] {
            let mut a = fixed([3, 70], 0..1 << m, dim);
            let mut b = fixed([3 + side, 70 + 2 * side], 0..1 << m, dim);
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "dim {dim} m {m}");
        }
        // another pixel of the tile: another entry
        assert_ne!(fixed([4, 70], 0..1, dim), fixed([3, 70], 0..1, dim));
        // past the table's ranks (below 2^16) and past the 2^6 samples it arranges: every
        // power-of-two prefix and every aligned block a net, as sobol's
        assert!(is_net_fixed(&fixed([3, 70], 0..1 << 17, dim)), "dim {dim}");
        assert!(
            is_net_fixed(&fixed([3, 70], 1 << 16..1 << 17, dim)),
            "dim {dim}"
        );
    }
}
