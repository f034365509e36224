//! Building the installation checks (SPEC V3): `[checks]` onto the assembly layer's
//! [`CheckSettings`], with each hose's minimum bend radius and outer diameter.

use crate::error::FieldError;
use crate::format::ChecksSection;
use crate::scene::HoseDiscretisation;
use crate::validate::positive;
use pliant_assembly::checks::{CheckSettings, HoseCheckLimits};

/// Checks `[checks]` (all on with the defaults when absent); `interval` is the scene's
/// record interval \[s\] (the checked instants).
pub fn build_checks(
    raw: Option<&ChecksSection>,
    hoses: &[HoseDiscretisation],
    interval: f64,
) -> Result<CheckSettings, FieldError> {
    let limits = hoses
        .iter()
        .map(|h| HoseCheckLimits {
            min_bend_radius: h.min_bend_radius,
            d_outer: h.d_outer,
            bend_radii: h.bend_radii.clone(),
        })
        .collect();
    let mut s = CheckSettings::with_hoses(limits);
    s.interval = interval;
    let Some(raw) = raw else { return Ok(s) };
    let flag = |v: Option<bool>, default: bool| v.unwrap_or(default);
    s.bend_radius = flag(raw.bend_radius, s.bend_radius);
    s.twist = flag(raw.twist, s.twist);
    s.tension_at_rest = flag(raw.tension_at_rest, s.tension_at_rest);
    s.straight_behind_stub = flag(raw.straight_behind_stub, s.straight_behind_stub);
    s.decide = flag(raw.decide, s.decide);
    if let Some(v) = raw.twist_limit_deg_per_m {
        s.twist_limit = positive("checks.twist_limit_deg_per_m", v, "°/m")?.to_radians();
    }
    if let Some(v) = raw.rest_strain_limit {
        s.rest_strain_limit = positive("checks.rest_strain_limit", v, "")?;
    }
    if let Some(v) = raw.straight_length_d_outer {
        s.straight_length_factor = positive("checks.straight_length_d_outer", v, "")?;
    }
    if let Some(v) = raw.straight_radius_factor {
        s.straight_radius_factor = positive("checks.straight_radius_factor", v, "")?;
    }
    Ok(s)
}
