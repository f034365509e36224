//! A VR user's own body posing the worker (SPEC E1, issue's "in VR the user's headset and
//! controllers drive it"): the headset gives the head target — where the eyes are and
//! which way they look — and each controller the target of its arm. The manikin keeps
//! its own stance and proportions; the inverse kinematics bends its trunk to bring its
//! eyes to the headset's and turns its neck along the gaze
//! ([`pliant_worker::Manikin::solve_with_head`]).

use glam::DVec3;
use pliant_worker::HeadTarget;
use serde::{Deserialize, Serialize};

/// The headset's and controllers' poses in the world frame \[m\].
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BodyPose {
    /// The eyes' midpoint and the gaze direction (any length but zero), if a headset.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head: Option<HeadTarget>,
    /// Each controller's grip (right, left), if tracked: the arm's target.
    #[serde(default)]
    pub hands: [Option<DVec3>; 2],
}

impl BodyPose {
    /// Refuses non-finite values and a zero gaze, naming the field.
    pub fn check(&self) -> Result<(), String> {
        if let Some(h) = &self.head {
            if !h.eyes.is_finite() {
                return Err(format!("head position {} is not finite", h.eyes));
            }
            if !h.gaze.is_finite() || h.gaze.length_squared() < 1e-18 {
                return Err(format!(
                    "head gaze {} must be a finite, non-zero direction",
                    h.gaze
                ));
            }
        }
        for (side, p) in ["right", "left"].iter().zip(&self.hands) {
            if let Some(p) = p {
                if !p.is_finite() {
                    return Err(format!("{side} hand position {p} is not finite"));
                }
            }
        }
        Ok(())
    }
}
