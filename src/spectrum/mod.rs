//! Power spectra of point sets: periodogram, expected spectrum, radial mean, anisotropy, and
//! the PSA point-set measures.
//!
//! # Definitions
//!
//! For points `x_1..x_N` on the unit torus and an integer frequency `w = (u, v)`,
//!
//! ```text
//! P(w) = |sum_k exp(-2 pi i w . x_k)|^2 / N
//! ```
//!
//! so white noise (independent uniform points) has `E[P(w)] = 1` for every `w != 0` and the DC
//! term is `P(0) = N`. A [`Spectrum`] holds `P` on the `(K+1) x (K+1)` grid `|u|, |v| <= K/2`,
//! DC in the centre. The **expected** spectrum averages `P` over `R` independent realizations;
//! by the Fourier view of Monte Carlo integration (Subr and Kautz 2013; Pilleboue et al. 2015)
//! it is what multiplies the integrand's power spectrum to give the variance of the estimate.
//!
//! The **radial mean** averages `P` over the frequencies `w != 0` with `round(|w|) = b`, for
//! `b = 1..K/2`; the **anisotropy** of that bin is `10 log10(var / mean^2)` in dB (Lagae and
//! Dutré 2008): about 0 dB for one white-noise periodogram, about `-10 log10(R)` dB for an
//! isotropic pattern averaged over `R` realizations, higher where the pattern prefers
//! directions.
//!
//! # Evaluation
//!
//! * [`periodogram_direct`] sums the exponentials term by term: `O(N K^2)` and obviously
//!   correct, kept as the reference.
//! * [`periodogram`] (the default everywhere) is a type-1 non-uniform FFT with Gaussian
//!   gridding (Greengard and Lee 2004): `O(N q^2 + K^2 log K)` with `q` about 12, accurate to
//!   better than `1e-7` absolute in the units above for any point set (tested against the
//!   direct sum).
//! * [`expected_spectrum`] runs realizations in parallel with rayon and sums them in a fixed
//!   order, so the result is bit-identical for any number of threads.

mod direct;
mod image;
mod measures;
mod nufft;

pub use crate::grid::relative_radius_max;
pub use image::{ErrorImage, LOW_BAND, error_image, error_image_masked};
pub use measures::{PointSetMeasures, nearest_neighbour_distances, point_set_measures};

use rayon::prelude::*;

use crate::{Error, Result};
use strata::Point2;

/// The largest resolution `K` accepted (the fast path's grid then needs about 300 MB).
pub const MAX_RESOLUTION: u32 = 2048;

/// The largest number of points accepted by the spectrum functions.
pub const MAX_POINTS: usize = 1 << 26;

/// The largest number of realizations [`expected_spectrum`] accepts.
pub const MAX_REALIZATIONS: u32 = 1 << 20;

/// How many realizations are computed between two in-order accumulations: fixed, so the
/// order of the floating-point sum never depends on the thread count.
const WAVE: usize = 16;

/// A power spectrum on the integer frequencies `|u|, |v| <= K/2` (DC in the centre).
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    resolution: u32,
    values: Vec<f64>,
}

