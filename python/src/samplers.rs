//! The registry (names, descriptions, count rules, parameters) and the samplers it builds, as
//! a Python class that fills numpy arrays.

use std::sync::Mutex;

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};
use strata::SamplerNd;
use strata_lab::registry::{self, Built, CountRule, Entry, Kind, Params, Strictness};

use crate::{borrow_output, output_slice, to_py_err, value_error};

/// A registered sampler built from its name, count, seed, dimensions and parameters, exactly
/// as the `points` program builds it; `fill` writes its next points into a float32 array.
///
/// The stream continues from call to call: a progressive sampler's next points, a fixed-count
/// sampler's next block (each complete block of `count` points is one independent set).
#[pyclass(module = "strata_sampling._strata", name = "Sampler", frozen)]
#[derive(Debug)]
pub struct PySampler {
    /// The sampler and the number of points it has given so far.
    /// The sampler and the points it has given (`u128`: `skip` can take it past `2^64`, as
    /// the crate's `Epochs` count).
    inner: Mutex<(Built, u128)>,
    entry: &'static Entry,
    params: Params,
    name: &'static str,
    dims: u32,
    count: u64,
    progressive: bool,
}

#[pymethods]
impl PySampler {
    /// Builds sampler `name` for `count` points per set, seeded by `seed`, with `dims`
    /// coordinates per point and the optional parameters its entry declares, by keyword
    /// (each `None` for the default).
    #[new]
    #[pyo3(signature = (name, count, seed, dims, **parameters))]
    fn new(
        py: Python<'_>,
        name: &str,
        count: u64,
        seed: u64,
        dims: u32,
        parameters: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let entry = registry::find(name).map_err(to_py_err)?;
        let params = params(count, seed, parameters)?.dims(dims);
        // some constructions do their work up front (Poisson disk, CCVT, Lloyd)
        let inner = py
            .detach(|| entry.make(&params, Strictness::Strict))
            .map_err(to_py_err)?;
        let progressive = inner.progression().is_progressive();
        Ok(PySampler {
            inner: Mutex::new((inner, 0)),
            entry,
            params,
            name: entry.name,
            dims,
            count,
            progressive,
        })
    }

    /// Writes the next `out.shape[0]` points into `out`, a C-contiguous, writable float32
    /// array of shape `(n, dims)`; the GIL is released meanwhile.
    fn fill(&self, py: Python<'_>, out: &Bound<'_, PyArray2<f32>>) -> PyResult<()> {
        let mut rw = borrow_output(out, "Sampler.fill")?;
        let values = output_slice(&mut rw, "Sampler.fill", self.dims as usize)?;
        // lock inside `detach`: a thread waiting for the lock must not hold the GIL
        py.detach(|| {
            let mut guard = self.inner.lock().unwrap_or_else(|e| e.into_inner());
            let (inner, drawn) = &mut *guard;
            if !self.fill_in_parallel(inner, *drawn, values) {
                inner.fill(values);
            }
            *drawn += (values.len() / self.dims as usize) as u128;
        });
        Ok(())
    }

    /// Moves `n` points on in constant time where the sampler can (Sobol'): returns True;
    /// otherwise changes nothing and returns False (the caller then draws and drops them).
    fn skip(&self, n: u64) -> bool {
        let mut guard = self.inner.lock().unwrap_or_else(|e| e.into_inner());
        let (inner, drawn) = &mut *guard;
        let skipped = inner.skip(n);
        if skipped {
            *drawn += n as u128;
        }
        skipped
    }

    /// The points given so far (by `fill` and `skip`).
    #[getter]
    fn drawn(&self) -> u128 {
        self.inner.lock().unwrap_or_else(|e| e.into_inner()).1
    }

    /// Pickling (and `copy.copy`, `copy.deepcopy`): the sampler is rebuilt from its name,
    /// count, seed, dimensions and parameters by `restore_sampler`, then moved on by the
    /// points it has given, so that the copy continues exactly where this one stands.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let parameters = PyDict::new(py);
        for (name, value) in self.params.given() {
            parameters.set_item(name, value)?;
        }
        let restore = py
            .import("strata_sampling._strata")?
            .getattr("restore_sampler")?;
        let args = (
            self.name,
            self.count,
            self.params.seed.0,
            self.dims,
            self.drawn(),
            parameters,
        )
            .into_pyobject(py)?;
        Ok((restore, args))
    }

    /// The registered name.
    #[getter]
    fn name(&self) -> &'static str {
        self.name
    }

    /// Coordinates per point.
    #[getter]
    fn dims(&self) -> u32 {
        self.dims
    }

    /// The count the sampler was built for (the size of each set of a fixed-count sampler).
    #[getter]
    fn count(&self) -> u64 {
        self.count
    }

    /// True for a progressive sequence, false for a fixed-count set.
    #[getter]
    fn progressive(&self) -> bool {
        self.progressive
    }

    fn __repr__(&self) -> String {
        format!(
            "Sampler({:?}, count={}, dims={}, {})",
            self.name,
            self.count,
            self.dims,
            if self.progressive {
                "progressive"
            } else {
                "fixed-count"
            }
        )
    }
}

