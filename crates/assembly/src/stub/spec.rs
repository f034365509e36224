//! A connector stub (SPEC L6, dissertation sections 4.3.5 and 5.3.5): a rigid cylinder a
//! hose end is pushed onto.
//!
//! Geometry: `origin` is the stub's **mouth** (its free end, where a hose first meets
//! it); `axis` is the unit push-on direction, from the mouth towards the stub's base. The
//! stub occupies origin + s·axis for s ∈ [0, length], so a hose end at e is at insertion
//! depth s = (e − origin)·axis, and insertion stops at s = length (the thesis's |n|).

use super::error::StubError;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Which friction coefficient applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Friction {
    /// Hose at rest on the stub: static coefficient (before sliding).
    Static,
    /// Hose sliding along the stub: sliding coefficient.
    Sliding,
}

/// A stub, checked: finite origin, unit axis, positive length and diameter, friction
/// coefficients ≥ 0. All SI.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawStubSpec", into = "RawStubSpec")]
pub struct StubSpec {
    origin: DVec3,
    axis: DVec3,
    length: f64,
    diameter: f64,
    friction_static: f64,
    friction_sliding: f64,
}

/// A stub as written in a file; `axis` may have any non-zero length (it is normalised).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawStubSpec {
    /// Mouth of the stub \[m\].
    pub origin: DVec3,
    /// Push-on direction (normalised on reading).
    pub axis: DVec3,
    /// Length a hose can be pushed on \[m\].
    pub length: f64,
    /// Outer diameter d_s \[m\].
    pub diameter: f64,
    /// Static friction coefficient γ_H [-].
    pub friction_static: f64,
    /// Sliding friction coefficient γ_G [-].
    pub friction_sliding: f64,
}

impl TryFrom<RawStubSpec> for StubSpec {
    type Error = StubError;
    fn try_from(raw: RawStubSpec) -> Result<Self, StubError> {
        StubSpec::new(
            raw.origin,
            raw.axis,
            raw.length,
            raw.diameter,
            raw.friction_static,
            raw.friction_sliding,
        )
    }
}

impl From<StubSpec> for RawStubSpec {
    fn from(s: StubSpec) -> Self {
        RawStubSpec {
            origin: s.origin,
            axis: s.axis,
            length: s.length,
            diameter: s.diameter,
            friction_static: s.friction_static,
            friction_sliding: s.friction_sliding,
        }
    }
}

fn refuse(field: &'static str, reason: &'static str) -> StubError {
    StubError::Spec { field, reason }
}

impl StubSpec {
    /// Checks and builds a stub; `axis` is normalised.
    pub fn new(
        origin: DVec3,
        axis: DVec3,
        length: f64,
        diameter: f64,
        friction_static: f64,
        friction_sliding: f64,
    ) -> Result<Self, StubError> {
        if !origin.is_finite() {
            return Err(refuse("origin", "must be finite"));
        }
        let axis = axis
            .try_normalize()
            .ok_or(refuse("axis", "must be finite and non-zero"))?;
        if !(length.is_finite() && length > 0.0) {
            return Err(refuse("length", "must be finite and positive"));
        }
        if !(diameter.is_finite() && diameter > 0.0) {
            return Err(refuse("diameter", "must be finite and positive"));
        }
        if !(friction_static.is_finite() && friction_static >= 0.0) {
            return Err(refuse("friction_static", "must be finite and >= 0"));
        }
        if !(friction_sliding.is_finite() && friction_sliding >= 0.0) {
            return Err(refuse("friction_sliding", "must be finite and >= 0"));
        }
        Ok(StubSpec {
            origin,
            axis,
            length,
            diameter,
            friction_static,
            friction_sliding,
        })
    }

    /// The mouth of the stub \[m\].
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// Unit push-on direction.
    pub fn axis(&self) -> DVec3 {
        self.axis
    }

    /// Length a hose can be pushed on \[m\].
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Outer diameter d_s \[m\].
    pub fn diameter(&self) -> f64 {
        self.diameter
    }

    /// Outer radius r_s = d_s / 2 \[m\].
    pub fn radius(&self) -> f64 {
        0.5 * self.diameter
    }

    /// The friction coefficient of this kind.
    pub fn friction(&self, kind: Friction) -> f64 {
        match kind {
            Friction::Static => self.friction_static,
            Friction::Sliding => self.friction_sliding,
        }
    }

    /// Axial coordinate s = (point − origin)·axis \[m\]: < 0 in front of the mouth, in
    /// [0, length] along the stub. Not clamped.
    pub fn axial_coordinate(&self, point: DVec3) -> f64 {
        (point - self.origin).dot(self.axis)
    }

    /// Distance of a point from the stub's axis line \[m\].
    pub fn lateral_distance(&self, point: DVec3) -> f64 {
        let d = point - self.origin;
        (d - d.dot(self.axis) * self.axis).length()
    }

    /// The insertion depth s clamped to [0, length] (SPEC L6: insertion stops at |n|);
    /// NaN gives 0.
    pub fn clamp_depth(&self, depth: f64) -> f64 {
        if depth.is_nan() {
            0.0
        } else {
            depth.clamp(0.0, self.length)
        }
    }
}
