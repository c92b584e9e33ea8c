//! Semi-discrete optimal transport on the torus: the weights that give every power cell a
//! prescribed area.
//!
//! For sites `s_i` and target areas `m_i` (summing to 1, the torus' area), the weights `w`
//! maximise the concave function (Aurenhammer, Hoffmann, Aronov 1998)
//!
//! ```text
//! Phi(w) = sum_i [ int_{V_i(w)} (|x - s_i|^2 - w_i) dx + w_i m_i ],
//! dPhi/dw_i = m_i - |V_i(w)|,
//! ```
//!
//! where `V_i(w)` is the power cell. Its Hessian is minus the weighted graph Laplacian
//! `L = d|V|/dw` of the diagram: moving `w_i` by `dt` moves the edge shared with the copy
//! `s_j + k` by `dt / (2 |s_j + k - s_i|)` into the neighbour, so
//!
//! ```text
//! d|V_i|/dw_j = -sum_{edges e of i with j} |e| / (2 |s_j + k_e - s_i|)   (j != i),
//! d|V_i|/dw_i =  sum_{edges e of i, j != i} |e| / (2 |s_j + k_e - s_i|),
//! ```
//!
//! symmetric positive semi-definite with the constants as null space (adding a constant to
//! every weight changes nothing). [`TransportSolver`] runs Newton's method on `Phi`: solve
//! `L d = m - |V(w)|` by conjugate gradients, then step `w <- w + tau d`, with the damping of
//! Kitagawa, Mérigot and Thibert ("Convergence of a Newton algorithm for semi-discrete optimal
//! transport", JEMS 2019): `tau` is halved from 1 until every cell keeps at least
//! `eps0 = min(min_i |V_i(w_0)|, min_i m_i) / 2` of area and the residual's norm falls by a
//! factor `1 - tau / 2`. This keeps every cell non-empty (so `L` keeps its rank) and converges
//! globally, quadratically near the solution.

use super::linalg::{CgWork, SparseSym, pcg};
use super::{MIN_MAGNITUDE, PowerDiagram};
use crate::{Error, Result};

/// The context named in this module's errors.
const CONTEXT: &str = "power::transport";

/// Options of [`TransportSolver::solve`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TransportOptions {
    /// Stop when every cell's area is within this fraction of its target:
    /// `max_i |area_i - m_i| / m_i <= tolerance`. In `(0, 1)`.
    pub(crate) tolerance: f64,
    /// The most Newton steps (each computes at least one diagram). At least 1.
    pub(crate) max_steps: u32,
    /// The conjugate gradient stops at this residual relative to the right-hand side. In
    /// `(0, 1)`.
    pub(crate) cg_tolerance: f64,
    /// The most conjugate-gradient iterations per Newton step. At least 1.
    pub(crate) cg_max_iterations: u32,
}

impl Default for TransportOptions {
    fn default() -> Self {
        TransportOptions {
            tolerance: 1e-6,
            max_steps: 100,
            cg_tolerance: 1e-3,
            cg_max_iterations: 2000,
        }
    }
}

impl TransportOptions {
    fn validate(&self) -> Result<()> {
        let unit = |name, v: f64| {
            if v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(Error::parameter(CONTEXT, name, v, "in (0, 1)"))
            }
        };
        unit("tolerance", self.tolerance)?;
        unit("cg_tolerance", self.cg_tolerance)?;
        for (name, v) in [
            ("max_steps", self.max_steps),
            ("cg_max_iterations", self.cg_max_iterations),
        ] {
            if v == 0 {
                return Err(Error::parameter(CONTEXT, name, 0, "at least 1"));
            }
        }
        Ok(())
    }
}

/// How a solve went.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct TransportReport {
    /// Whether the tolerance was reached.
    pub(crate) converged: bool,
    /// Newton steps taken.
    pub(crate) steps: u32,
    /// Power diagrams computed (including rejected line-search trials).
    pub(crate) diagrams: u32,
    /// Conjugate-gradient iterations, in total.
    pub(crate) cg_iterations: u32,
    /// The largest relative residual `|L d - r| / |r|` a conjugate-gradient solve ended with.
    pub(crate) cg_residual: f64,
    /// Step halvings in the line search, in total.
    pub(crate) halvings: u32,
    /// Whether the starting weights left a cell empty, so that the solve restarted from
    /// shrunken (or zero) weights.
    pub(crate) restarted: bool,
    /// `max_i |area_i - m_i| / m_i` at the end.
    pub(crate) max_relative_error: f64,
}

