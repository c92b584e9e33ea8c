//! `render`'s OpenQMC reference (`examples/render/openqmc.rs`, included here alone):
//! `SobolBnSampler`'s `drawSample<1>`, `<2>`, `<4>` (integers and floats) reproduce
//! `openqmc_vectors.txt` bit for bit. The vectors are printed by OpenQMC's own headers (commit
//! `294d65627f667b668373250a751862232cf21d65`) through its public API:
//! `tools/openqmc-vectors/vectors.cpp`, built with
//! `g++ -std=c++17 -O2 -DOQMC_FORCE_SCALAR -I <openqmc>/include vectors.cpp -o vectors`
//! (the SSE2 and AVX2 builds print the same); the file keeps the `bn` lines whose domain chain
//! is a plain `newDomain` list, each with probability 0.05 (Python's `random.Random(7)`), 573
//! of 11 472: pixels with negative and large coordinates, frames 0 to 123456, indices to
//! `2^20 + 3`, nested domains.

#[path = "../../examples/render/openqmc.rs"]
mod openqmc;

use openqmc::SobolBn;

/// One line of the vectors: the sampler's draws, each field as printed.
fn draws(line: &str) -> String {
    let w: Vec<&str> = line.split_whitespace().collect();
    let int = |s: &str| s.parse::<i32>().unwrap();
    let mut s = SobolBn::new(int(w[1]), int(w[2]), int(w[3]), int(w[4]));
    if w[5] != "root" {
        for k in w[5].split('.') {
            s = s.new_domain(int(k));
        }
    }
    let hex = |v: &[u32]| {
        v.iter()
            .map(|x| format!("{x:08x}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let bits = |v: &[f32]| hex(&v.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
    format!(
        "{} u1 {} u2 {} u4 {} f1 {} f2 {} f4 {}",
        w[..6].join(" "),
        hex(&s.draw_sample::<1>()),
        hex(&s.draw_sample::<2>()),
        hex(&s.draw_sample::<4>()),
        bits(&s.draw_sample_f32::<1>()),
        bits(&s.draw_sample_f32::<2>()),
        bits(&s.draw_sample_f32::<4>()),
    )
}

#[test]
fn render_openqmc_reference_reproduces_openqmcs_vectors_bit_for_bit() {
    let text = include_str!("openqmc_vectors.txt");
    let mut checked = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        // the printed line up to the drawRnd words, which the reference does not use
        let want = &line[..line.find(" r4 ").unwrap()];
        assert_eq!(draws(line), want);
        checked += 1;
    }
    assert_eq!(checked, 573);
}

#[test]
fn render_openqmc_reference_draws_every_dimension_from_its_own_domain() {
    // the film, the lens, the time and every bounce's draws: no two draws of a sample alike
    let mut s = openqmc::OpenQmcBn::new(3);
    s.start_pixel_sample([5, 9], 2, 0);
    let mut seen = Vec::new();
    for d in (0..8).chain(8..8 + 8 * 4) {
        s.set_dimension(d);
        let v = s.get_2d();
        assert!(!seen.contains(&v), "dimension {d} repeats a draw");
        seen.push(v);
    }
}
