//! Fixings by type, each with the degrees of freedom it leaves free, in
//! the VEC convention for fixings: origin on the support (here the seat centre p, where
//! the seated hose's centre line passes), **Y** along the hose (the clip's `orientation`
//! l), **Z** against the mounting direction (the clip's `opening` n: the hose is mounted
//! by pushing it along −n), **X** = Y × Z.
//!
//! | type | free | held by |
//! |---|---|---|
//! | `fixed` | nothing (all six fixed) | an L1 fix |
//! | `rotating` | rotation about Z (the clip turns on its mount) | a support |
//! | `sliding` | translation along Y, against Coulomb friction μ N | a support |
//! | `cable_tie` | nothing (tied to a part: all six fixed) | an L1 fix |
//!
//! Snap-in: `fixed`, `rotating` and `sliding` snap in by the clip's force law (snap force
//! k); a cable tie has no snap (k may be 0) and closes once the hose lies released in its
//! seat. Holding: each may have a pull-out force; a seated hose whose support pulls it
//! back into the seat harder than that (along −Z) comes loose.

use serde::{Deserialize, Serialize};

/// The type of a fixing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ClipKind {
    /// All six degrees of freedom fixed.
    #[default]
    Fixed,
    /// Free to turn about the clip's Z axis.
    Rotating,
    /// Free to slide along the hose (Y), with friction.
    Sliding,
    /// A cable tie around the hose to a part: all six fixed, no snap.
    CableTie,
}

impl ClipKind {
    /// Which translations along the fixing's (X, Y, Z) it leaves free.
    pub fn free_translation(self) -> [bool; 3] {
        match self {
            ClipKind::Sliding => [false, true, false],
            _ => [false; 3],
        }
    }

    /// Which rotations about the fixing's (X, Y, Z) it leaves free.
    pub fn free_rotation(self) -> [bool; 3] {
        match self {
            ClipKind::Rotating => [false, false, true],
            _ => [false; 3],
        }
    }

    /// Whether it holds all six degrees of freedom (an L1 fix serves).
    pub fn holds_all(self) -> bool {
        self.free_translation() == [false; 3] && self.free_rotation() == [false; 3]
    }

    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            ClipKind::Fixed => "fixed",
            ClipKind::Rotating => "rotating",
            ClipKind::Sliding => "sliding",
            ClipKind::CableTie => "cable_tie",
        }
    }
}
