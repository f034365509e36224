//! Material calibration (SPEC M5, D3): fits a hose material's stiffnesses to measured
//! test curves — E_t and E_c from tension and compression (force–displacement with the
//! specimen's geometry, or stress–strain), EI from three-point bending, a cantilever or
//! the force-to-bend-radius test of ISO 10619-1, GJ from torsion — by least squares over
//! the curve's linear range, which is found automatically. The result is a material for
//! scene files and the library (every value with its source), the fits with their
//! residuals and 95 % confidence intervals (`calibration.json`) and a page with the data
//! and the fits plotted (`calibration.html`). The method is documented in
//! docs/calibration.md.
//!
//! The inelastic laws (SPEC X1, X2) are fitted whole to their test curves by nonlinear
//! least squares: the yield stress and hardening from a bending test past yield with
//! unloading, moment against curvature ([`yield_fit`]) or force against deflection of a
//! cantilever or three-point bending ([`plastic_beam_fit`], [`beam_deflection`]), or from
//! a torsion test past yield ([`plastic_torsion_fit`]) — all by [`yield_law_fit`] with
//! Masing's unloading ([`load_unload`]) — Prony terms from a relaxation test ([`relaxation_fit`]),
//! Dahl's friction pair from a cyclic bending or torsion test ([`dahl_fit`]), each with
//! its intervals ([`nonlinear_least_squares`], shared parts in [`law_fit`], the
//! material's entries in [`law_entry`], the page's part in [`law_html`]; curves from the
//! simulator's own laws in [`synthetic_laws`]).
//!
//! One concept per module: [`csv_input`] (reading curves, units to SI), [`linear_range`]
//! (finding the range), [`least_squares`] and [`student_t`] (the fit and its interval),
//! [`mechanics`] (each test's formula), [`fit`] (one test), [`material_entry`] (the
//! material and its entries), [`html`] (the page), [`spec`] (the calibration file),
//! [`synthetic`] (curves with known answers).

pub mod beam_deflection;
pub mod csv_input;
pub mod dahl_fit;
pub mod error;
pub mod fit;
pub mod html;
pub mod law_entry;
pub mod law_fit;
pub mod law_html;
pub mod least_squares;
pub mod linear_range;
pub mod load_unload;
pub mod material_entry;
pub mod mechanics;
pub mod nonlinear_least_squares;
pub mod plastic_beam_fit;
pub mod plastic_torsion_fit;
pub mod relaxation_fit;
pub mod spec;
pub mod student_t;
pub mod synthetic;
pub mod synthetic_laws;
pub mod yield_combination;
pub mod yield_fit;
pub mod yield_law_fit;

pub use error::CalibError;
pub use fit::{fit_test, RangeReport, TestFit};
pub use law_fit::{fit_law, fit_law_with, LawFit, LawOptions};
pub use material_entry::MaterialResult;
pub use mechanics::{Geometry, Property, TestKind};
pub use spec::{Spec, TestSpec};

use std::path::{Path, PathBuf};

/// Most bytes a CSV or calibration file may have.
pub const MAX_FILE_BYTES: u64 = 256 * 1024 * 1024;

/// A calibration file's name without its folder; any other origin as it is.
fn short_origin(origin: &str) -> String {
    if origin.ends_with(".toml") {
        if let Some(name) = Path::new(origin).file_name() {
            return name.to_string_lossy().to_string();
        }
    }
    origin.to_string()
}

/// A finished calibration.
#[derive(Clone, Debug)]
pub struct Calibration {
    /// The calibration file (or a description of the inputs), for messages and sources.
    pub origin: String,
    pub spec: Spec,
    /// The stiffness tests' fits.
    pub fits: Vec<TestFit>,
    /// The inelastic laws' fits.
    pub laws: Vec<LawFit>,
    pub material: MaterialResult,
}

fn read_text(path: &Path, shown: &str) -> Result<String, CalibError> {
    pliant_files::read_regular_text(path, MAX_FILE_BYTES)
        .map_err(|e| CalibError::file(shown, format!("cannot read: {}", e.kind.into_io())))
}

/// Runs the calibration described by the file at `path` (CSV paths relative to it).
pub fn calibrate_file(path: &Path) -> Result<Calibration, CalibError> {
    let shown = path.display().to_string();
    let text = read_text(path, &shown)?;
    let spec = Spec::parse(&text, &shown)?;
    let base = path.parent().unwrap_or(Path::new("."));
    calibrate(spec, base, &shown)
}

