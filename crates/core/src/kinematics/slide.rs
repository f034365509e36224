//! A slide: translation by s(t) along a fixed direction (a seat rail, a drawer).
//! T = s d, Ṫ = ṡ d, no rotation.

use super::pose::{Placement, Pose, Twist};
use super::profile::Profile;
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Slide {
    /// The direction of travel (unit).
    pub direction: DVec3,
    /// The distance travelled over time \[m\].
    pub distance: Profile,
}

impl Slide {
    pub fn placement_at(&self, t: f64) -> Placement {
        let (s, rate) = self.distance.at(t);
        Placement {
            pose: Pose {
                rotation: DQuat::IDENTITY,
                translation: self.direction * s,
            },
            twist: Twist {
                linear: self.direction * rate,
                angular: DVec3::ZERO,
            },
        }
    }
}
