//! The interactive simulation behind `pliant.Simulation`, in plain Rust: the model, the
//! state, load cases added and removed by the user, hands, the scene's stubs and clips,
//! and the explicit step with a divergence check. Like the live session of
//! `pliant serve`, but stepped on request instead of in real time.

use glam::{DQuat, DVec3};
use pliant_assembly::ergonomics::{ErgonomicLimits, ErgonomicProfile, HandAssessment};
use pliant_assembly::fasteners::Fasteners;
use pliant_assembly::{Action, ClipSite, Hand, HandLoad, StubSite};
use pliant_core::health::{check, Divergence};
use pliant_core::loads::{DeadLoad, Drive, Fix, LoadCase, LoadCaseId};
use pliant_core::{Model, Solver, SolverKind, SolverSettings, State};
use pliant_scene::LoadedScene;
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

/// Health check interval in steps (as the timeline runner's).
const HEALTH_CHECK_EVERY: u64 = 16;

/// Why a request was refused (becomes ValueError / KeyError in Python).
#[derive(Debug, Clone, PartialEq)]
pub enum Refusal {
    /// An argument that does not fit the current state.
    Invalid(String),
    /// A load case or hand that is not there.
    Missing(String),
}

/// The simulation.
pub struct Engine {
    pub model: Arc<Model>,
    pub state: State,
    /// Hands by number.
    hands: BTreeMap<u32, Hand>,
    fasteners: Fasteners,
    sites: (Vec<StubSite>, Vec<ClipSite>),
    /// Load cases the user added (the ones `remove_load` may remove).
    user_loads: BTreeSet<LoadCaseId>,
    /// The scene's leading fixes and dead loads, applied at the start and on reset.
    initial: Vec<Action>,
    pub profile: ErgonomicProfile,
    limits: Option<&'static ErgonomicLimits>,
    /// Hand forces of the last step (scratch for the fasteners).
    hand_forces: Vec<(u32, DVec3)>,
    /// Set once the state has diverged; stepping is refused until `reset`.
    diverged: Option<Divergence>,
    /// Advances the state: the scene's solver unless chosen otherwise (issue 5).
    solver: Solver,
}

/// A scene's initial load cases: the leading fixes and dead loads of its timeline, up to
/// the first action that takes time or involves a hand (as `pliant serve` starts).
pub fn initial_actions(scene: &LoadedScene) -> Vec<Action> {
    scene
        .timeline
        .actions
        .iter()
        .take_while(|a| matches!(a, Action::Fix { .. } | Action::Load { .. }))
        .cloned()
        .collect()
}

impl Engine {
    /// A simulation of `scene` at rest in its rest shape, with `initial` applied.
    pub fn new(
        model: Arc<Model>,
        scene: &LoadedScene,
        initial: Vec<Action>,
    ) -> Result<Engine, String> {
        let sites = scene.fastener_sites(&model)?;
        let mut state = State::at_rest(&model);
        let fasteners = Fasteners::new(&mut state, sites.0.clone(), sites.1.clone());
        let mut engine = Engine {
            model: model.clone(),
            state,
            hands: BTreeMap::new(),
            fasteners,
            sites,
            user_loads: BTreeSet::new(),
            initial,
            profile: scene.ergonomics,
            limits: ErgonomicLimits::builtin().ok(),
            hand_forces: Vec::new(),
            diverged: None,
            solver: Solver::for_model(&model).map_err(|e| e.to_string())?,
        };
        engine.apply_initial();
        Ok(engine)
    }

    fn apply_initial(&mut self) {
        for a in self.initial.clone() {
            match a {
                Action::Fix { node } => {
                    let i = self.model.hoses[node.hose].node(node.node);
                    let _ = self.fix(i);
                }
                Action::Load {
                    node,
                    force,
                    moment,
                } => {
                    let i = self.model.hoses[node.hose].node(node.node);
                    self.dead_load(i, force, moment);
                }
                _ => {}
            }
        }
    }

    /// Back to rest in the rest shape at t = 0: hands released, user load cases removed,
    /// the initial load cases applied again, stubs and clips reset.
    pub fn reset(&mut self) {
        self.state = State::at_rest(&self.model);
        self.fasteners = Fasteners::new(
            &mut self.state,
            self.sites.0.clone(),
            self.sites.1.clone(),
        );
        self.hands.clear();
        self.user_loads.clear();
        self.diverged = None;
        self.solver.restart();
        self.apply_initial();
    }

    /// Advances with `kind` from now on (explicit, implicit or static).
    pub fn set_solver(&mut self, kind: SolverKind) -> Result<(), String> {
        let settings = SolverSettings {
            kind,
            ..self.model.solver
        };
        self.solver = Solver::new(&self.model, settings).map_err(|e| e.to_string())?;
        Ok(())
    }

