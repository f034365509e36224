//! L2 Translate + L3 Rotate: a node driven along a [`Motion`] — from its pose at the start
//! along a polyline of waypoints, turned by a rotation vector, with a smooth start and
//! stop — then held at the end pose.

use super::Motion;
use glam::{DQuat, DVec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Drive {
    pub node: usize,
    pub motion: Motion,
}

impl Drive {
    /// A drive of `node` from `start` (its current pose) through `waypoints` (absolute,
    /// may be empty for a pure rotation), turning by `rotation` (global rotation vector),
    /// over `duration` > 0 seconds starting at `start_time`.
    pub fn new(
        node: usize,
        start: (DVec3, DQuat),
        waypoints: &[DVec3],
        rotation: DVec3,
        start_time: f64,
        duration: f64,
    ) -> Drive {
        Drive {
            node,
            motion: Motion::new(start, waypoints, rotation, start_time, duration),
        }
    }

    /// Whether the motion is complete at time `t`.
    pub fn finished(&self, t: f64) -> bool {
        self.motion.finished(t)
    }

    /// Prescribed pose at time `t`.
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat) {
        self.motion.pose_at(t)
    }
}