/// A reusable semi-discrete transport solver (keeps its diagrams and buffers between solves).
#[derive(Clone, Debug, Default)]
pub(crate) struct TransportSolver {
    diagram: PowerDiagram,
    trial: PowerDiagram,
    hessian: SparseSym,
    cg: CgWork,
    residual: Vec<f64>,
    direction: Vec<f64>,
    trial_weights: Vec<f64>,
}

fn max_relative_error(areas: &[f64], targets: &[f64]) -> f64 {
    areas
        .iter()
        .zip(targets)
        .map(|(a, m)| (a - m).abs() / m)
        .fold(0.0, f64::max)
}

fn residual_norm(areas: &[f64], targets: &[f64]) -> f64 {
    areas
        .iter()
        .zip(targets)
        .map(|(a, m)| (m - a) * (m - a))
        .sum::<f64>()
        .sqrt()
}

/// Weights closer to zero than [`MIN_MAGNITUDE`] (2^-200) are set to zero: far below any
/// effect on the diagram, and the exact predicates need it.
pub(crate) fn flush_tiny(w: &mut [f64]) {
    for v in w {
        if v.abs() < MIN_MAGNITUDE {
            *v = 0.0;
        }
    }
}

/// Checks target areas: one per site, positive, finite, summing to 1.
pub(crate) fn validate_targets(n: usize, targets: &[f64]) -> Result<()> {
    if targets.len() != n {
        return Err(Error::input(
            CONTEXT,
            format!(
                "{n} sites but {} targets; there must be exactly one target area per site",
                targets.len()
            ),
        ));
    }
    if let Some(i) = targets.iter().position(|&m| !(m > 0.0 && m.is_finite())) {
        return Err(Error::input(
            CONTEXT,
            format!(
                "target area {i} is {}; every target must be positive and finite",
                targets[i]
            ),
        ));
    }
    let sum: f64 = targets.iter().sum();
    if (sum - 1.0).abs() > 1e-9 {
        return Err(Error::input(
            CONTEXT,
            format!(
                "the target areas sum to {sum}; they must sum to 1 (the torus' area) within 1e-9"
            ),
        ));
    }
    Ok(())
}

impl TransportSolver {
    /// A solver with empty buffers.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// The diagram at the weights of the last solve (empty before the first).
    pub(crate) fn diagram(&self) -> &PowerDiagram {
        &self.diagram
    }

