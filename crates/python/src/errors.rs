//! Python exceptions of the `pliant` package and the conversions from Pliant's Rust
//! errors. Messages are exactly the ones the `pliant` command prints (without its
//! `error: ` prefix); the parts are also attributes of the exception.

use pliant_core::{Divergence, ModelError};
use pliant_scene::SceneError as RustSceneError;
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    pliant,
    SceneError,
    PyValueError,
    "A scene could not be loaded or built.\n\n\
     The message names the file (or origin), the line and column where the parser knows \
     them, the field, the offending value and the reason, exactly as `pliant run` prints \
     it. Attributes: ``field`` (field path such as ``hoses[0].section.d_inner``, or None) \
     and ``location`` ((line, column) or None)."
);

create_exception!(
    pliant,
    SimulationDiverged,
    PyRuntimeError,
    "The simulation diverged (non-finite numbers or runaway speeds).\n\n\
     Attributes: ``step``, ``time`` [s], ``hose`` (name), ``node`` (index on that hose), \
     ``what`` went wrong and the likely ``cause``. Raised by :func:`run_timeline` with \
     ``result`` (the :class:`RunResult` up to the last healthy state) as well."
);

create_exception!(
    pliant,
    SolverNotConverged,
    PyRuntimeError,
    "A Newton solve ended out of balance, or on an unstable equilibrium it could not \
     leave (raised instead of :class:`SolverWarning` by a ``Simulation(..., strict=True)``). \
     The message says when and by how much; the state is kept."
);

create_exception!(
    pliant,
    SolverWarning,
    pyo3::exceptions::PyRuntimeWarning,
    "A Newton solve ended out of balance, or on an unstable equilibrium it could not \
     leave: the forces of those steps are not trustworthy (the verdict says \
     \"UNCERTAIN\"). ``warnings.simplefilter(\"error\", pliant.SolverWarning)`` or \
     ``Simulation(..., strict=True)`` makes it an error."
);

/// A scene loading error as `pliant.SceneError`.
pub fn scene_error(py: Python<'_>, e: &RustSceneError) -> PyErr {
    let err = SceneError::new_err(e.to_string());
    let value = err.value(py);
    let _ = value.setattr("field", e.field());
    let _ = value.setattr("location", e.location());
    err
}

/// A `pliant.SceneError` with a message only (model building, stubs and clips).
pub fn scene_error_message(py: Python<'_>, message: String) -> PyErr {
    let err = SceneError::new_err(message);
    let value = err.value(py);
    let _ = value.setattr("field", py.None());
    let _ = value.setattr("location", py.None());
    err
}

/// A model that could not be built from a loaded scene, worded as `pliant run` words it.
pub fn model_error(py: Python<'_>, source: &str, e: &ModelError) -> PyErr {
    scene_error_message(py, format!("building the model of {source}: {e}"))
}

/// A divergence as `pliant.SimulationDiverged`.
pub fn diverged(py: Python<'_>, d: &Divergence) -> PyErr {
    let err = SimulationDiverged::new_err(d.to_string());
    let value = err.value(py);
    let _ = value.setattr("step", d.step);
    let _ = value.setattr("time", d.time);
    let _ = value.setattr("hose", d.hose.as_str());
    let _ = value.setattr("node", d.node);
    let _ = value.setattr("what", d.what.as_str());
    let _ = value.setattr("cause", d.cause.as_str());
    let _ = value.setattr("result", py.None());
    err
}
