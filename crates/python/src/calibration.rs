//! `pliant.calibrate`: material calibration (SPEC M5, D3; docs/calibration.md) — the
//! same fits as `pliant calibrate`, from a calibration file, one CSV curve, or columns
//! given as arrays.

use crate::arrays::{scalars, to_python};
use numpy::PyArray1;
use pliant_calibrate::{CalibError, Spec, TestFit, TestKind, TestSpec};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::collections::BTreeMap;
use std::path::PathBuf;

create_exception!(
    pliant,
    CalibrationError,
    PyValueError,
    "A calibration could not be done: a file could not be read, a CSV row is malformed, \
     a curve has too few points, is not monotonic or has no linear range.\n\n\
     The message names the file, line and column, as `pliant calibrate` prints it. \
     Attributes: ``file``, ``line`` and ``column`` (1-based, or None)."
);

/// The Python exception for a calibration error, with its parts as attributes.
pub fn calib_err(py: Python<'_>, e: CalibError) -> PyErr {
    let err = CalibrationError::new_err(e.to_string());
    let value = err.value(py);
    let _ = value.setattr("file", e.file.clone());
    let _ = value.setattr("line", e.line);
    let _ = value.setattr("column", e.column);
    err
}

/// One fitted test curve.
///
/// ``kind`` (``"tension"``, …), ``csv``, the stiffness ``symbol`` (E_t, E_c, EI, GJ) and
/// ``value`` in SI (Pa or N·m²) with its ``std_error`` and 95 % interval ``ci95``; the
/// same in the display ``unit`` (MPa, N·m²) as ``value_display`` and ``ci95_display``;
/// the line's ``slope`` and ``intercept`` (curve units, SI), ``residual_rms``,
/// ``residual_std``, ``r_squared``; ``range`` (dict: rows, CSV lines, x and y at its ends
/// in the plot's units, the scatter ``noise_std``); ``formula``; and the fitted curve
/// ``x``, ``y`` (SI: strain and stress, deflection and force, angle and torque, or
/// curvature and force).
#[pyclass(module = "pliant", name = "CalibrationFit", frozen)]
pub struct CalibrationFit {
    fit: TestFit,
}

#[pymethods]
impl CalibrationFit {
    #[getter]
    fn kind(&self) -> &'static str {
        self.fit.kind.name()
    }
    #[getter]
    fn csv(&self) -> &str {
        &self.fit.csv
    }
    #[getter]
    fn symbol(&self) -> &str {
        &self.fit.symbol
    }
    #[getter]
    fn unit(&self) -> &str {
        &self.fit.unit
    }
    #[getter]
    fn value(&self) -> f64 {
        self.fit.value
    }
    #[getter]
    fn std_error(&self) -> f64 {
        self.fit.std_error
    }
    #[getter]
    fn ci95(&self) -> (f64, f64) {
        (self.fit.ci95[0], self.fit.ci95[1])
    }
    #[getter]
    fn value_display(&self) -> f64 {
        self.fit.value_display
    }
    #[getter]
    fn ci95_display(&self) -> (f64, f64) {
        (self.fit.ci95_display[0], self.fit.ci95_display[1])
    }
    #[getter]
    fn slope(&self) -> f64 {
        self.fit.line.slope
    }
    #[getter]
    fn intercept(&self) -> f64 {
        self.fit.line.intercept
    }
    #[getter]
    fn residual_rms(&self) -> f64 {
        self.fit.line.residual_rms
    }
    #[getter]
    fn residual_std(&self) -> f64 {
        self.fit.line.residual_std
    }
    #[getter]
    fn r_squared(&self) -> f64 {
        self.fit.line.r_squared
    }
    #[getter]
    fn range<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.fit.range)
    }
    #[getter]
    fn formula(&self) -> &str {
        &self.fit.formula
    }
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        scalars(py, self.fit.curve.x.clone())
    }
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        scalars(py, self.fit.curve.y.clone())
    }
    fn __repr__(&self) -> String {
        let f = &self.fit;
        format!(
            "CalibrationFit({} {}: {} = {:.6} {}, 95% CI [{:.6}, {:.6}], rows {}-{})",
            f.kind.name(),
            f.csv,
            f.symbol,
            f.value_display,
            f.unit,
            f.ci95_display[0],
            f.ci95_display[1],
            f.range.first_row,
            f.range.last_row
        )
    }
}

