//! `pliant calibrate` for bundles: a protection's coupling factor f_ei fitted from a
//! bending test of a bundle (a three-point bending or cantilever force–deflection curve),
//! or f_gj from a torsion test (a torque–twist curve).
//!
//! The curve is fitted as the material tests are (`pliant_calibrate`: least squares over
//! the linear range found automatically, 95 % confidence interval): its slope k gives the
//! bundle's EI = k L³/48 (three-point bending, span L) or k L³/3 (cantilever, free length
//! L), or GJ = k L (torsion, grips L apart). [`crate::calibrate::fit_protection_factor`]
//! inverts the bundle model EI = EI_slip + f_ei (EI_bond − EI_slip) for f_ei (GJ and f_gj
//! likewise); the interval of the stiffness maps onto the factor by the same straight
//! line. The bundle's wires come from a KBL segment (its routed wires
//! and, unless given, its protection) or from a list of wires.
//!
//! ```toml
//! format = "pliant-bundle-calibration"
//! kind = "three_point_bending"    # or "cantilever", or "torsion"
//! csv = "bend.csv"                # force_N, deflection_mm (torsion: torque_Nm, angle_deg)
//! length_mm = 200                 # span, free length, or grip distance
//! protection = "tape"             # none, tape, fleece_tape, corrugated_tube, sleeve, other
//! # the wires: a KBL segment …
//! kbl = "harness.kbl"
//! segment = "Segment_12"
//! # … or a list
//! wires = [{ outer_diameter_mm = 1.6, cross_section_mm2 = 0.5, count = 7 }]
//! ```
//!
//! Results: `bundle.toml` (the bundle model's data with the fitted factor and its source,
//! for `pliant import --bundle-data`), `calibration.json` and `calibration.html`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use pliant_calibrate::html::{curve_plot, escape, residual_plot};
use pliant_calibrate::material_entry::num;
use pliant_calibrate::{csv_input, fit_test, CalibError, Geometry, TestFit, TestKind};
use serde::{Deserialize, Serialize};

use crate::bundle::{bundle_section, BundleData, BundleSection, WireSection};
use crate::calibrate::{bundle_of_segment, fit_protection_factor, Fit, Stiffness};
use crate::model::ProtectionKind;

/// The format tag of bundle calibration files.
pub const FORMAT_TAG: &str = "pliant-bundle-calibration";

/// Most wires a listed bundle may have (a real bundle has at most a few hundred).
pub const MAX_WIRES: usize = 100_000;

/// Largest wire diameter or test length \[mm\] (10 m).
const MAX_MM: f64 = 1e4;

/// One entry of a wire list: `count` equal wires.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WireSpec {
    /// Outer diameter over the insulation \[mm\].
    pub outer_diameter_mm: f64,
    /// Conductor cross-section \[mm²\].
    pub cross_section_mm2: f64,
    /// How many such wires (default 1).
    pub count: Option<usize>,
}

/// A bundle calibration: the test and the bundle tested.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BundleSpec {
    /// `"pliant-bundle-calibration"` (required: it tells this file from a material's).
    pub format: String,
    /// `three_point_bending` or `cantilever` (f_ei), or `torsion` (f_gj).
    pub kind: TestKind,
    /// The force–deflection curve, relative to the calibration file.
    pub csv: String,
    /// Span (three-point bending) or free length (cantilever) \[mm\].
    pub length_mm: f64,
    /// The protection whose factor is fitted (a key of `data/bundle.toml`); default: the
    /// KBL segment's protection.
    pub protection: Option<String>,
    /// A KBL file (relative to the calibration file) and the segment tested in it.
    pub kbl: Option<String>,
    pub segment: Option<String>,
    /// Or the wires, listed.
    #[serde(default)]
    pub wires: Vec<WireSpec>,
}

/// Whether a TOML text is a bundle calibration (its `format` says so).
pub fn is_bundle_spec(text: &str) -> bool {
    text.parse::<toml::Table>()
        .ok()
        .and_then(|t| t.get("format").and_then(|f| f.as_str().map(str::to_string)))
        .is_some_and(|f| f == FORMAT_TAG)
}

