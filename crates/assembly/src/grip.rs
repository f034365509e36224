//! How a hand holds the hose: firm — the held beam follows the hand in
//! all six degrees of freedom, as in SPEC I1 — or loose: the hand holds the position and
//! the hose may turn in it, about its own axis (`axial`: both nodes of the beam held in
//! position only, so the hand carries no moment about the beam's axis) or about every axis
//! like a ball joint (`ball`: the one node nearest the hand held in position only, the hand
//! point on it, so the hand carries no moment at all).

use serde::{Deserialize, Serialize};

/// A hand's grip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Grip {
    /// Six degrees of freedom: the beam turns with the hand.
    #[default]
    Firm,
    /// Position held; free to turn about the hose's own axis.
    Axial,
    /// Position held; free to turn about every axis.
    Ball,
}

impl Grip {
    /// Whether this is the firm grip (the default, left out when written).
    pub fn is_firm(&self) -> bool {
        *self == Grip::Firm
    }

    /// The name used in scenes and the protocol.
    pub fn name(self) -> &'static str {
        match self {
            Grip::Firm => "firm",
            Grip::Axial => "axial",
            Grip::Ball => "ball",
        }
    }
}
