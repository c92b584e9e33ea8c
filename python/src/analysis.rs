//! The analysis tools on any point set: power spectra (periodogram, expected spectrum, radial
//! mean and anisotropy), the PSA measures, nearest-neighbour distances, discrepancies and the
//! convergence studies.

use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use strata_lab::analysis::Integrand;
use strata_lab::analysis::discrepancy as disc;
use strata_lab::analysis::study::{self, Config};
use strata_lab::spectrum::{self, Spectrum};

use crate::{input_slice, to_py_err, value_error};

/// A `(n, 2)` C-contiguous float32 array as points, without copying.
fn points_2d<'a>(a: &'a PyReadonlyArray2<'_, f32>, what: &str) -> PyResult<&'a [[f32; 2]]> {
    if a.shape()[1] != 2 {
        return Err(value_error(format!(
            "{what}: points have shape {:?}; (n, 2) is needed",
            a.shape()
        )));
    }
    let s = input_slice(a, &format!("{what}: points"))?;
    Ok(bytemuck::cast_slice(s))
}

/// Checks that every coordinate is finite and in `[0, 1)` (the rule of the crate's spectrum
/// and point-set functions), with a message naming the first bad point.
fn check_unit(points: &[[f32; 2]], what: &str) -> PyResult<()> {
    if points.is_empty() {
        return Err(value_error(format!(
            "{what}: the point set is empty; at least one point is needed"
        )));
    }
    match points
        .iter()
        .position(|p| !p.iter().all(|v| (0.0..1.0).contains(v)))
    {
        Some(i) => Err(value_error(format!(
            "{what}: point {i} is ({}, {}); coordinates must be finite and in [0, 1)",
            points[i][0], points[i][1]
        ))),
        None => Ok(()),
    }
}

/// The periodogram of a `(n, 2)` float32 point set on the frequencies `|u|, |v| <= K/2`:
/// a `(K+1, K+1)` float64 array, row `v`, column `u`, DC in the centre; by the non-uniform
/// FFT, or by direct summation with `direct`.
#[pyfunction]
#[pyo3(signature = (points, resolution, direct=false))]
fn periodogram<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f32>,
    resolution: u32,
    direct: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let p = points_2d(&points, "spectrum")?;
    let s = py
        .detach(|| {
            if direct {
                spectrum::periodogram_direct(p, resolution)
            } else {
                spectrum::periodogram(p, resolution)
            }
        })
        .map_err(to_py_err)?;
    to_array(py, &s)
}

/// The spectrum's values as a `(K+1, K+1)` array.
fn to_array<'py>(py: Python<'py>, s: &Spectrum) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let side = s.side();
    let a = numpy::ndarray::Array2::from_shape_vec((side, side), s.values().to_vec())
        .map_err(|e| value_error(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// The expected power spectrum: the mean periodogram of the sets (each `(n, 2)` float32, all
/// with the same `n`), computed in parallel and summed in a fixed order.
#[pyfunction]
fn expected_spectrum<'py>(
    py: Python<'py>,
    sets: Vec<PyReadonlyArray2<'py, f32>>,
    resolution: u32,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let views = sets
        .iter()
        .map(|s| points_2d(s, "expected_spectrum"))
        .collect::<PyResult<Vec<&[[f32; 2]]>>>()?;
    let count =
        u32::try_from(views.len()).map_err(|_| value_error("expected_spectrum: too many sets"))?;
    let s = py
        .detach(|| {
            spectrum::expected_spectrum(count, resolution, |r| Ok(views[r as usize].to_vec()))
        })
        .map_err(to_py_err)?;
    to_array(py, &s)
}

/// The expected spectrum of sampler `name` at `count` points over `realizations` sets,
/// realization `r` seeded by `seed + r` (wrapping) as in the `spectrum` program; the sets are
/// generated and transformed in parallel.
#[pyfunction]
#[pyo3(signature = (name, count, resolution, realizations, seed, **parameters))]
fn sampler_spectrum<'py>(
    py: Python<'py>,
    name: &str,
    count: u64,
    resolution: u32,
    realizations: u32,
    seed: u64,
    parameters: Option<&Bound<'py, pyo3::types::PyDict>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let entry = strata_lab::registry::find(name).map_err(to_py_err)?;
    let params = crate::samplers::params(count, seed, parameters)?;
    let n = usize::try_from(count).map_err(|_| value_error("sampler_spectrum: count too large"))?;
    // checks the parameters and the count before the parallel run
    entry.build(&params).map_err(to_py_err)?;
    let s = py
        .detach(|| {
            spectrum::expected_spectrum(realizations, resolution, |r| {
                let mut s = entry.build(
                    &params
                        .clone()
                        .seed(strata::Seed(seed.wrapping_add(r as u64))),
                )?;
                let mut v = vec![[0.0f32; 2]; n];
                s.fill(&mut v);
                Ok(v)
            })
        })
        .map_err(to_py_err)?;
    to_array(py, &s)
}

