//! The phases of pushing a hose end onto a stub and pulling it off (SPEC L6, dissertation
//! section 5.3.5), as a state machine driven once per step by what the hose end does.
//!
//! Rules, in terms of the end's axial coordinate s = (e − origin)·axis, its distance q
//! from the axis line and the angle α between its direction and the axis
//! ("in reach": q ≤ `lateral`, α ≤ `angle`):
//! - **Approach** (also after **PulledOff**): only a grabbed end engages (a hose that
//!   starts on its stub is set to Fixed by the scene). In reach with −`approach` ≤ s ≤ 0
//!   → Aligned; in reach with s > 0 (a fast move past the mouth) → Inserting, except for
//!   a law that must be entered through the mouth ([`AxialLaw::enters_through_mouth`]:
//!   a connector), which stays in Approach.
//! - **Aligned** (the physics layer aligns the end with the axis, thesis fig. 5.19): out of
//!   reach, s < −`approach`, or released → Approach; s > 0 → Inserting.
//! - **Inserting{depth}**, depth = clamp(s, 0, length) (insertion stops at the stub's
//!   length): released → Fixed{depth} (the end becomes an L1 fix); s ≤ 0 → PulledOff.
//!   Alignment is held by the load cases meanwhile, so reach is not checked.
//! - **Fixed{depth}**: grabbed and the hand's axial force exceeds the holding force
//!   p·γ_static·2π r_s·depth → Inserting{depth} (it breaks loose and slides), except a push
//!   at the stop (depth = length), which cannot move it; otherwise stays Fixed.
//! - **PulledOff** lasts one step (an event for the report), then behaves as Approach.

use super::bead::Sense;
use super::error::StubError;
use super::law::AxialLaw;
use super::spec::{Friction, StubSpec};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// How close a hose end must come to be taken onto the stub.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StubTolerance {
    /// Largest distance of the end from the stub axis \[m\].
    pub lateral: f64,
    /// Largest angle between the end's direction and the axis \[rad\].
    pub angle: f64,
    /// Largest distance in front of the mouth at which the end is aligned \[m\].
    pub approach: f64,
}

impl StubTolerance {
    /// Default for a stub: lateral = r_s (the end's centre over the stub's face),
    /// angle = 30°, approach = d_s.
    pub fn for_stub(stub: &StubSpec) -> Self {
        StubTolerance {
            lateral: stub.radius(),
            angle: 30f64.to_radians(),
            approach: stub.diameter(),
        }
    }

    /// The tolerance if it is valid (what [`StubState::next`] checks every call): a run
    /// checks its stubs' tolerances once and steps them with [`StubState::next_within`].
    pub(crate) fn checked(self) -> Option<Self> {
        self.check().ok().map(|_| self)
    }

    fn check(&self) -> Result<(), StubError> {
        let ok = self.lateral.is_finite()
            && self.lateral >= 0.0
            && self.approach.is_finite()
            && self.approach >= 0.0
            && (0.0..=std::f64::consts::PI).contains(&self.angle);
        if ok {
            Ok(())
        } else {
            Err(StubError::Observation {
                field: "tolerance",
                reason: "needs finite lateral, approach >= 0 and angle in [0, pi]",
            })
        }
    }
}

/// What the hose end does in one step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StubObservation {
    /// Position of the hose end node \[m\].
    pub end_position: DVec3,
    /// Direction the end faces: along the hose axis, out of the hose (from the
    /// second-to-last node towards the end node). Any non-zero length.
    pub end_direction: DVec3,
    /// The axial component of the force the hand applies to the hose, along the stub's
    /// axis \[N\]: > 0 pushes further on, < 0 pulls off.
    pub axial_force: f64,
    /// Whether a hand holds the hose at this end.
    pub grabbed: bool,
}

/// Where a hose end is relative to a stub.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StubState {
    /// Not engaged.
    #[default]
    Approach,
    /// In front of the mouth, aligned with the axis.
    Aligned,
    /// On the stub and moving with the hand; depth \[m\] in [0, length].
    Inserting { depth: f64 },
    /// Released on the stub: held by an L1 fix; depth \[m\].
    Fixed { depth: f64 },
    /// Just pulled off (one step).
    PulledOff,
}

