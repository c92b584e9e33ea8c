//! Lloyd relaxation on arbitrary point sets (duplicates, points on the border, out-of-range
//! values): an error or relaxed points in [0,1), never a panic or a hang.
#![no_main]

use libfuzzer_sys::fuzz_target;
use strata_lab::samplers::lloyd::{relax, voronoi_cells};

fuzz_target!(|data: &[u8]| {
    let mut pts: Vec<[f64; 2]> = data
        .chunks_exact(4)
        .take(200)
        .map(|c| {
            // coarse coordinates make duplicates and near-duplicates common
            let x = u16::from_le_bytes([c[0], c[1]]);
            let y = u16::from_le_bytes([c[2], c[3]]);
            [x as f64 / 65535.0, y as f64 / 65536.0]
        })
        .collect();
    match voronoi_cells(&pts) {
        Ok(cells) => {
            let area: f64 = cells.iter().flatten().map(|c| c.area).sum();
            assert!((area - 1.0).abs() < 1e-6, "cells cover {area}");
            relax(&mut pts, 3).unwrap();
            assert!(pts.iter().all(|p| (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1])));
        }
        Err(_) => assert!(pts.is_empty() || pts.iter().any(|p| p[0] >= 1.0 || p[1] >= 1.0)),
    }
});
