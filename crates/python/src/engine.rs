//! The interactive simulation behind `pliant.Simulation`: a thin shell over the scene's
//! [`Workcell`] — the same step, grab rules, stubs, clips and verdict as `pliant run` and
//! `pliant serve` — addressed by global node indices and hand numbers, stepped on
//! request instead of in real time. Every call that changes the study is a workcell
//! input, so a Python session has an input log like a live one.

use glam::{DQuat, DVec3};
use pliant_assembly::ergonomics::HandAssessment;
use pliant_assembly::workcell::{node_ref, rotation_between_poses, Refusal as CellRefusal};
use pliant_assembly::{
    Applied, HandLoad, InitialLoad, Input, NoObserver, Workcell, WorkcellError, WorkcellOptions,
    WorkcellSetup,
};
use pliant_core::health::Divergence;
use pliant_core::loads::{LoadCase, LoadCaseId};
use pliant_core::{Model, Solver, SolverKind, State};
use pliant_scene::LoadedScene;
use std::sync::Arc;

/// Why a request was refused (becomes ValueError / KeyError in Python).
#[derive(Debug, Clone, PartialEq)]
pub enum Refusal {
    /// An argument that does not fit the current state.
    Invalid(String),
    /// A load case or hand that is not there.
    Missing(String),
}

impl From<CellRefusal> for Refusal {
    fn from(r: CellRefusal) -> Self {
        match r {
            CellRefusal::Missing(m) => Refusal::Missing(m),
            other => Refusal::Invalid(other.to_string()),
        }
    }
}

/// The simulation.
pub struct Engine {
    cell: Workcell,
}

impl Engine {
    /// A simulation of `scene` at rest in its rest shape, with `initial` applied,
    /// advanced by `solver` (the scene's if `None`).
    pub fn new(
        model: Arc<Model>,
        scene: &LoadedScene,
        initial: Vec<InitialLoad>,
        solver: Option<SolverKind>,
    ) -> Result<Engine, String> {
        let setup = scene.workcell_setup_of(model).map_err(|e| match e {
            // the caller names the scene
            WorkcellError::Fasteners { reason, .. } => reason,
            e => e.to_string(),
        })?;
        let setup = WorkcellSetup { initial, ..setup };
        let options = WorkcellOptions {
            solver,
            ..Default::default()
        };
        Ok(Engine {
            cell: Workcell::new(setup, options).map_err(|e| e.to_string())?,
        })
    }

    pub fn model(&self) -> &Arc<Model> {
        self.cell.model()
    }

    pub fn state(&self) -> &State {
        self.cell.state()
    }

    fn give(&mut self, input: Input) -> Result<Applied, Refusal> {
        self.cell.apply(input).map_err(Refusal::from)
    }

    fn node(&self, global: usize) -> Result<pliant_assembly::NodeRef, Refusal> {
        node_ref(self.model(), global)
            .ok_or_else(|| Refusal::Invalid(format!("node {global} does not exist")))
    }

    /// Back to rest in the rest shape at t = 0: hands released, user load cases removed,
    /// the initial load cases applied again, stubs and clips reset.
    pub fn reset(&mut self) {
        let _ = self.give(Input::Reset);
    }

    /// The solver in use.
    pub fn solver(&self) -> &Solver {
        self.cell.solver()
    }

    /// Simulated time one step advances \[s\].
    pub fn time_step(&self) -> f64 {
        self.cell.time_step()
    }

    /// The divergence that stopped the simulation, if any.
    pub fn diverged(&self) -> Option<&Divergence> {
        self.cell.diverged()
    }

    /// The workcell itself (for reading).
    pub fn cell(&self) -> &Workcell {
        &self.cell
    }

    /// The Newton solvers' account so far (unconverged steps, instabilities met).
    pub fn solver_record(&self) -> &pliant_assembly::workcell::SolverRecord {
        &self.cell.tally().solver
    }

    /// The workcell itself (for [`Engine::settle`], which steps it).
    pub(crate) fn cell_mut(&mut self) -> &mut Workcell {
        &mut self.cell
    }

    /// `n` steps, then a health check, so that a successful call never leaves non-finite
    /// values behind. After a divergence every call fails until [`Engine::reset`].
    pub fn steps(&mut self, n: u64) -> Result<(), Divergence> {
        self.cell.steps(n, &mut NoObserver)
    }

    /// Whether a hand or a drive is still moving.
    pub fn moving(&self) -> bool {
        self.cell.moving()
    }

    /// The static equilibrium under the current loads (quasi-static Newton).
    pub fn solve_static(
        &mut self,
        force_tolerance: f64,
        moment_tolerance: f64,
        max_iterations: usize,
    ) -> Result<pliant_core::integrators::StaticReport, Refusal> {
        match self.give(Input::SolveStatic {
            force_tolerance,
            moment_tolerance,
            max_iterations,
            stable_only: false,
        })? {
            Applied::Static(r) => Ok(r),
            _ => Err(Refusal::Invalid("the static solve reported nothing".into())),
        }
    }

    // ---- load cases -------------------------------------------------------------

    fn load_id(applied: Applied) -> Result<LoadCaseId, Refusal> {
        match applied {
            Applied::Load(id) => Ok(id),
            _ => Err(Refusal::Invalid("no load case was added".into())),
        }
    }

