//! How each part of a session moves, as the welcome tells clients (docs/protocol.md
//! "welcome"): its scripted motion — a hinge or slide with the range its keyframes span, a
//! sampled path's time range, a periodic motion's oscillations — or, for a part inputs
//! may move, the hinge or slide its timeline's `rotate_part` / `move_part` actions
//! describe, with the range they reach. A viewer draws a slider per part from it.

use pliant_assembly::{Action, Timeline};
use pliant_core::kinematics::{Oscillation, PartMotion, Profile};
use pliant_core::RigidPartSpec;
use serde::Serialize;

/// A part's joint (world frame for a part without a parent, else its parent's reference
/// placement; metres, radians, seconds).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum JointData {
    /// Turns about `axis` (unit) through `point` \[m\]; `range` \[rad\] from where the scene
    /// placed the part, `null` when the angle has no end (a uniform acceleration).
    Hinge {
        axis: [f64; 3],
        point: [f64; 3],
        range: Option<[f64; 2]>,
    },
    /// Moves along `direction` (unit); `range` \[m\] as for a hinge.
    Slide {
        direction: [f64; 3],
        range: Option<[f64; 2]>,
    },
    /// A sampled 6-DOF path about `centre` \[m\], sampled over `time_range` \[s\] (the pose
    /// is held before and after).
    SampledPath {
        centre: [f64; 3],
        time_range: [f64; 2],
    },
    /// Oscillations about `centre` \[m\]: along x, y, z (`translation`, amplitude in m)
    /// and about x, y, z (`rotation`, amplitude in rad), each A sin(2π f t + φ).
    Periodic {
        centre: [f64; 3],
        translation: [Oscillation; 3],
        rotation: [Oscillation; 3],
    },
}

/// One part's motion as the welcome gives it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PartMotionData {
    /// Its joint; `null` for a part inputs may move freely (no timeline action describes
    /// a hinge or slide) and for a part that stands still.
    pub joint: Option<JointData>,
    /// The joint is the part's scripted `motion`: inputs cannot move the part.
    pub scripted: bool,
    /// Inputs (`move_part`, `rotate_part`, the timeline) may move the part.
    pub movable: bool,
    /// The part that carries this one (index into the welcome's `parts`).
    pub parent: Option<usize>,
}

impl PartMotionData {
    /// The motion of each of `parts`, in order, as `timeline` moves them.
    pub fn of(parts: &[RigidPartSpec], timeline: &Timeline) -> Vec<Self> {
        parts
            .iter()
            .map(|p| {
                let joint = match &p.motion {
                    Some(m) => Some(scripted_joint(m)),
                    None if p.movable => timeline_joint(timeline, &p.name, box_centre(p)),
                    None => None,
                };
                PartMotionData {
                    joint,
                    scripted: p.motion.is_some(),
                    movable: p.movable,
                    parent: p.parent,
                }
            })
            .collect()
    }
}

/// The centre of a part's bounding box where the scene placed it: the point a
/// `rotate_part` without one turns about.
fn box_centre(part: &RigidPartSpec) -> glam::DVec3 {
    let (lo, hi) = part.vertices.iter().fold(
        (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    if lo.is_finite() && hi.is_finite() {
        (lo + hi) / 2.0
    } else {
        glam::DVec3::ZERO
    }
}

/// The smallest and largest value a profile takes, with 0 (where the scene placed the
/// part); `None` when it has no end.
fn profile_range(profile: &Profile) -> Option<[f64; 2]> {
    match profile {
        Profile::Keyframes { values, .. } => Some(span(values.iter().copied())),
        Profile::UniformAcceleration {
            initial_rate,
            acceleration,
            ..
        } => (*initial_rate == 0.0 && *acceleration == 0.0).then_some([0.0, 0.0]),
    }
}

/// [min, max] of 0 and `values`.
fn span(values: impl Iterator<Item = f64>) -> [f64; 2] {
    values.fold([0.0, 0.0], |[lo, hi], v| [lo.min(v), hi.max(v)])
}

fn scripted_joint(motion: &PartMotion) -> JointData {
    match motion {
        PartMotion::Hinge(h) => JointData::Hinge {
            axis: h.axis.to_array(),
            point: h.point.to_array(),
            range: profile_range(&h.angle),
        },
        PartMotion::Slide(s) => JointData::Slide {
            direction: s.direction.to_array(),
            range: profile_range(&s.distance),
        },
        PartMotion::SampledPath(s) => JointData::SampledPath {
            centre: s.centre.to_array(),
            time_range: [
                s.times.first().copied().unwrap_or(0.0),
                s.times.last().copied().unwrap_or(0.0),
            ],
        },
        PartMotion::Periodic(p) => JointData::Periodic {
            centre: p.centre.to_array(),
            translation: p.translation,
            rotation: p.rotation,
        },
    }
}

/// The joint the timeline's actions on part `name` describe: the first `rotate_part`'s
/// axis and point (default `centre`) over the angles its turns about that axis reach
/// (`to` sets the angle, `by` adds to it), else the first `move_part`'s direction over
/// the travels its moves reach along it. `None` when the timeline neither turns nor
/// moves the part (inputs may move it freely).
fn timeline_joint(timeline: &Timeline, name: &str, centre: glam::DVec3) -> Option<JointData> {
    let own = || {
        timeline.actions.iter().filter(move |a| match a {
            Action::RotatePart { part, .. } | Action::MovePart { part, .. } => part == name,
            _ => false,
        })
    };
    let first_turn = own().find_map(|a| match a {
        Action::RotatePart { axis, point, .. } if axis.length() > 0.0 => {
            Some((axis.normalize(), point.unwrap_or(centre)))
        }
        _ => None,
    });
    if let Some((axis, point)) = first_turn {
        let mut angle = 0.0;
        let reached = own().filter_map(|a| match a {
            Action::RotatePart {
                axis: other,
                by,
                to,
                ..
            } if other.length() > 0.0 => {
                let sense = other.normalize().dot(axis);
                if (sense.abs() - 1.0).abs() > 1e-9 {
                    return None; // about another axis: not this hinge
                }
                angle = match (to, by) {
                    (Some(to), _) => to * sense,
                    (None, Some(by)) => angle + by * sense,
                    (None, None) => angle,
                };
                Some(angle)
            }
            _ => None,
        });
        return Some(JointData::Hinge {
            axis: axis.to_array(),
            point: point.to_array(),
            range: Some(span(reached)),
        });
    }
    let first_shift = own().find_map(|a| match a {
        Action::MovePart { by, to, .. } => to.or(*by).filter(|v| v.length() > 0.0),
        _ => None,
    })?;
    let direction = first_shift.normalize();
    let mut at = glam::DVec3::ZERO;
    let reached = own().filter_map(|a| match a {
        Action::MovePart { by, to, .. } => {
            at = match (to, by) {
                (Some(to), _) => *to,
                (None, Some(by)) => at + *by,
                (None, None) => at,
            };
            Some(at.dot(direction))
        }
        _ => None,
    });
    Some(JointData::Slide {
        direction: direction.to_array(),
        range: Some(span(reached)),
    })
}
