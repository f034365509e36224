//! The calibration description: one material, its specimen's section, and one or more
//! tests, each a CSV curve (a TOML file, format "pliant-calibration"; see
//! docs/calibration.md and examples/calibration/).
//!
//! ```toml
//! format = "pliant-calibration"
//! name = "my_hose"                # the material's name in scenes
//! d_inner_mm = 10                 # the tested hose's section
//! d_outer_mm = 16
//! density_kg_m3 = 1100            # not measured by these tests
//!
//! [[tests]]
//! kind = "tension"                # tension, compression, three_point_bending,
//! csv = "tension.csv"             # cantilever, torsion, iso10619; plastic_bending,
//!                                 # plastic_torsion, plastic_cantilever,
//!                                 # plastic_three_point_bending, relaxation,
//!                                 # cyclic_bending, cyclic_torsion
//! length_mm = 100                 # gauge length / span / free length / grip distance / lever arm
//! # relaxation only: terms = 2 (Prony terms, default chosen by BIC), held_strain = 0.05
//! ```

use crate::error::CalibError;
use crate::mechanics::TestKind;
use serde::Deserialize;

/// The format tag of calibration files.
pub const FORMAT_TAG: &str = "pliant-calibration";

/// Largest specimen diameter or length \[mm\] (10 m): beyond it a section's moments
/// overflow and the calibration would give no finite material.
pub const MAX_SPECIMEN_MM: f64 = 1e4;

/// A calibration: the material to produce and the tests to fit.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spec {
    /// `"pliant-calibration"` (optional).
    pub format: Option<String>,
    /// Name of the material in scene files (not a library name such as hose1).
    pub name: String,
    /// What the material is (for the library entry).
    pub description: Option<String>,
    /// The tested hose's inner diameter \[mm\] (0 for a solid rod).
    pub d_inner_mm: f64,
    /// Its outer diameter \[mm\].
    pub d_outer_mm: f64,
    /// Density [kg/m³] (not measured by these tests; required by the material).
    pub density_kg_m3: f64,
    /// Where the density comes from (default: "given in the calibration file").
    pub density_source: Option<String>,
    /// Poisson's ratio when no torsion test determines it (default 0.49, an assumption).
    pub poisson: Option<f64>,
    /// Smallest bend radius of the centre line \[mm\] (datasheet), passed on.
    pub min_bend_radius_mm: Option<f64>,
    /// The tests.
    pub tests: Vec<TestSpec>,
}

/// One test curve.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TestSpec {
    pub kind: TestKind,
    /// The CSV file, relative to the calibration file.
    pub csv: String,
    /// Gauge length, span, free length, grip distance or lever arm \[mm\] (see
    /// [`TestKind::length_meaning`]).
    pub length_mm: Option<f64>,
    /// The specimen's diameters when they differ from the material's \[mm\].
    pub d_inner_mm: Option<f64>,
    pub d_outer_mm: Option<f64>,
    /// Relaxation: the number of Prony terms to fit (default: chosen by BIC among
    /// 1 … [`crate::relaxation_fit::MAX_TERMS`]).
    pub terms: Option<usize>,
    /// Relaxation: the strain held [-], which turns the held force (over the section's
    /// area) or stress into the instantaneous modulus E₀.
    pub held_strain: Option<f64>,
}

/// 1-based line and column of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before
        .rfind('\n')
        .map_or(before.len(), |p| before.len() - p - 1)
        + 1;
    (line, col)
}

/// A TOML parse error of the file `origin` (text `text`) at its line and column.
pub fn toml_error(text: &str, origin: &str, e: &toml::de::Error) -> CalibError {
    let message = e.message().to_string();
    match e.span() {
        Some(span) => {
            let (l, c) = line_col(text, span.start);
            CalibError::cell(origin, l, c, message)
        }
        None => CalibError::file(origin, message),
    }
}

impl Spec {
    /// Parses a calibration file's text (`origin` names it in errors) and checks it.
    pub fn parse(text: &str, origin: &str) -> Result<Spec, CalibError> {
        let spec: Spec = toml::from_str(text).map_err(|e| toml_error(text, origin, &e))?;
        spec.check(origin)?;
        Ok(spec)
    }