impl Spectrum {
    /// A spectrum from its values, row-major with `v` then `u` ascending from `-K/2`; `values`
    /// must hold `(K+1)^2` finite numbers.
    pub fn from_values(resolution: u32, values: Vec<f64>) -> Result<Self> {
        check_resolution(resolution)?;
        let side = resolution as usize + 1;
        if values.len() != side * side {
            return Err(Error::input(
                "Spectrum::from_values",
                format!(
                    "{} values given; resolution {resolution} needs {}",
                    values.len(),
                    side * side
                ),
            ));
        }
        if let Some(bad) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::input(
                "Spectrum::from_values",
                format!("value {bad} is {}; values must be finite", values[bad]),
            ));
        }
        Ok(Spectrum { resolution, values })
    }

    /// `K`: frequencies run from `-K/2` to `K/2` on each axis.
    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// `K + 1`: the number of frequencies per axis.
    pub fn side(&self) -> usize {
        self.resolution as usize + 1
    }

    /// `P(u, v)`, or `None` outside `|u|, |v| <= K/2`.
    pub fn get(&self, u: i32, v: i32) -> Option<f64> {
        let h = (self.resolution / 2) as i32;
        if u.abs() > h || v.abs() > h {
            return None;
        }
        Some(self.values[(v + h) as usize * self.side() + (u + h) as usize])
    }

    /// All values, row-major with `v` (then `u`) ascending from `-K/2`.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The radial mean and anisotropy per radial bin `b = 1..=K/2` (see the module docs).
    pub fn radial(&self) -> Vec<RadialBin> {
        let h = (self.resolution / 2) as i32;
        let bins = h as usize;
        let (mut sum, mut sum_sq, mut count) = (
            vec![0.0f64; bins + 1],
            vec![0.0f64; bins + 1],
            vec![0usize; bins + 1],
        );
        for v in -h..=h {
            for u in -h..=h {
                if u == 0 && v == 0 {
                    continue;
                }
                let b = ((u * u + v * v) as f64).sqrt().round() as usize;
                if b > bins {
                    continue;
                }
                let p = self.get(u, v).expect("inside the grid");
                sum[b] += p;
                sum_sq[b] += p * p;
                count[b] += 1;
            }
        }
        (1..=bins)
            .map(|b| {
                let n = count[b] as f64;
                let mean = sum[b] / n;
                // Unbiased sample variance of the bin's values.
                let var = ((sum_sq[b] - n * mean * mean) / (n - 1.0)).max(0.0);
                let anisotropy = if mean > 0.0 && var > 0.0 {
                    10.0 * (var / (mean * mean)).log10()
                } else {
                    f64::NEG_INFINITY
                };
                RadialBin {
                    frequency: b as u32,
                    power: mean,
                    anisotropy,
                    count: count[b],
                }
            })
            .collect()
    }
}

/// One radial bin of a spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct RadialBin {
    /// The bin's radius `b`: frequencies with `round(|w|) = b`.
    pub frequency: u32,
    /// Mean of `P` over the bin.
    pub power: f64,
    /// `10 log10(variance / mean^2)` in dB (`-inf` when the bin's values are all equal).
    pub anisotropy: f64,
    /// How many frequencies the bin holds.
    pub count: usize,
}

/// Checks `K`: even, `2 <= K <= MAX_RESOLUTION`.
pub fn check_resolution(resolution: u32) -> Result<()> {
    if resolution < 2 || !resolution.is_multiple_of(2) || resolution > MAX_RESOLUTION {
        return Err(Error::parameter(
            "spectrum::check_resolution",
            "resolution",
            resolution,
            format!(
                "an even number from 2 to {MAX_RESOLUTION} (the grid is (K+1) x (K+1), DC in the centre)"
            ),
        ));
    }
    Ok(())
}

