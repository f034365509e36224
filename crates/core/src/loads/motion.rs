//! A prescribed rigid motion over time: from a start pose along a polyline of waypoints
//! and turned by a rotation vector over `duration`, then holding the end pose. Used by
//! node drives (L2 + L3) and by hands (I1).
//!
//! The thesis moves a node by (P_target − P)/n per step (§5.3.2); here the motion is
//! prescribed kinematically with the quintic smooth-step s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ of the
//! normalised time τ, so that velocity and acceleration start and end at zero and the
//! reported drive force has no jumps. Position follows the polyline at arc-length
//! fraction s; orientation is exp(s·φ)·q₀ (exponential map, angles beyond π allowed).

use crate::math::exp_map;
use glam::{DQuat, DVec3};

#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Polyline from the start position through the waypoints \[m\].
    points: Vec<DVec3>,
    /// Cumulative arc length at each point \[m\].
    arc: Vec<f64>,
    start_orientation: DQuat,
    /// Total rotation vector, global axes \[rad\].
    rotation: DVec3,
    start_time: f64,
    duration: f64,
}

/// Quintic smooth-step: 0 → 1 with zero slope and curvature at both ends.
fn smooth_step(tau: f64) -> f64 {
    let t = tau.clamp(0.0, 1.0);
    t * t * t * (10.0 + t * (-15.0 + 6.0 * t))
}

impl Motion {
    /// A motion from `start` through `waypoints` (absolute, may be empty for a pure
    /// rotation), turning by `rotation` (global rotation vector), over `duration` > 0
    /// seconds starting at `start_time`.
    pub fn new(
        start: (DVec3, DQuat),
        waypoints: &[DVec3],
        rotation: DVec3,
        start_time: f64,
        duration: f64,
    ) -> Motion {
        let mut points = Vec::with_capacity(waypoints.len() + 1);
        points.push(start.0);
        points.extend_from_slice(waypoints);
        let mut arc = Vec::with_capacity(points.len());
        arc.push(0.0);
        for i in 1..points.len() {
            arc.push(arc[i - 1] + (points[i] - points[i - 1]).length());
        }
        Motion {
            points,
            arc,
            start_orientation: start.1,
            rotation,
            start_time,
            duration: duration.max(1e-12),
        }
    }

    /// A motion that stays at `pose`.
    pub fn hold(pose: (DVec3, DQuat)) -> Motion {
        let mut motion = Motion {
            points: Vec::with_capacity(1),
            arc: Vec::with_capacity(1),
            start_orientation: pose.1,
            rotation: DVec3::ZERO,
            start_time: 0.0,
            duration: 0.0,
        };
        motion.hold_at(pose);
        motion
    }

    /// Makes this motion [`Motion::hold`] `pose`, in its own storage: interactive input
    /// (a pointer, a VR controller) sets a hand's pose at every step, and the step loop
    /// allocates nothing.
    pub fn hold_at(&mut self, pose: (DVec3, DQuat)) {
        self.points.clear();
        self.points.push(pose.0);
        self.arc.clear();
        self.arc.push(0.0);
        self.start_orientation = pose.1;
        self.rotation = DVec3::ZERO;
        self.start_time = 0.0;
        self.duration = 1e-12;
    }

    /// Whether the motion is complete at time `t`.
    pub fn finished(&self, t: f64) -> bool {
        t >= self.start_time + self.duration
    }

    /// End time of the motion \[s\].
    pub fn end_time(&self) -> f64 {
        self.start_time + self.duration
    }

    /// Prescribed pose at time `t`.
    pub fn pose_at(&self, t: f64) -> (DVec3, DQuat) {
        let s = smooth_step((t - self.start_time) / self.duration);
        let total = *self.arc.last().unwrap_or(&0.0);
        let position = if total <= 0.0 {
            self.points[0]
        } else {
            let target = s * total;
            let k = self
                .arc
                .partition_point(|&a| a < target)
                .clamp(1, self.points.len() - 1);
            let seg = self.arc[k] - self.arc[k - 1];
            let f = if seg > 0.0 {
                (target - self.arc[k - 1]) / seg
            } else {
                1.0
            };
            self.points[k - 1].lerp(self.points[k], f)
        };
        (
            position,
            (exp_map(s * self.rotation) * self.start_orientation).normalize(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Holding a pose in place is a motion from it through no waypoints over no time, and
    /// keeps the storage.
    #[test]
    fn holding_in_place_equals_a_new_hold_and_keeps_the_storage() {
        let mut m = Motion::new(
            (DVec3::ZERO, DQuat::IDENTITY),
            &[DVec3::X, DVec3::Y],
            DVec3::Z,
            0.5,
            1.0,
        );
        let storage = (m.points.as_ptr(), m.arc.as_ptr());
        let pose = (DVec3::new(0.1, 0.2, 0.3), DQuat::from_rotation_y(0.4));
        m.hold_at(pose);
        assert_eq!(m, Motion::hold(pose));
        assert_eq!(m, Motion::new(pose, &[], DVec3::ZERO, 0.0, 1e-12));
        assert_eq!((m.points.as_ptr(), m.arc.as_ptr()), storage);
    }

    #[test]
    fn drive_reaches_waypoints_and_rotation() {
        let d = Motion::new(
            (DVec3::ZERO, DQuat::IDENTITY),
            &[DVec3::X, DVec3::new(1.0, 1.0, 0.0)],
            DVec3::new(0.0, 0.0, 4.0),
            1.0,
            2.0,
        );
        let (p0, q0) = d.pose_at(0.5);
        assert_eq!(p0, DVec3::ZERO);
        assert!(q0.abs_diff_eq(DQuat::IDENTITY, 1e-15));
        let (p_mid, _) = d.pose_at(2.0);
        assert!(
            (p_mid - DVec3::X).length() < 1e-12,
            "half time, half arc: {p_mid:?}"
        );
        let (p1, q1) = d.pose_at(5.0);
        assert!((p1 - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-12);
        let expected = DQuat::from_axis_angle(DVec3::Z, 4.0);
        assert!((q1 * DVec3::X - expected * DVec3::X).length() < 1e-12);
    }
}
