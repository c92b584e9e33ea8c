//! Test integrands with exact reference values.
//!
//! The 2D set follows the ones used to compare sample patterns by Christensen, Kensler,
//! Kilpatrick (2018) and Pilleboue et al. (2015): a discontinuous disk, triangle and step, and
//! a smooth Gaussian and bilinear function, on `[0,1)^2`. Two 4D functions serve the
//! D-dimensional samplers (the lecture's "4D integral with uncorrelated jitter"): a smooth
//! product of Gaussians and a discontinuous 4D ball.

use std::f64::consts::PI;

use crate::registry::Rates;

/// A function on `[0,1)^D` with its exact integral.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Integrand {
    /// `1` inside the quarter disk `x^2 + y^2 < 2/pi` (area 1/2), else 0. Discontinuous.
    Disk,
    /// `1` below the diagonal, `y < x`. Discontinuous.
    Triangle,
    /// `1` for `x < 0.3`. Discontinuous along one axis.
    Step,
    /// `exp(-(x^2 + y^2))`. Smooth.
    Gaussian,
    /// `x y`. Smooth.
    Bilinear,
    /// `prod_k exp(-x_k^2)` in 4D. Smooth.
    Gaussian4d,
    /// `1` inside the 4D ball `|x - c| < 0.45` around the centre `c = (1/2, ..)`. Discontinuous.
    Ball4d,
}

// The published rate of a sampler on an integrand lives with the integrands: the entry types
// (`crate::entry`, below the samplers) do not know the analysis tools.
impl Rates {
    /// The rate on `integrand`, if published.
    pub fn on(&self, integrand: Integrand) -> Option<f64> {
        if integrand.dimensions() != 2 {
            self.higher
        } else if integrand.smooth() {
            self.smooth
        } else {
            self.discontinuous
        }
    }
}

/// `erf(1)`, to double precision.
const ERF_1: f64 = 0.842_700_792_949_714_9;

impl Integrand {
    /// Every integrand.
    pub const ALL: [Integrand; 7] = [
        Integrand::Disk,
        Integrand::Triangle,
        Integrand::Step,
        Integrand::Gaussian,
        Integrand::Bilinear,
        Integrand::Gaussian4d,
        Integrand::Ball4d,
    ];

