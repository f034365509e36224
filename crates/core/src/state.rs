//! The State: where the world is now (positions, orientations, velocities, active load
//! cases, last reactions). A step reads the Model and writes the State; a snapshot is a
//! clone of the State.

use crate::contact::friction::FrictionMemory;
use crate::contact::{ContactScratch, HoseContactScratch};
use crate::loads::LoadCases;
use crate::rod::element::BeamElement;
use crate::rod::inelastic::HistoryView;
use crate::rod::stiffened::BodyState;
use crate::sleep::Sleep;
use crate::Model;
use glam::{DQuat, DVec3};

#[derive(Clone, Debug)]
pub struct State {
    /// Simulated time \[s\].
    pub time: f64,
    /// Steps taken.
    pub step: u64,
    /// Node positions \[m\].
    pub x: Vec<DVec3>,
    /// Node material frames (local → global), unit quaternions.
    pub q: Vec<DQuat>,
    /// Node velocities \[m/s\].
    pub v: Vec<DVec3>,
    /// Node angular velocities, global axes \[rad/s\].
    pub w: Vec<DVec3>,
    /// Total force on each node in the last step, support reactions excluded \[N\].
    pub force: Vec<DVec3>,
    /// Total moment on each node in the last step, support reactions excluded \[N·m\].
    pub moment: Vec<DVec3>,
    /// Force the supports (fix / drive) applied to each node in the last step \[N\]; zero
    /// for free nodes.
    pub reaction_force: Vec<DVec3>,
    /// Moment the supports applied to each node in the last step \[N·m\].
    pub reaction_moment: Vec<DVec3>,
    /// Whether a kinematic load case held the node in the last step.
    pub held: Vec<bool>,
    /// Active load cases.
    pub loads: LoadCases,
    /// Force the rigid parts applied to each node in the last step \[N\] (SPEC I2).
    pub contact_force: Vec<DVec3>,
    /// Contact memory (sides of surfaces) and per-step contact list.
    pub contact: ContactScratch,
    /// Where each node's friction spring is anchored, and whether it slides (the Newton
    /// solvers' friction, [`crate::contact::friction`]).
    pub friction: FrictionMemory,
    /// Pose and velocity of each stiffened section (SPEC M6).
    pub bodies: Vec<BodyState>,
    /// Force other hoses, or the hose itself, applied to each node by contact in the last
    /// step \[N\] (SPEC L5); included in `force`.
    pub hose_contact_force: Vec<DVec3>,
    /// Hose–hose contact broad phase and per-beam data, allocated once.
    pub hose_contact: HoseContactScratch,
    /// Which hoses sleep (SPEC I6; off unless enabled).
    pub sleep: Sleep,
    /// What the implicit solver carries from step to step (empty for the others).
    pub implicit: ImplicitHistory,
    /// The inelastic elements' history — a yielding element's plastic strains, a relaxing
    /// element's viscous strains — committed at the last accepted step or equilibrium
    /// ([`crate::rod::inelastic`]); empty when no element is inelastic.
    pub inelastic_history: Vec<f64>,
    /// When `inelastic_history` was committed \[s\].
    pub inelastic_time: f64,
    /// The parts inputs moved, and how ([`crate::kinematics::PartMoves`]).
    pub part_moves: crate::kinematics::PartMoves,
}

impl State {
    /// The rest state of a model: at rest, in the rest shape, no load cases.
    pub fn at_rest(model: &Model) -> State {
        let n = model.node_count();
        State {
            time: 0.0,
            step: 0,
            x: model.rest_x.clone(),
            q: model.rest_q.clone(),
            v: vec![DVec3::ZERO; n],
            w: vec![DVec3::ZERO; n],
            force: vec![DVec3::ZERO; n],
            moment: vec![DVec3::ZERO; n],
            reaction_force: vec![DVec3::ZERO; n],
            reaction_moment: vec![DVec3::ZERO; n],
            held: vec![false; n],
            loads: LoadCases::default(),
            contact_force: vec![DVec3::ZERO; n],
            contact: ContactScratch::new(model),
            friction: FrictionMemory::new(&model.rest_x),
            bodies: model
                .bodies
                .iter()
                .map(|b| BodyState {
                    centre: b.rest_centre,
                    orientation: b.rest_orientation,
                    velocity: DVec3::ZERO,
                    angular_velocity: DVec3::ZERO,
                })
                .collect(),
            hose_contact_force: vec![DVec3::ZERO; n],
            hose_contact: HoseContactScratch::new(model),
            sleep: Sleep::new(model),
            implicit: ImplicitHistory::default(),
            inelastic_history: vec![0.0; model.inelastic.history_len],
            inelastic_time: 0.0,
            part_moves: Default::default(),
        }
    }

