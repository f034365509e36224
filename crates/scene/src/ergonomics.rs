//! Building the ergonomic profile (SPEC I3): `[ergonomics]` onto the assembly layer's
//! [`ErgonomicProfile`], with the names parsed by that layer's own parsers so that the
//! accepted spellings and the messages are the same everywhere.

use crate::error::FieldError;
use crate::format::ErgonomicsSection;
use pliant_assembly::ergonomics::ErgonomicProfile;

/// Checks `[ergonomics]`: the default profile when absent; `posture` first, then the
/// per-table overrides `push` and `pull`, then `population`, `duty`, `moments_decide` (the
/// assembly layer's [`ErgonomicProfile::set`] parses each; the error names the field).
pub fn build_ergonomics(raw: Option<&ErgonomicsSection>) -> Result<ErgonomicProfile, FieldError> {
    let mut profile = ErgonomicProfile::default();
    let Some(raw) = raw else { return Ok(profile) };
    let moments = raw.moments_decide.map(|b| b.to_string());
    let given = [
        &raw.posture,
        &raw.push,
        &raw.pull,
        &raw.population,
        &raw.duty,
        &moments,
    ];
    for (key, value) in ErgonomicProfile::KEYS.iter().zip(given) {
        if let Some(v) = value {
            profile.set(key, v).map_err(|e| {
                FieldError::new(
                    format!("ergonomics.{key}"),
                    format!("\"{v}\""),
                    e.to_string(),
                )
            })?;
        }
    }
    Ok(profile)
}
