//! Interleaved timing of strata's pmj02bn against the pmj crate's pmj02bn (best candidate,
//! 99 retries), 4096 points, fresh seed per set; mean NN distance on the torus / r_max.
use rand::rngs::SmallRng;
use rand::SeedableRng;
use std::time::Instant;
use strata_lab::registry::{self, Params};
use strata_lab::spectrum::{nearest_neighbour_distances, relative_radius_max};
use strata::Point2;

fn mean_nn(pts: &[Point2]) -> f64 {
    let d = nearest_neighbour_distances(pts).unwrap();
    d.iter().sum::<f64>() / d.len() as f64 / relative_radius_max(pts.len())
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn table() {
    // mean NN / r_max over 32 seeds, pmj02bn (sweeps from SWEEPS or default) and pmj02
    for n in [64usize, 256, 1024, 4096, 16384] {
        let mut row = vec![];
        for name in ["pmj02bn", "pmj02"] {
            let mut sum = 0.0;
            for seed in 0..32u64 {
                let mut params = Params::new(n as u64).seed(strata::Seed(seed));
                if name == "pmj02bn" {
                    params.iterations = std::env::var("SWEEPS").ok().map(|v| v.parse().unwrap());
                }
                let mut s = registry::build(name, &params).unwrap();
                let mut buf = vec![Point2::ZERO; n];
                s.fill(&mut buf);
                sum += mean_nn(&buf);
            }
            row.push(sum / 32.0);
        }
        println!(
            "{n}: pmj02bn {:.3} pmj02 {:.3} ratio {:.3}",
            row[0],
            row[1],
            row[0] / row[1]
        );
    }
}

fn main() {
    if std::env::var_os("TABLE").is_some() {
        return table();
    }
    let args: Vec<String> = std::env::args().collect();
    let rounds: usize = args.get(1).map_or(30, |s| s.parse().unwrap());
    let n: usize = args.get(2).map_or(4096, |s| s.parse().unwrap());
    let (mut ts, mut tp, mut ratio) = (vec![], vec![], vec![]);
    let (mut nns, mut nnp) = (0.0, 0.0);
    let mut buf = vec![Point2::ZERO; n];
    for r in 0..rounds {
        let run_ours = |buf: &mut Vec<Point2>| {
            let t = Instant::now();
            let mut params = Params::new(n as u64).seed(strata::Seed(1000 + r as u64));
            params.iterations = std::env::var("SWEEPS").ok().map(|v| v.parse().unwrap());
            let mut s = registry::build("pmj02bn", &params).unwrap();
            s.fill(buf);
            t.elapsed().as_secs_f64()
        };
        let run_peer = || {
            let mut rng = SmallRng::seed_from_u64(r as u64);
            let t = Instant::now();
            let v = pmj::generate(n, 99, &mut rng);
            (t.elapsed().as_secs_f64(), v)
        };
        let (a, (b, v)) = if r % 2 == 0 {
            let a = run_ours(&mut buf);
            (a, run_peer())
        } else {
            let b = run_peer();
            (run_ours(&mut buf), b)
        };
        ts.push(a);
        tp.push(b);
        ratio.push(a / b);
        nns += mean_nn(&buf);
        let pv: Vec<Point2> = v.iter().map(|s| [s.x(), s.y()]).collect();
        nnp += mean_nn(&pv);
    }
    let k = rounds as f64;
    println!(
        "n {n} rounds {rounds}: strata pmj02bn median {:.3} ms, pmj crate median {:.3} ms, median per-round ratio {:.3}; mean NN/r_max strata {:.4} pmj {:.4} (x{:.3})",
        1e3 * median(&mut ts),
        1e3 * median(&mut tp),
        median(&mut ratio),
        nns / k,
        nnp / k,
        nns / nnp
    );
}
