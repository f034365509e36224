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

/// How fast an aimed hand may follow its target.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandLimits {
    /// Fastest the hand moves [m/s].
    pub max_speed: f64,
    /// Largest acceleration towards (and braking before) the target [m/s²].
    pub max_acceleration: f64,
    /// Fastest the hand turns [rad/s].
    pub max_turn_rate: f64,
}

impl Default for HandLimits {
    fn default() -> Self {
        HandLimits {
            max_speed: 2.0,
            max_acceleration: 20.0,
            max_turn_rate: 4.0 * std::f64::consts::PI,
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
    /// as to stop on the target, v = min(v + a_max Δt, v_max, √(2 a_max d)).
    pub fn update(&mut self, state: &mut State, t: f64, dt: f64, limits: &HandLimits) {
        if let Some(aim) = &mut self.aim {
            let to_go = (aim.target.0 - aim.pose.0).length();
            let braking = (2.0 * limits.max_acceleration * to_go).sqrt();
            aim.speed = (aim.speed + limits.max_acceleration * dt)
                .min(limits.max_speed)
                .min(braking);
            aim.pose.0 = aim.pose.0.move_towards(aim.target.0, aim.speed * dt);
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
