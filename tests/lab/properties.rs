//! Property tests: for random seeds, counts and parameters, every sampler's promise holds
//! (cells counted), constructors never panic, and refusals say what is allowed.

use proptest::prelude::*;
use strata::SamplerNd;
use strata::samplers::{Cmj, Jittered, MultiJittered, NRooks, Pmj02Stochastic, Sobol};
use strata_lab::registry::{self, Params};
use strata_lab::samplers::{Bose, Pmj};

use crate::common::{counts, is_net_fixed as is_net, take};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn jittered_and_multijittered_fill_every_cell(side in 1u32..24, seed: u64, skip in 0usize..3) {
        let n = side * side;
        let mut j = Jittered::new(n as u64, strata::Seed(seed)).unwrap();
        let mut m = MultiJittered::new(n as u64, strata::Seed(seed)).unwrap();
        for _ in 0..skip { take(&mut j, n as usize); take(&mut m, n as usize); }
        let pj = take(&mut j, n as usize);
        prop_assert!(counts(&pj, side, side).iter().all(|&c| c == 1));
        let pm = take(&mut m, n as usize);
        prop_assert!(counts(&pm, side, side).iter().all(|&c| c == 1));
        prop_assert!(counts(&pm, n, 1).iter().all(|&c| c == 1));
        prop_assert!(counts(&pm, 1, n).iter().all(|&c| c == 1));
    }

    #[test]
    fn nrooks_and_cmj_are_latin_for_any_count(n in 1u32..600, seed: u64) {
        let mut r = NRooks::new(n as u64, strata::Seed(seed)).unwrap();
        let p = take(&mut r, n as usize);
        prop_assert!(counts(&p, n, 1).iter().all(|&c| c == 1));
        prop_assert!(counts(&p, 1, n).iter().all(|&c| c == 1));
        let mut c = Cmj::new(n as u64, strata::Seed(seed)).unwrap();
        let (cols, rows) = c.grid();
        let p = take(&mut c, n as usize);
        prop_assert!(counts(&p, cols, rows).iter().all(|&k| k <= 1));
        prop_assert!(counts(&p, cols * rows, 1).iter().all(|&k| k <= 1));
        prop_assert!(counts(&p, 1, cols * rows).iter().all(|&k| k <= 1));
    }

    #[test]
    fn progressive_nets_at_every_power_of_two(seed: u64, m in 0u32..11, block in 0usize..4) {
        let n = 1usize << m;
        let mut a = Pmj::pmj02(strata::Seed(seed));
        a.reserve((n * 4) as u64).unwrap();
        prop_assert!(is_net(&a.generated()[..n]));
        prop_assert!(is_net(&a.generated()[block * n..(block + 1) * n]));
        let mut b = Pmj02Stochastic::new(strata::Seed(seed));
        b.reserve((n * 4) as u64);
        prop_assert!(is_net(&b.generated()[block * n..(block + 1) * n]));
        let s = Sobol::new(strata::Seed(seed));
        let pts: Vec<[u32; 2]> = (block * n..(block + 1) * n).map(|i| s.sample_u32(i as u32)).collect();
        prop_assert!(is_net(&pts));
    }

    #[test]
    fn bose_projections_are_stratified(qi in 0usize..8, seed: u64, extra in 0u32..3) {
        let q = [2u32, 3, 4, 5, 7, 8, 9, 11][qi];
        let dims = (2 + extra).min(q + 1);
        let n = q * q;
        let mut s = Bose::new(n as u64, dims, strata::Seed(seed)).unwrap();
        let mut v = vec![0f32; (n * dims) as usize];
        s.fill(&mut v);
        for a in 0..dims as usize {
            let mut seen = vec![false; n as usize];
            for p in v.chunks_exact(dims as usize) {
                let cell = (p[a] as f64 * n as f64) as usize;
                prop_assert!(!std::mem::replace(&mut seen[cell], true));
            }
            for b in a + 1..dims as usize {
                let mut seen = vec![false; n as usize];
                for p in v.chunks_exact(dims as usize) {
                    let cell = (p[b] as f64 * q as f64) as usize * q as usize + (p[a] as f64 * q as f64) as usize;
                    prop_assert!(!std::mem::replace(&mut seen[cell], true));
                }
            }
        }
    }

    #[test]
    fn constructors_never_panic_and_errors_say_what_is_allowed(
        which in 0usize..64,
        n in prop_oneof![0u64..2000, any::<u64>()],
        seed: u64,
        radius in prop_oneof![any::<f64>(), 0.0f64..1.0],
        iterations in prop_oneof![0u32..300, any::<u32>()],
        strength in prop_oneof![0u32..6, any::<u32>()],
        candidates in prop_oneof![0u32..200, any::<u32>()],
        dims in prop_oneof![0u32..20, any::<u32>()],
        set_params in any::<[bool; 4]>(),
    ) {
        let entry = &registry::entries()[which % registry::entries().len()];
        // keep the valid-and-slow cases small: they are tested elsewhere
        // (a progressive one takes any count and optimises its longest prefix for a huge one:
        // minutes in a test build, so its huge counts are tested in tests/extremes.rs)
        let n = if entry.expensive && n > 300 && (n < 1 << 40 || entry.progressive) { n % 300 } else { n };
        let mut p = Params::new(n).seed(strata::Seed(seed));
        if set_params[0] { p.set("radius", radius); }
        if set_params[1] { p.set("iterations", (iterations.min(if entry.expensive { 20 } else { u32::MAX })) as f64); }
        if set_params[2] { p.set("strength", (strength) as f64); }
        if set_params[3] { p.set("candidates", (candidates.min(if n > 1000 { 4 } else { u32::MAX })) as f64); }
        let hint = |e: &strata_lab::Error| {
            let m = e.to_string();
            ["allowed", "must", "between", " to ", "nearest", "at most", "takes", "samplers that do", "saturated", "too small", "known"]
                .iter()
                .any(|h| m.contains(h))
        };
        match entry.build(&p) {
            Ok(mut s) => {
                for _ in 0..8 {
                    let q = s.next_sample();
                    prop_assert!((0.0..1.0).contains(&q[0]) && (0.0..1.0).contains(&q[1]));
                }
            }
            Err(e) => prop_assert!(hint(&e), "{}: {e}", entry.name),
        }
        let d = if entry.expensive { dims.min(4) } else { dims };
        match entry.build_nd(&p, d) {
            Ok(mut s) => {
                let mut v = vec![0f32; s.dimensions() as usize];
                s.next_point(&mut v);
                prop_assert!(v.iter().all(|x| (0.0..1.0).contains(x)));
            }
            Err(e) => prop_assert!(hint(&e), "{} (dims {d}): {e}", entry.name),
        }
    }
}
