//! `pliant.Simulation`: step or settle a scene interactively — add and remove load
//! cases, grab and move hands, read positions, orientations and forces as numpy arrays.
//!
//! `step`/`run` advance the simulation with its solver — explicit, implicit or
//! quasi-static, chosen by the scene or by `Simulation(scene, solver=…)`; `settle` relaxes
//! to static equilibrium with the same steps (settle.rs: the workcell's settle, as the
//! timeline's `settle` action); `solve_static` takes one
//! equilibrium solve of the quasi-static solver.

use crate::args::{hose_index, hose_node, points, quaternion, seconds, vec3, HoseRef};
use crate::arrays::{quaternion as quat_array, quaternions, to_python, vector, vectors};
use crate::engine::{Engine, Refusal};
use crate::errors::{diverged, scene_error_message};
use crate::hand_load::HandLoad;
use crate::load_id::LoadId;
use crate::scene::Scene;
use crate::settle_report::SettleReport;
use glam::DVec3;
use numpy::{PyArray1, PyArray2};
use pliant_assembly::Input;
use pliant_core::loads::{LoadCase, LoadCaseId};
use pliant_core::relax::RelaxOptions;
use pliant_core::State;
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use std::ops::Range;

/// A pose as numpy arrays: the position \[m\] (3,) and the orientation (w, x, y, z) (4,).
type PoseArrays<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// Steps run without the GIL before Python gets a chance to handle Ctrl-C.
const CHUNK: u64 = 4096;

fn refused(r: Refusal) -> PyErr {
    match r {
        Refusal::Invalid(m) => PyValueError::new_err(m),
        Refusal::Missing(m) => PyKeyError::new_err(m),
    }
}

/// A simulation of a scene, stepped on request.
///
/// It starts at rest in the scene's rest shape at t = 0 with the scene's initial load
/// cases — the fixes and dead loads its timeline begins with — unless
/// ``initial_loads=False``; the rest of the timeline is for :func:`run_timeline`. The
/// scene's stubs and clips act, and hand loads are judged with its ergonomic profile.
/// All values are SI: metres, newtons, seconds, radians; vectors are in global axes.
///
/// >>> import pliant
/// >>> sim = pliant.Simulation(pliant.demo_scene())
/// >>> sim.time
/// 0.0
/// >>> sim.run(0.05)                  # 0.05 s with the scene's solver; returns the steps
/// 206
/// >>> sim.positions("lower").shape   # (nodes, 3) \[m\]
/// (16, 3)
#[pyclass(module = "pliant", name = "Simulation")]
pub struct Simulation {
    engine: Engine,
    scene: Py<Scene>,
    /// Raise `SolverNotConverged` instead of warning.
    strict: bool,
}

impl Simulation {
    fn model(&self) -> &pliant_core::Model {
        self.engine.model()
    }

    fn nodes(&self, hose: &HoseRef) -> PyResult<Range<usize>> {
        let h = hose_index(self.model(), hose)?;
        Ok(self.model().hoses[h].nodes())
    }

