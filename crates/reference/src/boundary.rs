//! Boundary conditions: the clamped base pose and the two kinds of end condition.

use nalgebra::{Rotation3, Vector3};

use crate::error::{ReferenceError, Result};
use crate::so3;

/// Position of a rod cross-section and its material frame (columns d1 = tangent,
/// d2, d3), all global.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Centre-line position \[m\].
    pub position: Vector3<f64>,
    /// Material frame `R = [d1 d2 d3]`.
    pub frame: Rotation3<f64>,
}

impl Pose {
    /// Pose from a position and a material frame.
    pub fn new(position: Vector3<f64>, frame: Rotation3<f64>) -> Self {
        Self { position, frame }
    }

    /// This pose moved by the rigid motion `x ↦ rotation · x + translation`.
    pub fn transformed(&self, rotation: &Rotation3<f64>, translation: &Vector3<f64>) -> Self {
        Self::new(
            rotation * self.position + translation,
            rotation * self.frame,
        )
    }

    /// This pose translated by `offset`, frame unchanged.
    pub fn translated(&self, offset: &Vector3<f64>) -> Self {
        Self::new(self.position + offset, self.frame)
    }

    /// Geodesic interpolation: position linearly, frame along the SO(3) geodesic.
    pub(crate) fn interpolate(&self, other: &Self, t: f64) -> Self {
        Self::new(
            self.position + (other.position - self.position) * t,
            so3::interpolate(&self.frame, &other.frame, t),
        )
    }

    pub(crate) fn validate(&self, what: &str) -> Result<()> {
        let finite = self.position.iter().all(|v| v.is_finite())
            && self.frame.matrix().iter().all(|v| v.is_finite());
        if !finite {
            return Err(ReferenceError::InvalidBoundaryCondition(format!(
                "{what} pose contains non-finite values"
            )));
        }
        let m = self.frame.matrix();
        let orthogonality = (m.transpose() * m - nalgebra::Matrix3::identity()).amax();
        if orthogonality > 1e-9 || m.determinant() < 0.0 {
            return Err(ReferenceError::InvalidBoundaryCondition(format!(
                "{what} frame is not a rotation (|RᵀR − I| = {orthogonality:.2e})"
            )));
        }
        Ok(())
    }
}

/// Condition at the end `s = L` of the rod (the base `s = 0` is always clamped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EndCondition {
    /// End clamped at a prescribed position and material frame. Residual of the
    /// shooting map: `r(L) − p_L` and `log(R_Lᵀ R(L))`.
    Clamped(Pose),
    /// Free end under a dead force and a dead moment (global; the moment acts about
    /// the end point). Residual: `n(L) − F` and `m(L) − M`.
    Loaded {
        /// Dead force `F` \[N\] applied to the end.
        force: Vector3<f64>,
        /// Dead moment `M` \[N m\] applied to the end.
        moment: Vector3<f64>,
    },
}

impl EndCondition {
    /// Clamped end at `pose`.
    pub fn clamped(pose: Pose) -> Self {
        Self::Clamped(pose)
    }

    /// Free end with a dead force and moment.
    pub fn loaded(force: Vector3<f64>, moment: Vector3<f64>) -> Self {
        Self::Loaded { force, moment }
    }

    pub(crate) fn validate(&self) -> Result<()> {
        match self {
            Self::Clamped(pose) => pose.validate("end"),
            Self::Loaded { force, moment } => {
                if force.iter().chain(moment.iter()).all(|v| v.is_finite()) {
                    Ok(())
                } else {
                    Err(ReferenceError::InvalidBoundaryCondition(
                        "end load contains non-finite values".to_string(),
                    ))
                }
            }
        }
    }

    /// Interpolates towards `other` (positions and loads linearly, frames along
    /// the geodesic); `None` if the two conditions are of different kinds.
    pub(crate) fn interpolate(&self, other: &Self, t: f64) -> Option<Self> {
        match (self, other) {
            (Self::Clamped(a), Self::Clamped(b)) => Some(Self::Clamped(a.interpolate(b, t))),
            (
                Self::Loaded {
                    force: fa,
                    moment: ma,
                },
                Self::Loaded {
                    force: fb,
                    moment: mb,
                },
            ) => Some(Self::Loaded {
                force: fa + (fb - fa) * t,
                moment: ma + (mb - ma) * t,
            }),
            _ => None,
        }
    }
}
