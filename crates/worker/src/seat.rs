//! A seated worker: the seat under the pelvis and the legs on it. The worker sits on a
//! seat of height s (the seat surface above the floor) at its placement's floor point,
//! thighs horizontal and pointing forward, shanks down to the floor.
//!
//! The default seat height is the worker's popliteal height P (ANSUR II "popliteal
//! height", data/anthropometry.toml: floor to the underside of the thigh behind the knee,
//! seated with the knees at 90°). The body's own proportions put the knee joint at K
//! above the floor (Winter's knee height), so the thigh's thickness under the knee joint
//! is c = K − P, and on a seat of height s the hip and knee joints are at s + c. With the
//! thigh length T = hip height − knee height and the shank length L = K − ankle height
//! (both from the standing proportions), the ankles are where the shanks meet the floor:
//! the knee joint is d = s + c − ankle height above the ankles' height, and
//!
//! - d ≤ L (a seat at or below the popliteal height): the ankle on the floor, sqrt(L² − d²)
//!   in front of the knee, knee flexion asin(d / L) from the straight leg (90° at s = P,
//!   opening as the seat is lowered: thighs horizontal is kept, a modelling choice);
//! - d > L (a seat higher than the popliteal height): the shank hangs straight down with
//!   the knee at 90° and the feet d − L above the floor — not supported (RULA's leg score
//!   2, McAtamney & Corlett 1993: "legs and feet well supported and balanced" scores 1
//!   only with the feet on the floor).
//!
//! A seat so high that the seated hip joints would be at or above the standing ones is
//! not a seat and is refused, as is a seat height that is not positive.

use crate::anthropometry::Body;
use crate::error::WorkerError;
use crate::placement::Placement;
use crate::posture::Side;
use glam::DVec3;
use serde::Serialize;

/// How far above the floor the ankles may hang and still count as on the floor \[m\]
/// (1 µm: rounding, at a seat exactly at the popliteal height).
pub const FEET_ON_FLOOR: f64 = 1e-6;

/// The seat a worker sits on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Seat {
    /// Height of the seat surface above the floor \[m\].
    pub height: f64,
}

/// How a seated worker's legs sit (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SeatedLegs {
    /// Hip, knee and ankle joints \[m\], right then left.
    pub hips: [DVec3; 2],
    pub knees: [DVec3; 2],
    pub ankles: [DVec3; 2],
    /// Knee flexion from the straight leg \[rad\] (π/2: thigh horizontal, shank
    /// vertical).
    pub knee_flexion: f64,
    /// How far the ankles hang above their height standing on the floor \[m\] (0: the
    /// feet are on the floor).
    pub foot_gap: f64,
}

impl SeatedLegs {
    /// Whether the feet rest on the floor (within [`FEET_ON_FLOOR`]).
    pub fn feet_on_floor(&self) -> bool {
        self.foot_gap <= FEET_ON_FLOOR
    }
}

/// The seat drawn as a box (the viewer's and the report's): centre \[m\], full lengths
/// along the worker's forward, left and up directions \[m\], and those directions.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SeatBox {
    pub centre: DVec3,
    pub size: DVec3,
    pub forward: DVec3,
    pub up: DVec3,
}

impl Seat {
    /// A seat of `height` \[m\] for `body`: refuses a height that is not finite and
    /// positive, or that would put the seated hip joints at or above the standing ones
    /// (module doc). `field` names the value in the error.
    pub fn new(body: &Body, height: f64, field: &str) -> Result<Seat, WorkerError> {
        if !(height.is_finite() && height > 0.0) {
            return Err(WorkerError::field(
                field,
                format!("{height} m"),
                "the seat height must be a positive length",
            ));
        }
        let seat = Seat { height };
        if seat.hip_height(body) >= body.dims.hip_height {
            return Err(WorkerError::field(
                field,
                format!("{height} m"),
                format!(
                    "{} would sit with the hips at or above their standing height {:.3} m \
                     (the seat must be lower than {:.3} m)",
                    body.population.describe(),
                    body.dims.hip_height,
                    body.dims.hip_height - thigh_clearance(body)
                ),
            ));
        }
        Ok(seat)
    }

    /// The default seat of `body`: its popliteal height.
    pub fn for_body(body: &Body) -> Seat {
        Seat {
            height: body.popliteal_height,
        }
    }

    /// Height of the seated hip (and knee) joints above the floor \[m\]: the seat plus
    /// the thigh's thickness under the knee joint (module doc).
    pub fn hip_height(&self, body: &Body) -> f64 {
        self.height + thigh_clearance(body)
    }

    /// The legs of `body` seated at `placement` (its floor point under the pelvis).
    pub fn legs(&self, body: &Body, placement: &Placement) -> SeatedLegs {
        let d = &body.dims;
        let thigh = d.hip_height - d.knee_height;
        let shank = d.knee_height - d.ankle_height;
        let hip = self.hip_height(body);
        let drop = hip - d.ankle_height;
        let (ahead, foot_gap, knee_flexion) = if drop <= shank {
            let ahead = (shank * shank - drop * drop).max(0.0).sqrt();
            (ahead, 0.0, (drop / shank).clamp(-1.0, 1.0).asin())
        } else {
            (0.0, drop - shank, std::f64::consts::FRAC_PI_2)
        };
        let at = |s: Side, forward: f64, up: f64| {
            placement.point(DVec3::new(forward, s.outward() * 0.5 * d.hip_width, up))
        };
        SeatedLegs {
            hips: Side::BOTH.map(|s| at(s, 0.0, hip)),
            knees: Side::BOTH.map(|s| at(s, thigh, hip)),
            ankles: Side::BOTH.map(|s| at(s, thigh + ahead, d.ankle_height + foot_gap)),
            knee_flexion,
            foot_gap,
        }
    }

    /// The seat as a box under the pelvis at `placement`: from the floor to the seat
    /// height, from behind the hip joints by the pelvis's radius to 0.8 of the thigh's
    /// length in front of them (the knees stay clear of its front edge), as wide as the
    /// thighs. Drawn only: the seat is not an obstacle.
    pub fn seat_box(&self, body: &Body, placement: &Placement) -> SeatBox {
        let d = &body.dims;
        let back = -body.radii.pelvis;
        let front = 0.8 * (d.hip_height - d.knee_height);
        let size = DVec3::new(
            front - back,
            d.hip_width + 2.0 * body.radii.thigh,
            self.height,
        );
        SeatBox {
            centre: placement.point(DVec3::new(0.5 * (front + back), 0.0, 0.5 * self.height)),
            size,
            forward: placement.forward,
            up: placement.up,
        }
    }
}

/// The thigh's thickness under the knee joint \[m\]: the body's knee height less its
/// popliteal height (module doc), never negative.
pub fn thigh_clearance(body: &Body) -> f64 {
    (body.dims.knee_height - body.popliteal_height).max(0.0)
}