    fn vector_field<'py>(
        &self,
        py: Python<'py>,
        hose: &HoseRef,
        field: impl Fn(&State) -> &[DVec3],
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.nodes(hose)?;
        Ok(vectors(py, field(self.engine.state())[r].iter().copied()))
    }

    /// (hose name, local node) of a global node.
    fn locate(&self, node: usize) -> (String, usize) {
        self.model()
            .hoses
            .iter()
            .find(|h| h.nodes().contains(&node))
            .map_or(("?".into(), node), |h| {
                (h.name.clone(), node - h.first_node)
            })
    }

    fn load_id(&self, id: LoadCaseId, case: &LoadCase) -> LoadId {
        let kind = match case {
            LoadCase::Fix(_) => "fix",
            LoadCase::Mount(_) => "mount",
            LoadCase::Drive(_) => "drive",
            LoadCase::DeadLoad(_) => "dead_load",
            LoadCase::Support(_) => "support",
            LoadCase::Tie(_) => "tie",
        };
        let (hose, node) = self.locate(case.node());
        LoadId {
            id: id.0,
            kind: kind.into(),
            hose,
            node,
        }
    }

    fn new_load(&self, id: LoadCaseId) -> LoadId {
        let case = self
            .engine
            .state()
            .loads
            .iter()
            .find(|(i, _)| *i == id)
            .map(|(_, c)| c.clone());
        match case {
            Some(c) => self.load_id(id, &c),
            None => LoadId {
                id: id.0,
                kind: "?".into(),
                hose: "?".into(),
                node: 0,
            },
        }
    }

    /// `n` steps with the GIL released, in chunks so that Ctrl-C is honoured.
    fn advance(&mut self, py: Python<'_>, n: u64) -> PyResult<()> {
        let mut left = n;
        let (unconverged, unstable) = {
            let r = self.engine.solver_record();
            (r.unconverged_steps, r.unstable_steps)
        };
        loop {
            let k = left.min(CHUNK);
            let engine = &mut self.engine;
            py.allow_threads(|| engine.steps(k))
                .map_err(|d| diverged(py, &d))?;
            left -= k;
            if left == 0 {
                break;
            }
            py.check_signals()?;
        }
        let r = self.engine.solver_record();
        if r.unconverged_steps > unconverged || r.unstable_steps > unstable {
            let message = r
                .warnings()
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; ");
            if self.strict {
                return Err(crate::errors::SolverNotConverged::new_err(message));
            }
            let category = py.get_type::<crate::errors::SolverWarning>();
            PyErr::warn(
                py,
                &category,
                &std::ffi::CString::new(message).unwrap_or_default(),
                1,
            )?;
        }
        Ok(())
    }

    /// Whole steps in `duration` (rounded, as the timeline's `run`).
    fn steps_for(&self, duration: f64) -> u64 {
        self.engine.cell().steps_in(duration)
    }

    /// Gives a part's move and, with `wait`, runs until it has ended.
    fn give_part_move(
        &mut self,
        py: Python<'_>,
        input: Input,
        duration: f64,
        wait: bool,
    ) -> PyResult<()> {
        self.engine.move_part(input).map_err(refused)?;
        if wait {
            let n = self.steps_until_done(duration);
            self.advance(py, n)?;
        }
        Ok(())
    }

    /// Steps until a motion of `duration` starting now has ended (rounded up).
    fn steps_until_done(&self, duration: f64) -> u64 {
        self.engine.cell().steps_until_done(duration)
    }

    /// Waypoints from `to` (absolute) or `by` (offsets from `start`); at most one.
    fn waypoints(
        to: Option<&Bound<'_, PyAny>>,
        by: Option<&Bound<'_, PyAny>>,
        start: DVec3,
    ) -> PyResult<Vec<DVec3>> {
        match (to, by) {
            (Some(_), Some(_)) => Err(PyValueError::new_err(
                "give either `to` (absolute waypoints) or `by` (offsets), not both",
            )),
            (Some(t), None) => points(t, "to"),
            (None, Some(b)) => Ok(points(b, "by")?.into_iter().map(|d| start + d).collect()),
            (None, None) => Ok(Vec::new()),
        }
    }
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (scene, *, initial_loads = true, solver = None, strict = false))]
    fn new(
        py: Python<'_>,
        scene: Bound<'_, Scene>,
        initial_loads: bool,
        solver: Option<&str>,
        strict: bool,
    ) -> PyResult<Self> {
        let s = scene.get();
        let initial = if initial_loads {
            s.scene.initial_loads()
        } else {
            Vec::new()
        };
        let kind: Option<pliant_core::SolverKind> = solver
            .map(|name| name.parse())
            .transpose()
            .map_err(|e: String| PyValueError::new_err(format!("solver: {e}")))?;
        let engine = Engine::new(s.model.clone(), &s.scene, initial, kind)
            .map_err(|e| scene_error_message(py, format!("{}: {e}", s.scene.source)))?;
        Ok(Simulation {
            engine,
            strict,
            scene: scene.unbind(),
        })
    }

    /// The scene simulated.
    #[getter]
    fn scene(&self, py: Python<'_>) -> Py<Scene> {
        self.scene.clone_ref(py)
    }

    /// Simulated time \[s\].
    #[getter]
    fn time(&self) -> f64 {
        self.engine.state().time
    }

    /// Simulated time one step advances \[s\]: the explicit stable step, or the implicit /
    /// static solver's step (see :attr:`solver` and the scene's ``[simulation]``).
    #[getter]
    fn time_step(&self) -> f64 {
        self.engine.time_step()
    }

    /// The solver that advances the simulation: ``"explicit"`` (the dissertation's
    /// central differences), ``"implicit"`` (HHT-α, 10 ms steps) or ``"static"`` (one
    /// equilibrium solve per 10 ms of input). Chosen by the scene or by
    /// ``Simulation(scene, solver=...)``.
    ///
    /// >>> import pliant
    /// >>> pliant.Simulation(pliant.demo_scene(), solver="implicit").time_step
    /// 0.01
    #[getter]
    fn solver(&self) -> &'static str {
        self.engine.solver().kind().name()
    }

    /// Why the numbers so far are uncertain: Newton steps that ended out of balance or
    /// on an unstable equilibrium (empty when none did; each such step also warns with
    /// :class:`SolverWarning`).
    ///
    /// >>> import pliant
    /// >>> pliant.Simulation(pliant.demo_scene(), solver="static").solver_warnings
    /// []
    #[getter]
    fn solver_warnings(&self) -> Vec<String> {
        let warnings = self.engine.solver_record().warnings();
        warnings.iter().map(ToString::to_string).collect()
    }

    /// The unstable equilibria (buckling, bifurcations) the static solver met and left
    /// for the stable branch so far, each a dict: ``time`` \[s\], ``hose`` (name), ``node``
    /// (on that hose), ``negative_eigenvalues``, ``limit_point`` (a snap-through), ``energy_drop_j`` and ``mode`` (an
    /// (n, 3) array: each node's translation in the unstable mode, the largest 1).
    fn instabilities<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Vec<Bound<'py, pyo3::types::PyDict>>> {
        let model = self.model();
        self.engine
            .solver_record()
            .instabilities
            .iter()
            .map(|i| {
                let d = pyo3::types::PyDict::new(py);
                d.set_item("time", i.time)?;
                d.set_item("hose", model.hoses[i.hose].name.clone())?;
                d.set_item("node", i.node)?;
                d.set_item("negative_eigenvalues", i.negative_eigenvalues)?;
                d.set_item("limit_point", i.limit_point)?;
                d.set_item("energy_drop_j", i.energy_drop_j)?;
                let mode = numpy::PyArray2::from_vec2(
                    py,
                    &i.mode.iter().map(|m| m.to_vec()).collect::<Vec<_>>(),
                )
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
                d.set_item("mode", mode)?;
                Ok(d)
            })
            .collect()
    }

    /// Steps taken since the start (or the last reset).
    #[getter]
    fn step_count(&self) -> u64 {
        self.engine.state().step
    }

    /// Hose names, in index order.
    #[getter]
    fn hose_names(&self) -> Vec<String> {
        self.model().hoses.iter().map(|h| h.name.clone()).collect()
    }

    /// Number of nodes of a hose (by name or index).
    fn node_count(&self, hose: HoseRef) -> PyResult<usize> {
        Ok(self.nodes(&hose)?.len())
    }

    // ---- stepping ---------------------------------------------------------------

    /// Advances the simulation by ``n`` time steps of its solver (:attr:`solver`:
    /// explicit, implicit or static; :attr:`time_step` long each).
    ///
    /// Raises :class:`SimulationDiverged` (step, node, likely cause) if the state blows
    /// up; the simulation then refuses to step until :meth:`reset`.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> sim.step(10)
    /// >>> sim.step_count
    /// 10
    #[pyo3(signature = (n = 1))]
    fn step(&mut self, py: Python<'_>, n: u64) -> PyResult<()> {
        self.advance(py, n)
    }

    /// Advances the simulation by ``seconds`` of simulated time with its solver
    /// (:attr:`solver`), rounded to whole steps of :attr:`time_step`; returns the number
    /// of steps taken.
    fn run(&mut self, py: Python<'_>, seconds: f64) -> PyResult<u64> {
        let d = crate::args::seconds(seconds, "seconds", true)?;
        let n = self.steps_for(d);
        self.advance(py, n)?;
        Ok(n)
    }

    /// Relaxes to static equilibrium under the current load cases and hand poses by
    /// dynamic relaxation with kinetic damping (the simulation's solver steps on and all
    /// velocities are zeroed whenever the kinetic energy passes a peak) until the largest
    /// out-of-balance force and moment on a free node, contact with parts and hoses
    /// counted, are below the tolerances \[N\], \[N·m\], or ``max_steps`` steps have
    /// passed. Simulated time advances by the steps taken; with ``kinetic_damping`` the
    /// motion on the way is not physical, the end state is the equilibrium. The
    /// timeline's ``settle`` action is the same relaxation without kinetic damping.
    ///
    /// Returns a :class:`SettleReport` (true if converged). Raises ValueError while a
    /// hand or drive is still moving, :class:`SimulationDiverged` if it blows up.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> report = sim.settle(force_tolerance=1e-3)
    /// >>> report.converged, report.residual_force <= 1e-3
    /// (True, True)
    #[pyo3(signature = (force_tolerance = 1e-3, moment_tolerance = 1e-4, max_steps = 1_000_000, kinetic_damping = true))]
    fn settle(
        &mut self,
        py: Python<'_>,
        force_tolerance: f64,
        moment_tolerance: f64,
        max_steps: u64,
        kinetic_damping: bool,
    ) -> PyResult<SettleReport> {
        check_tolerances(force_tolerance, moment_tolerance)?;
        let opts = RelaxOptions {
            force_tolerance,
            moment_tolerance,
            max_steps,
            kinetic_damping,
        };
        let engine = &mut self.engine;
        let outcome = py.allow_threads(|| engine.settle(&opts)).map_err(refused)?;
        outcome
            .map(SettleReport::from)
            .map_err(|d| diverged(py, &d))
    }

    /// Solves directly for the static equilibrium under the current load cases and hand
    /// poses with the quasi-static Newton solver (consistent tangent, line search; issue
    /// 5) — the same equilibrium :meth:`settle` reaches, in a few iterations instead of
    /// thousands of steps. Time does not advance; velocities are set to zero.
    ///
    /// Returns a :class:`SettleReport` whose ``steps`` are the Newton iterations.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> report = sim.solve_static()
    /// >>> report.converged
    /// True
    #[pyo3(signature = (force_tolerance = 1e-7, moment_tolerance = 1e-8, max_iterations = 100))]
    fn solve_static(
        &mut self,
        py: Python<'_>,
        force_tolerance: f64,
        moment_tolerance: f64,
        max_iterations: usize,
    ) -> PyResult<SettleReport> {
        check_tolerances(force_tolerance, moment_tolerance)?;
        let engine = &mut self.engine;
        let report = py.allow_threads(|| {
            engine.solve_static(force_tolerance, moment_tolerance, max_iterations)
        });
        let r = report.map_err(|e| {
            let message = match e {
                Refusal::Invalid(m) | Refusal::Missing(m) => m,
            };
            pyo3::exceptions::PyRuntimeError::new_err(message)
        })?;
        Ok(SettleReport::from(pliant_core::relax::RelaxReport {
            steps: r.iterations as u64,
            residual_force: r.residual_force,
            residual_moment: r.residual_moment,
            converged: r.converged,
        }))
    }

    /// Back to the start: rest shape, t = 0, hands released, user load cases removed,
    /// the initial load cases applied again, stubs and clips reset. Also clears a
    /// divergence.
    fn reset(&mut self) {
        self.engine.reset();
    }

    // ---- load cases -------------------------------------------------------------

    /// Holds node ``node`` of ``hose`` where it is now, position and orientation (L1).
    /// Replaces fixes and drives you added on that node; refused for a node a hand
    /// holds. Returns the :class:`LoadId` for :meth:`remove_load`.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene(), initial_loads=False)
    /// >>> sim.fix("lower", -1)  # doctest: +ELLIPSIS
    /// LoadId(..., kind='fix', hose='lower', node=15)
    fn fix(&mut self, hose: HoseRef, node: i64) -> PyResult<LoadId> {
        let (_, i) = hose_node(self.model(), &hose, node)?;
        let id = self.engine.fix(i).map_err(refused)?;
        Ok(self.new_load(id))
    }

    /// Drives node ``node`` of ``hose`` through the waypoints ``to`` (absolute \[m\], one
    /// point or a list) or ``by`` (offsets from where it is now), turning it by the
    /// rotation vector ``rotate`` (axis × angle \[rad\], global axes; angles beyond π
    /// allowed) over ``duration`` seconds with a smooth start and stop (L2, L3); it stays
    /// held at the end pose until the load case is removed. With ``wait`` the
    /// simulation runs for ``duration``. Replaces fixes and drives you added on the node.
    #[pyo3(signature = (hose, node, to = None, *, by = None, rotate = None, duration = 1.0, wait = true))]
    #[allow(clippy::too_many_arguments)]
    fn drive(
        &mut self,
        py: Python<'_>,
        hose: HoseRef,
        node: i64,
        to: Option<&Bound<'_, PyAny>>,
        by: Option<&Bound<'_, PyAny>>,
        rotate: Option<&Bound<'_, PyAny>>,
        duration: f64,
        wait: bool,
    ) -> PyResult<LoadId> {
        let (_, i) = hose_node(self.model(), &hose, node)?;
        let duration = seconds(duration, "duration", false)?;
        let waypoints = Self::waypoints(to, by, self.engine.state().x[i])?;
        let phi = rotate
            .map(|r| vec3(r, "rotate"))
            .transpose()?
            .unwrap_or(DVec3::ZERO);
        let id = self
            .engine
            .drive(i, &waypoints, phi, duration)
            .map_err(refused)?;
        let load = self.new_load(id);
        if wait {
            let n = self.steps_until_done(duration);
            self.advance(py, n)?;
        }
        Ok(load)
    }

    /// Adds a constant ``force`` \[N\] and ``moment`` \[N·m\] (global axes; they do not turn
    /// with the hose) at node ``node`` of ``hose``, in full at once or rising linearly
    /// from zero over ``ramp`` seconds from now. Dead loads on one node add up; each can
    /// be removed alone with :meth:`remove_load`.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> load = sim.add_dead_load("lower", -1, force=[0, 0, -5.0])
    /// >>> load.kind, load.node
    /// ('dead_load', 15)
    /// >>> sim.remove_load(load)
    #[pyo3(signature = (hose, node, force = None, moment = None, *, ramp = 0.0))]
    fn add_dead_load(
        &mut self,
        hose: HoseRef,
        node: i64,
        force: Option<&Bound<'_, PyAny>>,
        moment: Option<&Bound<'_, PyAny>>,
        ramp: f64,
    ) -> PyResult<LoadId> {
        let (_, i) = hose_node(self.model(), &hose, node)?;
        let f = force
            .map(|v| vec3(v, "force"))
            .transpose()?
            .unwrap_or(DVec3::ZERO);
        let m = moment
            .map(|v| vec3(v, "moment"))
            .transpose()?
            .unwrap_or(DVec3::ZERO);
        let id = self.engine.dead_load(i, f, m, ramp).map_err(refused)?;
        Ok(self.new_load(id))
    }

    /// Removes a load case added with :meth:`fix`, :meth:`drive` or
    /// :meth:`add_dead_load` (or one of the scene's initial ones, see
    /// :attr:`load_cases`). Raises KeyError if it is no longer active.
    fn remove_load(&mut self, load: &LoadId) -> PyResult<()> {
        self.engine
            .remove_load(LoadCaseId(load.id))
            .map(|_| ())
            .map_err(refused)
    }

    /// The active load cases you can remove: the scene's initial fixes and dead loads
    /// and the ones you added (not the hands' and fasteners' internal ones).
    #[getter]
    fn load_cases(&self) -> Vec<LoadId> {
        self.engine
            .user_loads()
            .map(|(id, c)| self.load_id(id, c))
            .collect()
    }

    // ---- hands ------------------------------------------------------------------

    /// Hand ``hand`` (a number ≥ 0) grabs the beam nearest to the point ``at`` \[m\], or
    /// to node ``node`` of ``hose``; the beam's two nodes then follow the hand rigidly
    /// (I1). A hand that holds a beam lets go of it first; fixes and drives you added on
    /// the beam's nodes are replaced. Returns (hose name, first node, second node) of
    /// the beam.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> sim.grab(0, hose="lower", node=-1)
    /// ('lower', 14, 15)
    ///
    /// `grip`: "firm" (default: the beam turns with the hand), "axial" (the hose may turn
    /// about its own axis in the hand) or "ball" (about every axis).
    #[pyo3(signature = (hand, at = None, *, hose = None, node = None, grip = "firm"))]
    fn grab(
        &mut self,
        hand: u32,
        at: Option<&Bound<'_, PyAny>>,
        hose: Option<HoseRef>,
        node: Option<i64>,
        grip: &str,
    ) -> PyResult<(String, usize, usize)> {
        let grip = match grip {
            "firm" => pliant_assembly::Grip::Firm,
            "axial" => pliant_assembly::Grip::Axial,
            "ball" => pliant_assembly::Grip::Ball,
            other => {
                return Err(PyValueError::new_err(format!(
                    "grip: unknown grip {other:?}; allowed: firm, axial, ball"
                )))
            }
        };
        let point = match (at, hose, node) {
            (Some(p), None, None) => vec3(p, "at")?,
            (None, Some(h), Some(n)) => {
                let (_, i) = hose_node(self.model(), &h, n)?;
                self.engine.state().x[i]
            }
            _ => {
                return Err(PyValueError::new_err(
                    "grab needs either a point `at` or both `hose` and `node`",
                ))
            }
        };
        let element = self.engine.grab(hand, point, grip).map_err(refused)?;
        let el = &self.model().elements[element];
        let (name, a) = self.locate(el.node_a);
        let (_, b) = self.locate(el.node_b);
        Ok((name, a, b))
    }

    /// Moves hand ``hand`` through the waypoints ``to`` (absolute \[m\], one point or a
    /// list) or ``by`` (offsets from the hand's position now), and turns it to the
    /// absolute ``orientation`` (quaternion w, x, y, z; the hand starts with the global
    /// orientation when it grabs) or by the rotation vector ``rotate`` (axis × angle
    /// \[rad\]), over ``duration`` seconds — or at the mean ``speed`` \[m/s\] along the path
    /// — with a smooth start and stop. The held beam follows rigidly. With ``wait`` the
    /// simulation runs until the motion ends.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> _ = sim.grab(0, hose="lower", node=-1)
    /// >>> z0 = sim.hand_pose(0)[0][2]
    /// >>> sim.move_hand(0, by=[0.0, 0.0, 0.02], duration=0.1)   # lift 2 cm in 0.1 s
    /// >>> round(float(sim.hand_pose(0)[0][2] - z0), 6)
    /// 0.02
    #[pyo3(signature = (hand, to = None, *, by = None, orientation = None, rotate = None, duration = None, speed = None, wait = true))]
    #[allow(clippy::too_many_arguments)]
    fn move_hand(
        &mut self,
        py: Python<'_>,
        hand: u32,
        to: Option<&Bound<'_, PyAny>>,
        by: Option<&Bound<'_, PyAny>>,
        orientation: Option<&Bound<'_, PyAny>>,
        rotate: Option<&Bound<'_, PyAny>>,
        duration: Option<f64>,
        speed: Option<f64>,
        wait: bool,
    ) -> PyResult<()> {
        let ((start, _), _) = self.engine.hand_pose(hand).map_err(refused)?;
        let waypoints = Self::waypoints(to, by, start)?;
        let phi = match (orientation, rotate) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err(
                    "give either `orientation` (absolute) or `rotate` (relative), not both",
                ))
            }
            (Some(q), None) => {
                let q = quaternion(q, "orientation")?;
                self.engine.rotation_to(hand, q).map_err(refused)?
            }
            (None, Some(r)) => vec3(r, "rotate")?,
            (None, None) => DVec3::ZERO,
        };
        let duration = match (duration, speed) {
            (Some(_), Some(_)) => {
                return Err(PyValueError::new_err(
                    "give either `duration` or `speed`, not both",
                ))
            }
            (Some(d), None) => seconds(d, "duration", false)?,
            (None, Some(v)) => {
                if !(v.is_finite() && v > 0.0) {
                    return Err(PyValueError::new_err(format!(
                        "speed must be finite and > 0 m/s, got {v}"
                    )));
                }
                if waypoints.is_empty() {
                    return Err(PyValueError::new_err(
                        "`speed` needs a path: give `to` or `by`",
                    ));
                }
                pliant_assembly::move_speed::duration_at_speed(start, &waypoints, v)
            }
            (None, None) => 1.0,
        };
        self.engine
            .move_hand(hand, &waypoints, phi, duration)
            .map_err(refused)?;
        if wait {
            let n = self.steps_until_done(duration);
            self.advance(py, n)?;
        }
        Ok(())
    }

    /// Hand ``hand`` heads for ``position`` \[m\] (and ``orientation``, a quaternion
    /// ``[w, x, y, z]``, if given) at bounded speed and acceleration (2 m/s, 20 m/s²) — as
    /// a hand steered by a pointer or a VR controller in ``pliant serve`` does, and as
    /// the timeline action ``aim_hand``. Returns at once; :meth:`run` lets it get there.
    ///
    /// >>> import pliant
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> _ = sim.grab(0, hose="lower", node=-1)
    /// >>> p = sim.hand_pose(0)[0]
    /// >>> sim.aim_hand(0, [p[0], p[1], p[2] + 0.01])
    /// >>> _ = sim.run(0.2)
    /// >>> round(float(sim.hand_pose(0)[0][2] - p[2]), 6)
    /// 0.01
    #[pyo3(signature = (hand, position, orientation = None))]
    fn aim_hand(
        &mut self,
        hand: u32,
        position: &Bound<'_, PyAny>,
        orientation: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let position = vec3(position, "position")?;
        let orientation = orientation
            .map(|q| quaternion(q, "orientation"))
            .transpose()?;
        self.engine
            .aim_hand(hand, position, orientation)
            .map_err(refused)
    }

    /// Moves the part called ``part`` over ``duration`` seconds with a smooth start and
    /// stop: so that its centre (its bounding box's) is ``to`` \[m\] from where the scene
    /// placed it, or ``by`` an offset from where it is now — in its parent's axes for a part with a parent.
    /// Everything mounted or clipped on it goes with it. The part must be movable
    /// (``movable = true`` in the scene, or moved by its timeline) and have no
    /// ``motion``. With ``wait`` the simulation runs until the move ends.
    #[pyo3(signature = (part, to = None, *, by = None, duration = 1.0, wait = true))]
    fn move_part(
        &mut self,
        py: Python<'_>,
        part: &str,
        to: Option<&Bound<'_, PyAny>>,
        by: Option<&Bound<'_, PyAny>>,
        duration: f64,
        wait: bool,
    ) -> PyResult<()> {
        let input = Input::MovePart {
            part: part.to_string(),
            by: by.map(|v| vec3(v, "by")).transpose()?,
            to: to.map(|v| vec3(v, "to")).transpose()?,
            duration,
        };
        self.give_part_move(py, input, duration, wait)
    }

    /// Turns the part called ``part`` about ``axis`` through ``point`` \[m\] (a point of
    /// the part where the scene placed it; default: the centre of its bounding box) ``by``
    /// an angle \[rad\] from where it is, or ``to`` an angle from where the scene placed
    /// it, over ``duration`` seconds with a smooth start and stop. As :meth:`move_part`
    /// otherwise; a turn ``to`` an angle needs every earlier turn of the part to be about
    /// the same axis.
    #[pyo3(signature = (part, axis, *, by = None, to = None, point = None, duration = 1.0, wait = true))]
    #[allow(clippy::too_many_arguments)]
    fn rotate_part(
        &mut self,
        py: Python<'_>,
        part: &str,
        axis: &Bound<'_, PyAny>,
        by: Option<f64>,
        to: Option<f64>,
        point: Option<&Bound<'_, PyAny>>,
        duration: f64,
        wait: bool,
    ) -> PyResult<()> {
        let input = Input::RotatePart {
            part: part.to_string(),
            axis: vec3(axis, "axis")?,
            point: point.map(|v| vec3(v, "point")).transpose()?,
            by,
            to,
            duration,
        };
        self.give_part_move(py, input, duration, wait)
    }

    /// The part's pose now: where its reference origin went \[m\] (3,) and its rotation
    /// (w, x, y, z) (4,), from where the scene placed it (zero and identity for a part
    /// that has not moved).
    fn part_pose<'py>(&self, py: Python<'py>, part: &str) -> PyResult<PoseArrays<'py>> {
        let pose = self.engine.part_pose(part).map_err(refused)?;
        Ok((vector(py, pose.translation), quat_array(py, pose.rotation)))
    }

    /// Hand ``hand`` lets go: the beam's nodes move freely again.
    fn release(&mut self, hand: u32) -> PyResult<()> {
        self.engine.release(hand).map_err(refused)
    }

    /// Numbers of the hands that hold a beam.
    #[getter]
    fn hands(&self) -> Vec<u32> {
        self.engine.hands()
    }

    /// The hand's position \[m\] (3,) and orientation (w, x, y, z) (4,) now.
    fn hand_pose<'py>(&self, py: Python<'py>, hand: u32) -> PyResult<PoseArrays<'py>> {
        let ((p, q), _) = self.engine.hand_pose(hand).map_err(refused)?;
        Ok((vector(py, p), quat_array(py, q)))
    }

    /// The load hand ``hand`` applied in the last step with its ergonomic assessment.
    fn hand_load(&self, hand: u32) -> PyResult<HandLoad> {
        let (load, assessment) = self.engine.hand_load(hand).map_err(refused)?;
        let hose = self.model().hoses[load.hose].name.clone();
        Ok(HandLoad::new(hand, hose, &load, assessment.as_ref()))
    }

    /// The force \[N\] hand ``hand`` applied to the hose in the last step, shape (3,).
    ///
    /// >>> import pliant, numpy as np
    /// >>> sim = pliant.Simulation(pliant.demo_scene())
    /// >>> _ = sim.grab(0, hose="lower", node=-1)
    /// >>> sim.step(20)
    /// >>> bool(np.linalg.norm(sim.hand_force(0)) > 0)  # it carries the hose's weight
    /// True
    fn hand_force<'py>(&self, py: Python<'py>, hand: u32) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (load, _) = self.engine.hand_load(hand).map_err(refused)?;
        Ok(vector(py, load.force))
    }

    /// The torque \[N·m\] hand ``hand`` applied about its position in the last step, (3,).
    fn hand_torque<'py>(&self, py: Python<'py>, hand: u32) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (load, _) = self.engine.hand_load(hand).map_err(refused)?;
        Ok(vector(py, load.torque))
    }

    // ---- arrays -----------------------------------------------------------------

    /// Node positions of a hose \[m\], shape (N, 3), float64 (a copy).
    fn positions<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.x)
    }

    /// Node orientations of a hose as unit quaternions (w, x, y, z), shape (N, 4): each
    /// node's material frame, local → global (local x along the hose).
    fn orientations<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.nodes(&hose)?;
        Ok(quaternions(py, self.engine.state().q[r].iter().copied()))
    }

    /// Node velocities \[m/s\], shape (N, 3).
    fn velocities<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.v)
    }

    /// Node angular velocities \[rad/s\] (global axes), shape (N, 3).
    fn angular_velocities<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.w)
    }

    /// Net force on each node in the last step — elastic, damping, gravity, dead loads,
    /// contact — without the supports' reactions \[N\], shape (N, 3). On a free node at
    /// static equilibrium it is zero.
    fn forces<'py>(&self, py: Python<'py>, hose: HoseRef) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.force)
    }

    /// Net moment on each node in the last step, without the supports' \[N·m\], (N, 3).
    fn moments<'py>(&self, py: Python<'py>, hose: HoseRef) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.moment)
    }

    /// Force the supports (fixes, drives, hands, fitted stubs and clips) applied to each
    /// node in the last step \[N\], (N, 3); zero on free nodes (see :meth:`held`).
    fn reaction_forces<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.reaction_force)
    }

    /// Moment the supports applied to each node in the last step \[N·m\], (N, 3).
    fn reaction_moments<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.reaction_moment)
    }

    /// Whether a support held each node in the last step, shape (N,), bool.
    fn held<'py>(&self, py: Python<'py>, hose: HoseRef) -> PyResult<Bound<'py, PyArray1<bool>>> {
        let r = self.nodes(&hose)?;
        Ok(PyArray1::from_slice(py, &self.engine.state().held[r]))
    }

    /// Force the rigid parts applied to each node by contact in the last step \[N\], (N, 3).
    fn contact_forces<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.contact_force)
    }

    /// Force other hoses (or the hose itself) applied to each node by contact in the last
    /// step \[N\], (N, 3).
    fn hose_contact_forces<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        self.vector_field(py, &hose, |s| &s.hose_contact_force)
    }

    /// Rest positions of a hose's nodes \[m\], (N, 3).
    fn rest_positions<'py>(
        &self,
        py: Python<'py>,
        hose: HoseRef,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.nodes(&hose)?;
        Ok(vectors(py, self.model().rest_x[r].iter().copied()))
    }

    /// Lumped node masses \[kg\], shape (N,) (physical: without the mass scaling).
    fn masses<'py>(&self, py: Python<'py>, hose: HoseRef) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let r = self.nodes(&hose)?;
        let model = self.model();
        let masses: Vec<f64> = model.mass[r]
            .iter()
            .map(|m| m / model.mass_scaling)
            .collect();
        Ok(PyArray1::from_vec(py, masses))
    }

    /// Kinetic energy \[J\].
    #[getter]
    fn kinetic_energy(&self) -> f64 {
        self.engine.state().kinetic_energy(self.model())
    }

    /// Elastic strain energy \[J\].
    #[getter]
    fn strain_energy(&self) -> f64 {
        self.engine.state().strain_energy(self.model())
    }

    /// Potential energy of gravity −Σ m g·x \[J\].
    #[getter]
    fn gravity_energy(&self) -> f64 {
        self.engine.state().gravity_energy(self.model())
    }

    /// The scene's stubs and clips now: name, kind, max_force \[N\], max_force_time \[s\],
    /// final_state (e.g. ``"approach"``, ``"fixed"``, ``"seated"``), assembled.
    fn fasteners<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.engine.fastener_reports())
    }

    /// The worker of the scene's ``[worker]`` so far (SPEC E1–E2), or ``None`` without
    /// one: ``who``, ``body`` (stature and segment lengths [m], joint limits [rad]),
    /// ``seat`` (a seated worker's ``height`` [m], ``None`` standing), ``placement``,
    /// ``instants``, ``class_instants`` (per posture class: ``upright``, ``bent_trunk``,
    /// ``arms_above_shoulder``, ``sitting``, ``sitting_bent_trunk``), ``reach`` (per arm, right then left: ``worst``
    /// residual [m], its ``time`` [s], ``hand``, ``first_out``, ``last_out``),
    /// ``collisions`` (segment, part, depth [m], times), ``worst_rula`` and
    /// ``worst_reba`` (every body-part score and the time), ``worst_posture``, ``steps``
    /// and ``step_count`` (the steps taken, ``[worker] steps``),
    /// ``findings`` (out of reach and body collisions, typed) and ``series``: one list per
    /// column of ``worker.csv`` (``time``, ``right_residual`` and ``left_residual`` —
    /// ``None`` where the arm has no target —, ``rula``, ``reba``, ``trunk_flexion``, …
    /// in SI, and ``posture_class``, the class's name at each instant; ``numpy.asarray``
    /// makes arrays of them).
    fn worker<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let Some(track) = self.engine.cell().worker() else {
            return Ok(py.None().into_bound(py));
        };
        let summary = track.summary();
        let series = track.series();
        let column = |f: &dyn Fn(&pliant_assembly::worker::WorkerSample) -> f64| {
            series.iter().map(f).collect::<Vec<f64>>()
        };
        let nan = f64::NAN;
        let mut value = serde_json::to_value(&summary)
            .map_err(|e| PyValueError::new_err(format!("internal error serialising: {e}")))?;
        value["findings"] = serde_json::json!(summary.findings());
        value["series"] = serde_json::json!({
                "time": column(&|w| w.time),
                "right_residual": column(&|w| w.residual[0].unwrap_or(nan)),
                "left_residual": column(&|w| w.residual[1].unwrap_or(nan)),
                "rula": column(&|w| w.rula as f64),
                "reba": column(&|w| w.reba as f64),
                "trunk_flexion": column(&|w| w.trunk_flexion),
                "trunk_lateral": column(&|w| w.trunk_lateral),
                "trunk_twist": column(&|w| w.trunk_twist),
                "neck_flexion": column(&|w| w.neck_flexion),
                "collision_depth": column(&|w| w.collision_depth),
                "posture_class": series.iter().map(|w| w.posture_class.name()).collect::<Vec<_>>(),
        });
        to_python(py, &value)
    }

    /// The range-of-motion study of the scene's ``[sweep]`` so far, or ``None`` without
    /// one: ``columns`` — the columns of ``motion.csv`` as ``pliant run`` writes them
    /// (``time_s``, the motion coordinate such as ``angle_deg``, per hose its bend radius,
    /// ratio, twist and axial force, per hose and part the clearance, the largest fixing
    /// force), each a numpy array with one value per checked instant, the same as
    /// ``RunResult.motion()``; ``worst`` — each quantity's worst value with its ``time``,
    /// ``coordinate`` (SI) and ``position`` in words ("door angle 70°");
    /// ``clearance_violations``; ``over_the_motion`` — the verdict's sentence.
    fn sweep<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, pyo3::types::PyDict>>> {
        match self.engine.cell().checks().sweep() {
            Some(sweep) => crate::motion_table::sweep_findings(py, sweep.summary()),
            None => Ok(None),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "<pliant.Simulation t = {:.6} s, step {}, {} hose(s), {} hand(s) holding{}>",
            self.engine.state().time,
            self.engine.state().step,
            self.model().hoses.len(),
            self.engine.hands().len(),
            if self.engine.diverged().is_some() {
                ", DIVERGED"
            } else {
                ""
            }
        )
    }
}

/// Both tolerances finite and positive, or a ValueError naming the bad one.
fn check_tolerances(force_tolerance: f64, moment_tolerance: f64) -> PyResult<()> {
    for (v, name) in [
        (force_tolerance, "force_tolerance"),
        (moment_tolerance, "moment_tolerance"),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(PyValueError::new_err(format!(
                "{name} must be finite and > 0, got {v}"
            )));
        }
    }
    Ok(())
}
