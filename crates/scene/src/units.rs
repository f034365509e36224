//! The scene's length unit: one unit for every length, position and diameter in a file,
//! converted to metres at load time. Forces, moments, times, moduli and densities carry
//! their unit in the field name instead (`_n`, `_nm`, `_s`, `_mpa`, `_kg_m3`).

use schemars::JsonSchema;
use serde::Deserialize;
use std::fmt;

/// Unit of every length in a scene file (positions, diameters, element lengths,
/// offsets, waypoints).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, JsonSchema)]
pub enum LengthUnit {
    /// Millimetres: values are multiplied by 0.001 at load.
    #[serde(rename = "mm")]
    Millimetre,
    /// Metres: values are taken as they are.
    #[serde(rename = "m")]
    Metre,
}

impl LengthUnit {
    /// Every accepted spelling, as written in a file.
    pub const ALLOWED: [&'static str; 2] = ["mm", "m"];

    /// Factor that turns a value in this unit into metres.
    pub fn to_metres(self) -> f64 {
        match self {
            LengthUnit::Millimetre => 1e-3,
            LengthUnit::Metre => 1.0,
        }
    }

    /// The unit's symbol as written in a file.
    pub fn symbol(self) -> &'static str {
        match self {
            LengthUnit::Millimetre => "mm",
            LengthUnit::Metre => "m",
        }
    }
}

impl fmt::Display for LengthUnit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

/// Formats a number the way a person wrote it (`40`, `0.5`, `nan`, `inf`).
pub fn fmt_num(x: f64) -> String {
    if x.is_nan() {
        "nan".to_string()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.to_string()
    } else if x != 0.0 && !(1e-6..1e15).contains(&x.abs()) {
        // extreme values as 1e-300, not three hundred digits
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Formats a 3-vector as `[x, y, z]`.
pub fn fmt_vec(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", fmt_num(v[0]), fmt_num(v[1]), fmt_num(v[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors() {
        assert_eq!(LengthUnit::Millimetre.to_metres(), 1e-3);
        assert_eq!(LengthUnit::Metre.to_metres(), 1.0);
    }

    #[test]
    fn number_formatting() {
        assert_eq!(fmt_num(40.0), "40");
        assert_eq!(fmt_num(0.5), "0.5");
        assert_eq!(fmt_num(f64::NAN), "nan");
        assert_eq!(fmt_num(f64::NEG_INFINITY), "-inf");
        assert_eq!(fmt_vec([1.0, -2.5, 0.0]), "[1, -2.5, 0]");
    }
}
