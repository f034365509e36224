//! Where the worker stands: the point on the floor between the feet, the horizontal
//! direction the worker faces and the vertical (against gravity). Local coordinates are
//! (forward, left, up) — a right-handed frame.

use crate::error::WorkerError;
use glam::DVec3;

/// The worker's stance in the world.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Placement {
    /// The floor point midway between the feet \[m\].
    pub position: DVec3,
    /// Unit horizontal direction the worker faces.
    pub forward: DVec3,
    /// Unit vertical, against gravity.
    pub up: DVec3,
}

impl Placement {
    /// A stance at `position` facing `facing` (projected onto the horizontal), with `up`
    /// the vertical. Refuses non-finite values, a zero `up` and a vertical `facing`.
    pub fn new(position: DVec3, facing: DVec3, up: DVec3) -> Result<Placement, WorkerError> {
        if !position.is_finite() {
            return Err(WorkerError::field("position", position, "must be finite"));
        }
        let up = up.try_normalize().ok_or_else(|| {
            WorkerError::field("up", up, "the vertical must be a finite, non-zero vector")
        })?;
        let horizontal = facing - facing.dot(up) * up;
        let forward = horizontal
            .try_normalize()
            .filter(|_| horizontal.length() > 1e-9 * facing.length().max(1e-300))
            .ok_or_else(|| {
                WorkerError::field(
                    "facing",
                    facing,
                    "must be a finite direction with a horizontal component",
                )
            })?;
        Ok(Placement {
            position,
            forward,
            up,
        })
    }

    /// Unit vector to the worker's left.
    pub fn left(&self) -> DVec3 {
        self.up.cross(self.forward)
    }

    /// The world vector of local (forward, left, up) components.
    pub fn vector(&self, local: DVec3) -> DVec3 {
        local.x * self.forward + local.y * self.left() + local.z * self.up
    }

    /// The local (forward, left, up) components of world vector `v`.
    pub fn local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.forward), v.dot(self.left()), v.dot(self.up))
    }

    /// The same stance turned by `angle` \[rad\] about the vertical through its floor
    /// point (positive: to the left).
    pub fn turned(&self, angle: f64) -> Placement {
        let (sin, cos) = angle.sin_cos();
        Placement {
            forward: (cos * self.forward + sin * self.left()).normalize(),
            ..*self
        }
    }

    /// The turn \[rad, in (−π, π\]\] about the vertical from this stance's facing to
    /// `other`'s (positive: to the left).
    pub fn turn_to(&self, other: &Placement) -> f64 {
        let l = self.local(other.forward);
        l.y.atan2(l.x)
    }

    /// The world point of local coordinates `local` from the floor point.
    pub fn point(&self, local: DVec3) -> DVec3 {
        self.position + self.vector(local)
    }
}
