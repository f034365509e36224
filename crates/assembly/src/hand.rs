//! Hands (SPEC I1, I2; dissertation eq. 5.2): a hand grabs the beam nearest to a point and
//! its two nodes follow the hand rigidly — each node's target is the hand pose times the
//! node's offset from the hand at grab time, T = H_t · H_0⁻¹ · T_0 — as fix load cases
//! whose pose the hand updates every step. The load the hand applies is the sum of the
//! two supports' forces, and their moments plus the forces' moments about the hand point.
//! A loose grip ([`Grip`]) holds the node positions only, on supports the hand moves.

use crate::grip::Grip;
use glam::{DQuat, DVec3};
use pliant_core::loads::{DeadLoad, Fix, LoadCase, LoadCaseId, LoadRamp, Motion, Support};
use pliant_core::{Model, State};
use serde::Serialize;

/// How long a hand takes to let go \[s\] ([`Hand::let_go`]): the order of a voluntary
/// opening of the grip (an assumption), and many periods of a hose's fast axial modes
/// (≈ 8 ms for the demo's 0.76 m coolant hose: length over wave speed, both ways).
pub const RELEASE_TIME: f64 = 0.1;

/// A hand holding one beam.
#[derive(Clone, Debug)]
pub struct Hand {
    /// Index of the beam held.
    pub element: usize,
    /// The hose the beam belongs to.
    pub hose: usize,
    motion: Motion,
    /// (global node, its fix load case, offset position and rotation in the hand frame);
    /// the first `count` are used.
    held: [(usize, LoadCaseId, DVec3, DQuat); 2],
    count: usize,
    grip: Grip,
}

/// The load a hand applies to the hose in one step (global axes).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct HandLoad {
    /// The hose the hand holds.
    pub hose: usize,
    /// Hand position \[m\].
    pub position: DVec3,
    /// Force the hand applies \[N\].
    pub force: DVec3,
    /// Torque the hand applies about its position \[N·m\].
    pub torque: DVec3,
    /// Reference direction for push/pull: the held beam's axis, pointing towards the
    /// nearer end of the hose (pushing a hose end onto a stub is a push).
    pub direction: DVec3,
}