    /// Kinetic energy Σ ½ m v² + ½ I ω² \[J\].
    pub fn kinetic_energy(&self, model: &Model) -> f64 {
        let mut e = 0.0;
        for i in 0..self.x.len() {
            e += 0.5
                * (model.mass[i] * self.v[i].length_squared()
                    + model.inertia[i] * self.w[i].length_squared());
        }
        if model.has_own_masses() {
            e += model.own_mass_kinetic_energy((&self.x, &self.q), (&self.v, &self.w));
        }
        e
    }

    /// The inelastic elements' committed history, aged to the state's time.
    pub fn inelastic_view(&self) -> HistoryView<'_> {
        self.inelastic_view_at(self.time)
    }

    /// The inelastic elements' committed history, aged to time `t`.
    pub fn inelastic_view_at(&self, t: f64) -> HistoryView<'_> {
        HistoryView {
            values: &self.inelastic_history,
            age: self.inelastic_age(t),
        }
    }

    /// Time from the commit of the inelastic elements' history to `t` \[s\] (≥ 0).
    pub fn inelastic_age(&self, t: f64) -> f64 {
        (t - self.inelastic_time).max(0.0)
    }

    /// Commits the inelastic elements' history at the state's configuration as of time
    /// `t` ([`crate::rod::inelastic::InelasticElements::commit`]) for `elements` (the
    /// model's, or a solver's copy with rigid spans made elastic).
    pub fn commit_inelastic(&mut self, model: &Model, elements: &[BeamElement], t: f64) {
        if model.inelastic.any() {
            let age = self.inelastic_age(t);
            let history = &mut self.inelastic_history;
            model
                .inelastic
                .commit(elements, (&self.x, &self.q), age, history);
            self.inelastic_time = t;
        }
    }

    /// Strain energy stored in all elements \[J\] (an inelastic element's with its
    /// committed history).
    pub fn strain_energy(&self, model: &Model) -> f64 {
        model
            .elements
            .iter()
            .map(|e| {
                let x = [self.x[e.node_a], self.x[e.node_b]];
                let q = [self.q[e.node_a], self.q[e.node_b]];
                match &e.inelastic {
                    Some(inelastic) => {
                        let history = self.inelastic_view();
                        model
                            .inelastic
                            .strain_energy(e, inelastic, history, (x, q), false)
                    }
                    None => e.strain_energy(x, q),
                }
            })
            .sum()
    }

    /// Potential energy of gravity −Σ m g·x \[J\] (a junction body's own mass at its
    /// centre of mass).
    pub fn gravity_energy(&self, model: &Model) -> f64 {
        let nodes = -(0..self.x.len())
            .map(|i| model.mass[i] * model.gravity.dot(self.x[i]))
            .sum::<f64>();
        if model.has_own_masses() {
            nodes + model.own_mass_gravity_energy(&self.x, &self.q)
        } else {
            nodes
        }
    }
}

/// What the HHT-α step ([`crate::integrators::implicit`]) carries from one step to the next — a_n, α_n and f_n, m_n of the
/// last converged step. Part of the [`State`] (`state.implicit`), so that a state saved
/// and restored continues exactly, and a fresh state (a reset) starts the history anew.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImplicitHistory {
    pub(crate) acc: Vec<DVec3>,
    pub(crate) ang_acc: Vec<DVec3>,
    pub(crate) f_prev: Vec<DVec3>,
    pub(crate) m_prev: Vec<DVec3>,
    /// Whether the vectors hold the last step's values (false: initialise them first).
    pub(crate) started: bool,
    /// Initialise with zero accelerations ([`Self::restart_at_rest`]).
    pub(crate) zero_acceleration: bool,
}

impl ImplicitHistory {
    /// Forgets the last step's accelerations (after the state was changed from outside).
    pub fn restart(&mut self) {
        self.started = false;
        self.zero_acceleration = false;
    }

    /// Restarts from a state the caller has just brought to rest (velocities zeroed, as
    /// kinetic damping does): accelerations start at zero too, so the out-of-balance
    /// forces act through the next step's equation only, without a kick through the
    /// Newmark predictor terms.
    pub fn restart_at_rest(&mut self) {
        self.started = false;
        self.zero_acceleration = true;
    }
}
