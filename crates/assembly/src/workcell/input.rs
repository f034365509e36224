//! The inputs a workcell takes (SPEC W1): everything a timeline, a live client or a Python
//! script can do to a running study. Each input takes effect between two steps; the
//! workcell stamps it with the step count at that moment (its *tick*), which is all a
//! replay needs to reproduce a session bit for bit (SPEC W2).

use crate::ergonomics::ErgonomicProfile;
use crate::timeline::{Action, NodeRef};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// Hand numbers are chosen by the caller (a timeline's `hand`, a client's `hand_id`).
pub type HandNumber = u32;

/// One input. Positions in metres, global axes; rotations as rotation vectors \[rad\].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Input {
    /// L1: hold the node where it is now (replaces fixes and drives added by inputs on it;
    /// refused while a hand holds it).
    Fix { node: NodeRef },
    /// Hold the node to the part named `part` where it is now, carried with the part as
    /// it moves (as [`Input::Fix`] otherwise; refused for a part the scene has not).
    Mount { node: NodeRef, part: String },
    /// L2 + L3: drive the node through `waypoints` while turning it by `rotation` over
    /// `duration` seconds from now (smooth start and stop), then hold it.
    Drive {
        node: NodeRef,
        waypoints: Vec<DVec3>,
        rotation: DVec3,
        duration: f64,
    },
    /// A force \[N\] and moment \[N·m\] at the node (adds to others), in full at once or
    /// rising linearly from zero over `ramp` seconds from now; a `name` (unique among the
    /// active loads) lets [`Input::Unload`] remove this one alone.
    Load {
        node: NodeRef,
        force: DVec3,
        moment: DVec3,
        #[serde(default, skip_serializing_if = "is_zero")]
        ramp: f64,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        name: Option<String>,
    },
    /// Removes the dead load called `name` from the node, or (no name) every dead load
    /// on it.
    Unload {
        node: NodeRef,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        name: Option<String>,
    },
    /// Removes the fixes and drives inputs put on the node: it moves freely again.
    Release { node: NodeRef },
    /// A cable tie between two hoses: the two nodes are held at the distance they have
    /// now ([`pliant_core::loads::Tie`]); refused for one node with itself or two nodes at
    /// the same place.
    Tie { node: NodeRef, to: NodeRef },
    /// Removes one load case an input added (by the id [`crate::Workcell::apply`] gave).
    RemoveLoad { id: u64 },
    /// I1: the hand grabs the beam nearest to `at` (letting go of what it held). Refused
    /// if another hand holds that beam; the hand then keeps its grip.
    /// `grip`: firm (six degrees of freedom) or loose ([`crate::Grip`]).
    Grab {
        hand: HandNumber,
        at: DVec3,
        #[serde(default, skip_serializing_if = "crate::Grip::is_firm")]
        grip: crate::Grip,
    },
    /// I2, scripted: the hand moves through `waypoints` while turning by `rotation` over
    /// `duration` seconds from now, with a smooth start and stop.
    MoveHand {
        hand: HandNumber,
        waypoints: Vec<DVec3>,
        rotation: DVec3,
        duration: f64,
    },
    /// I2, interactive (a pointer, a VR controller): the hand heads for this pose at
    /// bounded speed, acceleration and turn rate ([`crate::workcell::HandLimits`]);
    /// `orientation` `None` keeps the orientation it aims at now.
    AimHand {
        hand: HandNumber,
        position: DVec3,
        orientation: Option<DQuat>,
    },
    /// The hand lets go.
    ReleaseHand { hand: HandNumber },
    /// Moves the part called `part` over `duration` seconds from now (smooth start and
    /// stop): by the offset `by` \[m\], or so that its centre (its bounding box's) is `to`
    /// \[m\] from where the scene placed it — one of the two — in its parent's reference
    /// axes (the world's for a part without a parent). Refused for a part with a scripted motion or one
    /// the scene built standing still ([`super::part_inputs`]).
    MovePart {
        part: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        by: Option<DVec3>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        to: Option<DVec3>,
        duration: f64,
    },
    /// Turns the part called `part` about `axis` through `point` (a point of the part
    /// where the scene placed it; default: its bounding box's centre) by the angle `by`
    /// \[rad\], or to the angle `to` from where the scene placed it, over `duration`
    /// seconds from now (smooth start and stop). Refused as [`Input::MovePart`].
    RotatePart {
        part: String,
        axis: DVec3,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        point: Option<DVec3>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        by: Option<f64>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        to: Option<f64>,
        duration: f64,
    },
    /// Judge hand loads with this profile from now on.
    SetErgonomics { profile: ErgonomicProfile },
    /// A VR user's body poses the worker from now on (SPEC E1): the headset's eyes and
    /// gaze, and the controllers' positions (right, left) \[m\] as the hands' targets
    /// ([`crate::worker::BodyPose`]). Refused without a worker or for non-finite values.
    WorkerPose { pose: crate::worker::BodyPose },
    /// All velocities set to zero (kinetic damping while relaxing to rest).
    Arrest,
    /// The state moved to the static equilibrium under the current loads by the
    /// quasi-static Newton solver; time does not advance. With `stable_only` the result is
    /// kept only if the solve converged to a stable equilibrium; otherwise the input is
    /// refused and the state stays as it was.
    SolveStatic {
        force_tolerance: f64,
        moment_tolerance: f64,
        max_iterations: usize,
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        stable_only: bool,
    },
    /// After a divergence: back to the newest healthy recovery point (a fraction of a
    /// second earlier; [`super::recovery`]), releasing the hands that held the diverging
    /// hose. Refused when the workcell keeps no recovery points or has none left.
    Rollback,
    /// Back to the start: rest shape, t = 0, hands released, loads added by inputs
    /// removed, the scene's initial load cases again, stubs and clips reset. Clears a
    /// divergence.
    Reset,
}