/// Index of the beam whose centre-line segment passes closest to `point`.
pub fn nearest_beam(model: &Model, state: &State, point: DVec3) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (e, el) in model.elements.iter().enumerate() {
        let (a, b) = (state.x[el.node_a], state.x[el.node_b]);
        let ab = b - a;
        let t = ((point - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        let d = (a + t * ab - point).length_squared();
        if best.is_none_or(|(_, bd)| d < bd) {
            best = Some((e, d));
        }
    }
    best.map(|(e, _)| e)
}

impl Hand {
    /// Grabs the beam nearest to `point` with a firm grip ([`Hand::grab_with`]).
    pub fn grab(model: &Model, state: &mut State, point: DVec3) -> Option<Hand> {
        Self::grab_with(model, state, point, Grip::Firm)
    }

    /// Grabs the beam nearest to `point` with `grip`; the hand's frame starts at `point`
    /// when that lies within the hose (a click on its surface), otherwise at the nearest
    /// point of the beam's chord — a hand holds the hose where the hose is, never through
    /// a lever of empty space (a grab beside the hose, e.g. a re-grab at a spot the hose
    /// has since left, would otherwise hold it at arm's length and drag it further off
    /// with each re-grab). Loose grips: at the nearest point
    /// of the chord, `ball` at its nearer node; the global orientation. Any other fix or drive on the held nodes is replaced.
    /// Firm: each node fixed (L1); loose: each held node on a support holding its
    /// position only (all rotations free).
    pub fn grab_with(model: &Model, state: &mut State, point: DVec3, grip: Grip) -> Option<Hand> {
        let element = nearest_beam(model, state, point)?;
        let el = &model.elements[element];
        let hose = model
            .hoses
            .iter()
            .position(|h| h.nodes().contains(&el.node_a))?;
        let (a, b) = (state.x[el.node_a], state.x[el.node_b]);
        let t = ((point - a).dot(b - a) / (b - a).length_squared().max(f64::MIN_POSITIVE))
            .clamp(0.0, 1.0);
        let on_chord = a + t * (b - a);
        let within =
            (point - on_chord).length() <= model.radius[el.node_a].max(model.radius[el.node_b]);
        let (nodes, point): (&[usize], DVec3) = match grip {
            Grip::Firm if within => (&[el.node_a, el.node_b], point),
            Grip::Firm => (&[el.node_a, el.node_b], on_chord),
            Grip::Axial => (&[el.node_a, el.node_b], on_chord),
            Grip::Ball if t < 0.5 => (&[el.node_a], a),
            Grip::Ball => (&[el.node_b], b),
        };
        let mut held = [(
            0,
            pliant_core::loads::LoadCaseId(0),
            DVec3::ZERO,
            DQuat::IDENTITY,
        ); 2];
        for (slot, &node) in nodes.iter().enumerate() {
            // what holds the node goes, and what an earlier hand left fading there; the
            // node's own dead loads stay
            state.loads.remove_on_node(
                node,
                |c| !matches!(c, LoadCase::DeadLoad(d) if !d.is_release()),
            );
            let (position, orientation) = (state.x[node], state.q[node]);
            let case = match grip {
                Grip::Firm => LoadCase::Fix(Fix {
                    node,
                    position,
                    orientation,
                }),
                Grip::Axial | Grip::Ball => LoadCase::Support(Support::new(
                    node,
                    position,
                    orientation,
                    DQuat::IDENTITY,
                    [false; 3],
                    [true; 3],
                    0.0,
                )),
            };
            let id = state.loads.add(case);
            held[slot] = (node, id, position - point, orientation);
        }
        Some(Hand {
            element,
            hose,
            motion: Motion::hold((point, DQuat::IDENTITY)),
            held,
            count: nodes.len(),
            grip,
        })
    }

    /// This hand in another numbering of the same world — a model cut out of this one
    /// (e.g. the part of the scene a hand can move): `node` and `case` give each held
    /// node's index and its load case's handle there, `element` and `hose` the held beam's
    /// and its hose's. `None` when a held node or its load case has no counterpart.
    pub fn renumbered(
        &self,
        node: impl Fn(usize) -> Option<usize>,
        case: impl Fn(LoadCaseId) -> Option<LoadCaseId>,
        element: usize,
        hose: usize,
    ) -> Option<Hand> {
        let mut hand = self.clone();
        for held in &mut hand.held[..self.count] {
            held.0 = node(held.0)?;
            held.1 = case(held.1)?;
        }
        hand.element = element;
        hand.hose = hose;
        Some(hand)
    }

    /// The hand's grip.
    pub fn grip(&self) -> Grip {
        self.grip
    }

    /// Whether the hand holds `node`.
    pub fn holds(&self, node: usize) -> bool {
        self.held_nodes().any(|n| n == node)
    }

    /// The nodes the hand holds (one or two).
    pub fn held_nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.held[..self.count].iter().map(|h| h.0)
    }

    /// The hand's pose at time `t`.
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat) {
        self.motion.pose_at(t)
    }

    /// Starts a new hand motion from its pose at `start_time`.
    pub fn move_along(
        &mut self,
        waypoints: &[DVec3],
        rotation: DVec3,
        start_time: f64,
        duration: f64,
    ) {
        let start = self.motion.pose_at(start_time);
        self.motion = Motion::new(start, waypoints, rotation, start_time, duration);
    }

    /// Sets the hand's pose directly (interactive input: a pointer or VR controller): the
    /// hand holds `position` and `orientation` from now on, until the next call or
    /// motion. Takes effect at the next [`Hand::update`].
    pub fn set_pose(&mut self, position: DVec3, orientation: DQuat) {
        self.motion.hold_at((position, orientation.normalize()));
    }

    /// Whether the hand is still moving at time `t`.
    pub fn moving(&self, t: f64) -> bool {
        !self.motion.finished(t)
    }

    /// Sets the held nodes' targets for time `t` (call before each step with its end time);
    /// returns the hand's pose at `t`.
    pub fn update(&self, state: &mut State, t: f64) -> (DVec3, DQuat) {
        let (p, q) = self.motion.pose_at(t);
        for &(_, id, offset, rotation) in &self.held[..self.count] {
            match state.loads.get_mut(id) {
                Some(LoadCase::Fix(fix)) => {
                    fix.position = p + q * offset;
                    fix.orientation = (q * rotation).normalize();
                }
                Some(LoadCase::Support(s)) => {
                    let target = p + q * offset;
                    s.moved |= target != s.position;
                    s.position = target;
                }
                _ => {}
            }
        }
        (p, q)
    }

    /// The force the hand exerted on the hose in the last step \[N\].
    pub fn force(&self, state: &State) -> DVec3 {
        self.held[..self.count]
            .iter()
            .map(|&(node, ..)| state.reaction_force[node])
            .sum()
    }

    /// The load the hand applied in the last step.
    pub fn load(&self, model: &Model, state: &State) -> HandLoad {
        self.load_at(model, state, self.motion.pose_at(state.time).0)
    }

    /// [`Hand::load`] with the hand's position now, `h`, already known (the pose
    /// [`Hand::update`] returned for this time: a step asks for it once).
    pub fn load_at(&self, model: &Model, state: &State, h: DVec3) -> HandLoad {
        let force = self.force(state);
        let mut torque = DVec3::ZERO;
        for &(node, ..) in &self.held[..self.count] {
            torque +=
                state.reaction_moment[node] + (state.x[node] - h).cross(state.reaction_force[node]);
        }
        let el = &model.elements[self.element];
        let info = &model.hoses[self.hose];
        let towards_start =
            el.node_a - info.first_node < info.first_node + info.node_count - 1 - el.node_b;
        let axis = (state.x[el.node_b] - state.x[el.node_a]).normalize_or_zero();
        HandLoad {
            hose: self.hose,
            position: h,
            force,
            torque,
            direction: if towards_start { -axis } else { axis },
        }
    }

    /// Lets go at once: the nodes move freely again (after a divergence, and under the
    /// static solver, which has no time for a hand to open in).
    pub fn release(self, state: &mut State) {
        for &(_, id, ..) in &self.held[..self.count] {
            state.loads.remove(id);
        }
    }

    /// Lets go as a hand opens, over `duration` \[s\]: each held node is freed, and the force
    /// and moment the hand held it with in the last step act on as a dead load that falls
    /// smoothly to zero ([`LoadRamp::smooth_fall`]). Dropping a load of ~200 N within one
    /// step sent a stress wave to the stub whose peak depended on the time step (232 N
    /// against 187 N at half the step in a study variant); a release over many periods of
    /// the hose's fast modes gives the same peaks at any step.
    pub fn let_go(self, state: &mut State, duration: f64) {
        for &(node, id, ..) in &self.held[..self.count] {
            state.loads.remove(id);
            state.loads.remove_on_node(
                node,
                |c| matches!(c, LoadCase::DeadLoad(d) if d.is_release()),
            );
            state.loads.add(LoadCase::DeadLoad(DeadLoad {
                node,
                force: state.reaction_force[node],
                moment: state.reaction_moment[node],
                ramp: Some(LoadRamp::smooth_fall(state.time, duration)),
            }));
        }
    }
}
