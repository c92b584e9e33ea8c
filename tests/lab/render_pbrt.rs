//! `render`'s pbrt-v4 references (`examples/render/pbrt.rs`, included here alone): the
//! hash, the index permutation, the scramblers, `PaddedSobolSampler` with each randomization
//! and `ZSobolSampler` at 16 and 8 spp reproduce `pbrt_vectors.txt` bit for bit. The vectors
//! were made by a model checked against pbrt-v4's own function bodies (commit
//! `5f7a606806a4ac7b939131ded9d7a30ebd02416e`): the same text, line by line, with each float in
//! C's `%a` spelling.

#[path = "../../examples/render/pbrt.rs"]
mod pbrt;

use pbrt::{PaddedSobol, Randomize, ZSobol};

/// `f` as Python's `float.hex()` without trailing zeros (C's `%a`): `0x1.f97d1p-2`.
fn hex(f: f32) -> String {
    if f == 0.0 {
        return "0x0p+0".to_string();
    }
    assert!(f.is_normal() && f > 0.0, "{f}");
    let bits = f.to_bits();
    let exponent = ((bits >> 23) & 0xff) as i32 - 127;
    // the 23 fraction bits as the 52 of a double: 13 hex digits, trailing zeros dropped
    let digits = format!("{:013x}", ((bits & 0x7f_ffff) as u64) << 29);
    let digits = digits.trim_end_matches('0');
    if digits.is_empty() {
        format!("0x1p{exponent:+}")
    } else {
        format!("0x1.{digits}p{exponent:+}")
    }
}

fn pair(p: [f32; 2]) -> String {
    format!("({}, {})", hex(p[0]), hex(p[1]))
}

/// The lines of `pbrt_vectors.txt`, computed by `pbrt.rs`.
fn vectors() -> Vec<String> {
    let mut out = vec![
        format!(
            "MurmurHash64A('', 0) = {:#018x}",
            pbrt::murmur_hash64a(&[], 0)
        ),
        format!("Hash(int 0, int 0) = {:#018x}", pbrt::hash_i32(&[0, 0])),
        format!(
            "Hash(Point2i(1,2), int 3, int 4) = {:#018x}",
            pbrt::hash_i32(&[1, 2, 3, 4])
        ),
        format!("MixBits(1) = {:#018x}", pbrt::mix_bits(1)),
        format!(
            "PermutationElement(0..7, 8, 0x12345678) = {:?}",
            (0..8)
                .map(|i| pbrt::permutation_element(i, 8, 0x1234_5678))
                .collect::<Vec<_>>()
        ),
        format!(
            "FastOwen(0x80000000, 0xdeadbeef) = {:#010x}",
            pbrt::fast_owen(0x8000_0000, 0xdead_beef)
        ),
        format!(
            "Owen(0x80000000, 0xdeadbeef) = {:#010x}",
            pbrt::owen(0x8000_0000, 0xdead_beef)
        ),
    ];
    for (name, r) in [
        ("fastowen", Randomize::FastOwen),
        ("owen", Randomize::Owen),
        ("permutedigits", Randomize::PermuteDigits),
        ("none", Randomize::None),
    ] {
        out.push(format!(
            "PaddedSobol spp=16 {name} seed=0 (GetPixel2D, Get1D, Get2D):"
        ));
        let mut s = PaddedSobol::new(16, 0, r);
        for (px, py) in [(0, 0), (3, 5)] {
            for i in 0..4 {
                s.start_pixel_sample([px, py], i, 0);
                let p = s.get_pixel_2d();
                let u = s.get_1d();
                let q = s.get_2d();
                out.push(format!(
                    "  pixel ({px},{py}) i={i}: pixel2d={} 1d={} 2d={}",
                    pair(p),
                    hex(u),
                    pair(q)
                ));
            }
        }
    }
    for spp in [16, 8] {
        let mut z = ZSobol::new(spp, [64, 48], 0, Randomize::FastOwen);
        out.push(format!(
            "ZSobol spp={spp} res=64x48 fastowen seed=0 (nBase4Digits=8):"
        ));
        for (px, py) in [(0, 0), (3, 5)] {
            for i in 0..4 {
                z.start_pixel_sample([px, py], i, 0);
                let index = z.sample_index();
                let p = z.get_pixel_2d();
                let u = z.get_1d();
                let q = z.get_2d();
                out.push(format!(
                    "  pixel ({px},{py}) i={i}: index(dim0)={index} pixel2d={} 1d={} 2d={}",
                    pair(p),
                    hex(u),
                    pair(q)
                ));
            }
        }
    }
    out
}

#[test]
fn render_pbrt_references_reproduce_pbrts_vectors_bit_for_bit() {
    let want = include_str!("pbrt_vectors.txt");
    let got = vectors();
    let want: Vec<&str> = want.lines().collect();
    assert_eq!(got.len(), want.len(), "line count");
    for (k, (g, w)) in got.iter().zip(&want).enumerate() {
        assert_eq!(g, w, "line {} of pbrt_vectors.txt", k + 1);
    }
}

#[test]
fn render_pbrt_padded_permutes_each_draw_within_the_pixel() {
    // every draw of a pixel's 16 samples is a permutation of the first 16 Sobol' points (one
    // value per 1/16 in each coordinate), whatever the dimension
    for dim in [0, 5, 9, 33] {
        let mut s = PaddedSobol::new(16, 7, Randomize::FastOwen);
        let mut cells = [[false; 16]; 2];
        for i in 0..16 {
            s.start_pixel_sample([3, 4], i, dim);
            let v = s.get_2d();
            for c in 0..2 {
                let k = (v[c] * 16.0) as usize;
                assert!(
                    !cells[c][k],
                    "dim {dim}: two samples in a 1/16 of coordinate {c}"
                );
                cells[c][k] = true;
            }
        }
    }
}
