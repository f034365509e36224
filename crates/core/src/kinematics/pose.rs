//! A part's pose and velocity: the rigid map from its reference placement (where its mesh
//! and everything mounted on it were given) to where it is now, and that map's rate.
//!
//! A point given at `x_ref` in the reference placement is at `x = R x_ref + T` (R the
//! rotation, T the translation: where the reference origin went). Differentiating,
//! `ẋ = ω × (x − T) + Ṫ` — the velocity field of a rigid body (Goldstein, Classical
//! Mechanics, §4.9), given by the twist (Ṫ, ω).

use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// A rigid map x ↦ R x + T.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub rotation: DQuat,
    /// Where the reference origin is now \[m\].
    pub translation: DVec3,
}

impl Default for Pose {
    fn default() -> Self {
        Pose::IDENTITY
    }
}

impl Pose {
    pub const IDENTITY: Pose = Pose {
        rotation: DQuat::IDENTITY,
        translation: DVec3::ZERO,
    };

    /// The image R x + T of a point given in the reference placement.
    #[inline]
    pub fn apply(&self, x: DVec3) -> DVec3 {
        self.rotation * x + self.translation
    }

    /// The reference point Rᵀ (x − T) that this pose maps to `x`.
    #[inline]
    pub fn inverse_apply(&self, x: DVec3) -> DVec3 {
        self.rotation.conjugate() * (x - self.translation)
    }

    /// `self ∘ inner`: first `inner`, then `self`.
    pub fn then_after(&self, inner: &Pose) -> Pose {
        Pose {
            rotation: (self.rotation * inner.rotation).normalize(),
            translation: self.rotation * inner.translation + self.translation,
        }
    }
}

/// The rate of a pose: Ṫ (the velocity of the point at T) and the angular velocity ω,
/// both in world axes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// Ṫ \[m/s\].
    pub linear: DVec3,
    /// ω \[rad/s\].
    pub angular: DVec3,
}

/// Where a part is and how fast it moves at one instant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Placement {
    pub pose: Pose,
    pub twist: Twist,
}

impl Placement {
    /// The velocity ω × (x − T) + Ṫ of the part's point now at `x` (module doc).
    #[inline]
    pub fn velocity_at(&self, x: DVec3) -> DVec3 {
        self.twist.angular.cross(x - self.pose.translation) + self.twist.linear
    }

    /// `self` carrying `inner` (a motion given in `self`'s reference placement, as a door's
    /// hinge on a body): the pose `self ∘ inner` and its twist ω = ω_s + R_s ω_i,
    /// Ṫ = Ṫ_s + ω_s × (T − T_s) + R_s Ṫ_i.
    pub fn carrying(&self, inner: &Placement) -> Placement {
        let pose = self.pose.then_after(&inner.pose);
        let r = self.pose.rotation;
        Placement {
            pose,
            twist: Twist {
                linear: self.velocity_at(pose.translation) + r * inner.twist.linear,
                angular: self.twist.angular + r * inner.twist.angular,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_undoes_apply_and_composition_applies_inner_first() {
        let a = Pose {
            rotation: DQuat::from_rotation_z(0.7),
            translation: DVec3::new(1.0, 2.0, 3.0),
        };
        let b = Pose {
            rotation: DQuat::from_rotation_x(-0.3),
            translation: DVec3::new(-0.5, 0.0, 0.2),
        };
        let x = DVec3::new(0.3, -0.4, 0.9);
        assert!((a.inverse_apply(a.apply(x)) - x).length() < 1e-15);
        assert!((a.then_after(&b).apply(x) - a.apply(b.apply(x))).length() < 1e-14);
    }
}
