//! A part's motion coordinate: the one number that says where the part is in its range —
//! a hinge's angle, a slide's travel, the phase of a periodic motion in its slowest cycle
//! (2π f t mod 2π), a sampled path's time — computed from the motion at a time; for a part
//! moved by inputs (`rotate_part`, `move_part`), the angle it has turned or the distance
//! its centre has travelled from where the scene placed it.

use pliant_core::kinematics::{PartMotion, Turns};
use pliant_core::{Model, State};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// What the coordinate measures, and in which unit it is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CoordinateKind {
    /// A hinge's angle \[rad\], shown in degrees.
    Angle,
    /// A slide's travel \[m\], shown in millimetres.
    Travel,
    /// The phase of a periodic motion in its slowest cycle \[rad\], shown in degrees.
    Phase,
    /// Time \[s\] (a sampled path, or a part moved only by its parent).
    Time,
}

impl CoordinateKind {
    /// The word in reports ("angle", "travel", "phase", "time").
    pub fn name(self) -> &'static str {
        match self {
            CoordinateKind::Angle => "angle",
            CoordinateKind::Travel => "travel",
            CoordinateKind::Phase => "phase",
            CoordinateKind::Time => "time",
        }
    }

    /// The unit shown and the factor from SI to it.
    pub fn unit(self) -> (&'static str, f64) {
        match self {
            CoordinateKind::Angle | CoordinateKind::Phase => ("deg", 180.0 / std::f64::consts::PI),
            CoordinateKind::Travel => ("mm", 1e3),
            CoordinateKind::Time => ("s", 1.0),
        }
    }
}

/// The coordinate of one part's motion.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Coordinate {
    pub part: usize,
    pub part_name: String,
    pub kind: CoordinateKind,
}

impl Coordinate {
    /// The coordinate of part `part` of `model`.
    pub fn of(model: &Model, part: usize) -> Coordinate {
        let kind = match model.kinematics.motion(part) {
            Some(PartMotion::Hinge(_)) => CoordinateKind::Angle,
            Some(PartMotion::Slide(_)) => CoordinateKind::Travel,
            Some(PartMotion::Periodic(_)) => CoordinateKind::Phase,
            Some(PartMotion::SampledPath(_)) | None => CoordinateKind::Time,
        };
        Coordinate {
            part,
            part_name: model
                .environment
                .parts
                .get(part)
                .map_or_else(String::new, |p| p.name.clone()),
            kind,
        }
    }

    /// Its value at time `t` (SI: rad, m or s), the parts moved by the inputs in `state`.
    /// A part moved by inputs: the angle it has turned from where the scene placed it
    /// (its turns all about one axis; else 0), or the distance its centre travelled.
    pub fn at(&self, model: &Model, state: &State, t: f64) -> f64 {
        let moved = state.part_moves.get(self.part);
        match (model.kinematics.motion(self.part), moved, self.kind) {
            (None, Some(m), CoordinateKind::Angle) => {
                return match m.turned_at(t) {
                    Turns::About { angle, .. } => angle,
                    Turns::Never | Turns::Mixed => 0.0,
                };
            }
            (None, Some(m), CoordinateKind::Travel) => {
                let centre = model.environment.parts[self.part]
                    .mesh
                    .local_aabb()
                    .center();
                return (m.last.placement_at(t).pose.apply(centre) - centre).length();
            }
            (None, None, CoordinateKind::Angle | CoordinateKind::Travel) => return 0.0,
            _ => {}
        }
        match model.kinematics.motion(self.part) {
            Some(PartMotion::Hinge(h)) => h.angle.at(t).0,
            Some(PartMotion::Slide(s)) => s.distance.at(t).0,
            Some(PartMotion::Periodic(p)) => {
                let slowest = p
                    .translation
                    .iter()
                    .chain(&p.rotation)
                    .filter(|o| o.amplitude != 0.0 && o.frequency > 0.0)
                    .map(|o| o.frequency)
                    .fold(f64::INFINITY, f64::min);
                if slowest.is_finite() {
                    (TAU * slowest * t).rem_euclid(TAU)
                } else {
                    0.0
                }
            }
            Some(PartMotion::SampledPath(_)) | None => t,
        }
    }

    /// "door angle 68°", "seat travel 120 mm", "engine phase 212°", "arm time 1.25 s".
    pub fn describe(&self, value: f64) -> String {
        let (unit, factor) = self.kind.unit();
        let v = value * factor;
        let shown = match self.kind {
            CoordinateKind::Angle | CoordinateKind::Phase => format!("{v:.0}°"),
            CoordinateKind::Travel => format!("{v:.0} {unit}"),
            CoordinateKind::Time => format!("{v:.2} {unit}"),
        };
        format!("{} {} {shown}", self.part_name, self.kind.name())
    }

    /// The CSV column, e.g. `angle_deg`.
    pub fn column(&self) -> String {
        format!("{}_{}", self.kind.name(), self.kind.unit().0)
    }
}
