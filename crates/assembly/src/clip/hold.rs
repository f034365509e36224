//! What holds a seated hose: the load case a clip of each type puts on
//! the seated node — an L1 fix when it fixes all six degrees of freedom, else a support
//! ([`pliant_core::loads::Support`]) free in the type's directions of the clip's VEC frame,
//! with the clip's friction along a free translation.

use super::spec::ClipSpec;
use glam::{DQuat, DVec3};
use pliant_core::loads::{Fix, LoadCase, Support};

impl ClipSpec {
    /// The load case holding `node`, seated at (`position`, `orientation`), in this clip.
    pub fn seat_hold(&self, node: usize, position: DVec3, orientation: DQuat) -> LoadCase {
        let kind = self.kind();
        if kind.holds_all() {
            return LoadCase::Fix(Fix {
                node,
                position,
                orientation,
            });
        }
        LoadCase::Support(Support::new(
            node,
            position,
            orientation,
            self.frame(),
            kind.free_translation(),
            kind.free_rotation(),
            self.friction(),
        ))
    }
}