    /// The name on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            Integrand::Disk => "disk",
            Integrand::Triangle => "triangle",
            Integrand::Step => "step",
            Integrand::Gaussian => "gaussian",
            Integrand::Bilinear => "bilinear",
            Integrand::Gaussian4d => "gaussian4d",
            Integrand::Ball4d => "ball4d",
        }
    }

    /// The integrand called `name`; the error lists the known names.
    pub fn by_name(name: &str) -> crate::Result<Self> {
        Self::ALL
            .iter()
            .copied()
            .find(|i| i.name() == name)
            .ok_or_else(|| {
                crate::Error::input(
                    "Integrand::by_name",
                    format!(
                        "unknown integrand '{name}'; known integrands: {}",
                        Self::ALL
                            .iter()
                            .map(|i| i.name())
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })
    }

    /// The number of dimensions.
    pub fn dimensions(&self) -> u32 {
        match self {
            Integrand::Gaussian4d | Integrand::Ball4d => 4,
            _ => 2,
        }
    }

    /// Smooth (true) or with discontinuities.
    pub fn smooth(&self) -> bool {
        matches!(
            self,
            Integrand::Gaussian | Integrand::Bilinear | Integrand::Gaussian4d
        )
    }

    /// The Monte Carlo estimate over a set of points of `dims` coordinates each (`dims >=
    /// dimensions()`; `points.len()` a multiple of `dims`): the mean of the values, summed in
    /// the points' order (the estimate of one seed in a convergence study).
    pub fn estimate(&self, points: &[f32], dims: u32) -> f64 {
        let dims = dims as usize;
        let n = points.len() / dims;
        points.chunks_exact(dims).map(|p| self.eval(p)).sum::<f64>() / n as f64
    }

    /// The value at `x` (`x.len() >= dimensions()`).
    #[inline]
    pub fn eval(&self, x: &[f32]) -> f64 {
        let c = |k: usize| x[k] as f64;
        match self {
            Integrand::Disk => f64::from(c(0) * c(0) + c(1) * c(1) < 2.0 / PI),
            Integrand::Triangle => f64::from(c(1) < c(0)),
            Integrand::Step => f64::from(c(0) < 0.3),
            Integrand::Gaussian => (-(c(0) * c(0) + c(1) * c(1))).exp(),
            Integrand::Bilinear => c(0) * c(1),
            Integrand::Gaussian4d => (-(0..4).map(|k| c(k) * c(k)).sum::<f64>()).exp(),
            Integrand::Ball4d => {
                f64::from((0..4).map(|k| (c(k) - 0.5).powi(2)).sum::<f64>() < 0.45 * 0.45)
            }
        }
    }

    /// The exact integral over `[0,1)^D`.
    pub fn exact(&self) -> f64 {
        let g1 = PI.sqrt() / 2.0 * ERF_1; // int_0^1 exp(-x^2)
        match self {
            Integrand::Disk | Integrand::Triangle => 0.5,
            Integrand::Step => 0.3,
            Integrand::Gaussian => g1 * g1,
            Integrand::Bilinear => 0.25,
            Integrand::Gaussian4d => g1.powi(4),
            // volume of a 4D ball: pi^2 r^4 / 2 (the ball fits inside the cube)
            Integrand::Ball4d => PI * PI * 0.45f64.powi(4) / 2.0,
        }
    }

    /// `int f^2 - (int f)^2`: the variance of one uniform sample (random sampling's variance is
    /// this over N).
    pub fn variance(&self) -> f64 {
        let i = self.exact();
        let second = match self {
            Integrand::Disk | Integrand::Triangle | Integrand::Step | Integrand::Ball4d => i, // indicators
            Integrand::Gaussian => {
                let g = PI.sqrt() / 2.0 * erf(2f64.sqrt()) / 2f64.sqrt(); // int_0^1 exp(-2x^2)
                g * g
            }
            Integrand::Bilinear => 1.0 / 9.0,
            Integrand::Gaussian4d => (PI.sqrt() / 2.0 * erf(2f64.sqrt()) / 2f64.sqrt()).powi(4),
        };
        second - i * i
    }
}

/// The error function (Abramowitz and Stegun 7.1.26 is too coarse here; this is the series /
/// continued-fraction evaluation to double precision for `|x| <= 3`).
pub(crate) fn erf(x: f64) -> f64 {
    // Maclaurin series: erf(x) = 2/sqrt(pi) sum_n (-1)^n x^(2n+1) / (n! (2n+1)); converges fast
    // for the small arguments used here.
    let mut term = x;
    let mut sum = x;
    let x2 = x * x;
    for n in 1..200 {
        term *= -x2 / n as f64;
        let add = term / (2 * n + 1) as f64;
        sum += add;
        if add.abs() < 1e-17 * sum.abs() {
            break;
        }
    }
    2.0 / PI.sqrt() * sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_values_match_numerical_integration() {
        // midpoint rule on a fine grid (2D), and the error function at 1
        assert!((erf(1.0) - ERF_1).abs() < 1e-15);
        for f in [
            Integrand::Disk,
            Integrand::Triangle,
            Integrand::Step,
            Integrand::Gaussian,
            Integrand::Bilinear,
        ] {
            let m = 2000;
            let mut sum = 0.0;
            for i in 0..m {
                for j in 0..m {
                    let x = [(i as f32 + 0.5) / m as f32, (j as f32 + 0.5) / m as f32];
                    sum += f.eval(&x);
                }
            }
            let numeric = sum / (m * m) as f64;
            assert!(
                (numeric - f.exact()).abs() < 2e-3,
                "{}: {numeric} vs {}",
                f.name(),
                f.exact()
            );
        }
    }
}
