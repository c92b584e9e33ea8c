//! The path-tracer adapter, [`strata::PixelSampler`], vectorized over arrays of pixels and
//! sample indices and parallel with rayon.

use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rayon::prelude::*;
use strata::{PixelSampler, Seed, Sequence};

use crate::{borrow_output, input_slice, output_slice, to_py_err, value_error};

/// Rows per rayon task: enough work to pay for a task and a clone of the sampler.
const ROWS_PER_TASK: usize = 512;

/// The path-tracer adapter over one sequence: values by (pixel, sample index, dimension).
#[pyclass(module = "strata_sampling._strata", name = "PixelSampler", frozen)]
#[derive(Debug)]
pub struct PyPixelSampler {
    inner: PixelSampler,
    /// The arguments it was built from, for pickling (the name as given: `zjoint-4`).
    name: String,
    seed: u64,
    resolution: (u32, u32),
}

#[pymethods]
impl PyPixelSampler {
    /// The adapter over sequence `sequence` (one of `Sequence::NAMES`) with `spp` samples per
    /// pixel, seeded by `seed`; `resolution` is the image of the Z-ordered sequences.
    #[new]
    #[pyo3(signature = (sequence, spp, seed, resolution=(256, 256)))]
    fn new(sequence: &str, spp: u32, seed: u64, resolution: (u32, u32)) -> PyResult<Self> {
        let seq = Sequence::by_name(sequence, [resolution.0, resolution.1]).map_err(to_py_err)?;
        let inner = PixelSampler::new(seq, spp, Seed(seed)).map_err(to_py_err)?;
        Ok(PyPixelSampler {
            inner,
            name: sequence.to_string(),
            seed,
            resolution,
        })
    }

    /// Pickling (and `copy.copy`, `copy.deepcopy`): rebuilt from the arguments it was made
    /// with (the adapter has no position: values are by pixel and sample index).
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let py = slf.py();
        let this = slf.get();
        let args = (
            this.name.as_str(),
            this.inner.samples_per_pixel(),
            this.seed,
            this.resolution,
        )
            .into_pyobject(py)?;
        Ok((slf.get_type().into_any(), args))
    }

    /// Fills `out` (C-contiguous float32, `(m, dims)`) with the values of pixel `pixels[k]`
    /// (uint32, `(m, 2)`) at sample `indices[k]` (uint64, `(m,)`), dimensions `first` to
    /// `first + dims - 1`, in parallel with the GIL released.
    #[pyo3(signature = (pixels, indices, out, first=0))]
    fn fill(
        &self,
        py: Python<'_>,
        pixels: PyReadonlyArray2<'_, u32>,
        indices: PyReadonlyArray1<'_, u64>,
        out: &Bound<'_, PyArray2<f32>>,
        first: u32,
    ) -> PyResult<()> {
        let m = indices.len();
        if pixels.shape() != [m, 2] {
            return Err(value_error(format!(
                "PixelSampler.fill: pixels has shape {:?}; ({m}, 2) is needed for {m} indices",
                pixels.shape()
            )));
        }
        let mut rw = borrow_output(out, "PixelSampler.fill")?;
        let dims = rw.shape()[1];
        if rw.shape()[0] != m || dims == 0 {
            return Err(value_error(format!(
                "PixelSampler.fill: the output has shape {:?}; ({m}, dims >= 1) is needed",
                rw.shape()
            )));
        }
        let values = output_slice(&mut rw, "PixelSampler.fill", dims)?;
        let px = input_slice(&pixels, "PixelSampler.fill: pixels")?;
        let idx = input_slice(&indices, "PixelSampler.fill: indices")?;
        let sampler = &self.inner;
        py.detach(|| {
            values
                .par_chunks_mut(dims * ROWS_PER_TASK)
                .zip(px.par_chunks(2 * ROWS_PER_TASK))
                .zip(idx.par_chunks(ROWS_PER_TASK))
                .for_each(|((rows, p), i)| {
                    let mut s = sampler.clone();
                    for ((row, p), &i) in rows.chunks_exact_mut(dims).zip(p.chunks_exact(2)).zip(i)
                    {
                        s.fill_sample([p[0], p[1]], i, first, row);
                    }
                });
        });
        Ok(())
    }

    /// Samples per pixel.
    #[getter]
    fn spp(&self) -> u32 {
        self.inner.samples_per_pixel()
    }

    /// The name of the sequence.
    #[getter]
    fn sequence(&self) -> &'static str {
        self.inner.sequence().name()
    }

    /// The sample count nearest above `n` at which the sequence is best stratified.
    fn round_count(&self, n: u32) -> u32 {
        self.inner.sequence().round_count(n)
    }

    /// The grids `(columns, rows)` on which the first `n` samples of every draw lie, each cell
    /// holding the same number of points (empty where the sequence promises none at `n`).
    fn promised_strata(&self, n: u64) -> Vec<(u32, u32)> {
        self.inner
            .promised_strata(n)
            .iter()
            .map(|g| (g.columns, g.rows))
            .collect()
    }
}

/// The names of the sequences the adapter knows.
#[pyfunction]
fn sequence_names() -> Vec<&'static str> {
    Sequence::NAMES.to_vec()
}

/// Adds the adapter class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyPixelSampler>()?;
    m.add_function(wrap_pyfunction!(sequence_names, m)?)?;
    Ok(())
}
