//! `pliant.run_timeline` and its `pliant.RunResult`: a scene's whole timeline run as
//! `pliant run` runs it, the verdict, peaks and per-hand series as numpy arrays, and
//! the same `report.json` / `report.html`.

use crate::args::{hose_index, HoseRef};
use crate::arrays::{scalars, to_python, vector_frames, vectors};
use crate::collector::Collector;
use crate::errors::{diverged, scene_error_message};
use crate::scene::Scene;
use glam::DVec3;
use numpy::{PyArray1, PyArray3};
use pliant_assembly::ergonomics::ErgonomicProfile;
use pliant_assembly::report::{write_reports, Drawing};
use pliant_assembly::{
    run_timeline as run_on, RunSummary, Runner, Stage, Verdict, WorkcellOptions,
};
use pliant_core::{Model, SolverKind};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::Arc;

/// The outcome of a timeline run (see :func:`run_timeline`).
///
/// ``feasible`` is True, False, or None when no hand acted; ``reasons`` explains it
/// (the lines ``pliant run`` prints under its verdict). ``summary`` is the whole run
/// summary as a dict (the ``run`` object of report.json); ``peaks``, ``hand_peaks``,
/// ``fasteners`` and ``contacts`` are its parts. ``times`` and :meth:`positions` give the
/// hoses' shapes at the scene's record interval; :meth:`hand_series` each hand's load
/// over time.
#[pyclass(module = "pliant", name = "RunResult", frozen)]
pub struct RunResult {
    scene_name: String,
    model: Arc<Model>,
    profile: ErgonomicProfile,
    run: RunSummary,
    diverged: Option<String>,
    stopped: Option<pliant_assembly::report::Stopped>,
    feasible: Option<bool>,
    reasons: Vec<String>,
    warnings: Vec<String>,
    standard: String,
    zones: Vec<String>,
    findings: pliant_assembly::Findings,
    word: &'static str,
    uncertain: bool,
    data: Collector,
}

/// Runs a scene's whole timeline as ``pliant run`` does (same steps, same verdict, same
/// report) and returns a :class:`RunResult`. ``ergonomics`` overrides the scene's
/// ergonomic profile, as ``pliant run --ergonomics`` does, e.g.
/// ``"posture=sitting, population=men"``.
///
/// A run planned at more than ``max_steps`` steps (its timeline's duration over the time
/// step; default ``DEFAULT_MAX_STEPS``, as ``pliant run --max-steps``) is refused before
/// it starts with :class:`SceneError` giving the estimate.
///
/// Raises :class:`SimulationDiverged` if the run blows up; its ``result`` attribute holds
/// the run up to the last healthy state (its verdict: not feasible). Raises ValueError
/// for a bad ``ergonomics`` text.
///
/// >>> import pliant
/// >>> result = pliant.run_timeline(pliant.demo_scene())
/// >>> result.feasible
/// False
/// >>> result.reasons[0]
/// "hand 0: push of 280.3 N at t = 8.99 s exceeds the limit 94.0 N (table 3.7; 298 % of it) — pressing the hose into clip 'clip engine corner'"
/// >>> result.hand_series(0)["force"].shape[1]
/// 3
#[pyfunction]
#[pyo3(signature = (scene, ergonomics = None, solver = None, max_steps = pliant_scene::budget::DEFAULT_MAX_STEPS))]
pub fn run_timeline(
    py: Python<'_>,
    scene: &Bound<'_, Scene>,
    ergonomics: Option<&str>,
    solver: Option<&str>,
    max_steps: u64,
) -> PyResult<RunResult> {
    let s = scene.get();
    let (loaded, model) = (s.scene.clone(), s.model.clone());
    let solver: Option<SolverKind> = solver
        .map(|t| t.parse().map_err(PyValueError::new_err))
        .transpose()?;
    let profile: ErgonomicProfile = match ergonomics {
        Some(text) => text
            .parse()
            .map_err(|e| PyValueError::new_err(format!("ergonomics '{text}': {e}")))?,
        None => loaded.ergonomics,
    };
    let setup = loaded
        .workcell_setup_of(model.clone())
        .map_err(|e| scene_error_message(py, e.to_string()))?;
    let setup = pliant_assembly::WorkcellSetup { profile, ..setup };
    let options = WorkcellOptions {
        solver,
        ..Default::default()
    };
    let mut cell = Runner::from_setup(setup, options)
        .workcell()
        .map_err(|e| scene_error_message(py, format!("{}: {e}", loaded.source)))?;
    loaded
        .check_planned_run(cell.time_step(), max_steps, true)
        .map_err(|e| scene_error_message(py, e))?;
    let mut data = Collector::new(loaded.record_interval);
    let outcome = py.allow_threads(|| run_on(&mut cell, &loaded.timeline, &mut data));
    data.finish(cell.state());
    let (run, divergence, stopped, typed) = match outcome {
        Ok(run) => (run, None, None, None),
        Err(e) => (
            e.partial.clone(),
            e.divergence.clone(),
            Some(e.reason.clone()),
            Some(e.stopped.clone()),
        ),
    };
    if let (None, Some(reason)) = (&divergence, &stopped) {
        return Err(PyValueError::new_err(reason.clone()));
    }
    let message = stopped;
    let v = Verdict::judge(&run, message.as_deref(), Stage::Final);
    let result = RunResult {
        scene_name: loaded.name.clone(),
        model,
        profile,
        run,
        diverged: message,
        stopped: typed,
        feasible: v.feasible,
        word: v.word(),
        uncertain: v.uncertain,
        reasons: v.reasons,
        warnings: v.warnings,
        standard: v.standard,
        zones: v.zones,
        findings: v.findings,
        data,
    };
    match divergence {
        None => Ok(result),
        Some(d) => {
            let err = diverged(py, &d);
            err.value(py).setattr("result", Py::new(py, result)?)?;
            Err(err)
        }
    }
}