impl BundleSpec {
    /// Parses a bundle calibration file's text (`origin` names it in errors) and checks it.
    pub fn parse(text: &str, origin: &str) -> Result<BundleSpec, CalibError> {
        let spec: BundleSpec = toml::from_str(text)
            .map_err(|e| pliant_calibrate::spec::toml_error(text, origin, &e))?;
        spec.check(origin)?;
        Ok(spec)
    }

    /// Checks what the types cannot, before any file is read.
    pub fn check(&self, origin: &str) -> Result<(), CalibError> {
        let bad = |m: String| Err(CalibError::file(origin, m));
        if self.format != FORMAT_TAG {
            return bad(format!(
                "format = \"{}\": expected \"{FORMAT_TAG}\"",
                self.format
            ));
        }
        if Stiffness::of_test(self.kind).is_none() {
            return bad(format!(
                "kind = \"{}\": a bundle is calibrated from a bending test, three_point_bending or cantilever, or a torsion test",
                self.kind.name()
            ));
        }
        if !(self.length_mm > 0.0 && self.length_mm <= MAX_MM) {
            return bad(format!(
                "length_mm = {}: must be positive and at most {MAX_MM} mm ({})",
                self.length_mm,
                self.kind.length_meaning()
            ));
        }
        if let Some(p) = &self.protection {
            if ProtectionKind::from_key(p).is_none() {
                return bad(format!(
                    "protection = \"{p}\": expected none, tape, fleece_tape, corrugated_tube, sleeve or other"
                ));
            }
        }
        match (&self.kbl, &self.segment, self.wires.is_empty()) {
            (Some(_), Some(_), true) => {}
            (None, None, false) => {
                if self.protection.is_none() {
                    return bad("protection: give the protection whose factor the listed wires calibrate (none, tape, …)".into());
                }
                let mut total = 0usize;
                for (i, w) in self.wires.iter().enumerate() {
                    let d = w.outer_diameter_mm;
                    let a = w.cross_section_mm2;
                    if !(d > 0.0 && d <= MAX_MM) {
                        return bad(format!(
                            "wires[{i}].outer_diameter_mm = {d}: must be positive and at most {MAX_MM}"
                        ));
                    }
                    if !(a >= 0.0 && a < d * d) {
                        return bad(format!(
                            "wires[{i}].cross_section_mm2 = {a}: must be ≥ 0 and fit inside the outer diameter {d} mm"
                        ));
                    }
                    let n = w.count.unwrap_or(1);
                    if n == 0 {
                        return bad(format!("wires[{i}].count = 0: must be at least 1"));
                    }
                    total = total.saturating_add(n);
                }
                if total > MAX_WIRES {
                    return bad(format!(
                        "{total} wires listed: at most {MAX_WIRES} in one bundle"
                    ));
                }
            }
            (_, _, false) => {
                return bad("give the bundle either as kbl + segment or as wires, not both".into())
            }
            _ => {
                return bad(
                    "the bundle is missing: give kbl = \"FILE.kbl\" with segment = \"ID\", or wires = [{ outer_diameter_mm, cross_section_mm2, count }]".into(),
                )
            }
        }
        Ok(())
    }
}

/// A finished bundle calibration.
#[derive(Clone, Debug)]
pub struct BundleCalibration {
    /// The calibration file (or a description of the inputs).
    pub origin: String,
    pub spec: BundleSpec,
    /// What was tested ("Segment_12 of harness.kbl" or "7 listed wires").
    pub bundle: String,
    /// The fitted test (EI or GJ and its interval).
    pub test: TestFit,
    /// The factor and the bounds.
    pub fit: Fit,
    /// 95 % interval of the factor (the interval of the stiffness mapped onto it, not
    /// clamped).
    pub factor_ci95: [f64; 2],
    /// The bundle's section under the fitted factor (its EI or GJ is the measured one).
    pub section: BundleSection,
    /// The bundle model's data with the fitted factor.
    pub data: BundleData,
}

fn read_text(path: &Path) -> Result<String, CalibError> {
    pliant_files::read_regular_text(path, pliant_calibrate::MAX_FILE_BYTES).map_err(|e| {
        CalibError::file(
            &path.display().to_string(),
            format!("cannot read: {}", e.kind.into_io()),
        )
    })
}

