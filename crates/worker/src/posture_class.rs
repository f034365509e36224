//! The posture class of a manikin posture (SPEC E2: "the posture class feeds the force
//! limits"): standing upright, with the trunk bent, or with an arm raised above the
//! shoulder. The ergonomic tables a hand force is judged by give a row per posture
//! (standing, crouching, sitting — drawn, not measured in angles), so the class is read
//! off the joint angles with the posture methods' band edges:
//!
//! - **bent trunk**: trunk flexion beyond [`BENT_TRUNK`] = 20°, the edge between RULA's
//!   and REBA's "0–20° flexion" and "20–60° flexion" trunk bands (McAtamney & Corlett
//!   1993, fig. 2; Hignett & McAtamney 2000, table 1);
//! - **arms above shoulder**: a working arm's upper arm raised beyond [`ARM_ABOVE_SHOULDER`]
//!   = 90° from hanging, measured against the vertical (the elbow above the shoulder,
//!   the arm held up against gravity), the edge of RULA's and REBA's highest upper-arm
//!   band ("over 90°").
//!
//! Arms above the shoulder outrank a bent trunk (both at once: arms above shoulder). An
//! arm without a target hangs and never counts.
//!
//! A seated worker ([`crate::seat`]) is in one of two sitting classes whatever the arms
//! do: the tables have a single seated push row (the dissertation's figure 3.24) and no
//! seated row for raised arms, and EN 1005-3 (table 1) distinguishes seated arm work
//! "with trunk support" from "without trunk support". The trunk counts as supported (by
//! the seat's backrest) while it is within [`BENT_TRUNK`] of upright — the same edge as
//! standing, a modelling choice: a trunk flexed further forward has left the backrest.
//! Kneeling and squatting are not classes.

use crate::posture::Posture;
use glam::DVec3;
use serde::Serialize;

/// Trunk flexion beyond which the trunk counts as bent \[rad\] (20°; module doc).
pub const BENT_TRUNK: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// Upper-arm elevation from hanging, against the vertical, beyond which an arm counts
/// as above the shoulder \[rad\] (90°; module doc).
pub const ARM_ABOVE_SHOULDER: f64 = 90.0 * std::f64::consts::PI / 180.0;

/// The posture class of one posed instant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PostureClass {
    /// Trunk within 20° of upright, arms below the shoulder.
    #[default]
    Upright,
    /// Trunk flexed beyond 20°.
    BentTrunk,
    /// A working arm's elbow above its shoulder.
    ArmsAboveShoulder,
    /// Seated, the trunk within 20° of upright (supported by the backrest).
    Sitting,
    /// Seated, the trunk flexed beyond 20° (off the backrest: no trunk support).
    SittingBentTrunk,
}

impl PostureClass {
    /// Every class, in the order of [`Self::index`].
    pub const ALL: [PostureClass; 5] = [
        PostureClass::Upright,
        PostureClass::BentTrunk,
        PostureClass::ArmsAboveShoulder,
        PostureClass::Sitting,
        PostureClass::SittingBentTrunk,
    ];

    /// Position in [`Self::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The snake_case name (`worker.csv`, `summary.json`).
    pub fn name(self) -> &'static str {
        match self {
            PostureClass::Upright => "upright",
            PostureClass::BentTrunk => "bent_trunk",
            PostureClass::ArmsAboveShoulder => "arms_above_shoulder",
            PostureClass::Sitting => "sitting",
            PostureClass::SittingBentTrunk => "sitting_bent_trunk",
        }
    }

    /// In words, as the verdict writes it: "standing upright", "bent trunk", "arms
    /// above shoulder", "sitting", "sitting with bent trunk".
    pub fn words(self) -> &'static str {
        match self {
            PostureClass::Upright => "standing upright",
            PostureClass::BentTrunk => "bent trunk",
            PostureClass::ArmsAboveShoulder => "arms above shoulder",
            PostureClass::Sitting => "sitting",
            PostureClass::SittingBentTrunk => "sitting with bent trunk",
        }
    }

    /// Whether the class is seated.
    pub fn is_sitting(self) -> bool {
        matches!(self, PostureClass::Sitting | PostureClass::SittingBentTrunk)
    }

    /// The class of `posture`, the world's vertical `up` (unit).
    pub fn of(posture: &Posture, up: DVec3) -> PostureClass {
        let bent = posture.trunk.flexion > BENT_TRUNK;
        if posture.sitting.is_some() {
            return if bent {
                PostureClass::SittingBentTrunk
            } else {
                PostureClass::Sitting
            };
        }
        let raised = posture.arms.iter().any(|arm| {
            let upper = (arm.elbow - arm.shoulder).normalize_or_zero();
            // angle from hanging (straight down) against the vertical
            arm.target.is_some() && (-upper.dot(up)).clamp(-1.0, 1.0).acos() > ARM_ABOVE_SHOULDER
        });
        if raised {
            PostureClass::ArmsAboveShoulder
        } else if bent {
            PostureClass::BentTrunk
        } else {
            PostureClass::Upright
        }
    }
}

impl std::fmt::Display for PostureClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.words())
    }
}
