//! STEP out (SPEC N3): the settled centre lines as curves in an
//! ISO 10303-21 exchange file of AP214 (ISO 10303-214, schema `AUTOMOTIVE_DESIGN`), so a
//! designer opens Pliant's route in the CAD system.
//!
//! The entities are written by hand — the smallest set that makes a part with wireframe
//! geometry (following the CAx-IF *Recommended Practices for AP203/AP214*, product
//! structure and units as OpenCASCADE and the commercial systems write them):
//!
//! | entity | what it is |
//! |---|---|
//! | `APPLICATION_CONTEXT`, `APPLICATION_PROTOCOL_DEFINITION` | the file is AP214 (`automotive_design`, IS 2000) |
//! | `PRODUCT_CONTEXT`, `PRODUCT`, `PRODUCT_RELATED_PRODUCT_CATEGORY` | one part, the harness ("part" category) |
//! | `PRODUCT_DEFINITION_FORMATION`, `PRODUCT_DEFINITION_CONTEXT`, `PRODUCT_DEFINITION` | its (only) version and design view |
//! | `PRODUCT_DEFINITION_SHAPE`, `SHAPE_DEFINITION_REPRESENTATION` | its shape is the representation below |
//! | `LENGTH_UNIT`/`SI_UNIT(.MILLI.,.METRE.)`, `PLANE_ANGLE_UNIT` (rad), `SOLID_ANGLE_UNIT` (sr) | units: mm, rad, sr |
//! | `UNCERTAINTY_MEASURE_WITH_UNIT` | the model's length tolerance (10⁻⁶ mm, the coordinates' last digit) |
//! | `GEOMETRIC_REPRESENTATION_CONTEXT(3)` + `GLOBAL_UNIT_ASSIGNED_CONTEXT` + `GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT` | the 3-D context |
//! | `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION` | a wireframe shape (ISO 10303-42/-214: its items are curve sets and placements) |
//! | `AXIS2_PLACEMENT_3D`, `DIRECTION` | its placement, the global frame |
//! | `GEOMETRIC_CURVE_SET` | the harness's curves |
//! | `B_SPLINE_CURVE_WITH_KNOTS`, `CARTESIAN_POINT` | one curve per segment, named by its KBL id: degree 1, `.POLYLINE_FORM.`, clamped knots (multiplicities 2, 1, …, 1, 2) at the cumulative chord length in mm, so the parameter is the arc length |
//!
//! Coordinates are millimetres with 6 decimals (the model is in metres inside; mm only
//! here, at the file boundary). Strings follow ISO 10303-21 §6.4.3: `'` and `\` doubled,
//! characters outside printable ASCII as `\X2\…\X0\` (UTF-16) or `\X4\…\X0\`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Serialize;

use crate::error::HarnessError;
use crate::settled::{clean, SettledHarness};

/// The names written into the file.
#[derive(Debug, Clone)]
pub struct StepNames {
    /// The product (part) name, e.g. the harness's KBL file or part number.
    pub product: String,
    /// A line for the header's `FILE_DESCRIPTION`.
    pub description: String,
    /// The header's time stamp (ISO 8601); `None`: now (UTC).
    pub timestamp: Option<String>,
}

impl StepNames {
    /// Product `product`, a default description, the current time.
    pub fn new(product: impl Into<String>) -> Self {
        StepNames {
            product: product.into(),
            description: "Pliant settled harness: segment centre lines".to_string(),
            timestamp: None,
        }
    }
}

/// What [`export_step`] wrote.
#[derive(Debug, Clone, Serialize)]
pub struct StepReport {
    pub out: PathBuf,
    /// Curves (one per segment) and their points in all.
    pub curves: usize,
    pub points: usize,
    /// Entity instances in the DATA section.
    pub entities: usize,
}