impl Input {
    /// A short name for messages ("grab", "move_hand", …).
    pub fn name(&self) -> &'static str {
        match self {
            Input::Fix { .. } => "fix",
            Input::Mount { .. } => "mount",
            Input::Drive { .. } => "drive",
            Input::Load { .. } => "load",
            Input::Unload { .. } => "unload",
            Input::Release { .. } => "release",
            Input::Tie { .. } => "tie",
            Input::RemoveLoad { .. } => "remove_load",
            Input::Grab { .. } => "grab",
            Input::MoveHand { .. } => "move_hand",
            Input::AimHand { .. } => "aim_hand",
            Input::ReleaseHand { .. } => "release_hand",
            Input::MovePart { .. } => "move_part",
            Input::RotatePart { .. } => "rotate_part",
            Input::SetErgonomics { .. } => "set_ergonomics",
            Input::WorkerPose { .. } => "worker_pose",
            Input::Arrest => "arrest",
            Input::SolveStatic { .. } => "solve_static",
            Input::Rollback => "rollback",
            Input::Reset => "reset",
        }
    }
}

/// A load case a study starts from, applied by [`super::Workcell::new`] and by every
/// reset: the scene's timeline's leading fixes, mounts and dead loads. It is the
/// [`Input`] of the same name, and only one of those three ([`InitialLoad::from_action`]).
#[derive(Clone, Debug, PartialEq)]
pub struct InitialLoad(Input);

impl InitialLoad {
    /// The initial load case a timeline action states, if it is one (a fix, a mount or a
    /// dead load).
    pub fn from_action(action: &Action) -> Option<InitialLoad> {
        let input = match action {
            Action::Fix { node } => Input::Fix { node: *node },
            Action::Mount { node, part } => Input::Mount {
                node: *node,
                part: part.clone(),
            },
            Action::Load {
                node,
                force,
                moment,
                ramp,
                name,
            } => Input::Load {
                node: *node,
                force: *force,
                moment: *moment,
                ramp: *ramp,
                name: name.clone(),
            },
            _ => return None,
        };
        Some(InitialLoad(input))
    }

    /// A fix of `node` where it is at the start.
    pub fn fix(node: NodeRef) -> InitialLoad {
        InitialLoad(Input::Fix { node })
    }

    /// The input that applies it.
    pub fn input(&self) -> &Input {
        &self.0
    }
}

impl From<InitialLoad> for Input {
    fn from(load: InitialLoad) -> Input {
        load.0
    }
}

/// An input and the tick (steps since the workcell was built, resets included) before
/// which it took effect.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StampedInput {
    pub tick: u64,
    pub input: Input,
}

/// Why an input was refused. Nothing changed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Refusal {
    /// The input does not fit the current state (a held node, a hand holding nothing, a
    /// node out of range, …).
    #[error("{0}")]
    Invalid(String),
    /// A load case or hand that is not there.
    #[error("{0}")]
    Missing(String),
    /// The simulation diverged; only `reset` is taken.
    #[error("the simulation diverged; reset first ({0})")]
    Diverged(String),
}