/// Checks a point set: not empty, at most [`MAX_POINTS`], every coordinate finite and in `[0, 1)`.
pub(crate) fn check_points(points: &[Point2]) -> Result<()> {
    if points.is_empty() {
        return Err(Error::input(
            "spectrum::check_points",
            "the point set is empty; at least one point is needed",
        ));
    }
    if points.len() > MAX_POINTS {
        return Err(Error::input(
            "spectrum::check_points",
            format!(
                "{} points given; at most {MAX_POINTS} are accepted",
                points.len()
            ),
        ));
    }
    for (i, p) in points.iter().enumerate() {
        for c in *p {
            if !(0.0..1.0).contains(&c) {
                return Err(Error::input(
                    "spectrum::check_points",
                    format!(
                        "point {i} is ({}, {}); coordinates must be finite and in [0, 1)",
                        p[0], p[1]
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The periodogram by direct summation (the reference): `O(N (K+1)^2)` complex exponentials,
/// parallel over frequencies.
pub fn periodogram_direct(points: &[Point2], resolution: u32) -> Result<Spectrum> {
    check_resolution(resolution)?;
    check_points(points)?;
    Ok(Spectrum {
        resolution,
        values: direct::periodogram(points, resolution as usize),
    })
}

/// The periodogram by the non-uniform FFT (the default): within `1e-7` of
/// [`periodogram_direct`] at every frequency.
///
/// ```
/// use strata_lab::spectrum::periodogram;
/// let pts = [[0.25, 0.5], [0.75, 0.5]];
/// let s = periodogram(&pts, 8)?;
/// assert!((s.get(0, 0).unwrap() - 2.0).abs() < 1e-9); // DC = N
/// assert!(s.get(1, 0).unwrap() < 1e-9); // the two points cancel at u = 1
/// # Ok::<(), strata_lab::Error>(())
/// ```
pub fn periodogram(points: &[Point2], resolution: u32) -> Result<Spectrum> {
    check_resolution(resolution)?;
    check_points(points)?;
    let plan = nufft::Plan::new(resolution as usize, points.len());
    Ok(Spectrum {
        resolution,
        values: plan.periodogram(points),
    })
}

/// The expected power spectrum of point sets already in memory (see [`expected_spectrum`]).
pub fn expected_spectrum_of_sets(sets: &[Vec<Point2>], resolution: u32) -> Result<Spectrum> {
    let count = u32::try_from(sets.len()).unwrap_or(u32::MAX);
    expected_spectrum(count, resolution, |r| Ok(sets[r as usize].clone()))
}

/// The expected power spectrum: the mean of the periodograms of `realizations` point sets,
/// where `make(r)` gives realization `r` (for example the sampler seeded with `seed + r`).
///
/// Realizations run in parallel; they are accumulated in a fixed order, so the result is
/// bit-identical for any number of rayon threads. All realizations must have the same number
/// of points.
pub fn expected_spectrum<F>(realizations: u32, resolution: u32, make: F) -> Result<Spectrum>
where
    F: Fn(u32) -> Result<Vec<Point2>> + Sync,
{
    check_resolution(resolution)?;
    if realizations == 0 || realizations > MAX_REALIZATIONS {
        return Err(Error::parameter(
            "spectrum::expected_spectrum",
            "realizations",
            realizations,
            format!("1 to {MAX_REALIZATIONS}"),
        ));
    }
    let side = resolution as usize + 1;
    let mut acc = vec![0.0f64; side * side];
    let mut plan: Option<(usize, nufft::Plan)> = None;
    let all: Vec<u32> = (0..realizations).collect();
    for wave in all.chunks(WAVE) {
        let sets = wave
            .par_iter()
            .map(|&r| make(r))
            .collect::<Result<Vec<_>>>()?;
        for s in &sets {
            check_points(s)?;
        }
        let n = plan.as_ref().map_or(sets[0].len(), |(n, _)| *n);
        if let Some(bad) = sets.iter().position(|s| s.len() != n) {
            return Err(Error::input(
                "spectrum::expected_spectrum",
                format!(
                    "realization {} has {} points, realization 0 has {n}; all must have the same count",
                    wave[bad],
                    sets[bad].len()
                ),
            ));
        }
        let plan_ref = &plan
            .get_or_insert_with(|| (n, nufft::Plan::new(resolution as usize, n)))
            .1;
        let spectra: Vec<Vec<f64>> = sets.par_iter().map(|s| plan_ref.periodogram(s)).collect();
        for p in &spectra {
            for (a, v) in acc.iter_mut().zip(p) {
                *a += v;
            }
        }
    }
    let r = realizations as f64;
    for a in &mut acc {
        *a /= r;
    }
    Ok(Spectrum {
        resolution,
        values: acc,
    })
}
