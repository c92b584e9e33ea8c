//! The WGSL kernel against the CPU, bit for bit.
//!
//! `naga` validates the shader; then, on the Vulkan adapter present (Mesa's lavapipe CPU driver
//! in CI), `2^22` draws of every sequence of `Sequence::NAMES` that `gpu_parameters` accepts
//! (and of `zjoint` at groups of 2 and 512, `sobol12` at 512), under both paddings the shader
//! has, half of them a renderer's grid of pixels, indices and dimensions, half hashed over the
//! whole `u32` range of each, are compared with `PixelSampler::sample_2d_u32`; every sequence
//! it refuses is CPU-only by its declaration. Without an adapter the test says which driver to install
//! and is skipped, unless `STRATA_GPU_REQUIRED` is set (as `.ci/run` sets it), where it fails.

use strata::{PixelSampler, Seed, Sequence};
use strata_gpu_test::{DRIVER_HINT, Gpu, compute_shader, tuple};

/// Draws per sequence.
const COUNT: u32 = 1 << 22;

#[test]
fn naga_validates_the_shader_and_the_test_kernel() {
    let module = format!(
        "{}\n@group(0) @binding(0) var<storage, read> strata_tables: array<u32>;",
        strata::pixel::WGSL,
    );
    for (what, source) in [
        ("strata.wgsl with its table", module),
        ("the test kernel", compute_shader()),
    ] {
        let module = naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{what}: {}", e.emit_to_string(&source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::empty(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{what}: {e:?}"));
    }
}

#[test]
fn the_gpu_computes_the_cpu_bits() {
    let gpu = match Gpu::new() {
        Ok(g) => g,
        Err(why) if std::env::var_os("STRATA_GPU_REQUIRED").is_none() => {
            eprintln!("skipped: {why}");
            return;
        }
        Err(why) => panic!("{why}"),
    };
    eprintln!("adapter: {}", gpu.name);
    // every sequence of the list (so a new one is tested as soon as it exists): those the
    // shader refuses are CPU-only by their declaration, and the others are drawn below, with
    // zjoint's smallest and largest groups and sobol12's largest
    let all: Vec<Sequence> = Sequence::NAMES
        .iter()
        .map(|n| Sequence::by_name(n, [64, 48]).unwrap())
        .collect();
    for s in &all {
        let spp = if s.name() == "jittered" { 16 } else { 8 };
        let refused = PixelSampler::new(s.clone(), spp, Seed(1))
            .unwrap()
            .gpu_parameters()
            .is_err();
        assert_eq!(refused, !s.runs_on_gpu(), "{}", s.name());
    }
    let sequences: Vec<Sequence> = all
        .into_iter()
        .filter(Sequence::runs_on_gpu)
        .chain([
            Sequence::zjoint(64, 64, 2).unwrap(),
            Sequence::zjoint(48, 64, 512).unwrap(),
            Sequence::sobol12(512).unwrap(),
            // a blue-noise table of another side than the built-in's (the shader reads the
            // side from the parameters): 64 x 64 entries of hashed keys and every rank
            Sequence::sobolbn_with(small_table()),
        ])
        .collect();
    assert!(sequences.len() >= 10, "{sequences:?}");
    let grid = COUNT / 2;
    // every sequence with the nested padding, and with the shell padding those it changes
    let cases = sequences.into_iter().flat_map(|s| {
        [
            (s.clone(), strata::Padding::Nested),
            (s, strata::Padding::Shells),
        ]
    });
    for (k, (sequence, padding)) in cases.enumerate() {
        let name = match sequence.group() {
            1 => sequence.name().to_string(),
            g => format!("{}-{g}", sequence.name()),
        };
        let name = format!("{name} ({padding:?}, case {k})");
        // the Z-ordered ones with 16 samples per pixel: the grid's indices up to 255 cross each
        // pixel's block; the others ignore the count
        let s = PixelSampler::new(sequence, 16, Seed(0x5eed + k as u64))
            .unwrap()
            .with_padding(padding);
        let params = s.gpu_parameters().expect("a kernel sequence");
        let got = gpu.draw(&params, COUNT, grid).unwrap();
        assert_eq!(got.len(), 2 * COUNT as usize);
        let mut mismatches = Vec::new();
        for i in 0..COUNT {
            let (pixel, index, dim) = tuple(i, grid);
            let want = s.sample_2d_u32(pixel, index as u64, dim).unwrap();
            let g = [got[2 * i as usize], got[2 * i as usize + 1]];
            if g != want {
                mismatches.push(format!(
                    "pixel {pixel:?} index {index} dim {dim}: gpu {g:08x?} cpu {want:08x?}"
                ));
            }
        }
        assert!(
            mismatches.is_empty(),
            "{name}: {} of {COUNT} draws differ, e.g.\n{}",
            mismatches.len(),
            mismatches[..mismatches.len().min(8)].join("\n")
        );
        eprintln!("{name}: {COUNT} draws bit-identical");
    }
}

/// A 64 x 64 blue-noise table of hashed entries (keys and ranks below 4096; not optimised:
/// the test checks the GPU's reading of a table of another side, not its noise).
fn small_table() -> strata::pixel::BlueNoiseTable {
    let side = 64u32;
    let entries: Vec<[u32; 2]> = (0..side * side)
        .map(|i| {
            let h = strata::hash::mix64(i as u64 ^ 0x0074_6162_6c65_3634);
            [h as u32, (h >> 52) as u32]
        })
        .collect();
    strata::pixel::BlueNoiseTable::new(side, &entries).unwrap()
}

#[test]
fn the_hint_names_the_driver() {
    assert!(DRIVER_HINT.contains("mesa-vulkan-drivers"));
}
