//! Hose routes from CAD (`route = { … }`): the points of a curve of a STEP file
//! (sampled by OpenCASCADE within a tolerance, through the STEP cache) or of a CSV file
//! exported from any CAD tool, in metres, as centre-line segments. The hose's nodes lie
//! on the polyline through the points, so they stay within the sampling tolerance of the
//! CAD curve (for a CSV: on the exported polyline itself).

use crate::centerline::Segment;
use crate::error::FieldError;
use crate::files::FileAccess;
use crate::format::RouteEntry;
use crate::step_cache::CurvePick;
use crate::step_cache::{cached_curve, DEFAULT_CURVE_TOLERANCE};
use crate::units::LengthUnit;
use crate::validate::positive;
use glam::DVec3;

/// Most points a route may have.
pub const MAX_ROUTE_POINTS: usize = 1_000_000;

/// The route's start and segments \[m\]; `field` is `hoses[i].route`.
pub fn route_segments(
    field: &str,
    route: &RouteEntry,
    unit: LengthUnit,
    files: &FileAccess,
) -> Result<(DVec3, Vec<Segment>), FieldError> {
    let at = |rest: &str| format!("{field}.{rest}");
    let points = match (&route.step, &route.csv) {
        (Some(_), Some(_)) => {
            return Err(FieldError::about(
                field,
                "give either `step` (a STEP curve) or `csv` (a point list), not both",
            ))
        }
        (None, None) => {
            return Err(FieldError::about(
                field,
                "a route needs `step` (a STEP curve) or `csv` (a point list)",
            ))
        }
        (Some(step), None) => {
            if route.units.is_some() {
                return Err(FieldError::about(
                    at("units"),
                    "only with `csv` (a STEP file carries its own unit)",
                ));
            }
            let pick = match (&route.curve, route.index) {
                (Some(n), None) => CurvePick::Name(n.clone()),
                (None, Some(i)) => CurvePick::Index(i as usize),
                (None, None) => CurvePick::Index(0),
                (Some(_), Some(_)) => {
                    return Err(FieldError::about(
                        at("curve"),
                        "give either `curve` (a name) or `index`, not both",
                    ))
                }
            };
            let tolerance = match route.tolerance {
                Some(t) => positive(&at("tolerance"), t, unit.symbol())? * unit.to_metres(),
                None => DEFAULT_CURVE_TOLERANCE,
            };
            cached_curve(files, step, &pick, tolerance)
                .map_err(|r| FieldError::new(at("step"), format!("\"{step}\""), r))?
        }
        (None, Some(csv)) => {
            for (name, given) in [
                ("curve", route.curve.is_some()),
                ("index", route.index.is_some()),
                ("tolerance", route.tolerance.is_some()),
            ] {
                if given {
                    return Err(FieldError::about(at(name), "only with `step`"));
                }
            }
            let err = |r: String| FieldError::new(at("csv"), format!("\"{csv}\""), r);
            let bytes = files.read(csv).map_err(err)?;
            let text = String::from_utf8(bytes).map_err(|_| err("is not UTF-8 text".into()))?;
            let given = match &route.units {
                Some(u) => Some(unit_scale(u).ok_or_else(|| {
                    FieldError::new(
                        at("units"),
                        format!("\"{u}\""),
                        "unknown unit; use \"mm\", \"cm\", \"m\" or \"in\"",
                    )
                })?),
                None => None,
            };
            parse_csv(&text, given, unit.to_metres()).map_err(err)?
        }
    };
    let points = dedup(points);
    if points.len() < 2 {
        return Err(FieldError::about(
            field,
            "the route has fewer than two distinct points",
        ));
    }
    let start = points[0];
    let rest = &points[1..];
    let segments = if route.smooth {
        vec![Segment::Spline {
            through: rest[..rest.len() - 1].to_vec(),
            to: rest[rest.len() - 1],
        }]
    } else {
        rest.iter().map(|&to| Segment::Line { to }).collect()
    };
    Ok((start, segments))
}

/// Drops points that repeat their predecessor (zero-length segments).
fn dedup(points: Vec<DVec3>) -> Vec<DVec3> {
    let extent = points
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
    let eps = 1e-12 * extent.max(1e-3);
    let mut out: Vec<DVec3> = Vec::with_capacity(points.len());
    for p in points {
        if out.last().is_none_or(|q| (p - *q).length() > eps) {
            out.push(p);
        }
    }
    out
}