/// A finished calibration: the ``fits`` (one :class:`CalibrationFit` per test), the
/// ``material`` (dict: every value with its source or assumption and its 95 % interval),
/// ``warnings``, the ``material_toml`` for a scene (``[materials.NAME]``), the
/// ``library_toml`` entry, the ``html`` page; ``to_dict()`` is calibration.json and
/// ``write(out)`` writes all four files.
#[pyclass(module = "pliant", name = "Calibration", frozen)]
pub struct Calibration {
    inner: pliant_calibrate::Calibration,
}

#[pymethods]
impl Calibration {
    #[getter]
    fn fits(&self) -> Vec<CalibrationFit> {
        self.inner
            .fits
            .iter()
            .map(|f| CalibrationFit { fit: f.clone() })
            .collect()
    }
    /// The inelastic laws fitted (one dict per plastic_bending, relaxation,
    /// cyclic_bending or cyclic_torsion test): ``kind``, ``csv``, ``fit`` (``estimates``:
    /// each parameter's ``name``, SI ``value``, ``ci95``, ``identified``; ``ssr``,
    /// ``residual_std``, ``points``), ``formula`` and ``checks``.
    #[getter]
    fn laws<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.laws)
    }
    #[getter]
    fn material<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.material)
    }
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner.material.warnings.clone()
    }
    #[getter]
    fn material_toml(&self) -> String {
        self.inner.material_toml()
    }
    #[getter]
    fn library_toml(&self) -> String {
        self.inner.library_toml()
    }
    #[getter]
    fn html(&self) -> String {
        self.inner.html()
    }
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.inner.json())
    }
    /// Writes material.toml, library_entry.toml, calibration.json and calibration.html
    /// into ``out`` (created) and returns their paths.
    fn write(&self, py: Python<'_>, out: PathBuf) -> PyResult<Vec<String>> {
        self.inner
            .write(&out)
            .map(|p| p.iter().map(|p| p.display().to_string()).collect())
            .map_err(|e| calib_err(py, e))
    }
    fn __repr__(&self) -> String {
        format!(
            "Calibration({:?}: {} fits, {} laws)",
            self.inner.material.name,
            self.inner.fits.len(),
            self.inner.laws.len()
        )
    }
}

/// Columns given as arrays → CSV text (header: the keys).
fn columns_csv(data: &BTreeMap<String, Vec<f64>>) -> Result<String, String> {
    let n = data.values().next().map_or(0, Vec::len);
    if data.values().any(|v| v.len() != n) {
        return Err("data: all columns must have the same length".into());
    }
    let mut s = data.keys().cloned().collect::<Vec<_>>().join(",");
    s.push('\n');
    for i in 0..n {
        let row: Vec<String> = data.values().map(|v| format!("{:e}", v[i])).collect();
        s.push_str(&row.join(","));
        s.push('\n');
    }
    Ok(s)
}

