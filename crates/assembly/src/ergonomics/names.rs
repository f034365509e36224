//! The axes of the ergonomic tables (SPEC I3, dissertation tables 3.6–3.11): the posture
//! of each kind of load, the population and the duty. Every name parses from text
//! (case-insensitive; `-` and spaces count as `_`) with an error that lists the allowed
//! values, and (de)serialises as its snake_case name.

use super::error::ErgonomicsError;
use serde::{Deserialize, Serialize};

/// A closed set of named values, parsable from and printable as text.
pub trait Named: Copy + Sized + 'static {
    /// What a value of this set names, for error messages (e.g. "pull posture").
    const WHAT: &'static str;
    /// Every value, in table order.
    const ALL: &'static [Self];
    /// The canonical (snake_case) name of the value.
    fn name(self) -> &'static str;
    /// Position of the value in [`Named::ALL`].
    fn index(self) -> usize;
}

/// Parses any [`Named`] set: trims, lower-cases and reads `-` and spaces as `_`.
pub fn parse_named<T: Named>(text: &str) -> Result<T, ErgonomicsError> {
    let key: String = text
        .trim()
        .chars()
        .map(|c| match c {
            '-' | ' ' => '_',
            c => c.to_ascii_lowercase(),
        })
        .collect();
    T::ALL
        .iter()
        .copied()
        .find(|v| v.name() == key)
        .ok_or_else(|| ErgonomicsError::UnknownName {
            what: T::WHAT,
            given: text.to_string(),
            allowed: allowed_names::<T>(),
        })
}

/// The allowed names of a set, comma-separated.
pub fn allowed_names<T: Named>() -> String {
    T::ALL
        .iter()
        .map(|v| v.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Implements `Named`, `FromStr` and `Display` for a fieldless enum.
macro_rules! named_enum {
    ($ty:ident, $what:literal, [$($variant:ident => $name:literal),+ $(,)?]) => {
        impl Named for $ty {
            const WHAT: &'static str = $what;
            const ALL: &'static [Self] = &[$($ty::$variant),+];
            fn name(self) -> &'static str {
                match self {
                    $($ty::$variant => $name),+
                }
            }
            fn index(self) -> usize {
                self as usize
            }
        }
        impl std::str::FromStr for $ty {
            type Err = ErgonomicsError;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                parse_named(s)
            }
        }
        impl std::fmt::Display for $ty {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

/// Body posture when pushing (rows of tables 3.6 / 3.7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PushPosture {
    /// Standing, flat hand against a vertical plane (figure 3.22).
    #[default]
    Standing,
    /// Crouching, flat hand against a vertical plane (figure 3.23).
    Crouching,
    /// Sitting, hand on a horizontal plane (figure 3.24).
    Sitting,
}
named_enum!(PushPosture, "push posture", [
    Standing => "standing",
    Crouching => "crouching",
    Sitting => "sitting",
]);

/// Body posture / grip when pulling (rows of tables 3.8 / 3.9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PullPosture {
    /// Standing, pulling a lever across the pull direction (figure 3.25).
    #[default]
    StandingLever,
    /// Crouching, pulling a lever across the pull direction (figure 3.26).
    CrouchingLever,
    /// Pulling a handle (figure 3.27).
    Handle,
}
named_enum!(PullPosture, "pull posture", [
    StandingLever => "standing_lever",
    CrouchingLever => "crouching_lever",
    Handle => "handle",
]);

/// Grip when turning (rows of tables 3.10 / 3.11). The dissertation (section 3.3.3)
/// equates the screwdriver with torsion of the hose about its own axis and the T-handle
/// with bending across it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TorqueGrip {
    /// Turning a screwdriver (figure 3.29): torsion.
    Screwdriver,
    /// Turning a T-handle in the vertical plane (figure 3.28): bending.
    #[default]
    THandle,
}
named_enum!(TorqueGrip, "torque grip", [
    Screwdriver => "screwdriver",
    THandle => "t_handle",
]);

/// Who does the work (the columns of every table). Every limit for women is lower than
/// the one for men, so `Women` is the conservative default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Population {
    #[default]
    Women,
    Men,
}
named_enum!(Population, "population", [Women => "women", Men => "men"]);

/// How long the force is held (the column groups of every table).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Duty {
    /// Held without a break for more than one minute ("Dauerbetätigung").
    Continuous,
    /// Everything shorter ("gelegentliche Betätigung"). The dissertation expects pushing a
    /// hose onto a stub, the critical action, to fall under this (section 3.3.3).
    #[default]
    Occasional,
}
named_enum!(Duty, "duty", [Continuous => "continuous", Occasional => "occasional"]);

/// One word for the worker's posture, as a user picks it; [`Posture::push`] and
/// [`Posture::pull`] map it onto the rows of the push and pull tables.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Posture {
    /// Push: standing; pull: standing lever.
    #[default]
    Standing,
    /// Push: crouching; pull: crouching lever.
    Crouching,
    /// Push: sitting; pull: handle (the only pull row not tied to standing or crouching).
    Sitting,
}
named_enum!(Posture, "posture", [
    Standing => "standing",
    Crouching => "crouching",
    Sitting => "sitting",
]);

impl Posture {
    /// The row of the push tables (3.6 / 3.7) for this posture.
    pub fn push(self) -> PushPosture {
        match self {
            Posture::Standing => PushPosture::Standing,
            Posture::Crouching => PushPosture::Crouching,
            Posture::Sitting => PushPosture::Sitting,
        }
    }

    /// The row of the pull tables (3.8 / 3.9) for this posture.
    pub fn pull(self) -> PullPosture {
        match self {
            Posture::Standing => PullPosture::StandingLever,
            Posture::Crouching => PullPosture::CrouchingLever,
            Posture::Sitting => PullPosture::Handle,
        }
    }
}
