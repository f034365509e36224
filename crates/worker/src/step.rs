//! Stepping: where the feet go when a hand target is out of reach with the feet kept, or
//! when a VR user walks away from the manikin's stance.
//!
//! Reach (closed form): with the trunk upright a straight arm reaches the sphere of
//! radius R (shoulder to grip centre, [`Body::arm_reach`]) round its shoulder S. A
//! target T at height v = (T − S)·up above the shoulder and horizontal distance h from
//! it lies on that sphere when h = √(R² − v²); a step of h − √(R² − v²) along the
//! horizontal from S to T brings it there (none helps when |v| ≥ R: the target is too
//! high or too low for the arm whatever the feet do). The step is at most
//! [`STEP_FRACTION`] of stature long; a longer one leaves the target out of reach by
//! what the inverse kinematics cannot bend to. The worker steps only as far as needed
//! to reach with the trunk upright — people step rather than bend at the waist when a
//! step is possible (a modelling choice).
//!
//! Turning: a target whose horizontal bearing from the stance is more than
//! [`TURN_BEARING`] off the facing makes the worker turn to face it before the step is
//! taken, about the vertical through the floor point between the feet — people turn
//! towards work beside or behind them rather than reach there with a twisted trunk (a
//! modelling choice; the arm's joint limits leave a target behind the shoulder out of
//! reach whatever the step).
//!
//! Walking (VR): the trunk is a rod of length L = eye height − hip height pivoting at
//! the lumbar joint, so a lean that puts the eyes at height h above the hips moves them
//! at most √(L² − h²) horizontally; the head turning on the neck adds at most the
//! head's length above the shoulders. A headset further from the stance than that
//! ([`lean_reach`]) cannot be reached by leaning: the user stepped, and the stance moves
//! under the headset (the pelvis under the head).

use crate::anthropometry::Body;
use crate::placement::Placement;
use crate::posture::Side;
use glam::DVec3;

/// The longest step, as a fraction of stature: 0.4. The step length of normal walking
/// is commonly estimated as about 0.41–0.42 of stature (the rule pedometers and gait
/// texts use, e.g. step length ≈ 0.413 H for women and 0.415 H for men; not checked
/// against a primary source) — a modelling choice rounded down for a step taken while
/// reaching.
pub const STEP_FRACTION: f64 = 0.4;

/// Largest bearing of a target off the facing (either side) the worker steps to without
/// turning first: 45° (module doc; a modelling choice — half the way to the side).
pub const TURN_BEARING: f64 = std::f64::consts::FRAC_PI_4;

/// The turn \[rad, positive to the left\] that makes a worker standing at `placement`
/// face `target` (its horizontal bearing from the floor point), `None` while that
/// bearing is within ±[`TURN_BEARING`] or the target is right above the stance.
pub fn reach_turn(placement: &Placement, target: DVec3) -> Option<f64> {
    let local = placement.local(target - placement.position);
    let bearing = local.y.atan2(local.x);
    (local.x.hypot(local.y) > 1e-9 && bearing.abs() > TURN_BEARING).then_some(bearing)
}

/// The longest step of `body` \[m\].
pub fn max_step(body: &Body) -> f64 {
    STEP_FRACTION * body.stature
}

/// How far from the stance, horizontally, leaning can bring the eyes when they are
/// `height` above the floor \[m\] (module doc): offsets of the head within this are leans.
pub fn lean_reach(body: &Body, height: f64) -> f64 {
    let d = &body.dims;
    let trunk = d.eye_height - d.hip_height;
    let above_hips = height - d.hip_height;
    (trunk * trunk - above_hips * above_hips).max(0.0).sqrt() + (d.eye_height - d.shoulder_height)
}

/// The step (a horizontal displacement of the stance \[m\]) that brings `target` within
/// the upright straight reach of the `side` arm of a worker standing at `placement`,
/// at most [`max_step`] long; `None` when the target is within that reach already or
/// no step brings it nearer (module doc).
pub fn reach_step(body: &Body, placement: &Placement, side: Side, target: DVec3) -> Option<DVec3> {
    let shoulder = placement.point(DVec3::new(
        0.0,
        side.outward() * 0.5 * body.dims.shoulder_width,
        body.dims.shoulder_height,
    ));
    let to = target - shoulder;
    let v = to.dot(placement.up);
    let horizontal = to - v * placement.up;
    let h = horizontal.length();
    let r = body.arm_reach();
    if !(v.abs() < r) || h < 1e-12 {
        return None;
    }
    let need = h - (r * r - v * v).sqrt();
    if !(need > 0.0) {
        return None;
    }
    Some(horizontal / h * need.min(max_step(body)))
}

/// The step that puts the stance under the VR user's eyes at `eyes` (the floor point
/// below them), `None` while they are within [`lean_reach`] of it (module doc).
pub fn walk_step(body: &Body, placement: &Placement, eyes: DVec3) -> Option<DVec3> {
    let offset = eyes - placement.position;
    let height = offset.dot(placement.up);
    let horizontal = offset - height * placement.up;
    (horizontal.length() > lean_reach(body, height)).then_some(horizontal)
}

/// A step from stance `from` to stance `to` in words: its length and the nearest of
/// eight directions from `from`'s facing, e.g. "0.32 m forward", "0.20 m back and to the
/// left", and the turn when the facing changed: "0.30 m to the left, turning 90° to the
/// left", "in place, turning 45° to the right".
pub fn describe_step(from: &Placement, to: &Placement) -> String {
    let step = to.position - from.position;
    let turn = from.turn_to(to).to_degrees();
    let turning = match turn {
        t if t.abs() < 0.5 => String::new(),
        t => format!(
            "turning {:.0}° to the {}",
            t.abs(),
            if t > 0.0 { "left" } else { "right" }
        ),
    };
    if step.length() < 5e-3 && !turning.is_empty() {
        return format!("in place, {turning}");
    }
    let moved = moved_words(from, step);
    if turning.is_empty() {
        moved
    } else {
        format!("{moved}, {turning}")
    }
}

/// A displacement `step` in words relative to `placement`'s facing (see [`describe_step`]).
fn moved_words(placement: &Placement, step: DVec3) -> String {
    let local = placement.local(step);
    let bearing = local.y.atan2(local.x).to_degrees();
    let octant = ((bearing + 360.0 + 22.5) / 45.0).floor() as usize % 8;
    const WORDS: [&str; 8] = [
        "forward",
        "forward and to the left",
        "to the left",
        "back and to the left",
        "back",
        "back and to the right",
        "to the right",
        "forward and to the right",
    ];
    format!("{:.2} m {}", step.length(), WORDS[octant])
}
