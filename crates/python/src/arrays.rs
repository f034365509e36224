//! Rust data to numpy arrays (always fresh float64 / bool copies: changing them changes
//! nothing in the simulation), and serde data to plain Python objects.

use glam::{DQuat, DVec3};
use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use serde::Serialize;

/// An (N, 3) array of vectors.
pub fn vectors<'py>(
    py: Python<'py>,
    v: impl ExactSizeIterator<Item = DVec3>,
) -> Bound<'py, PyArray2<f64>> {
    let n = v.len();
    let mut a = Array2::<f64>::zeros((n, 3));
    for (mut row, x) in a.rows_mut().into_iter().zip(v) {
        row[0] = x.x;
        row[1] = x.y;
        row[2] = x.z;
    }
    a.into_pyarray(py)
}

/// An (N, 4) array of quaternions as (w, x, y, z).
pub fn quaternions<'py>(
    py: Python<'py>,
    q: impl ExactSizeIterator<Item = DQuat>,
) -> Bound<'py, PyArray2<f64>> {
    let n = q.len();
    let mut a = Array2::<f64>::zeros((n, 4));
    for (mut row, x) in a.rows_mut().into_iter().zip(q) {
        row[0] = x.w;
        row[1] = x.x;
        row[2] = x.y;
        row[3] = x.z;
    }
    a.into_pyarray(py)
}

/// A (3,) array.
pub fn vector<'py>(py: Python<'py>, v: DVec3) -> Bound<'py, PyArray1<f64>> {
    Array1::from(v.to_array().to_vec()).into_pyarray(py)
}

/// A (4,) array (w, x, y, z).
pub fn quaternion<'py>(py: Python<'py>, q: DQuat) -> Bound<'py, PyArray1<f64>> {
    Array1::from(vec![q.w, q.x, q.y, q.z]).into_pyarray(py)
}

/// A 1-D array of numbers.
pub fn scalars<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    Array1::from(v).into_pyarray(py)
}

/// A (K, N, 3) array from K·N vectors stored record after record.
pub fn vector_frames<'py>(
    py: Python<'py>,
    frames: usize,
    per_frame: usize,
    v: impl Iterator<Item = DVec3>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    let flat: Vec<f64> = v.flat_map(|x| x.to_array()).collect();
    let a = Array3::from_shape_vec((frames, per_frame, 3), flat)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error shaping an array: {e}")))?;
    Ok(a.into_pyarray(py))
}

/// Any serialisable value as plain Python data (dicts, lists, floats, str, None).
pub fn to_python<'py, T: Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| PyRuntimeError::new_err(format!("internal error serialising: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}
