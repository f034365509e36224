//! A sampled 6-DOF path: poses at increasing times (a recorded engine motion, a robot
//! link), interpolated between samples.
//!
//! Position: cubic Hermite with Catmull–Rom tangents for uneven times,
//! m_k = (p_{k+1} − p_{k−1}) / (t_{k+1} − t_{k−1}) (one-sided at the ends) — C¹, through
//! every sample (Catmull & Rom 1974; Fritsch & Carlson 1980 for the Hermite form).
//! Rotation: slerp between consecutive samples (Shoemake 1985), so the angular velocity is
//! log(q_{k+1} q_k⁻¹)/Δt, constant over each interval. Before the first sample and after
//! the last the pose is held.

use super::pose::{Placement, Pose, Twist};
use crate::math::{exp_map, log_map};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SampledPath {
    /// Strictly increasing sample times \[s\].
    pub times: Vec<f64>,
    /// Displacement of the centre at each sample \[m\].
    pub positions: Vec<DVec3>,
    /// Rotation about the centre at each sample.
    pub rotations: Vec<DQuat>,
    /// The point the rotations turn about, in the reference placement \[m\]: a sample
    /// (p, R) maps x to R (x − c) + c + p.
    pub centre: DVec3,
}

impl SampledPath {
    /// Why the path cannot be used, if it cannot.
    pub fn check(&self) -> Result<(), String> {
        let n = self.times.len();
        if n == 0 || self.positions.len() != n || self.rotations.len() != n {
            return Err(format!(
                "a sampled path needs as many positions and rotations as times, at least one \
                 ({n} times, {} positions, {} rotations)",
                self.positions.len(),
                self.rotations.len()
            ));
        }
        if let Some(w) = self.times.windows(2).find(|w| !(w[1] > w[0])) {
            return Err(format!(
                "sample times must increase ({} then {})",
                w[0], w[1]
            ));
        }
        if !self.times.iter().all(|t| t.is_finite())
            || !self.positions.iter().all(|p| p.is_finite())
            || !self
                .rotations
                .iter()
                .all(|q| q.is_finite() && q.length() > 0.5)
        {
            return Err("sample times, positions and rotations must be finite".into());
        }
        Ok(())
    }

    /// Catmull–Rom tangent at sample `k`.
    fn tangent(&self, k: usize) -> DVec3 {
        let n = self.times.len();
        let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
        if a == b {
            return DVec3::ZERO;
        }
        (self.positions[b] - self.positions[a]) / (self.times[b] - self.times[a])
    }

    pub fn placement_at(&self, t: f64) -> Placement {
        let n = self.times.len();
        let c = self.centre;
        let hold = |k: usize| Placement {
            pose: Pose {
                rotation: self.rotations[k],
                translation: c + self.positions[k] - self.rotations[k] * c,
            },
            twist: Twist::default(),
        };
        if n == 0 {
            return Placement::default();
        }
        if t <= self.times[0] {
            return hold(0);
        }
        if t >= self.times[n - 1] {
            return hold(n - 1);
        }
        let k = self.times.partition_point(|&s| s <= t).clamp(1, n - 1);
        let (t0, t1) = (self.times[k - 1], self.times[k]);
        let h = t1 - t0;
        let s = (t - t0) / h;
        let (p0, p1) = (self.positions[k - 1], self.positions[k]);
        let (m0, m1) = (self.tangent(k - 1) * h, self.tangent(k) * h);
        // Hermite basis and its derivative in s
        let (s2, s3) = (s * s, s * s * s);
        let position = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * p1
            + (s3 - s2) * m1;
        let rate = ((6.0 * s2 - 6.0 * s) * p0
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (-6.0 * s2 + 6.0 * s) * p1
            + (3.0 * s2 - 2.0 * s) * m1)
            / h;
        let (q0, mut q1) = (self.rotations[k - 1], self.rotations[k]);
        if q0.dot(q1) < 0.0 {
            q1 = -q1; // the shorter way round
        }
        let turn = log_map(q1 * q0.conjugate());
        let rotation = (exp_map(s * turn) * q0).normalize();
        let angular = turn / h;
        // T = c + p − R c, Ṫ = ṗ − ω × R c
        let arm = rotation * c;
        Placement {
            pose: Pose {
                rotation,
                translation: c + position - arm,
            },
            twist: Twist {
                linear: rate - angular.cross(arm),
                angular,
            },
        }
    }
}
