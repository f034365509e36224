//! Ergonomics (SPEC I3–I5): the guide and limit values of one-handed push, pull and
//! torque (dissertation tables 3.6–3.11, as data), EN 1005-3 as an alternative standard
//! for the push and pull (data too), the user's choice of rows, columns and standard, the
//! classification of a hand load against them, the worker's posture class choosing the
//! rows (SPEC E2), and the colour feedback. Limits live
//! here, in the interaction layer, never in the physics (SPEC I4).

#[macro_use]
mod names;
mod classify;
mod colour;
mod en1005;
mod error;
mod limits;
mod posture_class;
mod profile;
mod quantile;

pub use classify::{Classification, HandAssessment, LoadKind};
pub use colour::{colour_rgb, colour_value, Rgb};
pub use en1005::{
    En1005Action, En1005Judgement, En1005Limit, En1005Params, En1005Tables, En1005Velocity,
    RiskZone, EN1005_3_TOML,
};
pub use error::ErgonomicsError;
pub use limits::{ErgonomicLimits, GuideRange, TableInfo, ERGONOMICS_TOML};
pub use names::{
    allowed_names, Duty, Named, Population, Posture, PullPosture, PushPosture, TorqueGrip,
};
pub use posture_class::{en1005_action, table_posture};
pub use profile::{ErgonomicProfile, Standard};
pub use quantile::normal_quantile;
