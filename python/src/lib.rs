//! `strata_sampling._strata`: the compiled half of the Python package `strata`.
//!
//! Every function here is a thin layer over the `strata` crate: it checks the shapes and types
//! of the numpy arrays it is given, views them as slices without copying, releases the GIL
//! around the crate's work and turns the crate's [`strata_lab::Error`] into a Python `ValueError`
//! carrying the same message. The pure-Python package (`python/strata_sampling/`) adds the friendly
//! signatures, argument checks and the `scipy.stats.qmc.QMCEngine` subclass.

#![warn(missing_docs, missing_debug_implementations)]

use numpy::{PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

mod analysis;
mod pixel;
mod samplers;

/// The crates' errors as a Python exception: `OSError` for I/O, `ValueError` for everything
/// else (what was wrong and what is allowed, the crate's message as is).
pub(crate) fn to_py_err(e: impl Into<strata_lab::Error>) -> PyErr {
    let e = e.into();
    match e {
        strata_lab::Error::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// A `ValueError` with `msg`.
pub(crate) fn value_error(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// A writable, C-contiguous `(rows, cols)` float32 output array as a slice, or a `ValueError`
/// naming `what` and the shape that was expected.
pub(crate) fn output_slice<'a>(
    out: &'a mut numpy::PyReadwriteArray2<'_, f32>,
    what: &str,
    cols: usize,
) -> PyResult<&'a mut [f32]> {
    let shape = out.shape().to_vec();
    if !out.is_c_contiguous() {
        return Err(value_error(format!(
            "{what}: the output array must be C-contiguous"
        )));
    }
    if shape[1] != cols {
        return Err(value_error(format!(
            "{what}: the output array has {} columns; {cols} are needed",
            shape[1]
        )));
    }
    out.as_slice_mut()
        .map_err(|_| value_error(format!("{what}: the output array must be C-contiguous")))
}

/// A C-contiguous input array as a slice (rust-numpy's `as_slice` also takes Fortran order,
/// which would read the values transposed), or a `ValueError` naming `what`.
pub(crate) fn input_slice<'a, T: numpy::Element, D: numpy::ndarray::Dimension>(
    a: &'a numpy::PyReadonlyArray<'_, T, D>,
    what: &str,
) -> PyResult<&'a [T]> {
    if !a.is_c_contiguous() {
        return Err(value_error(format!("{what} must be C-contiguous")));
    }
    a.as_slice()
        .map_err(|_| value_error(format!("{what} must be C-contiguous")))
}

/// Borrows `out` for writing (a `ValueError` if numpy or another borrow holds it).
pub(crate) fn borrow_output<'py>(
    out: &Bound<'py, PyArray2<f32>>,
    what: &str,
) -> PyResult<numpy::PyReadwriteArray2<'py, f32>> {
    out.try_readwrite().map_err(|e| {
        value_error(format!(
            "{what}: the output array cannot be written ({e}); pass a writable array"
        ))
    })
}

/// The compiled module: samplers, the path-tracer adapter and the analysis tools.
#[pymodule]
fn _strata(m: &Bound<'_, PyModule>) -> PyResult<()> {
    samplers::register(m)?;
    pixel::register(m)?;
    analysis::register(m)?;
    m.add("MAX_RESOLUTION", strata_lab::spectrum::MAX_RESOLUTION)?;
    m.add("MAX_DIMENSIONS", strata::samplers::MAX_DIMENSIONS)?;
    m.add("MAX_FIXED_COUNT", strata::counts::MAX_FIXED_COUNT)?;
    m.add(
        "MAX_STUDY_COUNT",
        strata_lab::analysis::study::MAX_STUDY_COUNT,
    )?;
    m.add("MAX_SEEDS", strata_lab::analysis::study::MAX_SEEDS)?;
    Ok(())
}
