//! KBL units (`<Unit>` elements referenced by id from every `Value_component`).
//!
//! A KBL unit is either an SI unit (`Si_unit_name` with an optional `Si_prefix` and
//! `Si_dimension` "square"/"cubic") or a free `Unit_name` (e.g. "GramPerMetre"). Values are
//! converted to SI: metres, square metres, kilograms, kilograms per metre.

/// The physical quantity a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// metre
    Length,
    /// square metre
    Area,
    /// cubic metre
    Volume,
    /// kilogram
    Mass,
    /// kilogram per metre
    MassPerLength,
    /// anything else (ampere, volt, …): not used by the importer
    Other,
}

/// A unit: its dimension and the factor that converts a value to SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    pub dimension: Dimension,
    pub to_si: f64,
}

/// The factor of an SI prefix (`milli` → 1e-3), `None` for an unknown prefix.
pub fn si_prefix(prefix: &str) -> Option<f64> {
    Some(match prefix.trim().to_ascii_lowercase().as_str() {
        "" => 1.0,
        "nano" => 1e-9,
        "micro" => 1e-6,
        "milli" => 1e-3,
        "centi" => 1e-2,
        "deci" => 1e-1,
        "deca" | "deka" => 1e1,
        "hecto" => 1e2,
        "kilo" => 1e3,
        "mega" => 1e6,
        "giga" => 1e9,
        _ => return None,
    })
}

/// An SI unit from its KBL fields. `None` if a field is not understood.
pub fn si_unit(name: &str, prefix: Option<&str>, dimension: Option<&str>) -> Option<Unit> {
    let p = si_prefix(prefix.unwrap_or(""))?;
    let power = match dimension.map(|d| d.trim().to_ascii_lowercase()) {
        None => 1,
        Some(d) if d.is_empty() => 1,
        Some(d) if d == "square" => 2,
        Some(d) if d == "cubic" => 3,
        Some(_) => return None,
    };
    let (dim, base) = match name.trim().to_ascii_lowercase().as_str() {
        "metre" | "meter" => (Dimension::Length, 1.0),
        // The SI base unit of mass is the kilogram; KBL names the gram with prefixes.
        "gram" => (Dimension::Mass, 1e-3),
        _ => {
            return Some(Unit {
                dimension: Dimension::Other,
                to_si: 1.0,
            })
        }
    };
    match (dim, power) {
        (Dimension::Length, 1) => Some(Unit {
            dimension: Dimension::Length,
            to_si: p,
        }),
        (Dimension::Length, 2) => Some(Unit {
            dimension: Dimension::Area,
            to_si: p * p,
        }),
        (Dimension::Length, 3) => Some(Unit {
            dimension: Dimension::Volume,
            to_si: p * p * p,
        }),
        (Dimension::Mass, 1) => Some(Unit {
            dimension: Dimension::Mass,
            to_si: base * p,
        }),
        _ => None,
    }
}

/// A unit given by a free `Unit_name`; the spellings seen in KBL files and a few obvious
/// others. `None` if not understood.
pub fn named_unit(name: &str) -> Option<Unit> {
    let n: String = name
        .chars()
        .filter(|c| !c.is_whitespace() && *c != '_')
        .collect::<String>()
        .to_ascii_lowercase();
    let u = |dimension, to_si| Some(Unit { dimension, to_si });
    match n.as_str() {
        "grampermetre" | "grampermeter" | "g/m" | "kilogramperkilometre" | "kg/km" => {
            u(Dimension::MassPerLength, 1e-3)
        }
        "kilogrampermetre" | "kilogrampermeter" | "kg/m" => u(Dimension::MassPerLength, 1.0),
        "mm" | "millimetre" | "millimeter" => u(Dimension::Length, 1e-3),
        "m" | "metre" | "meter" => u(Dimension::Length, 1.0),
        // International inch and foot (exact by definition, 1959).
        "in" | "inch" => u(Dimension::Length, 0.0254),
        "ft" | "foot" => u(Dimension::Length, 0.3048),
        "mm2" | "mm²" | "squaremillimetre" | "squaremillimeter" => u(Dimension::Area, 1e-6),
        "g" | "gram" => u(Dimension::Mass, 1e-3),
        "kg" | "kilogram" => u(Dimension::Mass, 1.0),
        _ => Some(Unit {
            dimension: Dimension::Other,
            to_si: 1.0,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prefixes_and_dimensions() {
        let mm = si_unit("metre", Some("milli"), None).unwrap();
        assert_eq!(mm.dimension, Dimension::Length);
        assert!((mm.to_si - 1e-3).abs() < 1e-18);
        let mm2 = si_unit("metre", Some("milli"), Some("square")).unwrap();
        assert_eq!(mm2.dimension, Dimension::Area);
        assert!((mm2.to_si - 1e-6).abs() < 1e-20);
        let g = si_unit("gram", None, None).unwrap();
        assert_eq!(g.dimension, Dimension::Mass);
        assert!((g.to_si - 1e-3).abs() < 1e-18);
        let kg = si_unit("gram", Some("kilo"), None).unwrap();
        assert!((kg.to_si - 1.0).abs() < 1e-15);
        assert!(si_unit("metre", Some("bogus"), None).is_none());
        assert_eq!(
            si_unit("ampere", None, None).unwrap().dimension,
            Dimension::Other
        );
    }

    #[test]
    fn named_units() {
        let gpm = named_unit("GramPerMetre").unwrap();
        assert_eq!(gpm.dimension, Dimension::MassPerLength);
        assert!((gpm.to_si - 1e-3).abs() < 1e-18);
        assert_eq!(named_unit("ampere").unwrap().dimension, Dimension::Other);
    }
}