/// Write the settled centre lines as an AP214 STEP file (see the module documentation):
/// one degree-1 B-spline curve per segment, named by its KBL id.
pub fn export_step(
    settled: &SettledHarness,
    names: &StepNames,
    out: &Path,
) -> Result<StepReport, HarnessError> {
    let (text, curves, points, entities) = step_text(settled, names, &file_label(out))?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| HarnessError::Write {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    std::fs::write(out, text).map_err(|source| HarnessError::Write {
        path: out.to_path_buf(),
        source,
    })?;
    Ok(StepReport {
        out: out.to_path_buf(),
        curves,
        points,
        entities,
    })
}

fn file_label(out: &Path) -> String {
    out.file_name()
        .map(|f| f.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// A STEP string literal (ISO 10303-21 §6.4.3), quotes included.
pub fn step_string(s: &str) -> String {
    let mut out = String::from("'");
    let mut wide: Vec<char> = Vec::new();
    let flush = |wide: &mut Vec<char>, out: &mut String| {
        if wide.is_empty() {
            return;
        }
        if wide.iter().all(|c| (*c as u32) <= 0xFFFF) {
            out.push_str("\\X2\\");
            for c in wide.iter() {
                let _ = write!(out, "{:04X}", *c as u32);
            }
        } else {
            out.push_str("\\X4\\");
            for c in wide.iter() {
                let _ = write!(out, "{:08X}", *c as u32);
            }
        }
        out.push_str("\\X0\\");
        wide.clear();
    };
    for c in s.chars() {
        if (' '..='~').contains(&c) {
            flush(&mut wide, &mut out);
            match c {
                '\'' => out.push_str("''"),
                '\\' => out.push_str("\\\\"),
                _ => out.push(c),
            }
        } else {
            wide.push(c);
        }
    }
    flush(&mut wide, &mut out);
    out.push('\'');
    out
}

/// A STEP real: always with a decimal point.
fn real(v: f64) -> String {
    format!("{v:.6}")
}

/// The current UTC time as ISO 8601 (`YYYY-MM-DDThh:mm:ss`), from the system clock
/// (days to civil date: H. Hinnant, "chrono-compatible low-level date algorithms").
fn now_iso8601() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// Entity instances, numbered from #1 in the order they are added.
struct Data {
    lines: Vec<String>,
}

impl Data {
    /// Add an instance; its id.
    fn add(&mut self, body: impl Into<String>) -> usize {
        self.lines.push(body.into());
        self.lines.len()
    }
}

fn refs(ids: &[usize]) -> String {
    ids.iter()
        .map(|i| format!("#{i}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// The file's text; (text, curves, points, entities).
pub fn step_text(
    settled: &SettledHarness,
    names: &StepNames,
    file: &str,
) -> Result<(String, usize, usize, usize), HarnessError> {
    settled
        .check()
        .map_err(|(kbl_id, reason)| HarnessError::Settled { kbl_id, reason })?;
    let mut d = Data { lines: Vec::new() };
    let product = step_string(&names.product);
    let app = d.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    d.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pc = d.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let prod = d.add(format!(
        "PRODUCT({product},{product},{},(#{pc}))",
        step_string(&names.description)
    ));
    d.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{prod}))"
    ));
    let pdf = d.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{prod})"));
    let pdc = d.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let pd = d.add(format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"));
    let pds = d.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
    let mm = d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
    let rad = d.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
    let sr = d.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
    let unc = d.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-06),#{mm},'distance_accuracy_value','confusion accuracy')"
    ));
    let ctx = d.add(format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc}))\
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{rad},#{sr}))REPRESENTATION_CONTEXT('',''))"
    ));
    let origin = d.add("CARTESIAN_POINT('',(0.,0.,0.))");
    let z = d.add("DIRECTION('',(0.,0.,1.))");
    let x = d.add("DIRECTION('',(1.,0.,0.))");
    let axis = d.add(format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
    let mut curves = Vec::new();
    let mut point_count = 0;
    for (id, pts) in settled.iter() {
        let pts = clean(pts);
        let ids: Vec<usize> = pts
            .iter()
            .map(|p| {
                let v = *p * 1e3;
                d.add(format!(
                    "CARTESIAN_POINT('',({},{},{}))",
                    real(v.x),
                    real(v.y),
                    real(v.z)
                ))
            })
            .collect();
        point_count += ids.len();
        curves.push(d.add(bspline_degree1(id, &pts, &ids)));
    }
    let set = d.add(format!(
        "GEOMETRIC_CURVE_SET('centre lines',({}))",
        refs(&curves)
    ));
    let rep = d.add(format!(
        "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION({product},(#{set},#{axis}),#{ctx})"
    ));
    d.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"));

    let stamp = names.timestamp.clone().unwrap_or_else(now_iso8601);
    let mut t = String::with_capacity(64 * d.lines.len() + 1024);
    t.push_str("ISO-10303-21;\nHEADER;\n");
    let _ = writeln!(
        t,
        "FILE_DESCRIPTION(({}),'2;1');",
        step_string(&names.description)
    );
    let _ = writeln!(
        t,
        "FILE_NAME({},{},(''),(''),{},'Pliant','');",
        step_string(file),
        step_string(&stamp),
        step_string(concat!("pliant-harness ", env!("CARGO_PKG_VERSION")))
    );
    t.push_str("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n");
    for (i, line) in d.lines.iter().enumerate() {
        let _ = writeln!(t, "#{}={};", i + 1, line);
    }
    t.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    Ok((t, curves.len(), point_count, d.lines.len()))
}

