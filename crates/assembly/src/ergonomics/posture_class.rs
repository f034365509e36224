//! The worker's posture class chooses the rows of the push and pull tables (SPEC E2:
//! "the posture class feeds the force limits"). With a `[worker]` in the scene, each
//! posed instant's class ([`PostureClass::of`]) replaces the profile's fixed `posture`
//! for the hand forces until the next posed instant; population, duty and standard stay
//! the user's.
//!
//! The dissertation's tables 3.6–3.9 (after Schmidtke) have rows for standing,
//! crouching and sitting only, drawn in figures 3.22–3.27 without angles:
//!
//! | class | push row (3.6 / 3.7) | pull row (3.8 / 3.9) |
//! |---|---|---|
//! | standing upright | standing | standing lever |
//! | bent trunk | crouching | crouching lever |
//! | arms above shoulder | crouching | crouching lever |
//!
//! A bent trunk is the tables' lowered posture; raised arms have no row of their own, and
//! the crouching rows — the lowest push limit in every column and the lowest pull limit
//! in three of four — stand in for them. Both are modelling choices, not measurements:
//! the class is reported with every force it judged, so that a reader sees which row
//! decided. Under EN 1005-3 (`standard = en1005-3`) the action, not the posture, sets the
//! limit: the class is reported but changes no number.

use super::names::Posture;
use super::profile::ErgonomicProfile;
use pliant_worker::PostureClass;

/// The posture word of the tables whose rows judge a hand force in `class` (module
/// table).
pub fn table_posture(class: PostureClass) -> Posture {
    match class {
        PostureClass::Upright => Posture::Standing,
        PostureClass::BentTrunk | PostureClass::ArmsAboveShoulder => Posture::Crouching,
    }
}

impl ErgonomicProfile {
    /// This profile with the push and pull rows of `class` (module table).
    pub fn for_class(&self, class: PostureClass) -> ErgonomicProfile {
        let posture = table_posture(class);
        ErgonomicProfile {
            push_posture: posture.push(),
            pull_posture: posture.pull(),
            ..*self
        }
    }
}