/// Runs the bundle calibration described by the file at `path` (paths relative to it).
pub fn calibrate_bundle_file(path: &Path) -> Result<BundleCalibration, CalibError> {
    let shown = path.display().to_string();
    let text = read_text(path)?;
    let spec = BundleSpec::parse(&text, &shown)?;
    calibrate_bundle(spec, path.parent().unwrap_or(Path::new(".")), &shown)
}

/// The wires of the bundle, what they are called, and the protection to calibrate.
fn tested_bundle(
    spec: &BundleSpec,
    base: &Path,
    origin: &str,
    data: &BundleData,
) -> Result<(Vec<WireSection>, String, Option<ProtectionKind>), CalibError> {
    let given = spec
        .protection
        .as_deref()
        .and_then(ProtectionKind::from_key);
    if let (Some(kbl), Some(segment)) = (&spec.kbl, &spec.segment) {
        let path = base.join(kbl);
        let shown = path.display().to_string();
        let h = crate::read_kbl(&path).map_err(|e| CalibError::file(&shown, e.to_string()))?;
        let b = bundle_of_segment(&h, data, segment)
            .map_err(|e| CalibError::file(&shown, e.to_string()))?;
        let kind = given.unwrap_or(b.protection.map(|p| p.kind));
        if !b.warnings.is_empty() {
            return Err(CalibError::file(
                &shown,
                format!(
                    "segment {}: its bundle is not fully known, so its bounds are not: {}",
                    b.kbl_id,
                    b.warnings.join("; ")
                ),
            ));
        }
        let name = format!("{} of {}", b.kbl_id, crate::file_name(&path));
        return Ok((b.wires, name, kind));
    }
    let Some(kind) = given else {
        return Err(CalibError::file(origin, "protection: missing or unknown"));
    };
    let mut wires = Vec::new();
    for w in &spec.wires {
        let one = WireSection::new(
            data,
            w.outer_diameter_mm * 1e-3,
            w.cross_section_mm2 * 1e-6,
            None,
            None,
        );
        wires.extend(std::iter::repeat_n(one, w.count.unwrap_or(1)));
    }
    let name = format!("{} listed wires", wires.len());
    Ok((wires, name, kind))
}

/// Runs a bundle calibration whose paths are relative to `base`; `origin` names it.
pub fn calibrate_bundle(
    spec: BundleSpec,
    base: &Path,
    origin: &str,
) -> Result<BundleCalibration, CalibError> {
    spec.check(origin)?;
    let mut data = BundleData::builtin();
    let (wires, bundle, kind) = tested_bundle(&spec, base, origin, &data)?;
    let csv_path = base.join(&spec.csv);
    let shown = csv_path.display().to_string();
    let table = csv_input::parse(&read_text(&csv_path)?, &shown)?;
    let d_outer = bundle_section(&data, &wires, None).d_outer;
    let geometry = Geometry {
        d_inner: 0.0,
        d_outer,
        length: Some(spec.length_mm * 1e-3),
    };
    let test = fit_test(spec.kind, &spec.csv, &table, geometry)?;
    let stiffness = Stiffness::of_test(spec.kind)
        .ok_or_else(|| CalibError::file(origin, "not a bending or torsion test"))?;
    let fit = fit_protection_factor(stiffness, test.value, &wires, kind)
        .map_err(|e| CalibError::file(&shown, format!("bundle {bundle}: {e}")))?;
    let span = fit.bond - fit.slip;
    let factor_ci95 = test.ci95.map(|v| (v - fit.slip) / span);
    if !(fit.factor.is_finite() && factor_ci95.iter().all(|f| f.is_finite())) {
        return Err(CalibError::file(
            &shown,
            format!(
                "bundle {bundle}: the fit gives {} = {} (95 % CI {:?}), not a finite number; nothing is written",
                stiffness.factor(),
                fit.factor,
                factor_ci95
            ),
        ));
    }
    fit.apply(&mut data);
    let cover = kind.map(|kind| crate::bundle::ProtectionCover {
        kind,
        coverage: 1.0,
        outer_diameter: None,
        mass_per_length: None,
    });
    let section = bundle_section(&data, &wires, cover);
    Ok(BundleCalibration {
        origin: origin.to_string(),
        spec,
        bundle,
        test,
        fit,
        factor_ci95,
        section,
        data,
    })
}

