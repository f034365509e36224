//! The phases of snapping a hose into a clip and taking it out again (SPEC L7,
//! dissertation section 5.3.6), as a state machine driven once per step.
//!
//! Rules, with m the hose centre in the clip's plane ([`ClipSpec::centre_on_segment`]),
//! s = (m − p)·n, q its lateral offset from the n–l plane, r the hose's outer radius:
//! - **Free**: the force law does not act. The hose engages (→ Snapping) when it crosses
//!   the clip plane, r > d₁/2 (a thinner hose never engages), q ≤ `lateral`, and
//!   −|n| < s < |n| + h (it touches the jaws or is inside the clip).
//! - **Snapping**: the force law acts. Out of the clip plane, q > `lateral`, s ≥ |n| + h
//!   (pulled back out past the opening until the jaws no longer touch) or s ≤ −|n| →
//!   Free. Released with |s| ≤ `seat`, or passing through the seat (s changing sign
//!   between two steps), → Seated. Released between the opening and the seat
//!   it stays Snapping: the pull-in branch draws it to the seat (the thesis moves it there
//!   by a translation load case) and it is seated once within `seat`.
//! - **Seated**: held at the seat by an L1 fix (the force law is not needed: it is 0 at
//!   the seat). Grabbed → Snapping (the fix is lifted and the force law acts again, so
//!   pulling it out takes the snap force).

use super::error::ClipError;
use super::spec::ClipSpec;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// How close a hose must be to engage and to count as seated.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClipTolerance {
    /// Largest |s| at which a released hose is seated \[m\].
    pub seat: f64,
    /// Largest lateral offset q at which the hose engages \[m\].
    pub lateral: f64,
}

impl ClipTolerance {
    /// Default for a clip: seat = |n| / 10, lateral = d₂ / 2.
    pub fn for_clip(clip: &ClipSpec) -> Self {
        ClipTolerance {
            seat: 0.1 * clip.opening_distance(),
            lateral: 0.5 * clip.inner_diameter(),
        }
    }

    /// The tolerance if it is valid (what [`ClipState::next`] checks every call): a run
    /// checks its clips' tolerances once and steps them with [`ClipState::next_within`].
    pub(crate) fn checked(self) -> Option<Self> {
        self.check().ok().map(|_| self)
    }

    fn check(&self) -> Result<(), ClipError> {
        if self.seat.is_finite()
            && self.seat >= 0.0
            && self.lateral.is_finite()
            && self.lateral >= 0.0
        {
            Ok(())
        } else {
            Err(ClipError::Observation {
                field: "tolerance",
                reason: "seat and lateral must be finite and >= 0",
            })
        }
    }
}

/// What the hose does at the clip in one step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClipObservation {
    /// The hose centre m in the clip's plane, `None` if the hose does not cross it.
    pub centre: Option<DVec3>,
    /// The hose's outer radius there \[m\].
    pub radius: f64,
    /// Whether a hand holds the hose near the clip.
    pub grabbed: bool,
    /// Whether the hose centre crossed the seat (its coordinate s along the opening changed
    /// sign) since the last step: a hose springing back through the seat within one step
    /// has been in it, however long the step.
    pub crossed_seat: bool,
}

/// Where a hose is relative to a clip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClipState {
    /// Not engaged: no clip force.
    #[default]
    Free,
    /// Engaged: the force law acts.
    Snapping,
    /// Seated and held by an L1 fix.
    Seated,
}

impl ClipState {
    /// Whether the force law of [`ClipSpec::force_on_hose`] acts in this state.
    pub fn force_acts(&self) -> bool {
        matches!(self, ClipState::Snapping)
    }

    /// The clip force on the hose in this state \[N\] (zero unless Snapping).
    pub fn force(&self, clip: &ClipSpec, obs: &ClipObservation) -> DVec3 {
        match (self.force_acts(), obs.centre) {
            (true, Some(m)) => clip.force_on_hose(m, obs.radius),
            _ => DVec3::ZERO,
        }
    }

    /// The state after one step; see the module's rules.
    pub fn next(
        self,
        clip: &ClipSpec,
        tolerance: &ClipTolerance,
        obs: &ClipObservation,
    ) -> Result<ClipState, ClipError> {
        tolerance.check()?;
        self.next_within(clip, tolerance, obs)
    }

    /// [`ClipState::next`] under a tolerance already checked ([`ClipTolerance::checked`]).
    pub(crate) fn next_within(
        self,
        clip: &ClipSpec,
        tolerance: &ClipTolerance,
        obs: &ClipObservation,
    ) -> Result<ClipState, ClipError> {
        if !(obs.radius.is_finite() && obs.radius > 0.0) {
            return Err(ClipError::Observation {
                field: "radius",
                reason: "must be finite and positive",
            });
        }
        if obs.centre.is_some_and(|m| !m.is_finite()) {
            return Err(ClipError::Observation {
                field: "centre",
                reason: "must be finite",
            });
        }
        // Inside the engagement region: in the plane, in line with the opening, between
        // −|n| and first touch, and thicker than the opening. Asked only where it decides
        // (a seated hose stays seated until grabbed).
        let engaged = || match (obs.centre, clip.first_touch(obs.radius)) {
            (Some(m), Some(touch)) => {
                let (n, s) = (clip.opening_distance(), clip.opening_coordinate(m));
                clip.lateral_offset(m) <= tolerance.lateral && s > -n && s < touch
            }
            _ => false,
        };
        let seated = || {
            obs.crossed_seat
                || obs
                    .centre
                    .is_some_and(|m| clip.opening_coordinate(m).abs() <= tolerance.seat)
        };
        Ok(match self {
            ClipState::Free if engaged() => ClipState::Snapping,
            ClipState::Free => ClipState::Free,
            ClipState::Snapping if !engaged() => ClipState::Free,
            ClipState::Snapping if !obs.grabbed && seated() => ClipState::Seated,
            ClipState::Snapping => ClipState::Snapping,
            ClipState::Seated if obs.grabbed => ClipState::Snapping,
            ClipState::Seated => ClipState::Seated,
        })
    }
}