impl StubState {
    /// Insertion depth \[m\] (0 when not on the stub).
    pub fn depth(&self) -> f64 {
        match *self {
            StubState::Inserting { depth } | StubState::Fixed { depth } => depth,
            _ => 0.0,
        }
    }

    /// The friction that acts: sliding while inserting, static when fixed, none off the
    /// stub.
    pub fn friction(&self) -> Option<Friction> {
        match self {
            StubState::Inserting { .. } => Some(Friction::Sliding),
            StubState::Fixed { .. } => Some(Friction::Static),
            _ => None,
        }
    }

    /// The axial force the stub opposes to motion in this state \[N\] (eq. 4.107 at the
    /// current depth with the current friction; 0 off the stub).
    pub fn resisting_force(&self, fit: &impl AxialLaw) -> f64 {
        self.friction().map_or(0.0, |friction| {
            fit.axial_force_moving(self.depth(), friction, Sense::On)
        })
    }

    /// As [`Self::resisting_force`] for motion in `sense`, a bead included (SPEC V4).
    pub fn resisting_force_moving(&self, fit: &impl AxialLaw, sense: Sense) -> f64 {
        self.friction().map_or(0.0, |friction| {
            fit.axial_force_moving(self.depth(), friction, sense)
        })
    }

    /// The state after one step; see the module's rules.
    pub fn next(
        self,
        fit: &impl AxialLaw,
        tolerance: &StubTolerance,
        obs: &StubObservation,
    ) -> Result<StubState, StubError> {
        tolerance.check()?;
        self.next_within(fit, tolerance, obs)
    }

    /// [`StubState::next`] under a tolerance already checked ([`StubTolerance::checked`]).
    pub(crate) fn next_within(
        self,
        fit: &impl AxialLaw,
        tolerance: &StubTolerance,
        obs: &StubObservation,
    ) -> Result<StubState, StubError> {
        let refuse = |field, reason| StubError::Observation { field, reason };
        if !obs.end_position.is_finite() {
            return Err(refuse("end_position", "must be finite"));
        }
        let direction = obs
            .end_direction
            .try_normalize()
            .ok_or(refuse("end_direction", "must be finite and non-zero"))?;
        if !obs.axial_force.is_finite() {
            return Err(refuse("axial_force", "must be finite"));
        }
        let stub = fit.stub();
        let s = stub.axial_coordinate(obs.end_position);
        // reach (a distance and an arc cosine) matters only off the stub: asked there only
        let in_reach = || {
            let angle = direction.dot(stub.axis()).clamp(-1.0, 1.0).acos();
            stub.lateral_distance(obs.end_position) <= tolerance.lateral && angle <= tolerance.angle
        };
        let inserting = StubState::Inserting {
            depth: stub.clamp_depth(s),
        };
        Ok(match self {
            StubState::Approach | StubState::PulledOff => {
                // not held, out of reach, or past a mouth it must enter through
                if !obs.grabbed
                    || !in_reach()
                    || s < -tolerance.approach
                    || (s > 0.0 && fit.enters_through_mouth())
                {
                    StubState::Approach
                } else if s > 0.0 {
                    inserting
                } else {
                    StubState::Aligned
                }
            }
            StubState::Aligned => {
                if !in_reach() || s < -tolerance.approach || !obs.grabbed {
                    StubState::Approach
                } else if s > 0.0 {
                    inserting
                } else {
                    StubState::Aligned
                }
            }
            StubState::Inserting { depth } => {
                if !obs.grabbed {
                    StubState::Fixed { depth }
                } else if s <= 0.0 {
                    StubState::PulledOff
                } else {
                    inserting
                }
            }
            StubState::Fixed { depth } => {
                let breaks_loose = || {
                    let at_stop = depth >= stub.length();
                    let sense = if obs.axial_force >= 0.0 {
                        Sense::On
                    } else {
                        Sense::Off
                    };
                    obs.axial_force.abs() > fit.holding_force_moving(depth, sense)
                        && !(at_stop && obs.axial_force > 0.0)
                };
                if obs.grabbed && breaks_loose() {
                    StubState::Inserting { depth }
                } else {
                    StubState::Fixed { depth }
                }
            }
        })
    }
}