    /// Adjusts `weights` (the starting point, updated in place) so that the power cells of
    /// `sites` have the areas `targets`. If the starting weights leave a cell empty, they are
    /// halved until none is (and set to zero, the Voronoi diagram, after 30 halvings).
    ///
    /// The result's `converged` says whether the tolerance was reached within `max_steps`
    /// (not reaching it is not an error: the weights are then the best found).
    ///
    /// # Errors
    ///
    /// Invalid sites or weights (see [`PowerDiagram::new`]), invalid targets (see
    /// [`validate_targets`]) or options.
    pub(crate) fn solve(
        &mut self,
        sites: &[[f64; 2]],
        weights: &mut [f64],
        targets: &[f64],
        options: &TransportOptions,
    ) -> Result<TransportReport> {
        options.validate()?;
        validate_targets(sites.len(), targets)?;
        flush_tiny(weights);
        let mut report = TransportReport::default();
        self.diagram.compute(sites, weights)?;
        report.diagrams += 1;
        // A start with an empty cell: shrink the weights toward the Voronoi diagram.
        let mut shrink = 0;
        while self.diagram.areas().iter().any(|&a| a.is_nan() || a <= 0.0) {
            report.restarted = true;
            shrink += 1;
            if shrink > 30 {
                weights.iter_mut().for_each(|w| *w = 0.0);
            } else {
                weights.iter_mut().for_each(|w| *w *= 0.5);
                flush_tiny(weights);
            }
            self.diagram.set_weights(weights)?;
            report.diagrams += 1;
            if shrink > 30 {
                break;
            }
        }
        let n = sites.len();
        let min_target = targets.iter().copied().fold(f64::INFINITY, f64::min);
        let min_area = self
            .diagram
            .areas()
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let eps0 = 0.5 * min_target.min(min_area);
        let mut norm = residual_norm(self.diagram.areas(), targets);
        report.max_relative_error = max_relative_error(self.diagram.areas(), targets);
        while report.max_relative_error > options.tolerance {
            if report.steps >= options.max_steps {
                return Ok(report);
            }
            report.steps += 1;
            // Newton direction: L d = m - |V|.
            self.assemble_hessian();
            self.residual.clear();
            self.residual
                .extend(targets.iter().zip(self.diagram.areas()).map(|(m, a)| m - a));
            self.direction.clear();
            self.direction.resize(n, 0.0);
            let cg = pcg(
                &self.hessian,
                &self.residual,
                &mut self.direction,
                options.cg_tolerance,
                options.cg_max_iterations,
                &mut self.cg,
            );
            report.cg_iterations += cg.iterations;
            report.cg_residual = report.cg_residual.max(cg.relative_residual);
            // Damped step.
            let mut tau = 1.0;
            let mut accepted = false;
            for _ in 0..40 {
                self.trial_weights.clear();
                self.trial_weights.extend(
                    weights
                        .iter()
                        .zip(&self.direction)
                        .map(|(w, d)| w + tau * d),
                );
                flush_tiny(&mut self.trial_weights);
                if self.trial.len() == n && self.trial.sites() == sites {
                    // Same sites: skip re-validation and the grid.
                    if self.trial.set_weights(&self.trial_weights).is_err() {
                        tau *= 0.5;
                        report.halvings += 1;
                        continue;
                    }
                } else if self.trial.compute(sites, &self.trial_weights).is_err() {
                    tau *= 0.5;
                    report.halvings += 1;
                    continue;
                }
                report.diagrams += 1;
                let areas = self.trial.areas();
                let min = areas.iter().copied().fold(f64::INFINITY, f64::min);
                let trial_norm = residual_norm(areas, targets);
                if min >= eps0 && trial_norm <= (1.0 - 0.5 * tau) * norm {
                    accepted = true;
                    norm = trial_norm;
                    break;
                }
                tau *= 0.5;
                report.halvings += 1;
            }
            if !accepted {
                // No step helps any more (rounding level): stop where we are.
                return Ok(report);
            }
            weights.copy_from_slice(&self.trial_weights);
            core::mem::swap(&mut self.diagram, &mut self.trial);
            report.max_relative_error = max_relative_error(self.diagram.areas(), targets);
        }
        report.converged = true;
        Ok(report)
    }

    /// The Laplacian `d|V|/dw` of the current diagram.
    fn assemble_hessian(&mut self) {
        assemble(&self.diagram, &mut self.hessian);
    }
}

fn assemble(d: &PowerDiagram, h: &mut SparseSym) {
    h.begin(d.len());
    for (i, cell) in d.cells().enumerate() {
        for nb in cell.neighbors() {
            if nb.site > i {
                h.add_edge(i, nb.site, nb.length / (2.0 * nb.distance));
            }
        }
    }
    h.finish();
}

/// The derivative of the cell areas with respect to the weights (the weighted Laplacian `L`
/// above) applied to `x`: `(L x)_i = sum_j d|V_i|/dw_j x_j`.
///
/// # Errors
///
/// `x` of the wrong length.
#[cfg(test)]
pub(crate) fn area_derivative_times(d: &PowerDiagram, x: &[f64]) -> Result<Vec<f64>> {
    if x.len() != d.len() {
        return Err(Error::input(
            CONTEXT,
            format!(
                "{} sites but {} vector entries; there must be one entry per site",
                d.len(),
                x.len()
            ),
        ));
    }
    let mut h = SparseSym::default();
    assemble(d, &mut h);
    let mut y = vec![0.0; x.len()];
    h.mul(x, &mut y);
    Ok(y)
}

