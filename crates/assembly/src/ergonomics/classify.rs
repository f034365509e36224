//! Judging a hand load against the ergonomic limits (SPEC I2, I3, I5).
//!
//! Rule: the hand force f is classified by the sign of f·d, where d is the reference
//! direction at the grabbed point (e.g. the hose axis pointing from the hand into the
//! hose, or the insertion direction onto a stub): f·d ≥ 0 is a **push**, f·d < 0 a
//! **pull**. The whole magnitude |f| — the lateral part included — is compared with that
//! kind's limit (a lateral force is as tiring as an axial one, and the tables give no
//! lateral values). A force with f·d = 0 (purely lateral, or zero) counts as a push.
//! The hand torque's magnitude |t| is compared with the torque limit of the profile's
//! grip. The verdict for the hand is the worse of the two ratios.

use super::colour::{colour_rgb, colour_value, Rgb};
use super::error::ErgonomicsError;
use super::limits::{ErgonomicLimits, GuideRange};
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
    /// Torque (tables 3.10 / 3.11).
    Torque,
}

/// One hand load against its limit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Classification {
    /// Push, pull or torque.
    pub kind: LoadKind,
    /// |f| [N] or |t| [N·m].
    pub magnitude: f64,
    /// The guide range of the profile's row and column [N or N·m].
    pub guide: GuideRange,
    /// The limit value of the profile's row and column [N or N·m].
    pub limit: f64,
    /// magnitude / limit; above 1 the limit is exceeded.
    pub ratio: f64,
}

impl Classification {
    fn new(kind: LoadKind, magnitude: f64, guide: GuideRange, limit: f64) -> Self {
        Classification {
            kind,
            magnitude,
            guide,
            limit,
            ratio: magnitude / limit,
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

/// A hand's force and torque, each judged.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct HandAssessment {
    /// The force, as push or pull.
    pub force: Classification,
    /// The torque.
    pub torque: Classification,
}

impl HandAssessment {
    /// The load with the larger ratio (the force on a tie).
    pub fn worst(&self) -> &Classification {
        if self.torque.ratio > self.force.ratio {
            &self.torque
        } else {
            &self.force
        }
    }

    /// Whether neither load exceeds its limit.
    pub fn feasible(&self) -> bool {
        !self.worst().exceeds_limit()
    }

    /// Colour value of the worse load (SPEC I4).
    pub fn colour_value(&self) -> f64 {
        self.worst().colour_value()
    }

    /// Colour of the grabbed hose for the worse load (SPEC I4).
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

impl ErgonomicLimits {
    /// Classifies a hand force `force` [N] as push or pull relative to the reference
    /// direction `direction` (any non-zero length; only its sense matters) and compares
    /// |f| with the profile's limit for that kind (see the module's rule).
    pub fn classify_force(
        &self,
        profile: &ErgonomicProfile,
        force: DVec3,
        direction: DVec3,
    ) -> Result<Classification, ErgonomicsError> {
        let force = finite(force, "hand force")?;
        let direction = finite(direction, "reference direction")?;
        if direction.length_squared() == 0.0 {
            return Err(ErgonomicsError::BadInput {
                what: "reference direction",
                reason: "must not be zero",
            });
        }
        let (pop, duty) = (profile.population, profile.duty);
        let magnitude = force.length();
        Ok(if force.dot(direction) >= 0.0 {
            let p = profile.push_posture;
            Classification::new(
                LoadKind::Push,
                magnitude,
                self.push_guide(p, pop, duty),
                self.push_limit(p, pop, duty),
            )
        } else {
            let p = profile.pull_posture;
            Classification::new(
                LoadKind::Pull,
                magnitude,
                self.pull_guide(p, pop, duty),
                self.pull_limit(p, pop, duty),
            )
        })
    }

    /// Compares the magnitude of a hand torque `torque` [N·m] with the profile's torque
    /// limit.
    pub fn classify_torque(
        &self,
        profile: &ErgonomicProfile,
        torque: DVec3,
    ) -> Result<Classification, ErgonomicsError> {
        let torque = finite(torque, "hand torque")?;
        let (g, pop, duty) = (profile.torque_grip, profile.population, profile.duty);
        Ok(Classification::new(
            LoadKind::Torque,
            torque.length(),
            self.torque_guide(g, pop, duty),
            self.torque_limit(g, pop, duty),
        ))
    }

    /// Judges a hand's force and torque together; see [`HandAssessment::worst`].
    pub fn assess(
        &self,
        profile: &ErgonomicProfile,
        force: DVec3,
        torque: DVec3,
        direction: DVec3,
    ) -> Result<HandAssessment, ErgonomicsError> {
        Ok(HandAssessment {
            force: self.classify_force(profile, force, direction)?,
            torque: self.classify_torque(profile, torque)?,
        })
    }
}
