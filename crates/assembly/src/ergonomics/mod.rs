//! Ergonomics (SPEC I3–I5): the guide and limit values of one-handed push, pull and
//! torque (dissertation tables 3.6–3.11, as data), the user's choice of rows and columns,
//! the classification of a hand load against them, and the colour feedback. Limits live
//! here, in the interaction layer, never in the physics (SPEC I4).

mod classify;
mod colour;
mod error;
mod limits;
mod names;
mod profile;

pub use classify::{Classification, HandAssessment, LoadKind};
pub use colour::{colour_rgb, colour_value, Rgb};
pub use error::ErgonomicsError;
pub use limits::{ErgonomicLimits, GuideRange, TableInfo, ERGONOMICS_TOML};
pub use names::{
    allowed_names, Duty, Named, Population, Posture, PullPosture, PushPosture, TorqueGrip,
};
pub use profile::ErgonomicProfile;
