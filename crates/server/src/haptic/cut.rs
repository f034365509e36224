//! The hand's component alone ([`pliant_core::integrators::component`]) as a model and
//! state of its own ([`pliant_core::integrators::cut::Cut`]), with the hand renumbered
//! into it: what the mirror solves for each pose the hand streams.

use pliant_assembly::workcell::HeldHand;
use pliant_core::integrators::cut::Cut;
use pliant_core::{Model, State};

/// The hand's component and the hand, renumbered into it.
pub struct HandCut {
    pub cut: Cut,
    /// The hand, renumbered into the cut.
    pub hand: HeldHand,
}

impl HandCut {
    /// The cut of `model` to `nodes` (sorted, the component of `hand`'s nodes) in
    /// `state`, with `hand` renumbered; `None` when the model has what a cut cannot
    /// carry ([`Cut::new`]) or the hand's nodes are not in `nodes`.
    pub fn new(model: &Model, state: &State, nodes: Vec<usize>, hand: &HeldHand) -> Option<Self> {
        let cut = Cut::new(model, state, nodes)?;
        let element = cut.element(hand.hand.element)?;
        let hose = cut.model.hoses.iter().position(|h| {
            (h.first_element..h.first_element + h.element_count).contains(&element)
        })?;
        let renumbered = hand
            .hand
            .renumbered(|i| cut.node(i), |id| cut.case(id), element, hose)?;
        let hand = HeldHand {
            hand: renumbered,
            aim: None,
        };
        Some(HandCut { cut, hand })
    }
}
