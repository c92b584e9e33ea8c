//! High-dimensional stratification, counted cell by cell: Latin hypercube (every 1D
//! projection), uncorrelated jitter (its pairs and its trailing dimension), orthogonal arrays
//! (every 1D projection into N strata, every 2D projection for Bose, every t-D one for Bush).

use strata::SamplerNd;
use strata::samplers::{LatinHypercube, UncorrelatedJitter};
use strata_lab::registry::{self, Params};
use strata_lab::samplers::{Bose, Bush};

fn points(s: &mut dyn SamplerNd, n: usize) -> Vec<Vec<f32>> {
    let d = s.dimensions() as usize;
    let mut flat = vec![0f32; n * d];
    s.fill(&mut flat);
    flat.chunks_exact(d).map(|c| c.to_vec()).collect()
}

/// Whether the projection of `pts` on `dims` has exactly one point in every cell of the grid
/// with `cells` strata per axis.
fn one_per_cell(pts: &[Vec<f32>], dims: &[usize], cells: u64) -> bool {
    let total = cells.pow(dims.len() as u32) as usize;
    let mut count = vec![0u32; total];
    for p in pts {
        let mut idx = 0usize;
        for &d in dims {
            assert!((0.0..1.0).contains(&p[d]));
            idx = idx * cells as usize + (p[d] as f64 * cells as f64) as usize;
        }
        count[idx] += 1;
    }
    count.iter().all(|&c| c == 1)
}

/// All subsets of `0..d` of size `k`.
fn subsets(d: usize, k: usize) -> Vec<Vec<usize>> {
    if k == 0 {
        return vec![vec![]];
    }
    (0..d)
        .flat_map(|first| {
            subsets(d, k - 1)
                .into_iter()
                .filter(move |s| s.first().is_none_or(|&f| f > first))
                .map(move |mut s| {
                    s.insert(0, first);
                    s
                })
        })
        .collect()
}

#[test]
fn latin_hypercube_stratifies_every_axis() {
    for (n, d) in [(1u64, 3u32), (7, 5), (64, 16), (1000, 4)] {
        for seed in [0u64, 9, u64::MAX] {
            let mut s = LatinHypercube::new(n, d, strata::Seed(seed)).unwrap();
            for block in 0..2 {
                let pts = points(&mut s, n as usize);
                for axis in 0..d as usize {
                    assert!(
                        one_per_cell(&pts, &[axis], n),
                        "latin n={n} d={d} seed={seed} block={block} axis {axis}"
                    );
                }
            }
        }
    }
}

#[test]
fn uncorrelated_jitter_stratifies_its_pairs_and_its_last_dimension() {
    for (side, d) in [(4u64, 2u32), (3, 5), (8, 6), (5, 1)] {
        let n = side * side;
        for seed in [1u64, 2] {
            let mut s = UncorrelatedJitter::new(n, d, strata::Seed(seed)).unwrap();
            let pts = points(&mut s, n as usize);
            let mut k = 0;
            while k + 1 < d as usize {
                assert!(
                    one_per_cell(&pts, &[k, k + 1], side),
                    "pair ({k},{}) d={d}",
                    k + 1
                );
                k += 2;
            }
            if d % 2 == 1 {
                assert!(
                    one_per_cell(&pts, &[d as usize - 1], n),
                    "trailing dimension d={d}"
                );
            }
        }
    }
    assert!(
        UncorrelatedJitter::new(10, 3, strata::Seed(1))
            .unwrap_err()
            .to_string()
            .contains("9 or 16")
    );
    assert!(UncorrelatedJitter::new(10, 1, strata::Seed(1)).is_ok());
}

