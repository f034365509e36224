//! Judging a hand load against the ergonomic limits (SPEC I2, I3, I5, V1) as the
//! dissertation judges it (section 3.3.3, after tables 3.10 / 3.11).
//!
//! Let d be the reference direction at the grabbed point (the hose axis at the hand,
//! pointing from the hand into the hose end it is nearer to — the insertion direction
//! onto a stub). The hand force f splits into its **axial** part f·d (along the grip
//! axis) and its **lateral** part |f − (f·d) d| (across it): f·d ≥ 0 is a **push**
//! (tables 3.6 / 3.7), f·d < 0 a **pull** (tables 3.8 / 3.9); a force with f·d = 0 counts
//! as a push. The tables give no lateral values, and a lateral force is pushing or pulling
//! the hose sideways, so the whole |f| is compared with that kind's limit. The force
//! decides feasibility.
//!
//! The hand torque t splits into the **twist** |t·d| about the hose axis — the
//! screwdriver row of tables 3.10 / 3.11: "the torque acts about the long axis of the
//! gripped object" — and the **bending** moment |t − (t·d) d| across it — the T-handle
//! row, "pure bending of the hose orthogonal to its main axis". The dissertation goes on:
//! "torsion and bending of the hose are never reasons for an installation to fail; the
//! critical cases are pushing the hose onto and pulling it off its stub", so these two are
//! warnings against their guide and limit values, and count towards feasibility only when
//! the profile asks for it ([`ErgonomicProfile::moments_decide`]).

use super::colour::{colour_rgb, colour_value, Rgb};
use super::en1005::En1005Judgement;
use super::error::ErgonomicsError;
use super::limits::{ErgonomicLimits, GuideRange};
use super::names::TorqueGrip;
use super::profile::ErgonomicProfile;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// What kind of hand load a value was judged as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadKind {
    /// Force with a component along +d (tables 3.6 / 3.7).
    Push,
    /// Force with a component along −d (tables 3.8 / 3.9).
    Pull,
    /// Torque about the hose axis at the hand: the screwdriver row of tables 3.10 / 3.11.
    Twist,
    /// Torque across the hose axis at the hand: the T-handle row of tables 3.10 / 3.11.
    Bending,
}

impl LoadKind {
    /// The name as written in reports: `push`, `pull`, `twist`, `bending`.
    pub fn name(self) -> &'static str {
        match self {
            LoadKind::Push => "push",
            LoadKind::Pull => "pull",
            LoadKind::Twist => "twist",
            LoadKind::Bending => "bending",
        }
    }

    /// The SI unit of its values: `N` or `N·m`.
    pub fn unit(self) -> &'static str {
        match self {
            LoadKind::Push | LoadKind::Pull => "N",
            LoadKind::Twist | LoadKind::Bending => "N·m",
        }
    }

    /// Whether this is a moment (twist or bending), a guide value only unless the
    /// profile's `moments_decide` is set.
    pub fn is_moment(self) -> bool {
        matches!(self, LoadKind::Twist | LoadKind::Bending)
    }

    /// The row of the torque tables 3.10 / 3.11 that judges a moment: screwdriver for
    /// twist, T-handle for bending (dissertation section 3.3.3). `None` for forces.
    pub fn torque_grip(self) -> Option<TorqueGrip> {
        match self {
            LoadKind::Twist => Some(TorqueGrip::Screwdriver),
            LoadKind::Bending => Some(TorqueGrip::THandle),
            LoadKind::Push | LoadKind::Pull => None,
        }
    }
}

/// One hand load against its limit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Classification {
    /// Push, pull, twist or bending.
    pub kind: LoadKind,
    /// |f| \[N\], |twist| or |bending| \[N·m\].
    pub magnitude: f64,
    /// The guide range of the profile's row and column [N or N·m].
    pub guide: GuideRange,
    /// The limit value of the profile's row and column [N or N·m].
    pub limit: f64,
    /// magnitude / limit; above 1 the limit is exceeded.
    pub ratio: f64,
    /// Under EN 1005-3 (push and pull only): F_R, the risk multiplier m_r = F / F_R and
    /// the risk zone. The guide range is then [0, 0.5 F_R] and the limit 0.7 F_R.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub en1005: Option<En1005Judgement>,
}

impl Classification {
    fn new(kind: LoadKind, magnitude: f64, guide: GuideRange, limit: f64) -> Self {
        Classification {
            kind,
            magnitude,
            guide,
            limit,
            ratio: magnitude / limit,
            en1005: None,
        }
    }

    /// Whether the load exceeds the limit value.
    pub fn exceeds_limit(&self) -> bool {
        self.ratio > 1.0
    }

    /// Whether the load is at most the upper end of the guide range.
    pub fn within_guide(&self) -> bool {
        self.magnitude <= self.guide.hi
    }

    /// Colour value c = min(magnitude / limit, 1) (SPEC I4, dissertation eq. 5.13).
    pub fn colour_value(&self) -> f64 {
        colour_value(self.ratio)
    }
}

/// A hand's load, split and judged (see the module's rule).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandAssessment {
    /// The force, as push or pull (decides feasibility).
    pub force: Classification,
    /// Signed force along the grip axis, f·d \[N\] (> 0 push).
    pub axial_force: f64,
    /// Force across the grip axis, |f − (f·d) d| \[N\].
    pub lateral_force: f64,
    /// Twist about the hose axis against the screwdriver row.
    pub twist: Classification,
    /// Bending moment across the hose axis against the T-handle row.
    pub bending: Classification,
    /// Whether twist and bending count towards feasibility (the profile's
    /// `moments_decide`).
    pub moments_decide: bool,
}

