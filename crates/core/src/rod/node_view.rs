//! A borrowed view of the node arrays the element kernels read, with the yielding
//! elements' committed history.

use glam::{DQuat, DVec3};

/// The node arrays the element kernels read, borrowed: positions, frames, velocities and
/// angular velocities of every node (a state's, or a trial configuration's).
pub struct NodeView<'a> {
    pub x: &'a [DVec3],
    pub q: &'a [DQuat],
    pub v: &'a [DVec3],
    pub w: &'a [DVec3],
    /// The yielding elements' committed plastic strains (`State::plastic_strain`;
    /// [`crate::rod::plastic_hinges`]); empty → never yielded.
    pub plastic_strain: &'a [f64],
}
