//! Building the ergonomic profile (SPEC I3): `[ergonomics]` onto the assembly layer's
//! [`ErgonomicProfile`], with the names parsed by that layer's own parsers so that the
//! accepted spellings and the messages are the same everywhere.

use crate::error::FieldError;
use crate::format::ErgonomicsSection;
use pliant_assembly::ergonomics::ErgonomicProfile;

/// Checks `[ergonomics]`: the default profile when absent; `posture` first, then the
/// per-table overrides `push` and `pull`, then `population`, `duty`, `moments_decide`,
/// `standard` and the EN 1005-3 parameters (the assembly layer's
/// [`ErgonomicProfile::set`] parses each, in the order of [`ErgonomicProfile::KEYS`]; the
/// error names the field).
pub fn build_ergonomics(raw: Option<&ErgonomicsSection>) -> Result<ErgonomicProfile, FieldError> {
    let mut profile = ErgonomicProfile::default();
    let Some(raw) = raw else { return Ok(profile) };
    let text = |v: Option<f64>| v.map(|x| x.to_string());
    let given = [
        raw.posture.clone(),
        raw.push.clone(),
        raw.pull.clone(),
        raw.population.clone(),
        raw.duty.clone(),
        raw.moments_decide.map(|b| b.to_string()),
        raw.standard.clone(),
        raw.action.clone(),
        raw.user_population.clone(),
        text(raw.percentile),
        raw.velocity.clone(),
        text(raw.frequency_per_min),
        text(raw.action_time_s),
        text(raw.duration_h),
    ];
    for (key, value) in ErgonomicProfile::KEYS.iter().zip(given) {
        if let Some(v) = value {
            profile.set(key, &v).map_err(|e| {
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