/// Solves for the weights in one call: see [`TransportSolver::solve`]. Returns the report and
/// the diagram at the final weights.
///
/// # Errors
///
/// As [`TransportSolver::solve`].
#[cfg(test)]
pub(crate) fn solve_weights(
    sites: &[[f64; 2]],
    weights: &mut [f64],
    targets: &[f64],
    options: &TransportOptions,
) -> Result<(TransportReport, PowerDiagram)> {
    let mut s = TransportSolver::new();
    let report = s.solve(sites, weights, targets, options)?;
    Ok((report, s.diagram))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::needless_range_loop)] // index loops read better in these checks

    use super::*;
    use rand::Rng;

    /// Test data: uniform points and values from a seeded PCG32.
    struct Pcg32(rand_pcg::Pcg32);

    impl Pcg32 {
        fn new(seed: u64) -> Self {
            Pcg32(rand_pcg::Pcg32::new(seed, 0xda3e_39cb_94b9_5bdb))
        }
        fn next_f64(&mut self) -> f64 {
            strata::float::unit_f64_from_u64(self.0.next_u64())
        }
        fn points(&mut self, n: usize) -> Vec<[f64; 2]> {
            (0..n).map(|_| [self.next_f64(), self.next_f64()]).collect()
        }
    }

    #[test]
    fn area_derivative_matches_finite_differences() {
        let mut g = Pcg32::new(21);
        let n = 60;
        let sites = g.points(n);
        let w: Vec<f64> = (0..n).map(|_| 0.05 / n as f64 * g.next_f64()).collect();
        let d = PowerDiagram::new(&sites, &w).unwrap();
        assert_eq!(d.empty_cells(), 0);
        for j in [0usize, 7, 33] {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            let analytic = area_derivative_times(&d, &e).unwrap();
            // Central differences (areas are piecewise quadratic in w: exact up to rounding for a
            // step that changes no combinatorics).
            let h = 1e-7;
            let mut wp = w.clone();
            wp[j] += h;
            let mut wm = w.clone();
            wm[j] -= h;
            let ap = PowerDiagram::new(&sites, &wp).unwrap();
            let am = PowerDiagram::new(&sites, &wm).unwrap();
            for i in 0..n {
                let fd = (ap.areas()[i] - am.areas()[i]) / (2.0 * h);
                assert!(
                    (fd - analytic[i]).abs() < 1e-5 * (1.0 + analytic[i].abs()),
                    "d area_{i} / d w_{j}: finite difference {fd}, Laplacian {}",
                    analytic[i]
                );
            }
            // Rows sum to zero (the total area is constant), the diagonal is positive.
            assert!(analytic.iter().sum::<f64>().abs() < 1e-10);
            assert!(analytic[j] > 0.0);
        }
    }

    #[test]
    fn newton_reaches_uniform_areas_from_zero_weights() {
        for (seed, n) in [(1u64, 2usize), (2, 3), (3, 64), (4, 1000)] {
            let mut g = Pcg32::new(seed);
            let sites = g.points(n);
            let mut w = vec![0.0; n];
            let targets = vec![1.0 / n as f64; n];
            let opts = TransportOptions {
                tolerance: 1e-9,
                ..TransportOptions::default()
            };
            let (report, d) = solve_weights(&sites, &mut w, &targets, &opts).unwrap();
            assert!(report.converged, "n {n}: {report:?}");
            assert!(report.steps <= 30, "n {n}: {report:?}");
            for (i, a) in d.areas().iter().enumerate() {
                assert!((a * n as f64 - 1.0).abs() <= 1e-9, "n {n} cell {i}: {a}");
            }
            // The weights reproduce the diagram.
            let again = PowerDiagram::new(&sites, &w).unwrap();
            assert_eq!(again.areas(), d.areas());
        }
    }

    #[test]
    fn newton_reaches_unequal_targets() {
        let mut g = Pcg32::new(8);
        let n = 200;
        let sites = g.points(n);
        // Targets proportional to 1 + x (a ramp), normalised.
        let raw: Vec<f64> = sites.iter().map(|s| 1.0 + 2.0 * s[0]).collect();
        let sum: f64 = raw.iter().sum();
        let targets: Vec<f64> = raw.iter().map(|r| r / sum).collect();
        let mut w = vec![0.0; n];
        let opts = TransportOptions {
            tolerance: 1e-8,
            ..TransportOptions::default()
        };
        let (report, d) = solve_weights(&sites, &mut w, &targets, &opts).unwrap();
        assert!(report.converged, "{report:?}");
        for i in 0..n {
            assert!((d.areas()[i] / targets[i] - 1.0).abs() <= 1e-8);
        }
    }

    #[test]
    fn one_site_needs_no_step() {
        let mut w = vec![0.3];
        let (report, d) =
            solve_weights(&[[0.5, 0.5]], &mut w, &[1.0], &TransportOptions::default()).unwrap();
        assert!(report.converged);
        assert_eq!(report.steps, 0);
        assert_eq!(d.areas(), &[1.0]);
    }

    #[test]
    fn a_start_with_empty_cells_is_recovered() {
        let mut g = Pcg32::new(13);
        let n = 100;
        let sites = g.points(n);
        // Wild weights: many empty cells at the start.
        let mut w: Vec<f64> = (0..n).map(|_| 0.5 * (g.next_f64() - 0.5)).collect();
        assert!(PowerDiagram::new(&sites, &w).unwrap().empty_cells() > 10);
        let targets = vec![1.0 / n as f64; n];
        let mut s = TransportSolver::new();
        let report = s
            .solve(&sites, &mut w, &targets, &TransportOptions::default())
            .unwrap();
        assert!(report.restarted);
        assert!(report.converged, "{report:?}");
        assert_eq!(s.diagram().empty_cells(), 0);
    }

    #[test]
    fn regular_grid_is_already_solved() {
        let k = 8;
        let sites: Vec<[f64; 2]> = (0..k * k)
            .map(|i| {
                [
                    ((i % k) as f64 + 0.5) / k as f64,
                    ((i / k) as f64 + 0.5) / k as f64,
                ]
            })
            .collect();
        let mut w = vec![0.0; k * k];
        let targets = vec![1.0 / (k * k) as f64; k * k];
        let (report, _) =
            solve_weights(&sites, &mut w, &targets, &TransportOptions::default()).unwrap();
        assert!(report.converged);
        assert_eq!(report.steps, 0);
    }

    #[test]
    fn step_cap_is_reported_not_hung() {
        let mut g = Pcg32::new(5);
        let n = 500;
        let sites = g.points(n);
        let mut w = vec![0.0; n];
        let targets = vec![1.0 / n as f64; n];
        let opts = TransportOptions {
            tolerance: 1e-12,
            max_steps: 1,
            ..TransportOptions::default()
        };
        let (report, _) = solve_weights(&sites, &mut w, &targets, &opts).unwrap();
        assert!(!report.converged);
        assert_eq!(report.steps, 1);
    }

    #[test]
    fn bad_targets_and_options_are_errors() {
        let sites = [[0.1, 0.1], [0.6, 0.6]];
        let mut w = vec![0.0; 2];
        let o = TransportOptions::default();
        let e = solve_weights(&sites, &mut w, &[0.5], &o).unwrap_err();
        assert!(e.to_string().contains("2 sites but 1 targets"), "{e}");
        let e = solve_weights(&sites, &mut w, &[0.5, 0.6], &o).unwrap_err();
        assert!(e.to_string().contains("sum to 1"), "{e}");
        let e = solve_weights(&sites, &mut w, &[1.0, 0.0], &o).unwrap_err();
        assert!(e.to_string().contains("positive"), "{e}");
        let bad = TransportOptions {
            tolerance: 0.0,
            ..o
        };
        let e = solve_weights(&sites, &mut w, &[0.5, 0.5], &bad).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Strata(strata::Error::InvalidParameter {
                    parameter: "tolerance",
                    ..
                })
            ),
            "{e}"
        );
        let bad = TransportOptions { max_steps: 0, ..o };
        assert!(solve_weights(&sites, &mut w, &[0.5, 0.5], &bad).is_err());
        let e = solve_weights(&[[0.1, 0.1], [0.1, 0.1]], &mut w, &[0.5, 0.5], &o).unwrap_err();
        assert!(e.to_string().contains("coincide"), "{e}");
    }
}