#[test]
fn bose_arrays_stratify_every_axis_and_every_pair() {
    for q in [2u64, 3, 4, 5, 7, 8, 9, 11, 16] {
        let n = q * q;
        for d in [2u32, q as u32 + 1] {
            for seed in [3u64, 4] {
                let mut s = Bose::new(n, d, strata::Seed(seed)).unwrap();
                let pts = points(&mut s, n as usize);
                for axis in 0..d as usize {
                    assert!(
                        one_per_cell(&pts, &[axis], n),
                        "bose q={q} axis {axis}: not N-rooks"
                    );
                }
                for pair in subsets(d as usize, 2) {
                    assert!(
                        one_per_cell(&pts, &pair, q),
                        "bose q={q} d={d} pair {pair:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn bush_arrays_stratify_every_axis_and_every_t_subset() {
    for (q, t) in [
        (2u64, 3u32),
        (3, 3),
        (4, 3),
        (5, 2),
        (5, 3),
        (3, 4),
        (7, 3),
        (8, 3),
        (9, 2),
    ] {
        let n = q.pow(t);
        let d = q as u32;
        for seed in [5u64, 6] {
            let mut s = Bush::new(n, t, d, strata::Seed(seed)).unwrap();
            let pts = points(&mut s, n as usize);
            for axis in 0..d as usize {
                assert!(
                    one_per_cell(&pts, &[axis], n),
                    "bush q={q} t={t} axis {axis}: not N-rooks"
                );
            }
            for subset in subsets(d as usize, t as usize) {
                assert!(
                    one_per_cell(&pts, &subset, q),
                    "bush q={q} t={t} subset {subset:?}"
                );
            }
        }
    }
}

#[test]
fn bad_dimensions_counts_and_strengths_are_refused() {
    assert!(Bose::new(49, 0, strata::Seed(1)).is_err());
    assert!(
        Bose::new(49, 9, strata::Seed(1))
            .unwrap_err()
            .to_string()
            .contains("1 to 8")
    );
    assert!(
        Bush::new(125, 3, 6, strata::Seed(1))
            .unwrap_err()
            .to_string()
            .contains("1 to 5")
    );
    let e = Bush::new(100, 3, 3, strata::Seed(1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("64 (4^3) or 125 (5^3)"), "{e}");
    assert!(
        Bush::new(125, 1, 3, strata::Seed(1))
            .unwrap_err()
            .to_string()
            .contains("strength")
    );
    assert!(LatinHypercube::new(10, 0, strata::Seed(1)).is_err());
    assert!(LatinHypercube::new(0, 3, strata::Seed(1)).is_err());
    let mut p = Params::new(125);
    p.set("strength", (3) as f64);
    assert!(registry::build_nd("oa-bush", &p, 5).is_ok());
    assert!(
        registry::build_nd("oa-bose", &Params::new(100), 3)
            .unwrap_err()
            .to_string()
            .contains("121")
    );
    assert!(registry::build_nd("random", &Params::new(10), 0).is_err());
    // huge counts are refused at once (found by fuzzing: the nearest-count search once scanned
    // billions of candidates); the refusal names the largest counts instead of searching
    for n in [u64::MAX, 9_259_542_122_566_407_766, 1 << 40, (1 << 31) + 1] {
        for e in [
            Bose::new(n, 3, strata::Seed(1)).unwrap_err(),
            Bush::new(n, 3, 3, strata::Seed(1)).unwrap_err(),
        ] {
            assert!(
                e.to_string().contains("the largest allowed are about"),
                "{e}"
            );
        }
    }
}

#[test]
fn registry_nd_samplers_are_reproducible() {
    for e in registry::entries().iter().filter(|e| e.has_dimensions()) {
        let name = e.name;
        let n = e.counts.nearest(100);
        let run = |seed| {
            let mut s = registry::build_nd(name, &Params::new(n).seed(seed), 4).unwrap();
            points(s.as_mut(), n as usize)
        };
        assert_eq!(
            run(strata::Seed(4)),
            run(strata::Seed(4)),
            "{name}: same seed, same bits"
        );
        assert_ne!(
            run(strata::Seed(4)),
            run(strata::Seed(5)),
            "{name}: another seed, other points"
        );
    }
}

#[test]
fn projection_strata_hold_equal_counts_per_cell() {
    // every grid a D-dimensional sampler reports for a 2D projection is counted cell by cell
    let mut checked = 0;
    for e in registry::entries().iter().filter(|e| e.has_dimensions()) {
        let n = e.counts.nearest(49);
        let dims = 4;
        let Ok(mut s) = registry::build_nd(e.name, &Params::new(n).seed(strata::Seed(8)), dims)
        else {
            continue;
        };
        let mut v = vec![0f32; n as usize * dims as usize];
        s.fill(&mut v);
        for x in 0..dims {
            for y in 0..dims {
                let Some(g) = s.projection_strata(x, y) else {
                    continue;
                };
                let cells = (g.columns * g.rows) as usize;
                assert_eq!(n as usize % cells, 0, "{}: {n} points on {g:?}", e.name);
                let mut c = vec![0usize; cells];
                for p in v.chunks_exact(dims as usize) {
                    let cx = (p[x as usize] as f64 * g.columns as f64) as usize;
                    let cy = (p[y as usize] as f64 * g.rows as f64) as usize;
                    c[cy * g.columns as usize + cx] += 1;
                }
                let want = n as usize / cells;
                assert!(
                    c.iter().all(|&k| k == want),
                    "{}: projection ({x}, {y}) on {g:?}",
                    e.name
                );
                checked += 1;
            }
        }
        assert!(s.projection_strata(0, 0).is_none() && s.projection_strata(0, dims).is_none());
    }
    // oa-bose and oa-bush: all 12 ordered pairs each; uncorrelated: (0,1), (1,0), (2,3), (3,2)
    assert_eq!(checked, 12 + 12 + 4);
}