    /// The solver in use.
    pub fn solver(&self) -> &Solver {
        &self.solver
    }

    /// Simulated time one step advances [s].
    pub fn time_step(&self) -> f64 {
        self.solver.time_step(&self.model)
    }

    /// The divergence that stopped the simulation, if any.
    pub fn diverged(&self) -> Option<&Divergence> {
        self.diverged.as_ref()
    }

    /// Records the outcome of stepping: a divergence stops the simulation.
    pub(crate) fn record(&mut self, outcome: &Result<(), Divergence>) {
        if let Err(d) = outcome {
            self.diverged = Some(d.clone());
        }
    }

    /// One step of the solver: hands move their held nodes, stubs and clips act, the state
    /// advances; the state is checked every few steps.
    pub(crate) fn step_once(&mut self) -> Result<(), Divergence> {
        let t_next = self.state.time + self.solver.time_step(&self.model);
        for hand in self.hands.values() {
            hand.update(&mut self.state, t_next);
        }
        if !self.fasteners.is_empty() {
            self.hand_forces.clear();
            for (&k, h) in &self.hands {
                self.hand_forces
                    .push((k, h.load(&self.model, &self.state).force));
            }
            let (hands, forces) = (&self.hands, &self.hand_forces);
            let holder = |node: usize| {
                hands
                    .iter()
                    .find(|(_, h)| h.holds(node))
                    .map(|(k, _)| *k)
            };
            let held = |node: usize| holder(node).is_some();
            let force = |node: usize| {
                holder(node)
                    .and_then(|k| forces.iter().find(|(h, _)| *h == k))
                    .map_or(DVec3::ZERO, |(_, f)| *f)
            };
            self.fasteners
                .update(&self.model, &mut self.state, &held, &force);
        }
        if let Err(e) = self.solver.step(&self.model, &mut self.state) {
            return Err(e.into_divergence(&self.model, &self.state));
        }
        if self.state.step % HEALTH_CHECK_EVERY == 0 {
            check(&self.model, &self.state)?;
        }
        Ok(())
    }

    /// `n` steps, then a health check, so that a successful call never leaves non-finite
    /// values behind. After a divergence every call fails until [`Engine::reset`].
    pub fn steps(&mut self, n: u64) -> Result<(), Divergence> {
        if let Some(d) = &self.diverged {
            return Err(d.clone());
        }
        let run = (|| {
            for _ in 0..n {
                self.step_once()?;
            }
            check(&self.model, &self.state)
        })();
        self.record(&run);
        run
    }

    /// Whether a hand or a drive is still moving.
    pub fn moving(&self) -> bool {
        let t = self.state.time;
        self.state.loads.any_drive_moving(t) || self.hands.values().any(|h| h.moving(t))
    }

    // ---- load cases -------------------------------------------------------------

    fn hand_holding(&self, node: usize) -> Option<u32> {
        self.hands
            .iter()
            .find(|(_, h)| h.holds(node))
            .map(|(k, _)| *k)
    }

    /// Removes the user's fixes and drives on `node` (the new one replaces them); refuses
    /// a node a hand holds.
    fn take_node(&mut self, node: usize) -> Result<(), Refusal> {
        if let Some(k) = self.hand_holding(node) {
            return Err(Refusal::Invalid(format!(
                "hand {k} holds this node; release the hand first"
            )));
        }
        let replaced: Vec<LoadCaseId> = self
            .state
            .loads
            .iter()
            .filter(|(id, c)| {
                c.node() == node
                    && !matches!(c, LoadCase::DeadLoad(_))
                    && self.user_loads.contains(id)
            })
            .map(|(id, _)| *id)
            .collect();
        for id in replaced {
            self.state.loads.remove(id);
            self.user_loads.remove(&id);
        }
        Ok(())
    }

    /// Holds global node `node` where it is now (position and orientation).
    pub fn fix(&mut self, node: usize) -> Result<LoadCaseId, Refusal> {
        self.take_node(node)?;
        let id = self.state.loads.add(LoadCase::Fix(Fix {
            node,
            position: self.state.x[node],
            orientation: self.state.q[node],
        }));
        self.user_loads.insert(id);
        Ok(id)
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
        self.take_node(node)?;
        let start = (self.state.x[node], self.state.q[node]);
        let drive = Drive::new(node, start, waypoints, rotation, self.state.time, duration);
        let id = self.state.loads.add(LoadCase::Drive(drive));
        self.user_loads.insert(id);
        Ok(id)
    }