/// Radial bins of a `(K+1, K+1)` spectrum: `(frequency, power, anisotropy, count)` arrays for
/// the bins `1..=K/2` (see `strata_lab::spectrum::Spectrum::radial`).
#[pyfunction]
#[allow(clippy::type_complexity)]
fn radial<'py>(
    py: Python<'py>,
    values: PyReadonlyArray2<'py, f64>,
) -> PyResult<(
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
)> {
    let shape = values.shape();
    if shape[0] != shape[1] || shape[0] < 3 || shape[0] % 2 == 0 {
        return Err(value_error(format!(
            "radial: the spectrum has shape {shape:?}; a (K+1, K+1) array with K even and at \
             least 2 is needed, as spectrum() returns"
        )));
    }
    let k = (shape[0] - 1) as u32;
    let v = input_slice(&values, "radial: the spectrum")?.to_vec();
    let bins = py
        .detach(|| Spectrum::from_values(k, v).map(|s| s.radial()))
        .map_err(to_py_err)?;
    Ok((
        bins.iter()
            .map(|b| b.frequency)
            .collect::<Vec<_>>()
            .into_pyarray(py),
        bins.iter()
            .map(|b| b.power)
            .collect::<Vec<_>>()
            .into_pyarray(py),
        bins.iter()
            .map(|b| b.anisotropy)
            .collect::<Vec<_>>()
            .into_pyarray(py),
        bins.iter()
            .map(|b| b.count as u64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    ))
}

/// The PSA point-set measures of one or more sets (all `(n, 2)` float32 with the same `n`): a
/// dict of count, global_min_distance, average_min_distance (relative to `r_max(n)`; `None`
/// for single points), effective_nyquist and oscillations (`None` above 2^16 points or below 2).
#[pyfunction]
fn psa<'py>(
    py: Python<'py>,
    sets: Vec<PyReadonlyArray2<'py, f32>>,
) -> PyResult<Bound<'py, PyDict>> {
    let owned = sets
        .iter()
        .map(|s| points_2d(s, "psa").map(<[[f32; 2]]>::to_vec))
        .collect::<PyResult<Vec<Vec<[f32; 2]>>>>()?;
    let m = py
        .detach(|| spectrum::point_set_measures(&owned))
        .map_err(to_py_err)?;
    let d = PyDict::new(py);
    d.set_item("count", m.count)?;
    d.set_item("global_min_distance", m.global_min_distance)?;
    d.set_item("average_min_distance", m.average_min_distance)?;
    d.set_item("effective_nyquist", m.effective_nyquist)?;
    d.set_item("oscillations", m.oscillations)?;
    Ok(d)
}

/// The toroidal distance from each point of a `(n, 2)` float32 set (n >= 2) to its nearest
/// neighbour.
#[pyfunction]
fn nearest_distances<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f32>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let p = points_2d(&points, "nearest_distances")?;
    check_unit(p, "nearest_distances")?;
    let d = py
        .detach(|| spectrum::nearest_neighbour_distances(p))
        .ok_or_else(|| {
            value_error("nearest_distances: a single point has no neighbour; at least 2 are needed")
        })?;
    Ok(d.into_pyarray(py))
}

/// `r_max(n)`: the neighbour distance of `n` points in a hexagonal packing of the unit torus.
#[pyfunction]
fn relative_radius_max(n: usize) -> f64 {
    spectrum::relative_radius_max(n)
}

