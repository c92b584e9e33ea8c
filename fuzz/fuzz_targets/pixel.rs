//! The path-tracer adapter with arbitrary pixels, indices and dimensions: values in [0,1),
//! the stateless and stateful forms equal.
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata::pixel::{PixelSampler, Sequence};

fuzz_target!(|data: &[u8]| {
    if data.len() < 32 {
        return;
    }
    let w = |i: usize| u64::from_le_bytes(data[i..i + 8].try_into().unwrap());
    let name = Sequence::NAMES[data[0] as usize % Sequence::NAMES.len()];
    let spp = (data[1] as u32).max(1);
    let Ok(s) = PixelSampler::new(Sequence::by_name(name, [64, 64]).unwrap(), spp, strata::Seed(w(2))) else { return };
    let pixel = [w(10) as u32, (w(10) >> 32) as u32];
    let (index, dim) = (w(18), w(24) as u32);
    let v = s.sample_2d(pixel, index, dim);
    assert!((0.0..1.0).contains(&v[0]) && (0.0..1.0).contains(&v[1]));
    let mut t = s.clone();
    t.start_pixel_sample(pixel, index, dim);
    assert_eq!(t.get_2d(), v);
    assert_eq!(t.get_1d(), s.sample_1d(pixel, index, dim.wrapping_add(2)));
});
