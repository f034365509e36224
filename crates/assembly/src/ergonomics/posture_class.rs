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
//! | sitting | sitting (figure 3.24) | handle (figure 3.27) |
//! | sitting with bent trunk | sitting | handle |
//!
//! A bent trunk is the tables' lowered posture; raised arms have no row of their own, and
//! the crouching rows — the lowest push limit in every column and the lowest pull limit
//! in three of four — stand in for them. Both are modelling choices, not measurements:
//! the class is reported with every force it judged, so that a reader sees which row
//! decided. A seated worker takes the one seated push row whatever the trunk and arms do
//! (the tables have no other), and the handle pull row — the only pull row not drawn
//! standing or crouching, as the profile's own `posture = "sitting"` does.
//!
//! Under EN 1005-3 (`standard = en1005-3`) the action sets the limit. Standing, the
//! class is reported but changes no number (the user's action stays). Seated, the
//! class chooses the action of table 1: "arm work, sitting, one arm, with trunk support"
//! while the trunk is within 20° of upright (leaning on the backrest), "without trunk
//! support" when it is bent further ([`pliant_worker::posture_class`]).

use super::en1005::En1005Action;
use super::names::Posture;
use super::profile::ErgonomicProfile;
use pliant_worker::PostureClass;

/// The posture word of the tables whose rows judge a hand force in `class` (module
/// table).
pub fn table_posture(class: PostureClass) -> Posture {
    match class {
        PostureClass::Upright => Posture::Standing,
        PostureClass::BentTrunk | PostureClass::ArmsAboveShoulder => Posture::Crouching,
        PostureClass::Sitting | PostureClass::SittingBentTrunk => Posture::Sitting,
    }
}

/// The EN 1005-3 action a seated class is judged by (module doc); `None` standing (the
/// profile's own action).
pub fn en1005_action(class: PostureClass) -> Option<En1005Action> {
    match class {
        PostureClass::Sitting => Some(En1005Action::ArmTrunkSupport),
        PostureClass::SittingBentTrunk => Some(En1005Action::Arm),
        PostureClass::Upright | PostureClass::BentTrunk | PostureClass::ArmsAboveShoulder => None,
    }
}

impl ErgonomicProfile {
    /// This profile with the push and pull rows of `class` (module table), and a seated
    /// class's EN 1005-3 action.
    pub fn for_class(&self, class: PostureClass) -> ErgonomicProfile {
        let posture = table_posture(class);
        let mut en1005 = self.en1005;
        if let Some(action) = en1005_action(class) {
            en1005.action = action;
        }
        ErgonomicProfile {
            push_posture: posture.push(),
            pull_posture: posture.pull(),
            en1005,
            ..*self
        }
    }
}
