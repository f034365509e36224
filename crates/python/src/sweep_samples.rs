//! Centre-line samples of recorded hose frames for tolerance envelopes (SPEC T2; the
//! method is `pliant_assembly::sweep::centreline_samples`, shared with `pliant run`'s
//! swept envelopes, and described in `pliant/studies/envelope.py`). A study unites the
//! keys of its runs and dilates the union to voxels once at its end, so this is the part of the
//! envelope each run pays for; numpy spent ≈ 20 ms on it per run of the engine-bay demo,
//! mostly in allocating its (T·E·(n+1), 3) temporaries.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray3};
use pliant_assembly::sweep::centreline_samples::sample_keys;
use pliant_assembly::sweep::voxels::VoxelGrid;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// `centreline_sample_keys(frames, h)`: sorted unique int64 keys of the centre-line
/// samples of frames (T, N, 3) \[m\] for voxels of size h \[m\] (see
/// `pliant.studies.envelope.sample_keys`). Raises ValueError for frames no hose has.
#[pyfunction]
pub fn centreline_sample_keys<'py>(
    py: Python<'py>,
    frames: PyReadonlyArray3<'py, f64>,
    h: f64,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let view = frames.as_array();
    let (count, nodes, dim) = view.dim();
    if dim != 3 {
        return Err(PyValueError::new_err(format!(
            "frames must be (T, N, 3), got (T, N, {dim})"
        )));
    }
    let standard = view.as_standard_layout();
    let flat = standard
        .as_slice()
        .ok_or_else(|| PyValueError::new_err("frames not in memory order"))?;
    let keys = sample_keys(flat, count, nodes, h).map_err(PyValueError::new_err)?;
    Ok(keys.into_pyarray(py))
}

/// `swept_voxel_keys(samples, radius, h)`: sorted int64 keys of the voxels of size h \[m\]
/// whose centre lies within r + (√3/2)(h + h/4) + h/4 of a sample (keys of
/// `centreline_sample_keys`): the tube of outer radius `radius` \[m\] around the sampled
/// centre lines (`pliant_assembly::sweep::voxels`, as `pliant run`'s swept envelopes).
/// Raises ValueError for a region too large for voxels of this size.
#[pyfunction]
pub fn swept_voxel_keys<'py>(
    py: Python<'py>,
    samples: PyReadonlyArray1<'py, i64>,
    radius: f64,
    h: f64,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let samples = samples.as_array();
    let standard = samples.as_standard_layout();
    let keys = standard
        .as_slice()
        .ok_or_else(|| PyValueError::new_err("samples not in memory order"))?;
    let grid = VoxelGrid::of_samples(keys, radius, h).map_err(PyValueError::new_err)?;
    Ok(grid.keys().into_pyarray(py))
}
