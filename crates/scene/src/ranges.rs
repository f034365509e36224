//! The physical ranges of scene values that are finite but absurd (a
//! gravity, load or rotation of 1e300 gives no study, only a blow-up and NaN): such a
//! value is refused at load, naming the field, instead of diverging in the first step.
//! The limits are far beyond any assembly study and stated in docs/scene-format.md.

use crate::error::FieldError;
use crate::validate::{vec_with_unit, with_unit};
use glam::DVec3;

/// Largest gravity \[m/s²\]: 100 g.
pub const MAX_GRAVITY: f64 = 1e3;
/// Largest force of a `load` action \[N\] (10 000 t, kept below the 1e9 N at which a
/// support force counts as a divergence; tests tear hoses with 1e7 N on purpose).
pub const MAX_LOAD_FORCE: f64 = 1e8;
/// Largest moment of a `load` action \[N·m\].
pub const MAX_LOAD_MOMENT: f64 = 1e8;
/// Largest angle of one `rotate` \[°\]: 100 turns.
pub const MAX_ROTATION_DEG: f64 = 36_000.0;

/// The vector `v` (already checked finite, in `unit`) with a length of at most `max`.
pub fn vec_at_most(
    field: &str,
    v: DVec3,
    max: f64,
    unit: &str,
    what: &str,
) -> Result<DVec3, FieldError> {
    if v.length() <= max {
        Ok(v)
    } else {
        Err(FieldError::new(
            field,
            vec_with_unit(v.to_array(), unit),
            format!(
                "is out of range: {what} may be at most {} long",
                with_unit(max, unit)
            ),
        ))
    }
}

/// The value `x` (already checked finite, in `unit`) of at most `max` in magnitude.
pub fn at_most(field: &str, x: f64, max: f64, unit: &str, what: &str) -> Result<f64, FieldError> {
    if x.abs() <= max {
        Ok(x)
    } else {
        Err(FieldError::new(
            field,
            with_unit(x, unit),
            format!(
                "is out of range: {what} may be at most {} in magnitude",
                with_unit(max, unit)
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absurd_values_are_refused_naming_field_and_limit() {
        let e = vec_at_most(
            "g",
            DVec3::new(0.0, 0.0, -1e300),
            MAX_GRAVITY,
            "m/s²",
            "gravity",
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("g") && e.contains("1e300") && e.contains("out of range"),
            "{e}"
        );
        assert!(at_most("a", 90.0, MAX_ROTATION_DEG, "°", "a rotation").is_ok());
        assert!(at_most("a", -1e300, MAX_ROTATION_DEG, "°", "a rotation").is_err());
    }
}