#[pymethods]
impl RunResult {
    /// The range-of-motion table of a scene with a ``[sweep]`` (docs/scene-format.md):
    /// the columns of ``motion.csv`` as ``pliant run`` writes it — ``time_s``, the motion
    /// coordinate (``angle_deg``, ``travel_mm``, ``phase_deg`` or ``time_s``), per hose its
    /// smallest bend radius, its ratio to the minimum, largest twist and axial force, per
    /// hose and watched part the clearance, the largest fixing force — each a numpy array
    /// with one value per checked instant; ``None`` without a sweep.
    fn motion<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        match &self.run.checks.sweep {
            Some(sweep) => crate::motion_table::motion_columns(py, sweep),
            None => Ok(None),
        }
    }

    /// True: every hand load within its limit and every stub and clip fitted; False;
    /// None: no hand acted, nothing to judge.
    #[getter]
    fn feasible(&self) -> Option<bool> {
        self.feasible
    }

    /// True when some Newton solve ended out of balance or on an unstable equilibrium:
    /// the verdict rests on forces that are not trustworthy there (``reasons`` says
    /// where; ``summary["warnings"]`` too).
    #[getter]
    fn uncertain(&self) -> bool {
        self.uncertain
    }

    /// Why (the lines under ``pliant run``'s verdict).
    #[getter]
    fn reasons(&self) -> Vec<String> {
        self.reasons.clone()
    }

    /// The verdict's lines as data, list by list as ``reasons``, ``warnings`` and
    /// ``zones`` word them (plus ``pending`` and, with a worker, ``worker``): a dict of
    /// lists of dicts, each with its ``kind`` (e.g. ``"hand_load_over_limit"`` with
    /// ``hand``, ``load``, ``value``, ``limit``, ``ratio``, ``time``; ``"check_violated"``
    /// with the ``violation``; ``"fastener_not_fitted"`` with ``fastener``, ``name``,
    /// ``final_state``) — docs/python.md lists them. ``findings["reasons"][i]`` is
    /// ``reasons[i]`` as data.
    #[getter]
    fn findings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.findings)
    }

    /// What does not decide feasibility but deserves a look: a hand's twist and bending
    /// moment above their guide or limit values (dissertation 3.3.3), unless the profile
    /// has ``moments_decide=true`` (the lines under ``warnings`` in ``pliant run``'s output).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The standard that judged the hand forces: ``"dissertation tables 3.6–3.11
    /// (Schmidtke)"`` or ``"EN 1005-3:2002+A1:2008"`` (profile ``standard=en1005-3``).
    #[getter]
    fn standard(&self) -> String {
        self.standard.clone()
    }

    /// Under EN 1005-3: each hand's peak push and pull with its risk zone (recommended,
    /// not recommended, to be avoided), m_r = F/F_R and how F_R came about; empty under
    /// the dissertation's tables.
    #[getter]
    fn zones(&self) -> Vec<String> {
        self.zones.clone()
    }

    /// Whether every action ran (False after a divergence).
    #[getter]
    fn completed(&self) -> bool {
        self.diverged.is_none()
    }

    /// The divergence message, or None.
    #[getter]
    fn diverged(&self) -> Option<String> {
        self.diverged.clone()
    }

    /// Why the run stopped early as ``summary.json`` holds it — a dict with ``kind``
    /// (e.g. ``"non_finite_state"``, ``"speed"``, ``"not_converged"``), its numbers, for a
    /// divergence ``step``, ``time_s``, ``hose`` and ``node``, and ``message`` — or None.
    #[getter]
    fn divergence<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.stopped.as_ref().map(|s| to_python(py, s)).transpose()
    }

    /// Steps taken.
    #[getter]
    fn steps(&self) -> u64 {
        self.run.steps
    }

    /// Simulated time at the end \[s\].
    #[getter]
    fn simulated_time(&self) -> f64 {
        self.run.simulated_time
    }

    /// The ergonomic profile the hand loads were judged with.
    #[getter]
    fn ergonomics(&self) -> String {
        self.run.ergonomics.clone()
    }

    /// The whole run summary as a dict (the ``run`` object of report.json).
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run)
    }

    /// The Newton solvers' record (the summary's ``solver``: iterations, unconverged
    /// steps, instabilities), without decoding the whole summary.
    #[getter]
    fn solver_record<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.solver)
    }

    /// The settles' outcomes (the summary's ``settles``: ``action``, ``at_rest``, ``time``
    /// \[s\], ``kinetic_energy``, ``residual_force``, ``residual_moment``,
    /// ``static_solve_time``), without decoding the whole summary.
    #[getter]
    fn settles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.settles)
    }

    /// Why the run is uncertain (the summary's ``solver_warnings``); empty when it is not.
    #[getter]
    fn solver_warnings(&self) -> Vec<String> {
        let warnings = self.run.solver_warnings.iter();
        warnings.map(ToString::to_string).collect()
    }

    /// Peak support loads per fixed or driven node: dicts with hose (name), hose_index,
    /// node, max_force \[N\], max_force_time \[s\], max_moment \[N·m\], max_moment_time \[s\],
    /// last_force, last_moment.
    #[getter]
    fn peaks<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.run
            .peaks
            .iter()
            .map(|p| {
                let d = PyDict::new(py);
                d.set_item("hose", &self.model.hoses[p.hose].name)?;
                d.set_item("hose_index", p.hose)?;
                d.set_item("node", p.node)?;
                d.set_item("max_force", p.max_force)?;
                d.set_item("max_force_time", p.max_force_time)?;
                d.set_item("max_moment", p.max_moment)?;
                d.set_item("max_moment_time", p.max_moment_time)?;
                d.set_item("last_force", p.last_force.to_array())?;
                d.set_item("last_moment", p.last_moment.to_array())?;
                Ok(d)
            })
            .collect()
    }

    /// Peak loads per hand and its worst moment against the limits (dicts).
    #[getter]
    fn hand_peaks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.hand_peaks)
    }

    /// What the worker of the scene's ``[worker]`` did (SPEC E1–E2), or ``None`` without
    /// one: the summary of ``Simulation.worker()`` without its ``series`` — ``who``,
    /// ``seat`` (a seated worker's ``height`` [m], ``None`` standing), ``reach`` per arm, ``collisions``, ``worst_rula``, ``worst_reba``,
    /// ``class_instants``, ``steps`` (each step: ``time``, ``length`` [m], ``turn`` [rad,
    /// positive to the left], ``words``,
    /// ``from``, ``to``, ``cause``) and ``step_count``, ``findings`` (typed).
    #[getter]
    fn worker<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let Some(w) = &self.run.worker else {
            return Ok(py.None().into_bound(py));
        };
        let mut value = serde_json::to_value(w)
            .map_err(|e| PyValueError::new_err(format!("internal error serialising: {e}")))?;
        value["findings"] = serde_json::json!(w.findings());
        to_python(py, &value)
    }

    /// Stubs and clips: peak force, final state, assembled (dicts).
    #[getter]
    fn fasteners<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.fasteners)
    }

    /// Installation-check violations (SPEC V3; dicts: ``check`` — bend_radius, twist,
    /// tension_at_rest, straight_behind_stub —, ``hose_name``, ``arc_length`` \[m\],
    /// ``time`` \[s\], ``value`` and ``limit`` in SI units, ``first_time``, ``last_time``).
    #[getter]
    fn violations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.checks.violations)
    }

    /// Per hose, curvature [1/m] and twist [rad/m] along it at its worst instants, with
    /// their limits (dicts; the report's plots).
    #[getter]
    fn check_profiles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.checks.profiles)
    }

    /// Rigid parts the hoses touched and when (dicts).
    #[getter]
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.run.contacts)
    }

    /// Recorded times \[s\], shape (K,).
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        scalars(py, self.data.times.clone())
    }

    /// A hose's node positions at the recorded times \[m\], shape (K, N, 3).
    fn positions<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let h = hose_index(&self.model, &hose)?;
        let nodes = self.model.hoses[h].nodes();
        let total = self.model.node_count();
        let k = self.data.times.len();
        let frames = (0..k).flat_map(|f| {
            let base = f * total;
            self.data.positions[base + nodes.start..base + nodes.end]
                .iter()
                .copied()
        });
        vector_frames(py, k, nodes.len(), frames)
    }

    /// Numbers of the hands that acted.
    #[getter]
    fn hands(&self) -> Vec<usize> {
        self.run.hand_peaks.iter().map(|p| p.hand).collect()
    }

    /// Hand ``hand``'s load at the recorded times while it held something, as numpy
    /// arrays: ``time`` (K,) \[s\], ``position`` (K, 3) \[m\], ``force`` (K, 3) \[N\],
    /// ``torque`` (K, 3) \[N·m\], ``ratio`` (K,) to the limit of the worst load kind,
    /// ``limit`` (K,), ``colour`` (K,) = min(ratio, 1).
    fn hand_series<'py>(&self, py: Python<'py>, hand: usize) -> PyResult<Bound<'py, PyDict>> {
        if !self.run.hand_peaks.iter().any(|p| p.hand == hand) {
            return Err(PyValueError::new_err(format!(
                "hand {hand} did not act in this run; hands that did: {:?}",
                self.hands()
            )));
        }
        let mine: Vec<_> = self
            .data
            .hand_records
            .iter()
            .filter(|(_, r)| r.hand == hand)
            .collect();
        let worst = |r: &pliant_assembly::HandRecord| r.assessment.map(|a| *a.worst());
        let d = PyDict::new(py);
        d.set_item("time", scalars(py, mine.iter().map(|(t, _)| *t).collect()))?;
        d.set_item(
            "position",
            vectors(
                py,
                mine.iter()
                    .map(|(_, r)| r.load.position)
                    .collect::<Vec<DVec3>>()
                    .into_iter(),
            ),
        )?;
        d.set_item(
            "force",
            vectors(
                py,
                mine.iter()
                    .map(|(_, r)| r.load.force)
                    .collect::<Vec<DVec3>>()
                    .into_iter(),
            ),
        )?;
        d.set_item(
            "torque",
            vectors(
                py,
                mine.iter()
                    .map(|(_, r)| r.load.torque)
                    .collect::<Vec<DVec3>>()
                    .into_iter(),
            ),
        )?;
        d.set_item(
            "ratio",
            scalars(
                py,
                mine.iter()
                    .map(|(_, r)| worst(r).map_or(0.0, |w| w.ratio))
                    .collect(),
            ),
        )?;
        d.set_item(
            "limit",
            scalars(
                py,
                mine.iter()
                    .map(|(_, r)| worst(r).map_or(0.0, |w| w.limit))
                    .collect(),
            ),
        )?;
        d.set_item(
            "colour",
            scalars(
                py,
                mine.iter()
                    .map(|(_, r)| r.assessment.map_or(0.0, |a| a.colour_value()))
                    .collect(),
            ),
        )?;
        Ok(d)
    }

    /// Writes ``report.json`` and ``report.html`` into the folder ``out`` (created if
    /// needed) — the same files, from the same code, as ``pliant run``.
    ///
    /// >>> import pliant, tempfile, os
    /// >>> out = tempfile.mkdtemp()
    /// >>> pliant.run_timeline(pliant.demo_scene()).write_report(out)
    /// >>> sorted(os.listdir(out))
    /// ['report.html', 'report.json']
    fn write_report(&self, py: Python<'_>, out: PathBuf) -> PyResult<()> {
        py.allow_threads(|| {
            std::fs::create_dir_all(&out)
                .map_err(|e| format!("creating output folder {}: {e}", out.display()))?;
            write_reports(
                &out,
                &self.scene_name,
                &self.run,
                &Drawing::of(&self.model, &self.run),
                self.diverged.as_deref(),
                &self.data.hand_samples,
                &self.profile,
                &[],
            )
            .map(|_| ())
            .map_err(|e| e.to_string())
        })
        .map_err(PyOSError::new_err)
    }

    fn __repr__(&self) -> String {
        let word = self.word;
        format!(
            "<pliant.RunResult '{}': {word}, {} steps, {:.3} s simulated{}>",
            self.scene_name,
            self.run.steps,
            self.run.simulated_time,
            if self.diverged.is_some() {
                ", diverged"
            } else {
                ""
            }
        )
    }
}
