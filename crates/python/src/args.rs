//! Checking and converting Python arguments: hose references by name or index, node
//! indices (negative counts from the end, as in Python), points and quaternions from
//! anything array-like. Bad values raise ValueError / IndexError / TypeError with a
//! message that names the argument; nothing here panics.

use glam::{DQuat, DVec3};
use numpy::{AllowTypeChange, PyArrayLike1, PyArrayLikeDyn, PyUntypedArrayMethods};
use pliant_core::Model;
use pyo3::exceptions::{PyIndexError, PyValueError};
use pyo3::prelude::*;

/// A hose, by name or by index.
#[derive(FromPyObject, Clone, Debug)]
pub enum HoseRef {
    #[pyo3(transparent, annotation = "int")]
    Index(i64),
    #[pyo3(transparent, annotation = "str")]
    Name(String),
}

/// The model's index of a hose given by name or (possibly negative) index.
pub fn hose_index(model: &Model, hose: &HoseRef) -> PyResult<usize> {
    let n = model.hoses.len();
    match hose {
        HoseRef::Index(i) => {
            let k = if *i < 0 { *i + n as i64 } else { *i };
            if k < 0 || k >= n as i64 {
                return Err(PyIndexError::new_err(format!(
                    "hose index {i} out of range: the scene has {n} hose(s)"
                )));
            }
            Ok(k as usize)
        }
        HoseRef::Name(name) => model
            .hoses
            .iter()
            .position(|h| h.name == *name)
            .ok_or_else(|| {
                let names: Vec<String> = model
                    .hoses
                    .iter()
                    .map(|h| format!("'{}'", h.name))
                    .collect();
                PyValueError::new_err(format!(
                    "no hose named '{name}'; the scene's hoses are {}",
                    names.join(", ")
                ))
            }),
    }
}

/// The global node index of node `node` (negative: from the end) of hose `hose`.
pub fn node_index(model: &Model, hose: usize, node: i64) -> PyResult<usize> {
    let info = &model.hoses[hose];
    let n = info.node_count as i64;
    let k = if node < 0 { node + n } else { node };
    if k < 0 || k >= n {
        return Err(PyIndexError::new_err(format!(
            "node {node} out of range: hose '{}' has {n} nodes (0 … {}, or -{n} … -1)",
            info.name,
            n - 1
        )));
    }
    Ok(info.node(k as usize))
}

/// Hose index and global node index of a (hose, node) pair.
pub fn hose_node(model: &Model, hose: &HoseRef, node: i64) -> PyResult<(usize, usize)> {
    let h = hose_index(model, hose)?;
    Ok((h, node_index(model, h, node)?))
}

/// A finite 3-vector from a sequence or array of three numbers.
pub fn vec3(value: &Bound<'_, PyAny>, what: &str) -> PyResult<DVec3> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = value
        .extract()
        .map_err(|_| PyValueError::new_err(format!("{what} must be three numbers [x, y, z]")))?;
    let v = a.as_array();
    if v.len() != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must be three numbers [x, y, z], got {}",
            v.len()
        )));
    }
    let p = DVec3::new(v[0], v[1], v[2]);
    if !p.is_finite() {
        return Err(PyValueError::new_err(format!(
            "{what} must be finite, got {:?}",
            p.to_array()
        )));
    }
    Ok(p)
}

/// One point (shape (3,)) or several (shape (K, 3)), all finite.
pub fn points(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<DVec3>> {
    let bad = || {
        PyValueError::new_err(format!(
            "{what} must be a point [x, y, z] or a list of points [[x, y, z], …]"
        ))
    };
    let a: PyArrayLikeDyn<'_, f64, AllowTypeChange> = value.extract().map_err(|_| bad())?;
    let shape = a.shape().to_vec();
    let view = a.as_array();
    let flat: Vec<f64> = view.iter().copied().collect();
    let pts: Vec<DVec3> = match shape.as_slice() {
        [3] => vec![DVec3::new(flat[0], flat[1], flat[2])],
        [k, 3] if *k > 0 => flat
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect(),
        _ => return Err(bad()),
    };
    if let Some(p) = pts.iter().find(|p| !p.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{what} must be finite, got {:?}",
            p.to_array()
        )));
    }
    Ok(pts)
}

/// A unit quaternion from (w, x, y, z) (normalised; must not be zero).
pub fn quaternion(value: &Bound<'_, PyAny>, what: &str) -> PyResult<DQuat> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = value
        .extract()
        .map_err(|_| PyValueError::new_err(format!("{what} must be a quaternion (w, x, y, z)")))?;
    let v = a.as_array();
    if v.len() != 4 {
        return Err(PyValueError::new_err(format!(
            "{what} must be a quaternion (w, x, y, z), got {} numbers",
            v.len()
        )));
    }
    let q = DQuat::from_xyzw(v[1], v[2], v[3], v[0]);
    let norm = q.length();
    if !q.is_finite() || norm < 1e-12 {
        return Err(PyValueError::new_err(format!(
            "{what} must be a finite, non-zero quaternion (w, x, y, z)"
        )));
    }
    Ok(q / norm)
}

/// A duration or time \[s\] that must be finite and positive (or ≥ 0 with `allow_zero`).
pub fn seconds(value: f64, what: &str, allow_zero: bool) -> PyResult<f64> {
    let ok = value.is_finite() && (value > 0.0 || (allow_zero && value == 0.0));
    if !ok {
        let want = if allow_zero { "≥ 0" } else { "> 0" };
        return Err(PyValueError::new_err(format!(
            "{what} must be finite and {want} seconds, got {value}"
        )));
    }
    Ok(value)
}
