//! The spectrum and the point-set measures on arbitrary point sets (any f32 bit patterns) and
//! resolutions: errors for bad input, finite values for good input, and the fast periodogram
//! within 1e-6 of the direct sum on small sets.
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata_lab::spectrum;

fuzz_target!(|data: &[u8]| {
    if data.len() < 2 {
        return;
    }
    let k = data[0] as u32 % 40;
    let pts: Vec<[f32; 2]> = data[1..]
        .chunks_exact(8)
        .take(300)
        .map(|c| [f32::from_le_bytes(c[..4].try_into().unwrap()), f32::from_le_bytes(c[4..].try_into().unwrap())])
        .collect();
    let fast = spectrum::periodogram(&pts, k);
    let direct = spectrum::periodogram_direct(&pts, k);
    assert_eq!(fast.is_ok(), direct.is_ok());
    if let (Ok(f), Ok(d)) = (fast, direct) {
        for (a, b) in f.values().iter().zip(d.values()) {
            assert!(a.is_finite() && (a - b).abs() < 1e-6, "{a} vs {b}");
        }
        for bin in f.radial() {
            assert!(bin.power.is_finite());
        }
        let m = spectrum::point_set_measures(&[pts]).unwrap();
        assert!(m.average_min_distance.is_nan() || m.average_min_distance >= 0.0);
    }
});
