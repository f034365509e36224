//! The inputs that move parts ([`super::Input::MovePart`], [`super::Input::RotatePart`]):
//! checked here and turned into a [`PartMove`] in the state, so that checkpoints,
//! rollbacks and replays carry them.
//!
//! A move starts from where the part is when it is given (a move given while another runs
//! takes over from there), in the part's parent's reference placement (the world for a
//! part without a parent). A part with a scripted motion (a hinge, a slide, …) is
//! refused: its pose is the motion's at every instant, and a second source would fight
//! it — a part carried by a moving parent may be moved on it.

use super::Refusal;
use glam::DVec3;
use pliant_core::kinematics::{MovedPart, PartMove, Pose, Turns};
use pliant_core::{Model, State};

/// Longest shift or translation a move may ask for \[m\].
pub const MAX_PART_SHIFT: f64 = 1.0e3;
/// Largest turn a rotation may ask for \[rad\]: ten full turns.
pub const MAX_PART_TURN: f64 = 20.0 * std::f64::consts::PI;
/// Longest duration of a move \[s\]: a week (no session runs longer).
pub const MAX_PART_MOVE_DURATION: f64 = super::log_reading::MAX_LOG_SECONDS;

/// The index of the part called `name`, or a refusal listing the parts; `what` names
/// the input.
pub fn part_named(model: &Model, name: &str, what: &str) -> Result<usize, Refusal> {
    let parts = &model.environment.parts;
    parts.iter().position(|p| p.name == name).ok_or_else(|| {
        let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
        Refusal::Invalid(format!(
            "{what}: no part named \"{name}\" (parts: {})",
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ))
    })
}

/// The centre of part `k`'s bounding box where the scene placed it.
fn centre(model: &Model, k: usize) -> DVec3 {
    model.environment.parts[k].mesh.local_aabb().center()
}

/// The part called `name`, if inputs may move it.
fn movable_part(model: &Model, name: &str, what: &str) -> Result<usize, Refusal> {
    let k = part_named(model, name, what)?;
    if let Some(m) = model.kinematics.motion(k) {
        let kind = serde_json::to_value(m)
            .ok()
            .and_then(|v| v["kind"].as_str().map(str::to_string))
            .unwrap_or_default();
        return Err(Refusal::Invalid(format!(
            "{what}: part \"{name}\" has a scripted motion ({kind}); inputs cannot move it as well (script the motion, or move a part it carries)"
        )));
    }
    if !model.kinematics.moves(k) {
        return Err(Refusal::Invalid(format!(
            "{what}: part \"{name}\" was built standing still; give it `movable = true` in the scene's [[parts]] (a timeline that moves it does so itself)"
        )));
    }
    Ok(k)
}

fn finite_vector(v: DVec3, what: &str) -> Result<DVec3, Refusal> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refusal::Invalid(format!("{what} must be finite, got {v}")))
    }
}

fn checked_duration(duration: f64, what: &str) -> Result<f64, Refusal> {
    if duration.is_finite() && duration > 0.0 && duration <= MAX_PART_MOVE_DURATION {
        Ok(duration)
    } else {
        Err(Refusal::Invalid(format!(
            "{what}: duration must be > 0 and at most {MAX_PART_MOVE_DURATION} s (a part does not jump), got {duration}"
        )))
    }
}

/// Exactly one of `by` and `to`.
fn by_or_to<T: Copy>(by: Option<T>, to: Option<T>, what: &str) -> Result<(T, bool), Refusal> {
    match (by, to) {
        (Some(b), None) => Ok((b, false)),
        (None, Some(t)) => Ok((t, true)),
        _ => Err(Refusal::Invalid(format!(
            "{what}: give either `by` or `to`, not {}",
            if by.is_some() { "both" } else { "neither" }
        ))),
    }
}

/// Part `k`'s own pose at the state's time and its turns so far.
fn now(state: &State, k: usize) -> (Pose, Turns) {
    let t = state.time;
    match state.part_moves.get(k) {
        Some(m) => (m.last.placement_at(t).pose, m.turned_at(t)),
        None => (Pose::IDENTITY, Turns::Never),
    }
}