impl BundleCalibration {
    /// The bundle model's data with the fitted factor (bundle.toml).
    pub fn bundle_toml(&self) -> String {
        let body = toml::to_string(&self.data).unwrap_or_default();
        format!(
            "# Bundle model data (crates/harness/data/bundle.toml) with protection.{}.{} fitted\n\
             # by `pliant calibrate` from {}; use with `pliant import FILE.kbl --bundle-data bundle.toml`.\n\n{body}",
            self.fit.key(),
            self.fit.stiffness.factor(),
            self.origin
        )
    }

    /// Everything as JSON (calibration.json).
    pub fn json(&self) -> serde_json::Value {
        let f = &self.fit;
        let symbol = f.stiffness.symbol().to_lowercase();
        let mut json = serde_json::json!({
            "format": "pliant-calibration-result",
            "kind": "bundle",
            "origin": self.origin,
            "bundle": self.bundle,
            "wire_count": f.wire_count,
            "protection": f.key(),
            "stiffness": f.stiffness,
            "section": self.section,
            "test": self.test,
        });
        let factor = f.stiffness.factor();
        for (key, value) in [
            (factor.to_string(), serde_json::json!(f.factor)),
            (
                format!("{factor}_ci95"),
                serde_json::json!(self.factor_ci95),
            ),
            (format!("{symbol}_n_m2"), serde_json::json!(f.measured)),
            (format!("{symbol}_slip_n_m2"), serde_json::json!(f.slip)),
            (format!("{symbol}_bond_n_m2"), serde_json::json!(f.bond)),
        ] {
            json[key] = value;
        }
        json
    }

    /// The page (calibration.html): the factor, the bounds and the fitted curve.
    pub fn html(&self) -> String {
        let mut s = String::from(
            "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Pliant bundle calibration</title><style>\
             body{font-family:sans-serif;margin:24px;max-width:1000px;color:#222}\
             table{border-collapse:collapse;margin:8px 0 16px}th,td{border:1px solid #ccc;padding:3px 8px;text-align:left;font-size:13px}\
             th{background:#f4f4f4}</style></head><body>",
        );
        let f = &self.fit;
        let _ = write!(
            s,
            "<h1>Bundle calibration: protection {}</h1><p>From <code>{}</code>: {} ({} wires), {} test (docs/calibration.md, <em>Bundles</em>).</p>\
             <table><tr><th>quantity</th><th>value</th></tr>\
             <tr><td>{factor}</td><td>{} (95 % CI {} – {})</td></tr>\
             <tr><td>{symbol} measured [N·m²]</td><td>{} (95 % CI {} – {})</td></tr>\
             <tr><td>{symbol} slip bound (f = 0) [N·m²]</td><td>{}</td></tr>\
             <tr><td>{symbol} bonded bound (f = 1) [N·m²]</td><td>{}</td></tr>\
             <tr><td>formula</td><td>{}</td></tr></table>",
            escape(f.key()),
            escape(&self.origin),
            escape(&self.bundle),
            f.wire_count,
            escape(self.test.kind.name()),
            num(f.factor),
            num(self.factor_ci95[0]),
            num(self.factor_ci95[1]),
            num(f.measured),
            num(self.test.ci95[0]),
            num(self.test.ci95[1]),
            num(f.slip),
            num(f.bond),
            escape(&self.test.formula),
            factor = f.stiffness.factor(),
            symbol = f.stiffness.symbol(),
        );
        s.push_str(&curve_plot(&self.test));
        s.push_str(&residual_plot(&self.test));
        let _ = write!(
            s,
            "<h2>bundle.toml</h2><pre>{}</pre></body></html>",
            escape(&self.bundle_toml())
        );
        s
    }

    /// Writes bundle.toml, calibration.html and calibration.json into `out` (created) and
    /// returns their paths.
    pub fn write(&self, out: &Path) -> Result<Vec<PathBuf>, CalibError> {
        pliant_calibrate::write_results(
            out,
            &self.json(),
            [
                ("bundle.toml", self.bundle_toml()),
                ("calibration.html", self.html()),
            ],
        )
    }
}
