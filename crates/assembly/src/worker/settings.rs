//! What a scene's `[worker]` asks for (SPEC E1): who the worker is, where they stand,
//! how often they are posed, and whether what they cannot do decides feasibility.

use glam::DVec3;
use pliant_worker::{Body, Placement, Population, ScoreOptions, Seat, WorkerError};
use serde::Serialize;

/// Where the worker stands.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stance {
    /// At a given placement.
    At(Placement),
    /// In front of the first point a hand holds, facing `facing` (horizontal unit), feet
    /// on the floor at height `floor` \[m\] along `up`: the grab point is straight ahead
    /// of the right shoulder, [`AUTO_REACH_FRACTION`] of the arm's reach in front of it.
    Auto {
        facing: DVec3,
        up: DVec3,
        floor: f64,
    },
}

/// How far in front of the feet an automatic placement puts the first grab point, as a
/// fraction of the straight arm's reach (shoulder to grip centre): 0.6, a modelling
/// choice — the elbow bent, the trunk upright for a grab point at chest height.
pub const AUTO_REACH_FRACTION: f64 = 0.6;

/// The worker of a study.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WorkerSettings {
    pub population: Population,
    pub stance: Stance,
    /// The seat a seated worker sits on, under the pelvis at the stance's floor point
    /// (`None`: standing). A seated worker neither steps nor turns.
    pub seat: Option<Seat>,
    /// Simulated time between posed instants \[s\] (the scene's record interval; 0: every
    /// step).
    pub interval: f64,
    /// Whether a hand target out of reach or a body segment inside a part makes the
    /// study NOT FEASIBLE (else they are warnings).
    pub decide: bool,
    /// Whether the worker may step towards a hand target out of reach with the feet
    /// kept ([`pliant_worker::step`]); a VR user's walking moves the stance either way
    /// (standing: a seated worker stays on the seat).
    pub steps: bool,
    /// What the posture scores need beyond the posture (REBA's coupling; whether the
    /// work is static is taken from the ergonomic profile's duty as the study runs).
    pub scores: ScoreOptions,
}

impl WorkerSettings {
    /// The manikin of `body` (these settings' posture) at `placement`.
    pub fn manikin(&self, body: Body, placement: Placement) -> pliant_worker::Manikin {
        match self.seat {
            Some(seat) => pliant_worker::Manikin::seated(body, placement, seat),
            None => pliant_worker::Manikin::new(body, placement),
        }
    }

    /// The automatic stance facing `facing` with `up` the vertical; refuses a facing
    /// without a horizontal component.
    pub fn auto_stance(facing: DVec3, up: DVec3, floor: f64) -> Result<Stance, WorkerError> {
        let p = Placement::new(DVec3::ZERO, facing, up)?;
        if !floor.is_finite() {
            return Err(WorkerError::field("floor", floor, "must be finite"));
        }
        Ok(Stance::Auto {
            facing: p.forward,
            up: p.up,
            floor,
        })
    }
}

impl Stance {
    /// The placement under a VR user's head before any hand acted: the feet below the
    /// eyes, facing the gaze's horizontal direction (the stance's facing when it looks
    /// straight up or down); a fixed stance ignores it.
    pub fn place_under(&self, head: pliant_worker::HeadTarget) -> Placement {
        match *self {
            Stance::At(p) => p,
            Stance::Auto { facing, up, floor } => {
                let ahead = head.gaze - head.gaze.dot(up) * up;
                Placement {
                    position: head.eyes - (head.eyes.dot(up) - floor) * up,
                    forward: ahead.try_normalize().unwrap_or(facing),
                    up,
                }
            }
        }
    }

    /// The placement for a first grab point at `grab` for `body` (a fixed stance ignores
    /// both).
    pub fn place(&self, grab: DVec3, body: &Body) -> Placement {
        match *self {
            Stance::At(p) => p,
            Stance::Auto { facing, up, floor } => {
                let left = up.cross(facing);
                let p = grab - facing * (AUTO_REACH_FRACTION * body.arm_reach())
                    + left * (0.5 * body.dims.shoulder_width);
                Placement {
                    position: p - (p.dot(up) - floor) * up,
                    forward: facing,
                    up,
                }
            }
        }
    }
}
