//! Checks on single values of a scene file, each returning a [`FieldError`] that names
//! the field path, the value as written (with its unit) and the reason.

use crate::error::FieldError;
use crate::format::Vec3;
use crate::units::{fmt_num, fmt_vec};
use glam::DVec3;

/// `x` followed by its unit, e.g. `40 mm`, or just `x` for a unitless value.
pub fn with_unit(x: f64, unit: &str) -> String {
    if unit.is_empty() {
        fmt_num(x)
    } else {
        format!("{} {unit}", fmt_num(x))
    }
}

/// A vector followed by its unit, e.g. `[0, 0, 1] mm`.
pub fn vec_with_unit(v: Vec3, unit: &str) -> String {
    if unit.is_empty() {
        fmt_vec(v)
    } else {
        format!("{} {unit}", fmt_vec(v))
    }
}

/// `x` must be finite (TOML allows `nan` and `inf`; a scene does not).
pub fn finite(field: &str, x: f64, unit: &str) -> Result<f64, FieldError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(FieldError::new(
            field,
            with_unit(x, unit),
            "must be a finite number",
        ))
    }
}

/// `x` must be finite and > 0.
pub fn positive(field: &str, x: f64, unit: &str) -> Result<f64, FieldError> {
    finite(field, x, unit)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(FieldError::new(
            field,
            with_unit(x, unit),
            "must be greater than 0",
        ))
    }
}

/// `x` must be finite and ≥ 0.
pub fn non_negative(field: &str, x: f64, unit: &str) -> Result<f64, FieldError> {
    finite(field, x, unit)?;
    if x >= 0.0 {
        Ok(x)
    } else {
        Err(FieldError::new(
            field,
            with_unit(x, unit),
            "must not be negative",
        ))
    }
}

/// Every component of `v` must be finite; the error names the component (`start[1]`).
pub fn finite_vec(field: &str, v: Vec3, unit: &str) -> Result<DVec3, FieldError> {
    for (i, x) in v.iter().enumerate() {
        finite(&format!("{field}[{i}]"), *x, unit)?;
    }
    Ok(DVec3::from_array(v))
}

/// A finite vector that is not the zero vector.
pub fn non_zero_vec(field: &str, v: Vec3, unit: &str) -> Result<DVec3, FieldError> {
    let d = finite_vec(field, v, unit)?;
    if d.length() > 0.0 {
        Ok(d)
    } else {
        Err(FieldError::new(
            field,
            vec_with_unit(v, unit),
            "must not be the zero vector",
        ))
    }
}

/// Resolves a node index of a hose with `count` nodes: 0 … count−1, or −count … −1
/// counting from the end.
pub fn node_index(field: &str, index: i64, count: usize, hose: &str) -> Result<usize, FieldError> {
    let n = count as i64;
    let resolved = if index < 0 { n + index } else { index };
    if (0..n).contains(&resolved) {
        Ok(resolved as usize)
    } else {
        Err(FieldError::new(
            field,
            index.to_string(),
            format!(
                "out of range: hose \"{hose}\" has {count} nodes (0 … {}, or −{count} … −1 counting from the end)",
                n - 1
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_name_field_value_and_reason() {
        let e = positive("hoses[0].section.d_outer", -3.0, "mm").unwrap_err();
        assert_eq!(
            e.to_string(),
            "hoses[0].section.d_outer = -3 mm: must be greater than 0"
        );
        let e = finite_vec("hoses[0].start", [0.0, f64::NAN, 0.0], "mm").unwrap_err();
        assert_eq!(
            e.to_string(),
            "hoses[0].start[1] = nan mm: must be a finite number"
        );
        let e = non_zero_vec("rotate.axis", [0.0; 3], "").unwrap_err();
        assert_eq!(
            e.to_string(),
            "rotate.axis = [0, 0, 0]: must not be the zero vector"
        );
    }

    #[test]
    fn node_indices_count_from_both_ends() {
        assert_eq!(node_index("n", 0, 5, "h"), Ok(0));
        assert_eq!(node_index("n", 4, 5, "h"), Ok(4));
        assert_eq!(node_index("n", -1, 5, "h"), Ok(4));
        assert_eq!(node_index("n", -5, 5, "h"), Ok(0));
        assert!(node_index("n", 5, 5, "h").is_err());
        assert!(node_index("n", -6, 5, "h").is_err());
        assert!(node_index("n", i64::MIN, 5, "h").is_err());
    }
}