/// Moves `inner` on by `n` points, in steps of at most `2^64 - 1` (one per `2^64` points, as
/// many as the `skip` calls that took a sampler there): false, with nothing moved, when it
/// cannot skip.
fn skip_far(inner: &mut Built, n: u128) -> bool {
    let first = n.min(u64::MAX as u128) as u64;
    if !inner.skip(first) {
        return false;
    }
    let mut left = n - first as u128;
    while left > 0 {
        let step = left.min(u64::MAX as u128) as u64;
        inner.skip(step);
        left -= step as u128;
    }
    true
}

/// Values drawn and dropped at once when a restored sampler cannot skip (a 4 MB buffer).
const REPLAY_CHUNK: usize = 1 << 20;

/// Sampler `name` (see `Sampler`) moved on by `drawn` points: what unpickling a `Sampler`
/// calls. The move is a constant-time skip where the sampler can (Sobol', Faure, the
/// lattice); otherwise the points are drawn and dropped (with the GIL released), which costs
/// what drawing them did.
#[pyfunction]
#[pyo3(signature = (name, count, seed, dims, drawn, parameters=None))]
fn restore_sampler(
    py: Python<'_>,
    name: &str,
    count: u64,
    seed: u64,
    dims: u32,
    drawn: u128,
    parameters: Option<&Bound<'_, PyDict>>,
) -> PyResult<PySampler> {
    let s = PySampler::new(py, name, count, seed, dims, parameters)?;
    py.detach(|| {
        let mut guard = s.inner.lock().unwrap_or_else(|e| e.into_inner());
        let (inner, given) = &mut *guard;
        if !skip_far(inner, drawn) {
            // only skipping takes a sampler past 2^64 points: one that cannot skip holds fewer
            let d = dims as usize;
            let chunk = (REPLAY_CHUNK / d).max(1) as u128;
            let mut scratch = vec![0.0f32; chunk.min(drawn) as usize * d];
            let mut left = drawn;
            while left > 0 {
                let k = chunk.min(left) as usize;
                inner.fill(&mut scratch[..k * d]);
                left -= k as u128;
            }
        }
        *given = drawn;
    });
    Ok(s)
}

/// The parameters of a sampler, as the command line's flags set them: `count`, `seed` and
/// the keyword arguments (`None` values skipped), each a number; which sampler takes which,
/// and their ranges, the crate checks against each sampler's declarations.
pub(crate) fn params(
    count: u64,
    seed: u64,
    parameters: Option<&Bound<'_, PyDict>>,
) -> PyResult<Params> {
    let mut p = Params::new(count).seed(strata::Seed(seed));
    for (key, value) in parameters.into_iter().flat_map(|d| d.iter()) {
        let name: String = key.extract()?;
        if value.is_none() {
            continue;
        }
        let v: f64 = value.extract().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err(format!(
                "{name} must be a number, not {}",
                value
                    .get_type()
                    .name()
                    .map_or("?".into(), |n| n.to_string())
            ))
        })?;
        p.set(&name, v);
    }
    Ok(p)
}

/// Values per thread below which a fill stays on one thread.
const PARALLEL_GRAIN: usize = 1 << 18;

impl PySampler {
    /// Fills `values` (the points after the first `drawn`) on rayon's threads when the
    /// sampler can skip ahead in constant time (`SamplerNd::skip`): each thread builds its own
    /// sampler from the same parameters and skips to its share; `inner` then skips past all
    /// of them. Bit-identical to one serial fill. False (nothing done) when it cannot.
    fn fill_in_parallel(&self, inner: &mut Built, drawn: u128, values: &mut [f32]) -> bool {
        let Built::Nd(main) = inner else {
            return false;
        };
        let d = self.dims as usize;
        let threads = rayon::current_num_threads().min(values.len() / PARALLEL_GRAIN);
        if threads < 2 {
            return false;
        }
        let points = values.len() / d;
        let per = points.div_ceil(threads);
        let mut forks = Vec::with_capacity(threads);
        for t in 0..threads {
            let Ok(mut s) = self.entry.make(&self.params, Strictness::Strict) else {
                return false;
            };
            if !skip_far(&mut s, drawn + (t * per) as u128) {
                return false;
            }
            forks.push(s);
        }
        if !main.skip(points as u64) {
            return false;
        }
        use rayon::prelude::*;
        values
            .par_chunks_mut(per * d)
            .zip(forks.par_iter_mut())
            .for_each(|(chunk, s)| s.fill(chunk));
        true
    }
}