/// Metres per unit of a unit name (`mm`, `cm`, `m`, `in`, `inch`, `ft`).
pub fn unit_scale(name: &str) -> Option<f64> {
    Some(match name.trim().to_ascii_lowercase().as_str() {
        "mm" | "millimetre" | "millimeter" => 1e-3,
        "cm" => 1e-2,
        "m" | "metre" | "meter" => 1.0,
        "in" | "inch" | "inches" => 0.0254,
        "ft" | "foot" | "feet" => 0.3048,
        _ => return None,
    })
}

/// The unit a header cell names: `x_mm`, `x \[mm\]`, `x (in)`, `X(mm)`.
fn header_unit(cell: &str) -> Option<f64> {
    let c = cell.trim();
    if let Some(open) = c.find(['[', '(']) {
        let inner = c[open + 1..].trim_end_matches([']', ')', ' ']);
        return unit_scale(inner);
    }
    c.split_once('_').and_then(|(_, u)| unit_scale(u))
}

/// Parses a CSV of points: `x,y,z` per line (`;` or tabs also separate; further
/// columns are ignored), an optional header, `#` comments. The unit: `given` [m per
/// unit], else the header's, else `default`.
pub fn parse_csv(text: &str, given: Option<f64>, default: f64) -> Result<Vec<DVec3>, String> {
    let mut points = Vec::new();
    let mut header_scale = None;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim().trim_start_matches('\u{feff}');
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line
            .split([',', ';', '\t'])
            .map(|c| c.trim().trim_matches('"'))
            .collect();
        let numbers: Vec<Option<f64>> = cells.iter().map(|c| c.parse::<f64>().ok()).collect();
        if points.is_empty()
            && header_scale.is_none()
            && numbers.iter().take(3).any(Option::is_none)
        {
            // the header
            if cells.len() < 3 {
                return Err(format!(
                    "line {}: a header needs three columns x, y, z",
                    k + 1
                ));
            }
            let units: Vec<Option<f64>> = cells[..3].iter().map(|c| header_unit(c)).collect();
            if units.iter().any(Option::is_some) {
                let first = units.iter().flatten().next().copied();
                if units.iter().flatten().any(|u| Some(*u) != first) {
                    return Err(format!("line {}: the columns give different units", k + 1));
                }
                header_scale = first;
            } else {
                header_scale = Some(f64::NAN); // a header without unit
            }
            continue;
        }
        if cells.len() < 3 {
            return Err(format!(
                "line {}: expected three numbers x, y, z, found {}",
                k + 1,
                cells.len()
            ));
        }
        let mut p = [0.0; 3];
        for j in 0..3 {
            match numbers[j] {
                Some(v) if v.is_finite() => p[j] = v,
                _ => {
                    return Err(format!(
                        "line {}, column {}: \"{}\" is not a finite number",
                        k + 1,
                        j + 1,
                        cells[j]
                    ))
                }
            }
        }
        if points.len() >= MAX_ROUTE_POINTS {
            return Err(format!("more than {MAX_ROUTE_POINTS} points"));
        }
        points.push(DVec3::from_array(p));
    }
    let scale = given
        .or(header_scale.filter(|s| !s.is_nan()))
        .unwrap_or(default);
    Ok(points.into_iter().map(|p| p * scale).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_header_units_and_comments() {
        let t = "# exported\nx_in,y_in,z_in\n0,0,0\n1, 2 ,3\n";
        let p = parse_csv(t, None, 1e-3).unwrap();
        assert_eq!(p.len(), 2);
        assert!((p[1] - DVec3::new(0.0254, 0.0508, 0.0762)).length() < 1e-12);
        // an explicit unit wins; no header: the default
        let p = parse_csv("0;0;0\n1;0;0\n", None, 1e-3).unwrap();
        assert_eq!(p[1].x, 1e-3);
        let p = parse_csv("x [mm],y [mm],z [mm]\n0,0,0\n5,0,0\n", Some(1.0), 1e-3).unwrap();
        assert_eq!(p[1].x, 5.0);
    }

    #[test]
    fn csv_errors_name_the_line() {
        let e = parse_csv("x,y,z\n0,0,0\n1,zz,0\n", None, 1.0).unwrap_err();
        assert!(e.contains("line 3, column 2") && e.contains("zz"), "{e}");
        let e = parse_csv("0,0\n", None, 1.0).unwrap_err();
        assert!(e.contains("line 1"), "{e}");
        let e = parse_csv("x_mm,y_m,z_mm\n", None, 1.0).unwrap_err();
        assert!(e.contains("different units"), "{e}");
    }
}
