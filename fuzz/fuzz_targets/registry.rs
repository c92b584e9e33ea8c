//! Every constructor through the registry, with arbitrary names and parameters: never a panic,
//! never a hang; valid samplers give points in [0,1).
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata_lab::registry::{self, Params};

fuzz_target!(|data: &[u8]| {
    if data.len() < 40 {
        return;
    }
    let word = |i: usize| u64::from_le_bytes(data[i..i + 8].try_into().unwrap());
    let entries = registry::entries();
    // the name: a registered one, or the raw tail bytes as text (unknown names)
    let name = if data[0] < 240 {
        entries[data[0] as usize % entries.len()].name.to_string()
    } else {
        String::from_utf8_lossy(&data[40..]).into_owned()
    };
    let Ok(entry) = registry::find(&name) else { return };
    let mut n = word(1) >> (data[9] % 64);
    // valid-but-huge counts are legitimate and slow; the fuzzer looks for crashes, not work
    if n > 1 << 14 && n < 1 << 40 {
        n %= 1 << 14;
    }
    if entry.expensive && n > 400 && n < 1 << 40 {
        n %= 400;
    }
    let mut p = Params::new(n).seed(strata::Seed(word(17)));
    let flags = data[25];
    if flags & 1 != 0 {
        p.set("radius", f64::from_bits(word(26)));
    }
    if flags & 2 != 0 {
        p.set("iterations", (data[34] as u32 * if entry.expensive { 1 } else { 40 }) as f64);
    }
    if flags & 4 != 0 {
        p.set("strength", (data[35] as u32 % 20) as f64);
    }
    if flags & 8 != 0 {
        p.set("candidates", (data[36] as u32) as f64);
    }
    let dims = data[37] as u32 % 40;
    if let Ok(mut s) = entry.build(&p) {
        for _ in 0..n.min(64) {
            let q = s.next_sample();
            assert!((0.0..1.0).contains(&q[0]) && (0.0..1.0).contains(&q[1]));
        }
    }
    if let Ok(mut s) = entry.build_nd(&p, dims) {
        let mut v = vec![0f32; s.dimensions() as usize];
        for _ in 0..n.min(16) {
            s.next_point(&mut v);
            assert!(v.iter().all(|x| (0.0..1.0).contains(x)));
        }
    }
});
