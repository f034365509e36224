//! The hands of a workcell: each holds one beam ([`Hand`], dissertation eq. 5.2) and is
//! steered either by a script (a smooth [`pliant_core::loads::Motion`]) or interactively,
//! by aiming it at a target pose that it follows at bounded speed, acceleration and turn
//! rate — a pointer or a VR controller jumps, a worker's hand does not, and an instant
//! start would give inertial force spikes the worker would not feel.

use super::input::HandNumber;
use crate::hand::Hand;
use glam::{DQuat, DVec3};
use pliant_core::State;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// How fast an aimed hand may follow its target, and how hard it can pull.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandLimits {
    /// Fastest the hand moves [m/s].
    pub max_speed: f64,
    /// Largest acceleration towards (and braking before) the target [m/s²].
    pub max_acceleration: f64,
    /// Fastest the hand turns [rad/s].
    pub max_turn_rate: f64,
    /// The hand's strength [N]: the largest force an interactively steered hand exerts on
    /// the hose ([`HeldHand::update`]). A person's strength, not an ergonomic limit: the
    /// verdict judges the loads below it. `None`: unlimited — a kinematic hand that
    /// drags the hose wherever it is sent (input logs written before this field replay
    /// so, bit for bit).
    #[serde(default)]
    pub max_force: Option<f64>,
}

/// Default hand strength [N]: of the order of the largest static pulling force of a
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
    /// Speed towards the target now [m/s].
    pub speed: f64,
    /// Whether the hand was at its strength ([`HandLimits::max_force`]) in the last step.
    pub at_strength: bool,
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
    /// as to stop on the target, v = min(v + a_max Δt, v_max, √(2 a_max d)). A hand at
    /// its strength F_max (the force F it exerted in the last step, |F| > F_max) does not
    /// move further along F, and gives way against F at v_max·min(|F|/F_max − 1, 1)
    /// (gently: a faster yield makes the held nodes' own inertia force oscillate):
    /// a person cannot drag a hose taut between its fixings by a kilonewton.
    pub fn update(&mut self, state: &mut State, t: f64, dt: f64, limits: &HandLimits) {
        if let Some(aim) = &mut self.aim {
            let to_go = (aim.target.0 - aim.pose.0).length();
            let braking = (2.0 * limits.max_acceleration * to_go).sqrt();
            aim.speed = (aim.speed + limits.max_acceleration * dt)
                .min(limits.max_speed)
                .min(braking);
            let mut step = aim.pose.0.move_towards(aim.target.0, aim.speed * dt) - aim.pose.0;
            let force = self.hand.force(state);
            aim.at_strength = false;
            if let Some(f_max) = limits.max_force {
                let over = force.length() / f_max;
                if over > 1.0 {
                    let along = force / force.length();
                    step -= step.dot(along).max(0.0) * along;
                    step -= along * (limits.max_speed * dt * (over - 1.0).min(1.0));
                    aim.speed = 0.0; // sets off again from rest once the hose gives
                    aim.at_strength = true;
                }
            }
            aim.pose.0 += step;
            aim.pose.1 = aim
                .pose
                .1
                .rotate_towards(aim.target.1, limits.max_turn_rate * dt);
            self.hand.set_pose(aim.pose.0, aim.pose.1);
        }
        self.hand.update(state, t);
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

/// The hands by number.
pub type Hands = BTreeMap<HandNumber, HeldHand>;

/// The number of the hand holding `node`, if any.
pub fn holder(hands: &Hands, node: usize) -> Option<HandNumber> {
    hands
        .iter()
        .find(|(_, h)| h.hand.holds(node))
        .map(|(k, _)| *k)
}
