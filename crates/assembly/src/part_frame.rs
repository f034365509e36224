//! A fastener's part at one instant: the map between the world and the part's reference
//! placement, where the fastener (a stub, a connector's counterpart, a clip) was given.
//! A fastener on a moving part observes the hose in the part's reference placement and
//! acts on it in the world: a point seen at x is at Rᵀ(x − T) on the part, a direction d
//! at Rᵀd, and the part's own point at x moves with ω × (x − T) + Ṫ (the rigid velocity
//! field, Goldstein, Classical Mechanics, §4.9; [`pliant_core::kinematics::Placement`]).
//! A fastener on a part that stands still, or on no part, sees the world unchanged, bit
//! for bit.

use glam::{DQuat, DVec3};
use pliant_core::kinematics::{Placement, Pose};
use pliant_core::loads::{Fix, LoadCase, Mount};
use pliant_core::{Model, State};

/// Where a fastener's part is and how fast it moves at one instant.
#[derive(Clone, Copy, Debug, Default)]
pub struct PartFrame {
    /// The part (index into the model's parts), if it moves; `None` for the world.
    part: Option<usize>,
    placement: Placement,
}

impl PartFrame {
    /// Part `part`'s frame at time `t`, the parts moved by the state's inputs (the
    /// world's for no part or a part that stands still).
    pub fn at(model: &Model, state: &State, part: Option<usize>, t: f64) -> PartFrame {
        match part.filter(|&k| model.part_moves(k)) {
            Some(k) => PartFrame {
                part: Some(k),
                placement: model.part_placement(state, k, t),
            },
            None => PartFrame::default(),
        }
    }

    /// Whether the part moves (the frame is not the world's).
    pub fn moves(&self) -> bool {
        self.part.is_some()
    }

    /// The part's pose.
    pub fn pose(&self) -> Pose {
        self.placement.pose
    }

    /// The point of the part's reference placement now at `x`.
    #[inline]
    pub fn point_to_part(&self, x: DVec3) -> DVec3 {
        if self.moves() {
            self.placement.pose.inverse_apply(x)
        } else {
            x
        }
    }

    /// A world direction in the part's reference axes.
    #[inline]
    pub fn direction_to_part(&self, d: DVec3) -> DVec3 {
        if self.moves() {
            self.placement.pose.rotation.conjugate() * d
        } else {
            d
        }
    }

    /// A direction of the part's reference axes in world axes.
    #[inline]
    pub fn direction_to_world(&self, d: DVec3) -> DVec3 {
        if self.moves() {
            self.placement.pose.rotation * d
        } else {
            d
        }
    }

    /// The velocity of the part's point now at `x` (zero in the world's frame).
    #[inline]
    pub fn velocity_at(&self, x: DVec3) -> DVec3 {
        if self.moves() {
            self.placement.velocity_at(x)
        } else {
            DVec3::ZERO
        }
    }

    /// The part's angular velocity (zero in the world's frame).
    pub fn spin(&self) -> DVec3 {
        self.placement.twist.angular
    }

    /// A hold of `node` where it is now (`x`, `q` in the world), in all six degrees of
    /// freedom: an L1 fix in the world's frame, a mount carried with a moving part.
    pub fn hold(&self, node: usize, x: DVec3, q: DQuat) -> LoadCase {
        match self.part {
            Some(part) => LoadCase::Mount(Mount {
                node,
                part,
                position: self.point_to_part(x),
                orientation: (self.placement.pose.rotation.conjugate() * q).normalize(),
            }),
            None => LoadCase::Fix(Fix {
                node,
                position: x,
                orientation: q,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pliant_core::kinematics::Twist;

    #[test]
    fn a_moving_frame_maps_points_and_directions_both_ways() {
        let f = PartFrame {
            part: Some(0),
            placement: Placement {
                pose: Pose {
                    rotation: DQuat::from_rotation_z(0.6),
                    translation: DVec3::new(0.1, -0.2, 0.3),
                },
                twist: Twist {
                    linear: DVec3::X,
                    angular: DVec3::Z,
                },
            },
        };
        let x = DVec3::new(0.4, 0.5, -0.1);
        let on_part = f.point_to_part(x);
        assert!((f.pose().apply(on_part) - x).length() < 1e-15);
        let d = DVec3::new(0.0, 1.0, 2.0);
        assert!((f.direction_to_world(f.direction_to_part(d)) - d).length() < 1e-15);
        assert!((f.direction_to_part(d) - d).length() > 0.1);
        // ω × (x − T) + Ṫ
        let v = DVec3::Z.cross(x - DVec3::new(0.1, -0.2, 0.3)) + DVec3::X;
        assert!((f.velocity_at(x) - v).length() < 1e-15);
        let still = PartFrame::default();
        assert_eq!(still.point_to_part(x), x);
        assert_eq!(still.velocity_at(x), DVec3::ZERO);
        assert!(matches!(
            still.hold(3, x, DQuat::IDENTITY),
            LoadCase::Fix(_)
        ));
        assert!(matches!(f.hold(3, x, DQuat::IDENTITY), LoadCase::Mount(m) if m.part == 0));
    }
}