/// Runs a calibration whose CSV paths are relative to `base_dir`; `origin` names it.
pub fn calibrate(spec: Spec, base_dir: &Path, origin: &str) -> Result<Calibration, CalibError> {
    spec.check(origin)?;
    let mut curves = Vec::with_capacity(spec.tests.len());
    for t in &spec.tests {
        let path = base_dir.join(&t.csv);
        let shown = path.display().to_string();
        let text = read_text(&path, &shown)?;
        curves.push((shown, text));
    }
    calibrate_texts(spec, &curves, origin)
}

/// Runs a calibration whose curves are given as (file name for messages, CSV text), one
/// per test of `spec`, in order.
pub fn calibrate_texts(
    spec: Spec,
    curves: &[(String, String)],
    origin: &str,
) -> Result<Calibration, CalibError> {
    spec.check(origin)?;
    if curves.len() != spec.tests.len() {
        return Err(CalibError::file(
            origin,
            format!("{} tests but {} curves", spec.tests.len(), curves.len()),
        ));
    }
    let mut fits = Vec::with_capacity(spec.tests.len());
    let mut laws = Vec::new();
    for (t, (shown, text)) in spec.tests.iter().zip(curves) {
        let table = csv_input::parse(text, shown)?;
        let g = Geometry {
            d_inner: t.d_inner_mm.unwrap_or(spec.d_inner_mm) * 1e-3,
            d_outer: t.d_outer_mm.unwrap_or(spec.d_outer_mm) * 1e-3,
            length: t.length_mm.map(|l| l * 1e-3),
        };
        if t.kind.is_law() {
            let options = LawOptions {
                terms: t.terms,
                held_strain: t.held_strain,
            };
            laws.push(fit_law_with(t.kind, &t.csv, &table, g, options)?);
        } else {
            fits.push(fit_test(t.kind, &t.csv, &table, g)?);
        }
    }
    let material = material_entry::derive(&spec, &fits, &laws, &short_origin(origin))
        .map_err(|m| CalibError::file(origin, m))?;
    if let Some((key, value)) = material.first_non_finite() {
        return Err(CalibError::file(
            origin,
            format!(
                "the calibration gives {key} = {value}, not a finite number: the specimen's dimensions or the curves are out of range, and no material is written"
            ),
        ));
    }
    Ok(Calibration {
        origin: origin.to_string(),
        spec,
        fits,
        laws,
        material,
    })
}

impl Calibration {
    fn origin_name(&self) -> String {
        short_origin(&self.origin)
    }

    /// The `[materials.NAME]` table for a scene (material.toml).
    pub fn material_toml(&self) -> String {
        self.material.scene_toml(&self.origin_name())
    }

    /// The entry in the library's format (library_entry.toml).
    pub fn library_toml(&self) -> String {
        self.material.library_toml(&self.origin_name())
    }

    /// Everything as JSON (calibration.json).
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "format": "pliant-calibration-result",
            "origin": self.origin,
            "material": self.material,
            "tests": self.fits,
            "laws": self.laws,
        })
    }

    /// The page (calibration.html).
    pub fn html(&self) -> String {
        html::page(
            &self.origin,
            &self.fits,
            &self.laws,
            &self.material,
            &self.material_toml(),
        )
    }

    /// Writes material.toml, library_entry.toml, calibration.json and calibration.html
    /// into `out` (created) and returns their paths.
    pub fn write(&self, out: &Path) -> Result<Vec<PathBuf>, CalibError> {
        write_results(
            out,
            &self.json(),
            [
                ("material.toml", self.material_toml()),
                ("library_entry.toml", self.library_toml()),
                ("calibration.html", self.html()),
            ],
        )
    }
}

/// Writes a calibration's files into `out` (created): `calibration.json` from `json`
/// and the named texts; returns their paths (calibration.json last).
pub fn write_results<const N: usize>(
    out: &Path,
    json: &serde_json::Value,
    texts: [(&str, String); N],
) -> Result<Vec<PathBuf>, CalibError> {
    let shown = out.display().to_string();
    std::fs::create_dir_all(out)
        .map_err(|e| CalibError::file(&shown, format!("cannot create the folder: {e}")))?;
    let json = serde_json::to_string_pretty(json)
        .map_err(|e| CalibError::file(&shown, format!("JSON: {e}")))?;
    let mut paths = Vec::with_capacity(N + 1);
    for (name, text) in texts.into_iter().chain([("calibration.json", json + "\n")]) {
        let p = out.join(name);
        std::fs::write(&p, text).map_err(|e| {
            CalibError::file(&p.display().to_string(), format!("cannot write: {e}"))
        })?;
        paths.push(p);
    }
    Ok(paths)
}
