//! A hinge: rotation by θ(t) about a fixed axis through a point (a door, a tailgate, a
//! lid). R = rot(a, θ), T = p − R p (the axis point stays put), ω = θ̇ a, and the
//! velocity field ω × (x − p).

use super::pose::{Placement, Pose, Twist};
use super::profile::Profile;
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hinge {
    /// A point on the axis \[m\] (reference placement).
    pub point: DVec3,
    /// The axis direction (unit; the angle turns right-handed about it).
    pub axis: DVec3,
    /// The angle over time \[rad\].
    pub angle: Profile,
}

impl Hinge {
    pub fn placement_at(&self, t: f64) -> Placement {
        let (theta, rate) = self.angle.at(t);
        let rotation = DQuat::from_axis_angle(self.axis, theta);
        let translation = self.point - rotation * self.point;
        let angular = self.axis * rate;
        Placement {
            pose: Pose {
                rotation,
                translation,
            },
            twist: Twist {
                linear: angular.cross(translation - self.point),
                angular,
            },
        }
    }
}