/// Fits a material's stiffness to measured test curves (docs/calibration.md).
///
/// Either ``spec``, a calibration file (TOML, format "pliant-calibration"), or one test:
/// ``kind`` (tension, compression, three_point_bending, cantilever, torsion, iso10619;
/// or an inelastic law: plastic_cantilever, plastic_three_point_bending, plastic_torsion,
/// relaxation, cyclic_bending, cyclic_torsion) with its curve as ``csv`` (a file) or
/// ``data`` (a dict of columns named with units,
/// e.g. ``{"force_N": f, "displacement_mm": d}``), ``length_mm`` (gauge length, span,
/// free length, grip distance or lever arm), the specimen's ``d_outer_mm`` and
/// ``d_inner_mm``, and the material's ``name``, ``density_kg_m3`` and ``poisson``.
/// A relaxation test alone needs ``held_strain`` (the strain held: it gives E₀);
/// ``terms`` forces its number of Prony terms (else chosen by BIC). Both are refused
/// for the other kinds, as in a calibration file.
/// ``out``: also write the four files there. Raises :class:`CalibrationError`.
#[pyfunction]
#[pyo3(signature = (spec=None, *, kind=None, csv=None, data=None, length_mm=None, d_outer_mm=None, d_inner_mm=0.0, name="calibrated", density_kg_m3=1100.0, poisson=None, terms=None, held_strain=None, out=None))]
#[allow(clippy::too_many_arguments)]
pub fn calibrate(
    py: Python<'_>,
    spec: Option<PathBuf>,
    kind: Option<&str>,
    csv: Option<PathBuf>,
    data: Option<BTreeMap<String, Vec<f64>>>,
    length_mm: Option<f64>,
    d_outer_mm: Option<f64>,
    d_inner_mm: f64,
    name: &str,
    density_kg_m3: f64,
    poisson: Option<f64>,
    terms: Option<usize>,
    held_strain: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Calibration> {
    let inner = match spec {
        Some(path) => {
            if kind.is_some() || csv.is_some() || data.is_some() {
                return Err(PyValueError::new_err(
                    "give either a calibration file or kind with csv or data, not both",
                ));
            }
            if terms.is_some() || held_strain.is_some() {
                return Err(PyValueError::new_err(
                    "terms and held_strain are for one test given by kind; in a calibration file they belong to its [[tests]] entry",
                ));
            }
            py.allow_threads(|| pliant_calibrate::calibrate_file(&path))
                .map_err(|e| calib_err(py, e))?
        }
        None => {
            let kind_name = kind.ok_or_else(|| {
                PyValueError::new_err(
                    "give a calibration file (spec) or a test's kind with csv or data",
                )
            })?;
            let kind = TestKind::parse(kind_name).ok_or_else(|| {
                let names: Vec<&str> = TestKind::ALL.iter().map(|k| k.name()).collect();
                PyValueError::new_err(format!(
                    "kind={kind_name:?}: expected one of {}",
                    names.join(", ")
                ))
            })?;
            let d_outer = d_outer_mm.ok_or_else(|| {
                PyValueError::new_err("d_outer_mm is needed: the specimen's outer diameter")
            })?;
            let (shown, text) = match (csv, data) {
                (Some(p), None) => {
                    let shown = p.display().to_string();
                    let text = std::fs::read_to_string(&p).map_err(|e| {
                        calib_err(py, CalibError::file(&shown, format!("cannot read: {e}")))
                    })?;
                    (shown, text)
                }
                (None, Some(d)) => (
                    "data".to_string(),
                    columns_csv(&d).map_err(PyValueError::new_err)?,
                ),
                _ => return Err(PyValueError::new_err("give exactly one of csv and data")),
            };
            let spec = Spec {
                format: None,
                name: name.to_string(),
                description: None,
                d_inner_mm,
                d_outer_mm: d_outer,
                density_kg_m3,
                density_source: None,
                poisson,
                min_bend_radius_mm: None,
                tests: vec![TestSpec {
                    kind,
                    csv: shown.clone(),
                    length_mm,
                    d_inner_mm: None,
                    d_outer_mm: None,
                    terms,
                    held_strain,
                }],
            };
            let origin = format!("pliant.calibrate(kind={:?})", kind.name());
            pliant_calibrate::calibrate_texts(spec, &[(shown, text)], &origin)
                .map_err(|e| calib_err(py, e))?
        }
    };
    if let Some(out) = out {
        inner.write(&out).map_err(|e| calib_err(py, e))?;
    }
    Ok(Calibration { inner })
}
