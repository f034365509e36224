//! A borrowed view of the node arrays the element kernels read, with the inelastic
//! elements' committed history.

use crate::rod::inelastic::HistoryView;
use glam::{DQuat, DVec3};

/// The node arrays the element kernels read, borrowed: positions, frames, velocities and
/// angular velocities of every node (a state's, or a trial configuration's).
pub struct NodeView<'a> {
    pub x: &'a [DVec3],
    pub q: &'a [DQuat],
    pub v: &'a [DVec3],
    pub w: &'a [DVec3],
    /// The inelastic elements' committed history and its age
    /// ([`crate::rod::inelastic`]); [`HistoryView::NONE`] → virgin.
    pub inelastic_history: HistoryView<'a>,
}
