//! A periodic motion about a centre: an engine rocking on its mounts. Each of the six
//! coordinates oscillates on its own, u_k(t) = A_k sin(2π f_k t + φ_k): translations along
//! x, y, z and turns about x (roll), y (pitch), z (yaw) through the centre c, composed as
//! R = R_z(ψ) R_y(θ) R_x(φ) (Tait–Bryan z-y-x). T = c + u − R c, and the angular velocity
//! of that product is ω = ψ̇ e_z + R_z θ̇ e_y + R_z R_y φ̇ e_x (Craig, Introduction to
//! Robotics, §2.8 and §5.3).

use super::pose::{Placement, Pose, Twist};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// One coordinate's sine: A sin(2π f t + φ).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Oscillation {
    /// Amplitude (m or rad).
    pub amplitude: f64,
    /// Frequency \[Hz\].
    pub frequency: f64,
    /// Phase \[rad\].
    pub phase: f64,
}

impl Oscillation {
    /// The value and its rate at `t`.
    fn at(&self, t: f64) -> (f64, f64) {
        let w = TAU * self.frequency;
        let arg = w * t + self.phase;
        (self.amplitude * arg.sin(), self.amplitude * w * arg.cos())
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Periodic {
    /// The centre the turns are about \[m\].
    pub centre: DVec3,
    /// Along x, y, z.
    pub translation: [Oscillation; 3],
    /// About x (roll), y (pitch), z (yaw).
    pub rotation: [Oscillation; 3],
}

impl Periodic {
    pub fn placement_at(&self, t: f64) -> Placement {
        let u = self.translation.map(|o| o.at(t));
        let a = self.rotation.map(|o| o.at(t));
        let (rz, ry, rx) = (
            DQuat::from_rotation_z(a[2].0),
            DQuat::from_rotation_y(a[1].0),
            DQuat::from_rotation_x(a[0].0),
        );
        let rotation = rz * ry * rx;
        let offset = DVec3::new(u[0].0, u[1].0, u[2].0);
        let translation = self.centre + offset - rotation * self.centre;
        let angular =
            DVec3::Z * a[2].1 + rz * (DVec3::Y * a[1].1) + (rz * ry) * (DVec3::X * a[0].1);
        // velocity of the point at T: ω × (T − (c + u)) + u̇ (the centre moves with u̇)
        let centre_now = self.centre + offset;
        let linear = angular.cross(translation - centre_now) + DVec3::new(u[0].1, u[1].1, u[2].1);
        Placement {
            pose: Pose {
                rotation,
                translation,
            },
            twist: Twist { linear, angular },
        }
    }
}