/// A point set of either float type, C-contiguous, `(n, d)`.
#[derive(FromPyObject)]
enum AnyPoints<'py> {
    /// float32 coordinates.
    F32(PyReadonlyArray2<'py, f32>),
    /// float64 coordinates.
    F64(PyReadonlyArray2<'py, f64>),
}

/// The number of columns of a point array as the library's dimension count.
fn dims_of(columns: usize, what: &str) -> PyResult<u32> {
    u32::try_from(columns).map_err(|_| {
        value_error(format!(
            "{what}: points have {columns} columns; at most {} dimensions",
            u32::MAX
        ))
    })
}

/// Runs `f` on the coordinates of `points` (a slice of either float type) and its dimension.
macro_rules! with_points {
    ($points:expr, $what:expr, |$s:ident, $d:ident| $body:expr) => {
        match &$points {
            AnyPoints::F32(a) => {
                let $d = dims_of(a.shape()[1], $what)?;
                let $s = input_slice(a, &format!("{}: points", $what))?;
                $body
            }
            AnyPoints::F64(a) => {
                let $d = dims_of(a.shape()[1], $what)?;
                let $s = input_slice(a, &format!("{}: points", $what))?;
                $body
            }
        }
    };
}

/// The discrepancies scipy computes, by the same names: "CD" (centered, squared), "WD"
/// (wrap-around, squared), "MD" (mixture, squared), "L2-star" (not squared), and "star" (the
/// exact star discrepancy of a 2D set of at most 2^14 points).
pub(crate) const METHODS: [&str; 5] = ["CD", "WD", "MD", "L2-star", "star"];

/// The discrepancy of a `(n, d)` point set (float32 or float64, coordinates in `[0, 1]`) by
/// `method` (see [`METHODS`]).
#[pyfunction]
fn discrepancy(py: Python<'_>, points: AnyPoints<'_>, method: &str) -> PyResult<f64> {
    if !METHODS.contains(&method) {
        return Err(value_error(format!(
            "discrepancy: unknown method '{method}'; allowed: {}",
            METHODS.join(", ")
        )));
    }
    with_points!(points, "discrepancy", |s, d| {
        py.detach(|| match method {
            "CD" => disc::centered_squared(s, d),
            "WD" => disc::wrap_around_squared(s, d),
            "MD" => disc::mixture_squared(s, d),
            "L2-star" => disc::l2_star(s, d),
            _ if d != 2 => Err(strata_lab::Error::input(
                "analysis::discrepancy::star_2d",
                format!(
                    "the exact star discrepancy is for 2D sets; these points have {d} dimensions"
                ),
            )),
            _ => disc::star_2d(s),
        })
        .map_err(to_py_err)
    })
}

/// The t-value of a 2D set of `2^m` points as a base-2 `(t, m, 2)`-net (`None` when the count
/// is not a power of two).
#[pyfunction]
fn net_t_value(py: Python<'_>, points: AnyPoints<'_>) -> PyResult<Option<u32>> {
    with_points!(points, "net_t_value", |s, d| {
        if d != 2 {
            return Err(value_error(format!(
                "net_t_value: points have {d} columns; (n, 2) is needed"
            )));
        }
        py.detach(|| disc::net_t_value(s)).map_err(to_py_err)
    })
}

/// The test integrands with exact values: a list of dicts of name, dimensions, smooth, exact
/// and variance (of one uniform sample).
#[pyfunction]
fn integrands(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let list = PyList::empty(py);
    for f in Integrand::ALL {
        let d = PyDict::new(py);
        d.set_item("name", f.name())?;
        d.set_item("dimensions", f.dimensions())?;
        d.set_item("smooth", f.smooth())?;
        d.set_item("exact", f.exact())?;
        d.set_item("variance", f.variance())?;
        list.append(d)?;
    }
    Ok(list)
}

/// The convergence study of `tradeoff` for one sampler: for each count in `ns` (each one the
/// sampler accepts) and each integrand, the estimates over seeds `0..seeds`, as rows (dicts
/// with the columns of `tradeoff.csv`).
#[pyfunction]
#[pyo3(signature = (name, integrands, ns, seeds, predict=true))]
fn convergence<'py>(
    py: Python<'py>,
    name: &str,
    integrands: Vec<String>,
    ns: Vec<u64>,
    seeds: u32,
    predict: bool,
) -> PyResult<Bound<'py, PyList>> {
    let entry = strata_lab::registry::find(name).map_err(to_py_err)?;
    let integrands = integrands
        .iter()
        .map(|f| Integrand::by_name(f))
        .collect::<strata_lab::Result<Vec<_>>>()
        .map_err(to_py_err)?;
    if ns.is_empty() {
        return Err(value_error(
            "convergence: no count given; give one or more counts the sampler accepts",
        ));
    }
    let mut rows = Vec::new();
    for &n in &ns {
        let config = Config {
            samplers: vec![entry],
            integrands: integrands.clone(),
            min_n: n,
            max_n: n,
            seeds: study::Seeds::Fixed(seeds),
            predict,
        };
        let (r, _) = py
            .detach(|| study::run(&config, &|_, _| {}))
            .map_err(to_py_err)?;
        rows.extend(r);
    }
    let list = PyList::empty(py);
    for r in &rows {
        let d = PyDict::new(py);
        d.set_item("sampler", r.sampler)?;
        d.set_item("integrand", r.integrand.name())?;
        d.set_item("n", r.n)?;
        d.set_item("seeds", r.seeds)?;
        d.set_item("mean", r.mean)?;
        d.set_item("variance", r.variance)?;
        d.set_item("rmse", r.rmse)?;
        d.set_item("ns_per_sample", r.ns_per_sample)?;
        d.set_item("predicted_variance", r.predicted_variance)?;
        list.append(d)?;
    }
    Ok(list)
}

