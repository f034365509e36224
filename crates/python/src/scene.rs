//! `pliant.Scene`: a loaded, checked scene (SI units) and the model built from it.

use crate::arrays::to_python;
use crate::errors::{model_error, scene_error, scene_error_message};
use pliant_assembly::WorkcellError;
use pliant_core::Model;
use pliant_runs::load::{load_scene_file, load_scene_json_str_in, load_scene_str_in};
use pliant_scene::{demo_scene as rust_demo_scene, LoadedScene, SceneError as RustSceneError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Arc;

/// A scene: hoses, materials, rigid parts, stubs, clips, settings, ergonomic profile and
/// timeline, loaded and checked (all values in SI units: metres, newtons, seconds), with
/// its physics model built.
///
/// Create one with :func:`load_scene`, :func:`demo_scene`, :meth:`Scene.from_toml`,
/// :meth:`Scene.from_json` or :meth:`Scene.from_dict` (the scene file's schema, see
/// docs/scene-format.md). A scene is immutable; any number of :class:`Simulation` objects
/// and timeline runs can use it.
///
/// >>> import pliant
/// >>> scene = pliant.demo_scene()
/// >>> scene.hose_names
/// ['upper', 'lower']
/// >>> scene.node_count("lower")
/// 16
#[pyclass(module = "pliant", name = "Scene", frozen)]
pub struct Scene {
    pub scene: Arc<LoadedScene>,
    pub model: Arc<Model>,
}

impl Scene {
    /// Builds the model of a loaded scene; errors as `pliant run` words them.
    pub fn build(py: Python<'_>, loaded: Result<LoadedScene, RustSceneError>) -> PyResult<Scene> {
        let scene = loaded.map_err(|e| scene_error(py, &e))?;
        // the workcell's setup, as `pliant run` makes it: the model, and the stubs and
        // clips bound to its nodes — checked now rather than on use
        let setup = scene.workcell_setup().map_err(|e| match e {
            WorkcellError::Model { error, .. } => model_error(py, &scene.source, &error),
            e => scene_error_message(py, e.to_string()),
        })?;
        Ok(Scene {
            scene: Arc::new(scene),
            model: setup.model,
        })
    }

    fn hose(&self, hose: &crate::args::HoseRef) -> PyResult<usize> {
        crate::args::hose_index(&self.model, hose)
    }
}

#[pymethods]
impl Scene {
    /// Loads a scene file (TOML, or JSON for ``*.json``); relative mesh paths are
    /// resolved against the file's folder. Same as :func:`load_scene`.
    ///
    /// Raises :class:`SceneError` naming the file, field, value and reason.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
        Scene::build(py, load_scene_file(&path))
    }

    /// A scene from TOML text. ``origin`` names it in error messages; relative mesh
    /// paths are resolved against ``base_dir`` (default: the current folder).
    ///
    /// >>> import pliant
    /// >>> text = '''
    /// ... format = "pliant-scene"
    /// ... version = 1
    /// ... length_unit = "m"
    /// ... [[hoses]]
    /// ... name = "h"
    /// ... material = "hose1"
    /// ... elements = 10
    /// ... start = [0, 0, 0]
    /// ... path = [{ line = { to = [1, 0, 0] } }]
    /// ... '''
    /// >>> pliant.Scene.from_toml(text).node_count("h")
    /// 11
    /// >>> pliant.Scene.from_toml(text.replace("hose1", "hose9"))  # doctest: +ELLIPSIS
    /// Traceback (most recent call last):
    /// ...
    /// pliant.SceneError: <string>: hoses[0].material = "hose9": ...
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>", base_dir = None))]
    fn from_toml(
        py: Python<'_>,
        text: &str,
        origin: &str,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Scene> {
        let dir = base_dir.unwrap_or_default();
        Scene::build(py, load_scene_str_in(text, origin, &dir))
    }

    /// A scene from JSON text (the same structure as the TOML format).
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>", base_dir = None))]
    fn from_json(
        py: Python<'_>,
        text: &str,
        origin: &str,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Scene> {
        let dir = base_dir.unwrap_or_default();
        Scene::build(py, load_scene_json_str_in(text, origin, &dir))
    }

    /// A scene built in code: a dict with the scene file's structure (keys and units as
    /// in docs/scene-format.md; numpy arrays and numbers are accepted where the file has
    /// lists and numbers).
    ///
    /// >>> import pliant, numpy as np
    /// >>> scene = pliant.Scene.from_dict({
    /// ...     "format": "pliant-scene", "version": 1, "length_unit": "m",
    /// ...     "hoses": [{"name": "h", "material": "hose1", "elements": 8,
    /// ...                "start": np.zeros(3),
    /// ...                "path": [{"line": {"to": [0.5, 0, 0]}}]}],
    /// ...     "timeline": [{"action": "fix", "hose": "h", "node": 0}],
    /// ... })
    /// >>> scene.node_count(0)
    /// 9
    /// >>> pliant.Scene.from_dict({"format": "pliant-scene", "version": 1,
    /// ...                         "length_unit": "m", "hoses": []})
    /// Traceback (most recent call last):
    /// ...
    /// pliant.SceneError: <dict>: hoses: a scene needs at least one hose
    #[staticmethod]
    #[pyo3(signature = (scene, origin = "<dict>", base_dir = None))]
    fn from_dict(
        py: Python<'_>,
        scene: &Bound<'_, PyDict>,
        origin: &str,
        base_dir: Option<PathBuf>,
    ) -> PyResult<Scene> {
        let text: String = py
            .import("pliant._json")?
            .call_method1("dumps", (scene,))
            .map_err(|e| {
                scene_error_message(py, format!("{origin}: cannot be written as a scene: {e}"))
            })?
            .extract()?;
        let dir = base_dir.unwrap_or_default();
        // a dict has no lines and columns: report the field only
        let loaded = load_scene_json_str_in(&text, origin, &dir).map_err(|e| match e {
            RustSceneError::Structure {
                origin,
                field,
                message,
                ..
            } => RustSceneError::Structure {
                origin,
                location: None,
                field,
                message,
            },
            other => other,
        });
        Scene::build(py, loaded)
    }

    /// Scene name.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Where the scene came from (a path, ``<string>``, ``<dict>`` or the built-in demo).
    #[getter]
    fn source(&self) -> &str {
        &self.scene.source
    }

    /// The scene's text as loaded (TOML or JSON).
    #[getter]
    fn text(&self) -> &str {
        &self.scene.text
    }

    /// Hose names, in index order.
    #[getter]
    fn hose_names(&self) -> Vec<String> {
        self.scene.hose_names.clone()
    }

    /// Number of nodes of a hose (by name or index).
    fn node_count(&self, hose: crate::args::HoseRef) -> PyResult<usize> {
        Ok(self.model.hoses[self.hose(&hose)?].node_count)
    }

    /// Per hose: name, nodes, elements, length \[m\], element_length \[m\] and stiffened
    /// spans (first, last node).
    #[getter]
    fn hoses<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.scene
            .hoses
            .iter()
            .map(|h| {
                let d = PyDict::new(py);
                d.set_item("name", &h.name)?;
                d.set_item("nodes", h.elements + 1)?;
                d.set_item("elements", h.elements)?;
                d.set_item("length", h.length)?;
                d.set_item("element_length", h.element_length)?;
                d.set_item("stiffened", h.stiffened.clone())?;
                Ok(d)
            })
            .collect()
    }

    /// Names of the rigid parts.
    #[getter]
    fn part_names(&self) -> Vec<String> {
        self.scene.parts.iter().map(|p| p.name.clone()).collect()
    }

    /// Names of the connector stubs.
    #[getter]
    fn stub_names(&self) -> Vec<String> {
        self.scene.stubs.iter().map(|s| s.name.clone()).collect()
    }

    /// Names of the clips.
    #[getter]
    fn clip_names(&self) -> Vec<String> {
        self.scene.clips.iter().map(|c| c.name.clone()).collect()
    }

    /// Interval between recorded states of a timeline run \[s\] (0: every step).
    #[getter]
    fn record_interval(&self) -> f64 {
        self.scene.record_interval
    }

    /// The explicit solver's stable time step of the model \[s\]. A simulation with the
    /// implicit or static solver advances by its own step (``Simulation.time_step``).
    #[getter]
    fn time_step(&self) -> f64 {
        self.model.time_step
    }

    /// The ergonomic profile hand loads are judged with, as
    /// ``push=…,pull=…,population=…,duty=…,moments_decide=…``.
    #[getter]
    fn ergonomics(&self) -> String {
        self.scene.ergonomics.to_string()
    }

    /// The timeline's actions as dicts (SI units, node references as indices).
    #[getter]
    fn timeline<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.scene.timeline.actions)
    }

    fn __repr__(&self) -> String {
        format!(
            "<pliant.Scene '{}' from {}: {} hose(s), {} part(s), {} timeline action(s)>",
            self.scene.name,
            self.scene.source,
            self.scene.hose_names.len(),
            self.scene.parts.len(),
            self.scene.timeline.actions.len()
        )
    }
}

/// Loads a scene file (TOML, or JSON for ``*.json``).
///
/// Raises :class:`SceneError` with the message ``pliant run`` prints: file, line and
/// column, field, value and reason.
///
/// >>> import pliant
/// >>> pliant.load_scene("no/such/scene.toml")  # doctest: +ELLIPSIS
/// Traceback (most recent call last):
/// ...
/// pliant.SceneError: no/such/scene.toml: cannot read scene file: ...
#[pyfunction]
pub fn load_scene(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
    Scene::build(py, load_scene_file(&path))
}

/// The built-in demo scene: the engine bay of ``pliant run`` without a scene argument
/// (examples/engine_bay.toml; its engine block mesh is read from the repository's
/// examples folder).
///
/// >>> import pliant
/// >>> pliant.demo_scene().name
/// 'Engine bay with rigid parts'
#[pyfunction]
pub fn demo_scene(py: Python<'_>) -> PyResult<Scene> {
    Scene::build(py, rust_demo_scene())
}
