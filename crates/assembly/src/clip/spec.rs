//! A hose clip (SPEC L7; dissertation sections 4.3.6 and 5.3.6, figures 4.21 and 5.9).
//!
//! Geometry: `origin` p is the seat centre (where a seated hose's centre line passes);
//! `opening` n is the unit direction from the seat out through the opening;
//! `orientation` l is the unit direction of a seated hose's axis, perpendicular to n.
//! The clip's cross-section plane passes through p with normal l. The opening of width d₁
//! lies at distance |n| = √(d₂² − d₁²)/2 from p (eq. 4.108): the ends of the opening sit
//! on the circle of diameter d₂. A hose of outer radius r > d₁/2 first touches the
//! opening when its centre is at |n| + h from p, h = √(r² − (d₁/2)²) (eq. 4.109).

use super::error::ClipError;
use super::kind::ClipKind;
use glam::{DMat3, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Smallest sine of the angle between `opening` and `orientation` accepted.
const MIN_SINE: f64 = 1e-6;

/// A clip, checked: finite seat, unit opening direction, unit orientation perpendicular
/// to it, 0 < d₁ < d₂, snap force ≥ 0. All SI.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawClipSpec", into = "RawClipSpec")]
pub struct ClipSpec {
    origin: DVec3,
    opening: DVec3,
    orientation: DVec3,
    opening_width: f64,
    inner_diameter: f64,
    snap_force: f64,
    kind: ClipKind,
    friction: f64,
    holding_force: Option<f64>,
}

/// A clip as written in a file: `opening` may have any non-zero length, `orientation`
/// any direction not parallel to it (its part along `opening` is removed).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawClipSpec {
    /// Seat centre p \[m\].
    pub origin: DVec3,
    /// Opening direction n.
    pub opening: DVec3,
    /// Orientation l about n: the seated hose's axis.
    pub orientation: DVec3,
    /// Opening width d₁ \[m\].
    pub opening_width: f64,
    /// Inner diameter d₂ \[m\].
    pub inner_diameter: f64,
    /// Snap force k \[N\]: the force at the opening (dissertation section 5.3.1: the force
    /// needed to stretch the clip open to d₂; given by the user).
    pub snap_force: f64,
    /// The fixing's type (default fixed).
    #[serde(default)]
    pub kind: ClipKind,
    /// Coulomb coefficient μ along the free translation (sliding guide) [-].
    #[serde(default)]
    pub friction: f64,
    /// Pull-out force \[N\]: a seated hose pulled out harder comes loose (None: it stays).
    #[serde(default)]
    pub holding_force: Option<f64>,
}

impl TryFrom<RawClipSpec> for ClipSpec {
    type Error = ClipError;
    fn try_from(raw: RawClipSpec) -> Result<Self, ClipError> {
        ClipSpec::new(
            raw.origin,
            raw.opening,
            raw.orientation,
            raw.opening_width,
            raw.inner_diameter,
            raw.snap_force,
        )?
        .with_fixing(raw.kind, raw.friction, raw.holding_force)
    }
}

impl From<ClipSpec> for RawClipSpec {
    fn from(c: ClipSpec) -> Self {
        RawClipSpec {
            origin: c.origin,
            opening: c.opening,
            orientation: c.orientation,
            opening_width: c.opening_width,
            inner_diameter: c.inner_diameter,
            snap_force: c.snap_force,
            kind: c.kind,
            friction: c.friction,
            holding_force: c.holding_force,
        }
    }
}

fn refuse(field: &'static str, reason: &'static str) -> ClipError {
    ClipError::Spec { field, reason }
}

impl ClipSpec {
    /// Checks and builds a clip; `opening` is normalised, `orientation` made perpendicular
    /// to it and normalised.
    pub fn new(
        origin: DVec3,
        opening: DVec3,
        orientation: DVec3,
        opening_width: f64,
        inner_diameter: f64,
        snap_force: f64,
    ) -> Result<Self, ClipError> {
        if !origin.is_finite() {
            return Err(refuse("origin", "must be finite"));
        }
        let opening = opening
            .try_normalize()
            .ok_or(refuse("opening", "must be finite and non-zero"))?;
        let orientation = orientation
            .try_normalize()
            .ok_or(refuse("orientation", "must be finite and non-zero"))?;
        let across = orientation - orientation.dot(opening) * opening;
        if across.length() < MIN_SINE {
            return Err(refuse("orientation", "must not be parallel to the opening"));
        }
        let orientation = across.normalize();
        if !(opening_width.is_finite() && opening_width > 0.0) {
            return Err(refuse("opening_width", "must be finite and positive"));
        }
        if !(inner_diameter.is_finite() && inner_diameter > opening_width) {
            return Err(refuse(
                "inner_diameter",
                "must be finite and larger than the opening width",
            ));
        }
        if !(snap_force.is_finite() && snap_force >= 0.0) {
            return Err(refuse("snap_force", "must be finite and >= 0"));
        }
        Ok(ClipSpec {
            origin,
            opening,
            orientation,
            opening_width,
            inner_diameter,
            snap_force,
            kind: ClipKind::Fixed,
            friction: 0.0,
            holding_force: None,
        })
    }