impl HandAssessment {
    /// The moment (twist or bending) with the larger ratio (twist on a tie).
    pub fn worst_moment(&self) -> &Classification {
        if self.bending.ratio > self.twist.ratio {
            &self.bending
        } else {
            &self.twist
        }
    }

    /// The load that decides feasibility with the larger ratio: the force, or — when
    /// moments decide — the worst of force, twist and bending (the force on a tie).
    pub fn worst(&self) -> &Classification {
        let m = self.worst_moment();
        if self.moments_decide && m.ratio > self.force.ratio {
            m
        } else {
            &self.force
        }
    }

    /// Whether no deciding load exceeds its limit.
    pub fn feasible(&self) -> bool {
        !self.worst().exceeds_limit()
    }

    /// Colour value of the worst deciding load (SPEC I4).
    pub fn colour_value(&self) -> f64 {
        self.worst().colour_value()
    }

    /// Colour of the grabbed hose for the worst deciding load (SPEC I4).
    pub fn colour(&self) -> Rgb {
        colour_rgb(self.colour_value())
    }
}

fn finite(v: DVec3, what: &'static str) -> Result<DVec3, ErgonomicsError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ErgonomicsError::BadInput {
            what,
            reason: "must be finite",
        })
    }
}

/// The unit reference direction; an error if it is zero or not finite.
fn unit_direction(direction: DVec3) -> Result<DVec3, ErgonomicsError> {
    let direction = finite(direction, "reference direction")?;
    if direction.length_squared() == 0.0 {
        return Err(ErgonomicsError::BadInput {
            what: "reference direction",
            reason: "must not be zero",
        });
    }
    Ok(direction.normalize())
}

/// (component along `d`, length of the part across `d`) of `v`, `d` a unit vector.
fn split(v: DVec3, d: DVec3) -> (f64, f64) {
    let along = v.dot(d);
    (along, (v - along * d).length())
}

impl ErgonomicLimits {
    /// Classifies a hand force `force` \[N\] as push or pull relative to the reference
    /// direction `direction` (any non-zero length; only its sense matters) and compares
    /// |f| with the profile's limit for that kind (see the module's rule).
    pub fn classify_force(
        &self,
        profile: &ErgonomicProfile,
        force: DVec3,
        direction: DVec3,
    ) -> Result<Classification, ErgonomicsError> {
        let force = finite(force, "hand force")?;
        Ok(self.force_class(profile, force, unit_direction(direction)?))
    }

    /// [`Self::classify_force`] of a finite force along a unit direction `d`.
    fn force_class(&self, profile: &ErgonomicProfile, force: DVec3, d: DVec3) -> Classification {
        let magnitude = force.length();
        let push = force.dot(d) >= 0.0;
        let kind = if push { LoadKind::Push } else { LoadKind::Pull };
        let (guide, limit, en1005) = self.force_limits(profile, push);
        let mut c = Classification::new(kind, magnitude, guide, limit);
        c.en1005 = en1005.map(|l| l.judge(magnitude));
        c
    }

    /// Splits a hand torque `torque` \[N·m\] into the twist about the hose axis
    /// `direction` (screwdriver row) and the bending moment across it (T-handle row) and
    /// judges each (dissertation section 3.3.3, tables 3.10 / 3.11).
    pub fn classify_moments(
        &self,
        profile: &ErgonomicProfile,
        torque: DVec3,
        direction: DVec3,
    ) -> Result<(Classification, Classification), ErgonomicsError> {
        let torque = finite(torque, "hand torque")?;
        Ok(self.moment_classes(profile, torque, unit_direction(direction)?))
    }

    /// [`Self::classify_moments`] of a finite torque about a unit direction `d`.
    fn moment_classes(
        &self,
        profile: &ErgonomicProfile,
        torque: DVec3,
        d: DVec3,
    ) -> (Classification, Classification) {
        let (twist, bending) = split(torque, d);
        (
            self.moment(profile, LoadKind::Twist, twist.abs()),
            self.moment(profile, LoadKind::Bending, bending),
        )
    }

    fn moment(&self, profile: &ErgonomicProfile, kind: LoadKind, magnitude: f64) -> Classification {
        let grip = kind.torque_grip().unwrap_or(TorqueGrip::THandle);
        let (pop, duty) = (profile.population, profile.duty);
        Classification::new(
            kind,
            magnitude,
            self.torque_guide(grip, pop, duty),
            self.torque_limit(grip, pop, duty),
        )
    }

    /// Judges a hand's force, twist and bending together; see [`HandAssessment::worst`].
    /// The inputs are checked (and the direction made a unit vector) once, in the order
    /// [`Self::classify_force`] and [`Self::classify_moments`] check them.
    pub fn assess(
        &self,
        profile: &ErgonomicProfile,
        force: DVec3,
        torque: DVec3,
        direction: DVec3,
    ) -> Result<HandAssessment, ErgonomicsError> {
        let force = finite(force, "hand force")?;
        let d = unit_direction(direction)?;
        let torque = finite(torque, "hand torque")?;
        let force_c = self.force_class(profile, force, d);
        let (axial_force, lateral_force) = split(force, d);
        let (twist, bending) = self.moment_classes(profile, torque, d);
        Ok(HandAssessment {
            force: force_c,
            axial_force,
            lateral_force,
            twist,
            bending,
            moments_decide: profile.moments_decide,
        })
    }
}