/// One seed's estimate of the integrand named `integrand` over `points` (`(n, d)` float32,
/// `d` at least the integrand's dimensions): the mean of its values, summed in the points'
/// order, as the convergence study computes it.
#[pyfunction]
fn estimate(py: Python<'_>, integrand: &str, points: PyReadonlyArray2<'_, f32>) -> PyResult<f64> {
    let f = Integrand::by_name(integrand).map_err(to_py_err)?;
    let (n, d) = (points.shape()[0], points.shape()[1]);
    if n == 0 || d < f.dimensions() as usize {
        return Err(value_error(format!(
            "estimate: points have shape ({n}, {d}); (n, d) with n >= 1 and d >= {} (the \
             dimensions of {integrand}) is needed",
            f.dimensions()
        )));
    }
    let s = input_slice(&points, "estimate: points")?;
    if let Some(i) = s.iter().position(|v| !v.is_finite()) {
        return Err(value_error(format!(
            "estimate: coordinate {} of point {} is {}; finite values are needed",
            i % d,
            i / d,
            s[i]
        )));
    }
    let dims = dims_of(d, "estimate")?;
    Ok(py.detach(|| f.estimate(s, dims)))
}

/// The statistics of the estimates of `integrand` over seeds, in the seeds' order: `(mean,
/// variance, rmse)` as a row of the convergence study has them (its sums run in that order).
#[pyfunction]
fn summarize(integrand: &str, estimates: Vec<f64>) -> PyResult<(f64, f64, f64)> {
    let f = Integrand::by_name(integrand).map_err(to_py_err)?;
    if estimates.is_empty() {
        return Err(value_error(
            "summarize: no estimates; one per seed (at least one) is needed",
        ));
    }
    let s = study::Summary::of(f, &estimates);
    Ok((s.mean, s.variance, s.rmse))
}

/// The least-squares slope of `log y` against `log x` over the pairs with `x, y > 0` (`None`
/// with fewer than two such pairs).
#[pyfunction]
fn fit_slope(pairs: Vec<(f64, f64)>) -> Option<f64> {
    study::fit_slope(&pairs)
}

/// The published variance exponent of sampler `name` on integrand `integrand`, if any.
#[pyfunction]
fn published_rate(name: &str, integrand: &str) -> PyResult<Option<f64>> {
    let e = strata_lab::registry::find(name).map_err(to_py_err)?;
    let f = Integrand::by_name(integrand).map_err(to_py_err)?;
    Ok(e.rates.on(f))
}

/// Adds the analysis functions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(periodogram, m)?)?;
    m.add_function(wrap_pyfunction!(expected_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(radial, m)?)?;
    m.add_function(wrap_pyfunction!(sampler_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(psa, m)?)?;
    m.add_function(wrap_pyfunction!(nearest_distances, m)?)?;
    m.add_function(wrap_pyfunction!(relative_radius_max, m)?)?;
    m.add_function(wrap_pyfunction!(discrepancy, m)?)?;
    m.add_function(wrap_pyfunction!(net_t_value, m)?)?;
    m.add_function(wrap_pyfunction!(integrands, m)?)?;
    m.add_function(wrap_pyfunction!(convergence, m)?)?;
    m.add_function(wrap_pyfunction!(estimate, m)?)?;
    m.add_function(wrap_pyfunction!(summarize, m)?)?;
    m.add_function(wrap_pyfunction!(fit_slope, m)?)?;
    m.add_function(wrap_pyfunction!(published_rate, m)?)?;
    m.add("DISCREPANCY_METHODS", METHODS.to_vec())?;
    Ok(())
}