    /// Adds a constant force and moment (global axes) at global node `node`.
    pub fn dead_load(&mut self, node: usize, force: DVec3, moment: DVec3) -> LoadCaseId {
        let id = self.state.loads.add(LoadCase::DeadLoad(DeadLoad {
            node,
            force,
            moment,
        }));
        self.user_loads.insert(id);
        id
    }

    /// Removes a load case the user added.
    pub fn remove_load(&mut self, id: LoadCaseId) -> Result<LoadCase, Refusal> {
        if !self.user_loads.remove(&id) {
            return Err(Refusal::Missing(format!(
                "load case {} is not active (removed, replaced by a later fix or drive on its node, or reset)",
                id.0
            )));
        }
        self.state
            .loads
            .remove(id)
            .ok_or_else(|| Refusal::Missing(format!("load case {} is not active", id.0)))
    }

    /// The user's active load cases.
    pub fn user_loads(&self) -> impl Iterator<Item = (LoadCaseId, &LoadCase)> {
        self.state
            .loads
            .iter()
            .filter(|(id, _)| self.user_loads.contains(id))
            .map(|(id, c)| (*id, c))
    }

    // ---- hands ------------------------------------------------------------------

    /// Hand `hand` grabs the beam nearest to `point` (letting go of what it held);
    /// returns the beam's element index.
    pub fn grab(&mut self, hand: u32, point: DVec3) -> Result<usize, Refusal> {
        if let Some(old) = self.hands.remove(&hand) {
            old.release(&mut self.state);
        }
        // the hand's fixes replace the user's fixes and drives on the beam's nodes
        let element = pliant_assembly::hand::nearest_beam(&self.model, &self.state, point)
            .ok_or_else(|| Refusal::Invalid("there is no beam to grab".into()))?;
        let el = &self.model.elements[element];
        let nodes = [el.node_a, el.node_b];
        if let Some(other) = nodes.iter().find_map(|&n| self.hand_holding(n)) {
            return Err(Refusal::Invalid(format!(
                "hand {other} already holds that beam; release it first"
            )));
        }
        for n in nodes {
            self.take_node(n)?;
        }
        let h = Hand::grab(&self.model, &mut self.state, point)
            .ok_or_else(|| Refusal::Invalid("there is no beam to grab".into()))?;
        let element = h.element;
        self.hands.insert(hand, h);
        Ok(element)
    }

    fn hand(&self, hand: u32) -> Result<&Hand, Refusal> {
        self.hands
            .get(&hand)
            .ok_or_else(|| Refusal::Invalid(format!("hand {hand} holds nothing; grab first")))
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
        self.hand(hand)?;
        let t = self.state.time;
        if let Some(h) = self.hands.get_mut(&hand) {
            h.move_along(waypoints, rotation, t, duration);
        }
        Ok(())
    }

    /// The rotation vector that turns hand `hand` from its orientation now to `target`
    /// (the shorter way).
    pub fn rotation_to(&self, hand: u32, target: DQuat) -> Result<DVec3, Refusal> {
        let (_, q) = self.hand(hand)?.pose_at(self.state.time);
        let mut d = (target * q.conjugate()).normalize();
        if d.w < 0.0 {
            d = -d;
        }
        Ok(d.to_scaled_axis())
    }

    /// Hand `hand` lets go.
    pub fn release(&mut self, hand: u32) -> Result<(), Refusal> {
        let h = self
            .hands
            .remove(&hand)
            .ok_or_else(|| Refusal::Invalid(format!("hand {hand} holds nothing")))?;
        h.release(&mut self.state);
        Ok(())
    }

    /// Numbers of the hands holding a beam.
    pub fn hands(&self) -> Vec<u32> {
        self.hands.keys().copied().collect()
    }

    /// The hand's pose now and the beam it holds.
    pub fn hand_pose(&self, hand: u32) -> Result<((DVec3, DQuat), usize), Refusal> {
        let h = self.hand(hand)?;
        Ok((h.pose_at(self.state.time), h.element))
    }

    /// The load hand `hand` applied in the last step and its ergonomic assessment.
    pub fn hand_load(&self, hand: u32) -> Result<(HandLoad, Option<HandAssessment>), Refusal> {
        let load = self.hand(hand)?.load(&self.model, &self.state);
        let assessment = self.limits.and_then(|l| {
            l.assess(&self.profile, load.force, load.torque, load.direction)
                .ok()
        });
        Ok((load, assessment))
    }

    /// The stubs' and clips' states now.
    pub fn fastener_reports(&self) -> Vec<pliant_assembly::FastenerReport> {
        self.fasteners.reports()
    }
}