/// `B_SPLINE_CURVE_WITH_KNOTS` of degree 1 through `points` (ids `ids`): clamped knots at
/// the cumulative chord length \[mm\] with multiplicities 2, 1, …, 1, 2 (n + 1 points, n + 3
/// knots: ISO 10303-42 `b_spline_curve_with_knots`, upper index of knots = n + 1 distinct
/// values).
fn bspline_degree1(name: &str, points: &[DVec3], ids: &[usize]) -> String {
    let mut knots = vec![0.0];
    for w in points.windows(2) {
        let last = knots[knots.len() - 1];
        knots.push(last + w[0].distance(w[1]) * 1e3);
    }
    let n = knots.len();
    let mult: Vec<String> = (0..n)
        .map(|i| if i == 0 || i == n - 1 { "2" } else { "1" }.to_string())
        .collect();
    let knots: Vec<String> = knots.into_iter().map(real).collect();
    format!(
        "B_SPLINE_CURVE_WITH_KNOTS({},1,({}),.POLYLINE_FORM.,.F.,.F.,({}),({}),.UNSPECIFIED.)",
        step_string(name),
        refs(ids),
        mult.join(","),
        knots.join(",")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_are_escaped() {
        assert_eq!(step_string("Segment_1"), "'Segment_1'");
        assert_eq!(step_string("it's a\\b"), "'it''s a\\\\b'");
        assert_eq!(
            step_string("Kabelbaum Tür"),
            "'Kabelbaum T\\X2\\00FC\\X0\\r'"
        );
        assert_eq!(step_string("a😀"), "'a\\X4\\0001F600\\X0\\'");
    }

    #[test]
    fn degree_one_curve_knots() {
        let p = [DVec3::ZERO, DVec3::X * 1e-3, DVec3::new(1e-3, 2e-3, 0.0)];
        let s = bspline_degree1("S", &p, &[4, 5, 6]);
        assert_eq!(
            s,
            "B_SPLINE_CURVE_WITH_KNOTS('S',1,(#4,#5,#6),.POLYLINE_FORM.,.F.,.F.,(2,1,2),\
             (0.000000,1.000000,3.000000),.UNSPECIFIED.)"
        );
    }

    #[test]
    fn time_stamp_is_iso() {
        let t = now_iso8601();
        assert_eq!(t.len(), 19, "{t}");
        assert_eq!(&t[4..5], "-");
        assert_eq!(&t[10..11], "T");
        assert!(t[..4].parse::<i32>().unwrap() >= 2024);
    }
}
