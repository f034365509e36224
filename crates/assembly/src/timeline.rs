//! A scripted timeline of actions (SPEC L1–L3 + dead loads): executed in order,
//! each action starting when the previous one is done (instantaneous actions take no
//! time; `Move` blocks for its duration unless `wait` is false).

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A node of a hose, by index (already resolved and range-checked by the loader).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct NodeRef {
    pub hose: usize,
    pub node: usize,
}

/// Where a driven node goes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MovePath {
    /// Absolute waypoints \[m\]; the last one is the target.
    To(Vec<DVec3>),
    /// Waypoints as offsets \[m\] from the node's position when the action starts.
    By(Vec<DVec3>),
}

/// A rotation given as axis–angle in the global frame, applied on top of the node's
/// orientation when the action starts.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rotation {
    /// Unit axis (global frame).
    pub axis: DVec3,
    /// Angle \[rad\]; may exceed π (several turns are fine).
    pub angle: f64,
}

/// One step of a timeline.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Action {
    /// L1: hold the node in all six degrees of freedom where it is now.
    Fix { node: NodeRef },
    /// Hold the node to the part named `part` where it is now: it moves with the part
    /// (a hose end clamped to a door or an engine).
    Mount { node: NodeRef, part: String },
    /// L2 (+ L3): drive the node along `path` and/or rotate it by `rotation` over
    /// `duration` seconds with a smooth start and stop. While and after moving, the node
    /// stays held (its orientation too) until released. With `wait == false` the
    /// timeline goes on at once and the move runs alongside the next actions.
    Move {
        node: NodeRef,
        path: Option<MovePath>,
        rotation: Option<Rotation>,
        duration: f64,
        wait: bool,
    },
    /// Dead load: a force \[N\] and moment \[N·m\] (global frame) added at the node, in full
    /// at once or rising linearly over `ramp` seconds; `name` lets `unload` remove this
    /// one alone.
    Load {
        node: NodeRef,
        force: DVec3,
        moment: DVec3,
        ramp: f64,
        name: Option<String>,
    },
    /// Remove the dead load called `name` from the node, or all of them.
    Unload { node: NodeRef, name: Option<String> },
    /// Remove the fix / drive from the node: it moves freely again.
    Release { node: NodeRef },
    /// A cable tie bundles two hoses: `node` and `to` are held at the
    /// distance they have now ([`pliant_core::loads::Tie`]) for the rest of the run.
    Tie { node: NodeRef, to: NodeRef },
    /// I1: hand `hand` grabs the beam nearest to `at` \[m\]; its two nodes follow the hand
    /// (replacing any fix or drive on them) until the hand lets go.
    /// `grip`: firm, or loose — the hose may turn in the hand ([`crate::Grip`]).
    Grab {
        hand: usize,
        at: DVec3,
        #[serde(default, skip_serializing_if = "crate::Grip::is_firm")]
        grip: crate::Grip,
    },
    /// I1: hand `hand` takes the hose at `node`, wherever it is when the action runs (a
    /// worker picking up a connector by its housing): as [`Action::Grab`] at the node's
    /// position then, taking the beam from the node to the next one (from the last node:
    /// the last beam), the hand's frame at the node.
    GrabNode {
        hand: usize,
        node: NodeRef,
        #[serde(default, skip_serializing_if = "crate::Grip::is_firm")]
        grip: crate::Grip,
    },
    /// Turns hand `hand` over `duration` seconds (a smooth start and stop) so that the
    /// beam it holds ends pointing along `direction` — its axis taken towards the nearer
    /// end of its hose (a plug turned to face its counterpart) — while it moves along
    /// `path` (if given; else it turns where it is). The turn is the shortest one from
    /// where the beam points when the action starts.
    AlignHand {
        hand: usize,
        direction: DVec3,
        path: Option<MovePath>,
        duration: f64,
    },
    /// Moves hand `hand` along `path` and/or turns it by `rotation` over `duration`
    /// seconds — or, when `speed` \[m/s\] is given, over the path's length divided by it —
    /// with a smooth start and stop; through the waypoints as a polyline, or along a
    /// Catmull-Rom spline through them when `spline`. `wait` as for `Move`.
    MoveHand {
        hand: usize,
        path: Option<MovePath>,
        rotation: Option<Rotation>,
        duration: f64,
        speed: Option<f64>,
        spline: bool,
        wait: bool,
    },
    /// Hand `hand` heads for `position` \[m\] (and `orientation`, if given) at bounded
    /// speed and acceleration, as a live hand driven by a pointer or a VR controller
    /// does; the timeline goes on at once.
    AimHand {
        hand: usize,
        position: DVec3,
        orientation: Option<glam::DQuat>,
    },
    /// Hand `hand` lets go of its beam.
    ReleaseHand { hand: usize },
    /// Moves the part called `part` by the offset `by` \[m\] or so that its centre is
    /// `to` from where the scene placed it, over `duration` seconds with a smooth start and stop
    /// ([`crate::Input::MovePart`]); `wait` as for `Move`.
    MovePart {
        part: String,
        by: Option<DVec3>,
        to: Option<DVec3>,
        duration: f64,
        wait: bool,
    },
    /// Turns the part called `part` about `axis` through `point` by the angle `by` \[rad\]
    /// or to the angle `to` from where the scene placed it, over `duration` seconds
    /// ([`crate::Input::RotatePart`]); `wait` as for `Move`.
    RotatePart {
        part: String,
        axis: DVec3,
        point: Option<DVec3>,
        by: Option<f64>,
        to: Option<f64>,
        duration: f64,
        wait: bool,
    },
    /// Simulate for `duration` seconds.
    Run { duration: f64 },
    /// Relax to static equilibrium ([`Workcell::settle`](crate::Workcell::settle)): at
    /// rest when the largest out-of-balance force and moment on a free node, contact
    /// counted, are within `force_tolerance` \[N\] and `moment_tolerance` \[N·m\],
    /// nothing moves and the total kinetic energy is below `kinetic_energy_threshold`
    /// \[J\]; after `max_duration` \[s\] it is reported as not at rest. `finish` says
    /// how the rest is reached ([`SettleFinish`]).
    Settle {
        kinetic_energy_threshold: f64,
        force_tolerance: f64,
        moment_tolerance: f64,
        max_duration: f64,
        #[serde(default, skip_serializing_if = "SettleFinish::is_dynamic")]
        finish: SettleFinish,
    },
}

/// How a `settle` reaches static equilibrium.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SettleFinish {
    /// Dynamic relaxation all the way: the explicit model's own motion to rest
    /// ([`Workcell::settle`](crate::Workcell::settle)).
    #[default]
    Dynamic,
    /// Dynamic relaxation until the hands, drives and fasteners are done, then the
    /// quasi-static solver's stable equilibrium from there, confirmed (or, where the static
    /// solve fails, reached) by dynamic relaxation
    /// ([`Workcell::settle_finishing_static`](crate::Workcell::settle_finishing_static)).
    Static,
    /// As [`SettleFinish::Static`] up to the static solve, and at rest there: the state is
    /// the quasi-static solver's stable equilibrium within the settle's tolerances, not
    /// confirmed by the scene's solver (where the solve is refused, the settle stays
    /// dynamic) ([`Workcell::settle_ending_static`](crate::Workcell::settle_ending_static)).
    StaticEquilibrium,
}

impl SettleFinish {
    /// Whether this is the default, [`SettleFinish::Dynamic`].
    pub fn is_dynamic(&self) -> bool {
        *self == SettleFinish::Dynamic
    }
}

/// The ordered list of actions of a scene.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Timeline {
    pub actions: Vec<Action>,
}