    /// Checks values that the types cannot (ranges included: a specimen of 1e308 mm gives no material)
    /// before any curve is read.
    pub fn check(&self, origin: &str) -> Result<(), CalibError> {
        let bad = |m: String| Err(CalibError::file(origin, m));
        if let Some(f) = &self.format {
            if f != FORMAT_TAG {
                return bad(format!("format = \"{f}\": expected \"{FORMAT_TAG}\""));
            }
        }
        if self.name.trim().is_empty() {
            return bad("name: must not be empty".into());
        }
        if !(self.d_inner_mm >= 0.0
            && self.d_outer_mm > self.d_inner_mm
            && self.d_outer_mm.is_finite())
        {
            return bad(format!(
                "d_inner_mm = {}, d_outer_mm = {}: need 0 ≤ d_inner < d_outer",
                self.d_inner_mm, self.d_outer_mm
            ));
        }
        if self.d_outer_mm > MAX_SPECIMEN_MM {
            return bad(format!(
                "d_outer_mm = {}: out of range, a specimen is at most {MAX_SPECIMEN_MM} mm across",
                self.d_outer_mm
            ));
        }
        if !(self.density_kg_m3 > 0.0 && self.density_kg_m3.is_finite()) {
            return bad(format!(
                "density_kg_m3 = {}: must be positive",
                self.density_kg_m3
            ));
        }
        if let Some(nu) = self.poisson {
            if !(nu > -1.0 && nu < 0.5) {
                return bad(format!("poisson = {nu}: must lie in (−1, 0.5)"));
            }
        }
        if let Some(r) = self.min_bend_radius_mm {
            if !(r > 0.5 * self.d_outer_mm && r.is_finite()) {
                return bad(format!("min_bend_radius_mm = {r}: must exceed d_outer / 2"));
            }
        }
        if self.tests.is_empty() {
            return bad("no [[tests]]: give at least one test curve".into());
        }
        for (i, t) in self.tests.iter().enumerate() {
            let field = format!("tests[{i}] ({} {})", t.kind.name(), t.csv);
            if let Some(l) = t.length_mm {
                if !(l > 0.0 && l.is_finite()) {
                    return bad(format!("{field}: length_mm = {l} must be positive"));
                }
                if l > MAX_SPECIMEN_MM {
                    return bad(format!(
                        "{field}: length_mm = {l} is out of range: a specimen is at most {MAX_SPECIMEN_MM} mm long"
                    ));
                }
            }
            let relaxation = t.kind == crate::mechanics::TestKind::Relaxation;
            if let Some(n) = t.terms {
                if !relaxation {
                    return bad(format!("{field}: terms is for a relaxation test"));
                }
                if !(1..=crate::relaxation_fit::MAX_FORCED_TERMS).contains(&n) {
                    return bad(format!(
                        "{field}: terms = {n}: must be 1 to {}",
                        crate::relaxation_fit::MAX_FORCED_TERMS
                    ));
                }
            }
            if let Some(e) = t.held_strain {
                if !relaxation {
                    return bad(format!("{field}: held_strain is for a relaxation test"));
                }
                if !(e > 0.0 && e < 1.0) {
                    return bad(format!(
                        "{field}: held_strain = {e}: must lie in (0, 1) (a strain, not percent)"
                    ));
                }
            }
            let (di, da) = (
                t.d_inner_mm.unwrap_or(self.d_inner_mm),
                t.d_outer_mm.unwrap_or(self.d_outer_mm),
            );
            if !(di >= 0.0 && da > di && da <= MAX_SPECIMEN_MM) {
                return bad(format!(
                    "{field}: need 0 ≤ d_inner_mm < d_outer_mm ≤ {MAX_SPECIMEN_MM}"
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_point_at_the_line() {
        let e = Spec::parse(
            "name = \"x\"\nd_inner_mm = 1\nd_outer_mm = 2\ndensity_kg_m3 = 1000\n[[tests]]\nkind = \"bend\"\ncsv = \"a.csv\"\n",
            "c.toml",
        )
        .unwrap_err();
        assert_eq!(e.line, Some(6), "{e}");
        let e = Spec::parse(
            "name = \"x\"\nd_inner_mm = 3\nd_outer_mm = 2\ndensity_kg_m3 = 1000\n[[tests]]\nkind = \"tension\"\ncsv = \"a.csv\"\n",
            "c.toml",
        )
        .unwrap_err();
        assert!(e.message.contains("d_inner"), "{e}");
    }
}
