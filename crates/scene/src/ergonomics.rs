//! Building the ergonomic profile (SPEC I3): `[ergonomics]` onto the assembly layer's
//! [`ErgonomicProfile`], with the names parsed by that layer's own parsers so that the
//! accepted spellings and the messages are the same everywhere.

use crate::error::FieldError;
use crate::format::ErgonomicsSection;
use pliant_assembly::ergonomics::{
    Duty, ErgonomicProfile, Population, Posture, PullPosture, PushPosture, TorqueGrip,
};
use std::str::FromStr;

/// Parses one named value of `[ergonomics]`; the error names the field and the value.
fn named<T>(key: &str, value: &str) -> Result<T, FieldError>
where
    T: FromStr,
    T::Err: std::fmt::Display,
{
    value.parse().map_err(|e: T::Err| {
        FieldError::new(
            format!("ergonomics.{key}"),
            format!("\"{value}\""),
            e.to_string(),
        )
    })
}

/// Checks `[ergonomics]`: the default profile when absent; `posture` first, then the
/// per-table overrides `push` and `pull`, then `torque`, `population`, `duty`.
pub fn build_ergonomics(raw: Option<&ErgonomicsSection>) -> Result<ErgonomicProfile, FieldError> {
    let mut profile = ErgonomicProfile::default();
    let Some(raw) = raw else { return Ok(profile) };
    if let Some(v) = &raw.posture {
        let posture: Posture = named("posture", v)?;
        profile.push_posture = posture.push();
        profile.pull_posture = posture.pull();
    }
    if let Some(v) = &raw.push {
        profile.push_posture = named::<PushPosture>("push", v)?;
    }
    if let Some(v) = &raw.pull {
        profile.pull_posture = named::<PullPosture>("pull", v)?;
    }
    if let Some(v) = &raw.torque {
        profile.torque_grip = named::<TorqueGrip>("torque", v)?;
    }
    if let Some(v) = &raw.population {
        profile.population = named::<Population>("population", v)?;
    }
    if let Some(v) = &raw.duty {
        profile.duty = named::<Duty>("duty", v)?;
    }
    Ok(profile)
}