    /// Holds global node `node` where it is now (position and orientation).
    pub fn fix(&mut self, node: usize) -> Result<LoadCaseId, Refusal> {
        let node = self.node(node)?;
        Self::load_id(self.give(Input::Fix { node })?)
    }

    /// Drives global node `node` through `waypoints` and turns it by the rotation vector
    /// `rotation` over `duration` seconds from now; it stays held at the end pose.
    pub fn drive(
        &mut self,
        node: usize,
        waypoints: &[DVec3],
        rotation: DVec3,
        duration: f64,
    ) -> Result<LoadCaseId, Refusal> {
        let node = self.node(node)?;
        Self::load_id(self.give(Input::Drive {
            node,
            waypoints: waypoints.to_vec(),
            rotation,
            duration,
        })?)
    }

    /// Adds a force and moment (global axes) at global node `node`, rising over `ramp`
    /// seconds (0: at once).
    pub fn dead_load(
        &mut self,
        node: usize,
        force: DVec3,
        moment: DVec3,
        ramp: f64,
    ) -> Result<LoadCaseId, Refusal> {
        let node = self.node(node)?;
        Self::load_id(self.give(Input::Load {
            node,
            ramp,
            name: None,
            force,
            moment,
        })?)
    }

    /// Removes a load case the user added.
    pub fn remove_load(&mut self, id: LoadCaseId) -> Result<LoadCase, Refusal> {
        let case = self
            .cell
            .user_loads()
            .find(|(i, _)| *i == id)
            .map(|(_, c)| c.clone());
        self.give(Input::RemoveLoad { id: id.0 })?;
        case.ok_or_else(|| Refusal::Missing(format!("load case {} is not active", id.0)))
    }

    /// The user's active load cases.
    pub fn user_loads(&self) -> impl Iterator<Item = (LoadCaseId, &LoadCase)> {
        self.cell.user_loads()
    }

    // ---- hands ------------------------------------------------------------------

    /// Hand `hand` grabs the beam nearest to `point` (letting go of what it held);
    /// returns the beam's element index. Refused — the hand keeping its grip — if
    /// another hand holds that beam.
    pub fn grab(
        &mut self,
        hand: u32,
        point: DVec3,
        grip: pliant_assembly::Grip,
    ) -> Result<usize, Refusal> {
        match self.give(Input::Grab {
            grip,
            hand,
            at: point,
        })? {
            Applied::Grabbed { element } => Ok(element),
            _ => Err(Refusal::Invalid("nothing was grabbed".into())),
        }
    }

    /// Moves hand `hand` through `waypoints` turning by the rotation vector `rotation`
    /// over `duration` seconds from now, with a smooth start and stop.
    pub fn move_hand(
        &mut self,
        hand: u32,
        waypoints: &[DVec3],
        rotation: DVec3,
        duration: f64,
    ) -> Result<(), Refusal> {
        self.give(Input::MoveHand {
            hand,
            waypoints: waypoints.to_vec(),
            rotation,
            duration,
        })
        .map(|_| ())
    }

    /// Moves or turns a part ([`Input::MovePart`], [`Input::RotatePart`]).
    pub fn move_part(&mut self, input: Input) -> Result<(), Refusal> {
        self.give(input).map(|_| ())
    }

    /// Part `part`'s pose now (identity for a part that stands still).
    pub fn part_pose(&self, part: &str) -> Result<pliant_core::kinematics::Pose, Refusal> {
        let k = pliant_assembly::workcell::part_inputs::part_named(self.model(), part, "part")?;
        let state = self.state();
        Ok(self
            .model()
            .kinematics
            .placement_at(k, state.time, &state.part_moves)
            .pose)
    }

    /// Hand `hand` heads for `position` (and `orientation`) at bounded speed and
    /// acceleration, as a live hand does.
    pub fn aim_hand(
        &mut self,
        hand: u32,
        position: DVec3,
        orientation: Option<DQuat>,
    ) -> Result<(), Refusal> {
        self.give(Input::AimHand {
            hand,
            position,
            orientation,
        })
        .map(|_| ())
    }

    /// The rotation vector that turns hand `hand` from its orientation now to `target`
    /// (the shorter way).
    pub fn rotation_to(&self, hand: u32, target: DQuat) -> Result<DVec3, Refusal> {
        let (_, q) = self.cell.hand(hand)?.pose_at(self.state().time);
        Ok(rotation_between_poses(q, target))
    }

    /// Hand `hand` lets go.
    pub fn release(&mut self, hand: u32) -> Result<(), Refusal> {
        self.give(Input::ReleaseHand { hand }).map(|_| ())
    }

    /// Numbers of the hands holding a beam.
    pub fn hands(&self) -> Vec<u32> {
        self.cell.hands().map(|(k, _)| k).collect()
    }

    /// The hand's pose now and the beam it holds.
    pub fn hand_pose(&self, hand: u32) -> Result<((DVec3, DQuat), usize), Refusal> {
        let h = self.cell.hand(hand)?;
        Ok((h.pose_at(self.state().time), h.hand.element))
    }

    /// The load hand `hand` applied in the last step and its ergonomic assessment.
    pub fn hand_load(&self, hand: u32) -> Result<(HandLoad, Option<HandAssessment>), Refusal> {
        let r = self.cell.hand_record(hand)?;
        Ok((r.load, r.assessment))
    }

    /// The stubs' and clips' states now.
    pub fn fastener_reports(&self) -> Vec<pliant_assembly::FastenerReport> {
        self.cell.fastener_reports()
    }
}