/// The facts of one registry entry as a dict.
fn entry_dict<'py>(py: Python<'py>, e: &Entry) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", e.name)?;
    d.set_item("description", e.description)?;
    d.set_item("paper", e.paper)?;
    d.set_item("progressive", e.progressive)?;
    d.set_item("seeded", e.seeded)?;
    d.set_item("counts", e.counts.to_string())?;
    d.set_item("dimensions", if e.has_dimensions() { "D" } else { "2" })?;
    let params = PyList::empty(py);
    for p in e.parameters {
        let pd = PyDict::new(py);
        pd.set_item("name", p.name)?;
        pd.set_item("kind", p.kind.name())?;
        pd.set_item("default", p.default)?;
        pd.set_item("allowed", p.allowed())?;
        pd.set_item("help", p.help)?;
        params.append(pd)?;
    }
    d.set_item("parameters", params)?;
    d.set_item("promise", e.promise)?;
    let rates = PyDict::new(py);
    rates.set_item("discontinuous", e.rates.discontinuous)?;
    rates.set_item("smooth", e.rates.smooth)?;
    rates.set_item("higher", e.rates.higher)?;
    d.set_item("rates", rates)?;
    d.set_item("expensive", e.expensive)?;
    Ok(d)
}

/// Every sampler parameter some registered sampler declares, in the registry's order, as
/// `(name, kind)` pairs, kind `"whole"` or `"real"` (what the Python keyword checks accept).
#[pyfunction]
fn parameter_kinds() -> Vec<(&'static str, &'static str)> {
    registry::parameter_names()
        .into_iter()
        .map(|n| {
            let kind = match registry::parameter_kind(n) {
                Some(Kind::Whole) => "whole",
                _ => "real",
            };
            (n, kind)
        })
        .collect()
}

/// Every registered sampler, in the registry's order, as a list of dicts: name, description,
/// paper, progressive, counts (the count rule in words), dimensions ("2" or "D"), parameters
/// (name, default, allowed), promise, rates (published variance exponents) and expensive.
#[pyfunction]
fn registry_entries(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let list = PyList::empty(py);
    for e in registry::entries() {
        list.append(entry_dict(py, e)?)?;
    }
    Ok(list)
}

/// Whether sampler `name` accepts `n` points (always true for progressive samplers, n >= 1).
#[pyfunction]
fn allows_count(name: &str, n: u64) -> PyResult<bool> {
    let e = registry::find(name).map_err(to_py_err)?;
    Ok(n >= 1 && (e.progressive || e.counts.allows(n)))
}

/// The count nearest to `n` that sampler `name` accepts (the smaller one on a tie).
#[pyfunction]
fn nearest_count(name: &str, n: u64) -> PyResult<u64> {
    let e = registry::find(name).map_err(to_py_err)?;
    Ok(e.counts.nearest(n))
}

/// The largest range `allowed_counts` lists for samplers that take any count.
const MAX_LISTED_RANGE: u64 = 1 << 24;

/// The counts in `[lo, hi]` that sampler `name` accepts, in increasing order.
#[pyfunction]
fn allowed_counts(name: &str, lo: u64, hi: u64) -> PyResult<Vec<u64>> {
    let e = registry::find(name).map_err(to_py_err)?;
    // the counts listed: 1 to 2^31 (a fixed-count set's largest count)
    let (from, to) = (lo.max(1), hi.min(strata::counts::MAX_FIXED_COUNT));
    if matches!(e.counts, CountRule::Any) && to.saturating_sub(from) >= MAX_LISTED_RANGE {
        return Err(value_error(format!(
            "{} takes any count; listing {from} to {to} would make {} numbers (at most \
             {MAX_LISTED_RANGE}): ask for a narrower range",
            e.name,
            to - from + 1
        )));
    }
    Ok(e.counts.counts_between(lo, hi).collect())
}

/// The error the crate gives for a fixed-count sampler asked for `n` points (`None` when `n`
/// is allowed), so that Python can say which counts the sampler takes without building it.
#[pyfunction]
fn count_error(name: &str, n: u64) -> PyResult<Option<String>> {
    let e = registry::find(name).map_err(to_py_err)?;
    if e.progressive {
        return Ok((n == 0).then(|| format!("{} cannot make 0 samples: at least 1", e.name)));
    }
    Ok(e.counts.check(e.name, n).err().map(|err| err.to_string()))
}

/// Adds the sampler class and the registry functions to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySampler>()?;
    m.add_function(wrap_pyfunction!(restore_sampler, m)?)?;
    m.add_function(wrap_pyfunction!(registry_entries, m)?)?;
    m.add_function(wrap_pyfunction!(parameter_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(allows_count, m)?)?;
    m.add_function(wrap_pyfunction!(nearest_count, m)?)?;
    m.add_function(wrap_pyfunction!(allowed_counts, m)?)?;
    m.add_function(wrap_pyfunction!(count_error, m)?)?;
    Ok(())
}