fn start(model: &Model, state: &mut State, k: usize, last: PartMove, turned: Turns) {
    state
        .part_moves
        .set(model.environment.parts.len(), k, MovedPart { last, turned });
    // a hose asleep on or near the part must follow it
    state.sleep.wake_all(model);
}

/// `move_part`: shifts part `name` by `by`, or so that its centre (its bounding box's,
/// where the scene placed it) is `to` from where the scene placed that centre, over
/// `duration` \[s\].
pub fn move_part(
    model: &Model,
    state: &mut State,
    name: &str,
    by: Option<DVec3>,
    to: Option<DVec3>,
    duration: f64,
) -> Result<(), Refusal> {
    const WHAT: &str = "move_part";
    let k = movable_part(model, name, WHAT)?;
    let (amount, absolute) = by_or_to(by, to, WHAT)?;
    let amount = finite_vector(amount, &format!("{WHAT}: the offset"))?;
    if amount.length() > MAX_PART_SHIFT {
        return Err(Refusal::Invalid(format!(
            "{WHAT}: {} m is farther than a part moves (at most {MAX_PART_SHIFT} m)",
            amount.length()
        )));
    }
    let duration = checked_duration(duration, WHAT)?;
    let (pose, turned) = now(state, k);
    let shift = if absolute {
        let centre = centre(model, k);
        centre + amount - pose.apply(centre)
    } else {
        amount
    };
    let last = PartMove {
        start: pose,
        pivot: DVec3::ZERO,
        turn: DVec3::ZERO,
        shift,
        start_time: state.time,
        duration,
    };
    start(model, state, k, last, turned);
    Ok(())
}

/// `rotate_part`: turns part `name` about `axis` through `point` (a point of the part,
/// given where the scene placed it; default: the centre of its bounding box) by the
/// angle `by`, or to the angle `to` from where the scene placed it, over `duration`
/// \[s\]. A turn *to* an angle needs every earlier turn of the part to be about the same
/// axis.
#[allow(clippy::too_many_arguments)]
pub fn rotate_part(
    model: &Model,
    state: &mut State,
    name: &str,
    axis: DVec3,
    point: Option<DVec3>,
    by: Option<f64>,
    to: Option<f64>,
    duration: f64,
) -> Result<(), Refusal> {
    const WHAT: &str = "rotate_part";
    let k = movable_part(model, name, WHAT)?;
    let axis = finite_vector(axis, &format!("{WHAT}: the axis"))?;
    if axis.length() < 1e-12 {
        return Err(Refusal::Invalid(format!(
            "{WHAT}: the axis must not be zero"
        )));
    }
    let axis = axis.normalize();
    let point = match point {
        Some(p) => finite_vector(p, &format!("{WHAT}: the point"))?,
        None => centre(model, k),
    };
    if point.length() > MAX_PART_SHIFT {
        return Err(Refusal::Invalid(format!(
            "{WHAT}: the point is {} m from the origin (at most {MAX_PART_SHIFT} m)",
            point.length()
        )));
    }
    let (angle, absolute) = by_or_to(by, to, WHAT)?;
    if !(angle.is_finite() && angle.abs() <= MAX_PART_TURN) {
        return Err(Refusal::Invalid(format!(
            "{WHAT}: the angle must be finite and at most {MAX_PART_TURN:.4} rad (ten turns) either way, got {angle}"
        )));
    }
    let duration = checked_duration(duration, WHAT)?;
    let (pose, turned) = now(state, k);
    let angle = if absolute {
        let so_far = turned.about(axis).ok_or_else(|| {
            Refusal::Invalid(format!(
                "{WHAT}: part \"{name}\" has turned about another axis, so an angle `to` about this one is not defined; turn it `by` an angle"
            ))
        })?;
        angle - so_far
    } else {
        angle
    };
    let turn = angle * axis;
    let last = PartMove {
        start: pose,
        // the part's own point stays where it is now
        pivot: pose.apply(point),
        turn,
        shift: DVec3::ZERO,
        start_time: state.time,
        duration,
    };
    start(model, state, k, last, turned.and(turn));
    Ok(())
}