    /// The same clip as a fixing of type `kind` (see [`ClipKind`]) with Coulomb
    /// coefficient `friction` along its free translation (≥ 0; only a sliding guide has
    /// one) and pull-out force `holding_force` \[N\] (> 0, or None).
    pub fn with_fixing(
        mut self,
        kind: ClipKind,
        friction: f64,
        holding_force: Option<f64>,
    ) -> Result<Self, ClipError> {
        if !(friction.is_finite() && friction >= 0.0) {
            return Err(refuse("friction", "must be finite and >= 0"));
        }
        if friction > 0.0 && kind.free_translation() == [false; 3] {
            return Err(refuse(
                "friction",
                "only a sliding guide (free along the hose) has friction",
            ));
        }
        if holding_force.is_some_and(|h| !(h.is_finite() && h > 0.0)) {
            return Err(refuse("holding_force", "must be finite and positive"));
        }
        self.kind = kind;
        self.friction = friction;
        self.holding_force = holding_force;
        Ok(self)
    }

    /// The fixing's type.
    pub fn kind(&self) -> ClipKind {
        self.kind
    }

    /// Coulomb coefficient μ along the free translation [-].
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// Pull-out force \[N\], if the clip has one.
    pub fn holding_force(&self) -> Option<f64> {
        self.holding_force
    }

    /// The fixing's frame in the VEC convention ([`ClipKind`]): X = Y × Z, Y = l (along
    /// the hose), Z = n (against the mounting direction).
    pub fn frame(&self) -> DQuat {
        let (y, z) = (self.orientation, self.opening);
        DQuat::from_mat3(&DMat3::from_cols(y.cross(z), y, z)).normalize()
    }

    /// Seat centre p \[m\].
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// Unit opening direction n.
    pub fn opening(&self) -> DVec3 {
        self.opening
    }

    /// Unit axis of a seated hose l (perpendicular to n).
    pub fn orientation(&self) -> DVec3 {
        self.orientation
    }

    /// Opening width d₁ \[m\].
    pub fn opening_width(&self) -> f64 {
        self.opening_width
    }

    /// Inner diameter d₂ \[m\].
    pub fn inner_diameter(&self) -> f64 {
        self.inner_diameter
    }

    /// Snap force k \[N\].
    pub fn snap_force(&self) -> f64 {
        self.snap_force
    }

    /// Distance from the seat to the opening, |n| = √(d₂² − d₁²)/2 \[m\] (eq. 4.108).
    pub fn opening_distance(&self) -> f64 {
        0.5 * (self.inner_diameter.powi(2) - self.opening_width.powi(2)).sqrt()
    }

    /// h = √(r² − (d₁/2)²) \[m\] (eq. 4.109) for a hose of outer radius `radius`; `None`
    /// when r ≤ d₁/2 (the hose passes the opening untouched) or r is not finite.
    pub fn touch_height(&self, radius: f64) -> Option<f64> {
        let half = 0.5 * self.opening_width;
        (radius.is_finite() && radius > half).then(|| (radius * radius - half * half).sqrt())
    }

    /// Distance of the hose centre from the seat at first touch, |n| + h \[m\]; `None` for a
    /// hose thinner than the opening.
    pub fn first_touch(&self, radius: f64) -> Option<f64> {
        self.touch_height(radius)
            .map(|h| self.opening_distance() + h)
    }

    /// Signed coordinate s = (m − p)·n of a hose centre m along the opening \[m\]: 0 at the
    /// seat, |n| at the opening.
    pub fn opening_coordinate(&self, centre: DVec3) -> f64 {
        (centre - self.origin).dot(self.opening)
    }

    /// Distance of a hose centre from the clip's n–l plane (across the opening) \[m\].
    pub fn lateral_offset(&self, centre: DVec3) -> f64 {
        (centre - self.origin)
            .dot(self.opening.cross(self.orientation))
            .abs()
    }

    /// Where a beam from `a` to `b` crosses the clip's cross-section plane (through p,
    /// normal l) — the hose centre m of eq. 4.110; `None` if it does not cross it.
    pub fn centre_on_segment(&self, a: DVec3, b: DVec3) -> Option<DVec3> {
        let (da, db) = (self.plane_distance(a), self.plane_distance(b));
        Self::crosses(da, db).then(|| Self::crossing_point(a, b, da, db))
    }

    /// Signed distance of `point` from the clip's cross-section plane, (x − p)·l \[m\].
    pub fn plane_distance(&self, point: DVec3) -> f64 {
        (point - self.origin).dot(self.orientation)
    }

    /// Whether a segment whose ends lie at plane distances `da`, `db`
    /// ([`ClipSpec::plane_distance`]) crosses the plane: finite, not on one side, not
    /// in it. Tells the common case (one side) first.
    pub fn crosses(da: f64, db: f64) -> bool {
        !(da * db > 0.0 || !(da.is_finite() && db.is_finite()) || da == db)
    }

    /// Where the segment from `a` to `b` crosses the plane, given that it does
    /// ([`ClipSpec::crosses`]).
    pub fn crossing_point(a: DVec3, b: DVec3, da: f64, db: f64) -> DVec3 {
        let t = da / (da - db);
        a + t * (b - a)
    }
}
