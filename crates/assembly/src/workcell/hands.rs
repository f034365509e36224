//! The hands of a workcell: each holds one beam ([`Hand`], dissertation eq. 5.2) and is
//! steered either by a script (a smooth [`pliant_core::loads::Motion`]) or interactively,
//! by aiming it at a target pose that it follows at bounded speed, acceleration and turn
//! rate — a pointer or a VR controller jumps, a worker's hand does not, and an instant
//! start would give inertial force spikes the worker would not feel.

use super::input::HandNumber;
use crate::hand::Hand;
use glam::{DQuat, DVec3};
use pliant_core::newton::RIGID_FACTOR;
use pliant_core::{Model, State};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How fast an aimed hand may follow its target, and how hard it can pull.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandLimits {
    /// Fastest the hand moves \[m/s\].
    pub max_speed: f64,
    /// Largest acceleration towards (and braking before) the target [m/s²].
    pub max_acceleration: f64,
    /// Fastest the hand turns \[rad/s\].
    pub max_turn_rate: f64,
    /// The hand's strength \[N\]: the largest force an interactively steered hand exerts on
    /// the hose ([`HeldHand::update`]). A person's strength, not an ergonomic limit: the
    /// verdict judges the loads below it. `None`: unlimited — a kinematic hand that
    /// drags the hose wherever it is sent (input logs written before this field replay
    /// so, bit for bit).
    #[serde(default)]
    pub max_force: Option<f64>,
}

/// Default hand strength \[N\]: of the order of the largest static pulling force of a
/// standing adult with both hands (maximum action forces of DIN 33411-5 and
/// Chaffin et al., *Occupational Biomechanics*, ch. 10: a few hundred newtons, rarely
/// above 600 N) — an assumption, set per session; far above every ergonomic limit of
/// the dissertation's tables (≤ 250 N), so it never decides a verdict.
pub const DEFAULT_HAND_STRENGTH: f64 = 600.0;

impl Default for HandLimits {
    fn default() -> Self {
        HandLimits {
            max_speed: 2.0,
            max_acceleration: 20.0,
            max_turn_rate: 4.0 * std::f64::consts::PI,
            max_force: Some(DEFAULT_HAND_STRENGTH),
        }
    }
}

/// Where an aimed hand is, where it heads, and how fast it goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aim {
    pub pose: (DVec3, DQuat),
    pub target: (DVec3, DQuat),
    /// Speed towards the target now \[m/s\].
    pub speed: f64,
    /// Whether the hand was at its strength ([`HandLimits::max_force`]) in the last step.
    pub at_strength: bool,
    /// What the hand felt in the last step, to size the next ([`Feel`]).
    pub feel: Feel,
}

/// What a hand with a strength F_max feels of the hose: the stiffness k with which its
/// force F changed as it moved. Taking the hose as a spring of 2k (a relaxed secant
/// step), the force after a step s, F + 2k s, stays within F_max when s lies in the ball
/// about −F/(2k) of radius F_max/(2k); the hand takes the point of that ball nearest to
/// where it is heading. Below its strength it slows as the hose stiffens, sideways as
/// much as along F; above it, it gives way until the force after the step is at most
/// (|F| + F_max)/2. Relaxed (2k, not k): two hands on one stiff span — a metal tube held
/// at two points — each remove half of their common excess, not twice all of it (whole
/// steps swung such a pair between ± meganewtons). A hand that moved at a fixed speed
/// until its force passed F_max and gave way at a fixed speed overshot once the hose was
/// stiffer than F_max/(v_max Δt) — a taut hose under the implicit solver's 10 ms step:
/// ±10 kN within two steps, the soak's divergences.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Feel {
    /// Force the hand exerted before its last step \[N\].
    pub force: DVec3,
    /// How the hand moved in its last step \[m\].
    pub step: DVec3,
    /// The stiffness it feels, k \[N/m\] (0: not yet estimated).
    pub stiffness: f64,
}

/// A hand of the workcell.
#[derive(Clone, Debug)]
pub struct HeldHand {
    pub hand: Hand,
    /// `Some` while the hand is steered interactively.
    pub aim: Option<Aim>,
}

impl HeldHand {
    /// Sets the held nodes' targets for the step ending at `t` (length `dt`). An aimed
    /// hand first moves towards its target: it accelerates at most `a_max` and brakes so
    /// as to stop on the target, v = min(v + a_max Δt, v_max, √(2 a_max d)). A hand with
    /// a strength F_max then keeps its next force within F_max by the stiffness it felt
    /// ([`Feel`]); over its strength it gives way — a person cannot drag a hose taut
    /// between its fixings by a kilonewton. Returns the hand's pose at `t`.
    pub fn update(
        &mut self,
        model: &Model,
        state: &mut State,
        t: f64,
        dt: f64,
        limits: &HandLimits,
    ) -> (DVec3, DQuat) {
        if let Some(aim) = &mut self.aim {
            let to_go = (aim.target.0 - aim.pose.0).length();
            let braking = (2.0 * limits.max_acceleration * to_go).sqrt();
            aim.speed = (aim.speed + limits.max_acceleration * dt)
                .min(limits.max_speed)
                .min(braking);
            let mut step = aim.pose.0.move_towards(aim.target.0, aim.speed * dt) - aim.pose.0;
            let force = self.hand.force(state);
            aim.at_strength = false;
            let mut feel = Feel::default();
            if let Some(f_max) = limits.max_force {
                let reach = limits.max_speed * dt;
                let k = felt_stiffness(&aim.feel, force, f_max, reach, || {
                    grip_stiffness(model, self.hand.element, dt)
                });
                let centre = -force / (2.0 * k);
                let radius = f_max / (2.0 * k);
                let off = step - centre;
                if off.length() > radius {
                    step = (centre + off * (radius / off.length())).clamp_length_max(reach);
                }
                if force.length() > f_max {
                    aim.speed = 0.0; // sets off again from rest once the hose gives
                    aim.at_strength = true;
                }
                feel = Feel {
                    force,
                    step,
                    stiffness: k,
                };
            }
            aim.feel = feel;
            aim.pose.0 += step;
            aim.pose.1 = aim
                .pose
                .1
                .rotate_towards(aim.target.1, limits.max_turn_rate * dt);
            self.hand.set_pose(aim.pose.0, aim.pose.1);
        }
        self.hand.update(state, t)
    }

