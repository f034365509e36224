//! A mount: a node held in all six degrees of freedom to a part, at a pose given in the
//! part's reference placement, and carried with the part as it moves (a hose end clamped
//! to a door, a connector on a rocking engine). At time t the node is held at
//! P(t) x₀ and P(t)'s rotation times q₀, P(t) the part's pose ([`crate::kinematics`]);
//! on a part that stands still it is a [`super::Fix`].

use crate::kinematics::{PartKinematics, PartMoves};
use glam::{DQuat, DVec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Mount {
    pub node: usize,
    /// The part (index into the model's parts) the node is mounted on.
    pub part: usize,
    /// Held position in the part's reference placement \[m\].
    pub position: DVec3,
    /// Held orientation in the part's reference placement.
    pub orientation: DQuat,
}

impl Mount {
    /// The held pose at time `t`, the parts moved by `moves`.
    pub fn pose_at(&self, t: f64, parts: &PartKinematics, moves: &PartMoves) -> (DVec3, DQuat) {
        if !parts.moves(self.part) {
            return (self.position, self.orientation);
        }
        let pose = parts.placement_at(self.part, t, moves).pose;
        (
            pose.apply(self.position),
            (pose.rotation * self.orientation).normalize(),
        )
    }
}