    /// Whether the hand is still on its way at time `t`.
    pub fn moving(&self, t: f64) -> bool {
        match &self.aim {
            Some(aim) => aim.pose != aim.target,
            None => self.hand.moving(t),
        }
    }

    /// The hand's pose at time `t`.
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat) {
        match &self.aim {
            Some(aim) => aim.pose,
            None => self.hand.pose_at(t),
        }
    }
}

/// The stiffness k a hand feels, for its next step. After a step s (with force F₀
/// before it), the secant k = (F − F₀)·ŝ / |s|: taken at once when it is stiffer than
/// the estimate (an overshoot is not repeated), approached by halving when softer, kept
/// when the force fell as the hand moved into it (what else moved decided it). A
/// change below the noise of 10⁻³ F_max over a short step (under 10⁻³ of the largest,
/// `reach` = v_max Δt) measures nothing but bounds k by that noise over |s|, so that a
/// hand held back by a stiffness it no longer meets gets going again; no step, no news.
/// What else moved in the step (other hands, contact, the hose's own swing) blurs the
/// secant; the relaxed step of [`Feel`] absorbs it. Never softer than F_max/`reach`: far
/// below its strength a hand is not slowed. The first estimate is the grip's own
/// stiffness ([`grip_stiffness`]).
fn felt_stiffness(
    last: &Feel,
    force: DVec3,
    f_max: f64,
    reach: f64,
    grip: impl FnOnce() -> f64,
) -> f64 {
    let softest = f_max / reach;
    let k = if last.stiffness > 0.0 {
        last.stiffness
    } else {
        grip()
    };
    let moved = last.step.length();
    let change = (force - last.force).dot(last.step) / moved.max(f64::MIN_POSITIVE);
    let noise = 1e-3 * f_max;
    let k = if moved == 0.0 {
        k
    } else if moved > 1e-3 * reach || change.abs() > noise {
        let secant = change / moved;
        if secant > k {
            secant
        } else if secant > 0.0 {
            (0.5 * k).max(secant)
        } else {
            k // the force fell as the hand moved into it: something else moved
        }
    } else {
        (0.5 * k).max(k.min(noise / moved))
    };
    if k.is_finite() {
        k.max(softest)
    } else {
        softest
    }
}

/// An upper estimate of the stiffness with which a hose resists moving the grip on
/// `element` (both its nodes, held) by a small distance in one step of `dt`: the axial
/// and bending springs of the beams on either side, Σ (EA/l₀ + 12 EI/l₀³) (the clamped
/// beam's end stiffnesses), plus the held nodes' inertia Σ m/Δt² (a node moved by d
/// within a step is accelerated by ≈ d/Δt²). A beam of a stiffened section counts as the
/// Newton solvers make it, [`RIGID_FACTOR`] times stiffer: a hand on a metal tube that
/// another hand holds too starts out careful. The rest of the hose, in series, only
/// makes it softer.
fn grip_stiffness(model: &Model, element: usize, dt: f64) -> f64 {
    let held = &model.elements[element];
    let nodes = [held.node_a, held.node_b];
    let springs: f64 = [element.wrapping_sub(1), element + 1]
        .into_iter()
        .filter_map(|e| model.elements.get(e))
        .filter(|e| nodes.contains(&e.node_a) || nodes.contains(&e.node_b))
        .map(|e| {
            let l = e.rest_length;
            let ea = e.axial_stiffness_tension.max(e.axial_stiffness_compression);
            let ei = e.bending_stiffness[0].max(e.bending_stiffness[1]);
            let body = model.body_of[e.node_a];
            let rigid = if body.is_some() && body == model.body_of[e.node_b] {
                RIGID_FACTOR
            } else {
                1.0
            };
            rigid * (ea / l + 12.0 * ei / (l * l * l))
        })
        .sum();
    let inertia: f64 = nodes.iter().map(|&n| model.mass[n]).sum::<f64>() / (dt * dt);
    springs + inertia
}

/// The hands by number.
pub type Hands = BTreeMap<HandNumber, HeldHand>;

/// The number of the hand holding `node`, if any.
pub fn holder(hands: &Hands, node: usize) -> Option<HandNumber> {
    hands
        .iter()
        .find(|(_, h)| h.hand.holds(node))
        .map(|(k, _)| *k)
}
