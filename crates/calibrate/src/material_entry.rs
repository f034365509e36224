//! From the fitted stiffnesses to a Pliant material: the `[materials.NAME]` table a scene
//! accepts and an entry in the library's format (`crates/scene/data/materials.toml`),
//! every value with its source or marked as an assumption.
//!
//! Conversion (consistent with `pliant_core::Section` and `pliant_core::Material`):
//! a tube of diameters d_i, d_a has A = π/4 (d_a² − d_i²), I = π/64 (d_a⁴ − d_i⁴),
//! J = 2 I; the model's bending stiffness is E_b I and its torsional stiffness G J with
//! G = E_b / (2 (1 + ν)). So
//!
//! * E_t, E_c: the tension and compression moduli as fitted (one missing: taken equal
//!   to the other, an assumption; both missing: the bending modulus);
//! * a bending test's EI gives the explicit bending modulus `e_bending_mpa` = EI / I of
//!   the tested section;
//! * a torsion test's GJ gives G = GJ / J and so Poisson's ratio ν = E_b / (2 G) − 1,
//!   which the material holds only while −1 < ν < 0.5. Outside that range (reinforced
//!   hoses often are) the material cannot hold the measured GJ: ν stays at the given or
//!   default value, a warning says so, and the measured EI and GJ are written as a
//!   `section = { …, ei1_n_m2, ei2_n_m2, gj_n_m2 }` line for the hose (SPEC S3), which
//!   holds them exactly.
//!
//! Several tests of one kind are combined by their inverse-variance weighted mean, its
//! standard error 1/√Σwᵢ, and a 95 % interval ±1.96 se (normal approximation).

use crate::fit::TestFit;
use crate::law_entry::{self, LawEntries};
use crate::law_fit::LawFit;
use crate::mechanics::{Geometry, Property, TestKind};
use crate::spec::Spec;
use serde::Serialize;
use std::fmt::Write as _;

/// Default Poisson's ratio (elastomers, an assumption as in the library).
pub const DEFAULT_POISSON: f64 = 0.49;

/// A value of the material with where it comes from.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Derived {
    /// In the unit its key names (MPa, N·m², kg/m³, mm, -).
    pub value: f64,
    /// 95 % confidence interval where the value is measured.
    pub ci95: Option<[f64; 2]>,
    /// Exactly one of source and assumption.
    pub source: Option<String>,
    pub assumption: Option<String>,
}

impl Derived {
    pub(crate) fn source(value: f64, ci95: Option<[f64; 2]>, s: String) -> Self {
        Self {
            value,
            ci95,
            source: Some(s),
            assumption: None,
        }
    }
    fn assumption(value: f64, a: String) -> Self {
        Self {
            value,
            ci95: None,
            source: None,
            assumption: Some(a),
        }
    }
    pub(crate) fn provenance(&self) -> (&'static str, &str) {
        match (&self.source, &self.assumption) {
            (Some(s), _) => ("source", s),
            (None, Some(a)) => ("assumption", a),
            _ => ("source", ""),
        }
    }
}

/// The calibrated material.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MaterialResult {
    pub name: String,
    pub description: String,
    pub d_inner_mm: f64,
    pub d_outer_mm: f64,
    pub e_tension_mpa: Derived,
    pub e_compression_mpa: Derived,
    pub e_bending_mpa: Option<Derived>,
    pub poisson: Derived,
    pub density_kg_m3: Derived,
    pub min_bend_radius_mm: Option<Derived>,
    /// Measured bending and torsional stiffness of the specimen's section \[N·m²\].
    pub ei_n_m2: Option<Derived>,
    pub gj_n_m2: Option<Derived>,
    /// Whether the material reproduces the measured GJ (else give it in the section).
    pub gj_held_by_material: bool,
    /// The inelastic law fitted (yield, relaxation or hysteresis), if any.
    #[serde(flatten)]
    pub laws: LawEntries,
    pub warnings: Vec<String>,
}

impl MaterialResult {
    /// The first derived value (or confidence bound) that is not finite, by its key:
    /// such a material is never written.
    pub fn first_non_finite(&self) -> Option<(&'static str, f64)> {
        let derived: [(&'static str, Option<&Derived>); 8] = [
            ("e_tension_mpa", Some(&self.e_tension_mpa)),
            ("e_compression_mpa", Some(&self.e_compression_mpa)),
            ("e_bending_mpa", self.e_bending_mpa.as_ref()),
            ("poisson", Some(&self.poisson)),
            ("density_kg_m3", Some(&self.density_kg_m3)),
            ("min_bend_radius_mm", self.min_bend_radius_mm.as_ref()),
            ("ei_n_m2", self.ei_n_m2.as_ref()),
            ("gj_n_m2", self.gj_n_m2.as_ref()),
        ];
        let plain = [
            ("d_inner_mm", self.d_inner_mm),
            ("d_outer_mm", self.d_outer_mm),
        ];
        plain
            .into_iter()
            .chain(
                derived
                    .into_iter()
                    .filter_map(|(k, d)| d.map(|d| (k, d)))
                    .chain(self.laws.values())
                    .flat_map(|(k, d)| {
                        std::iter::once((k, d.value))
                            .chain(d.ci95.into_iter().flatten().map(move |b| (k, b)))
                    }),
            )
            .find(|(_, v)| !v.is_finite())
    }
}

/// A number with about 6 significant digits, plainly written.
pub fn num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..=9).contains(&mag) {
        return format!("{v:.5e}");
    }
    let decimals = (5 - mag).max(0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        let s = s.trim_end_matches('0');
        s.trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A stiffness one test measured (a stiffness test's slope, or the elastic part of a
/// law fit), with the test's description for a source line.
#[derive(Clone, Debug)]
pub struct Measured {
    pub property: Property,
    /// SI, with its standard error and 95 % interval.
    pub value: f64,
    pub std_error: f64,
    pub ci95: [f64; 2],
    pub geometry: Geometry,
    pub description: String,
}

impl Measured {
    fn of_test(t: &TestFit) -> Self {
        Self {
            property: t.property,
            value: t.value,
            std_error: t.std_error,
            ci95: t.ci95,
            geometry: t.geometry,
            description: describe(t),
        }
    }
}

/// One test described for a source line.
pub fn describe(t: &TestFit) -> String {
    let r = &t.range;
    format!(
        "{} test {} (pliant calibrate; linear range rows {}-{} of {}, CSV lines {}-{}, {} {}-{}): {} = {} {}, 95% CI {}-{}",
        t.kind.name(),
        t.csv,
        r.first_row + 1,
        r.last_row + 1,
        r.total_points,
        r.first_line,
        r.last_line,
        r.x_label,
        num(r.x_from),
        num(r.x_to),
        t.symbol,
        num(t.value_display),
        t.unit,
        num(t.ci95_display[0]),
        num(t.ci95_display[1])
    )
}

/// Inverse-variance weighted mean of (value, se) with its se and 95 % interval; a single
/// value keeps its own (Student-t) interval.
fn combine(items: &[(f64, f64, [f64; 2])]) -> (f64, [f64; 2]) {
    if items.len() == 1 {
        return (items[0].0, items[0].2);
    }
    if items.iter().all(|(_, se, _)| *se > 0.0) {
        let w: f64 = items.iter().map(|(_, se, _)| 1.0 / (se * se)).sum();
        let m = items.iter().map(|(v, se, _)| v / (se * se)).sum::<f64>() / w;
        let se = 1.0 / w.sqrt();
        (m, [m - 1.96 * se, m + 1.96 * se])
    } else {
        let m = items.iter().map(|i| i.0).sum::<f64>() / items.len() as f64;
        (m, [m, m])
    }
}

/// The reduced bimodular modulus of SPEC M3.
fn reduced(e_t: f64, e_c: f64) -> f64 {
    let s = e_t.sqrt() + e_c.sqrt();
    4.0 * e_t * e_c / (s * s)
}

/// Builds the material from the stiffness tests' `fits` and the `laws` (`origin` names
/// the calibration file); an error when the laws cannot make one material.
pub fn derive(
    spec: &Spec,
    fits: &[TestFit],
    laws: &[LawFit],
    origin: &str,
) -> Result<MaterialResult, String> {
    let mut warnings = Vec::new();
    let law_entries = law_entry::entries(laws)?;
    warnings.extend(law_entries.notes.iter().cloned());
    let measured: Vec<Measured> = fits
        .iter()
        .map(Measured::of_test)
        .chain(laws.iter().filter_map(law_entry::measured))
        .collect();
    if measured.is_empty() {
        return Err(
            "a relaxation test gives ratios of moduli only: give its held_strain (--held-strain on the command line) for the instantaneous modulus E0, or add a tension, compression, bending or torsion test (or a plastic or cyclic one)".into(),
        );
    }
    if !law_entries.relaxation.is_empty() {
        warnings.push("relaxation: the moduli above are the relaxation law's instantaneous ones E0; measure them faster than the shortest relaxation time".into());
    }
    let sec = pliant_core::Section::new(spec.d_inner_mm * 1e-3, spec.d_outer_mm * 1e-3);
    let (i_spec, j_spec) = (sec.second_moment(), sec.polar_moment());
    let of = |p: Property| measured.iter().filter(move |f| f.property == p);
    let sources = |p: Property| {
        let d: Vec<String> = of(p).map(|m| m.description.clone()).collect();
        let n = d.len();
        let joined = d.join("; ");
        if n > 1 {
            format!("{joined} (inverse-variance weighted mean of {n} tests)")
        } else {
            joined
        }
    };
    // moduli in MPa from each kind
    let modulus = |p: Property| -> Option<(f64, [f64; 2])> {
        let items: Vec<(f64, f64, [f64; 2])> = of(p)
            .map(|f| {
                (
                    f.value * 1e-6,
                    f.std_error * 1e-6,
                    [f.ci95[0] * 1e-6, f.ci95[1] * 1e-6],
                )
            })
            .collect();
        (!items.is_empty()).then(|| combine(&items))
    };
    // bending modulus E_b = EI / I of each test's section; G = GJ / J
    let per_section = |p: Property, polar: bool| -> Option<(f64, [f64; 2])> {
        let items: Vec<(f64, f64, [f64; 2])> = of(p)
            .map(|f| {
                let s = f.geometry.section();
                let m = if polar {
                    s.polar_moment()
                } else {
                    s.second_moment()
                } * 1e6;
                (f.value / m, f.std_error / m, [f.ci95[0] / m, f.ci95[1] / m])
            })
            .collect();
        (!items.is_empty()).then(|| combine(&items))
    };
    let e_t = modulus(Property::ETension);
    let e_c = modulus(Property::ECompression);
    let e_b = per_section(Property::BendingStiffness, false);
    let g = per_section(Property::TorsionalStiffness, true);
    let given_nu = spec.poisson;
    let nu_default = given_nu.unwrap_or(DEFAULT_POISSON);
    let nu_assumption = || match given_nu {
        Some(_) => format!("given in {origin}; no torsion test determines it"),
        None => "typical of elastomers (0.48-0.49); no torsion test determines it".to_string(),
    };
    let e_b_text = |v: f64, ci: [f64; 2]| {
        format!(
            "{}; E_b = EI / I with I = pi/64 (d_a^4 - d_i^4) of the tested section: {} MPa, 95% CI {}-{}",
            sources(Property::BendingStiffness),
            num(v),
            num(ci[0]),
            num(ci[1])
        )
    };
    let from_other = |what: &str, other: &str| format!("no {what} test: taken equal to {other}");
    let (e_tension, e_compression) = match (e_t, e_c) {
        (Some((t, tci)), Some((c, cci))) => (
            Derived::source(t, Some(tci), sources(Property::ETension)),
            Derived::source(c, Some(cci), sources(Property::ECompression)),
        ),
        (Some((t, tci)), None) => (
            Derived::source(t, Some(tci), sources(Property::ETension)),
            Derived::assumption(
                t,
                from_other("compression", &format!("E_t = {} MPa", num(t))),
            ),
        ),
        (None, Some((c, cci))) => (
            Derived::assumption(c, from_other("tension", &format!("E_c = {} MPa", num(c)))),
            Derived::source(c, Some(cci), sources(Property::ECompression)),
        ),
        (None, None) => {
            let (e, what) = match (e_b, g) {
                (Some((b, _)), _) => (b, format!("the bending modulus E_b = {} MPa", num(b))),
                (None, Some((gv, _))) => (
                    2.0 * gv * (1.0 + nu_default),
                    format!(
                        "2 G (1 + nu) with G = {} MPa from torsion and nu = {nu_default}",
                        num(gv)
                    ),
                ),
                (None, None) => (f64::NAN, String::new()),
            };
            warnings.push(format!(
                "no tension or compression test: E_t and E_c are taken equal to {what}"
            ));
            (
                Derived::assumption(e, from_other("tension or compression", &what)),
                Derived::assumption(e, from_other("tension or compression", &what)),
            )
        }
    };
    if e_t.is_some() != e_c.is_some() {
        warnings.push(
            "only one of tension and compression was tested: the other modulus is taken equal to it".into(),
        );
    }
    let e_bending = e_b.map(|(v, ci)| Derived::source(v, Some(ci), e_b_text(v, ci)));
    let e_b_model = e_b
        .map(|b| b.0)
        .unwrap_or_else(|| reduced(e_tension.value, e_compression.value));
    let mut gj_held = true;
    // with neither an axial nor a bending test, E came from G and ν: G cannot give ν too
    let e_from_g = e_t.is_none() && e_c.is_none() && e_b.is_none();
    let poisson = match g {
        Some(_) if e_from_g => Derived::assumption(nu_default, nu_assumption()),
        Some((gv, _)) => {
            let nu = e_b_model / (2.0 * gv) - 1.0;
            if nu > -1.0 && nu < 0.5 {
                Derived::source(
                    nu,
                    None,
                    format!(
                        "nu = E_b / (2 G) - 1 with G = GJ / J = {} MPa ({}) and E_b = {} MPa",
                        num(gv),
                        sources(Property::TorsionalStiffness),
                        num(e_b_model)
                    ),
                )
            } else {
                gj_held = false;
                warnings.push(format!(
                    "torsion gives G = {} MPa, but with E_b = {} MPa that needs nu = {:.3}, outside (-1, 0.5): the material keeps nu = {nu_default} (G = {} MPa); give the measured GJ in the hose's section (gj_n_m2, see material.toml)",
                    num(gv),
                    num(e_b_model),
                    nu,
                    num(e_b_model / (2.0 * (1.0 + nu_default)))
                ));
                Derived::assumption(nu_default, nu_assumption())
            }
        }
        None => Derived::assumption(nu_default, nu_assumption()),
    };
    if given_nu.is_some() && g.is_some() && gj_held {
        warnings.push("the torsion test determines Poisson's ratio: the calibration file's poisson is not used".into());
    }
    let density = match &spec.density_source {
        Some(s) => Derived::source(spec.density_kg_m3, None, s.clone()),
        None => Derived::assumption(
            spec.density_kg_m3,
            format!("given in {origin}; not measured by these tests"),
        ),
    };
    let min_bend_radius_mm = spec
        .min_bend_radius_mm
        .map(|r| Derived::source(r, None, format!("given in {origin}")));
    let ei = (!measured
        .iter()
        .all(|f| f.property != Property::BendingStiffness))
    .then(|| {
        let (b, ci) = e_b.unwrap_or((f64::NAN, [f64::NAN; 2]));
        Derived::source(
            b * 1e6 * i_spec,
            Some([ci[0] * 1e6 * i_spec, ci[1] * 1e6 * i_spec]),
            sources(Property::BendingStiffness),
        )
    });
    let gj = g.map(|(gv, ci)| {
        Derived::source(
            gv * 1e6 * j_spec,
            Some([ci[0] * 1e6 * j_spec, ci[1] * 1e6 * j_spec]),
            sources(Property::TorsionalStiffness),
        )
    });
    if fits.iter().any(|f| f.kind == TestKind::Iso10619) {
        warnings.push("EI from the ISO 10619-1 test rests on the lever-arm model M = F a (docs/calibration.md): an estimate".into());
    }
    Ok(MaterialResult {
        name: spec.name.clone(),
        description: spec
            .description
            .clone()
            .unwrap_or_else(|| format!("calibrated from {origin}")),
        d_inner_mm: spec.d_inner_mm,
        d_outer_mm: spec.d_outer_mm,
        e_tension_mpa: e_tension,
        e_compression_mpa: e_compression,
        e_bending_mpa: e_bending,
        poisson,
        density_kg_m3: density,
        min_bend_radius_mm,
        ei_n_m2: ei,
        gj_n_m2: gj,
        gj_held_by_material: gj_held,
        laws: law_entries,
        warnings,
    })
}

fn toml_str(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

impl MaterialResult {
    /// The `[materials.NAME]` table for a scene file, each value's provenance in a
    /// comment above it, and the measured EI/GJ as a section line.
    pub fn scene_toml(&self, origin: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Material calibrated by `pliant calibrate {origin}` (docs/calibration.md)."
        );
        let _ = writeln!(
            s,
            "# Paste the table into a scene file (docs/scene-format.md, [materials.NAME])."
        );
        let _ = writeln!(s, "# The fits, 95 % confidence intervals and linear ranges: calibration.json and calibration.html.");
        for w in &self.warnings {
            let _ = writeln!(s, "# warning: {w}");
        }
        let key = if self
            .name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            self.name.clone()
        } else {
            toml_str(&self.name)
        };
        let _ = writeln!(s, "\n[materials.{key}]");
        let mut line = |k: &str, d: &Derived| {
            let (what, text) = d.provenance();
            let _ = writeln!(s, "# {what}: {text}");
            let _ = writeln!(s, "{k} = {}", num(d.value));
        };
        line("e_tension_mpa", &self.e_tension_mpa);
        line("e_compression_mpa", &self.e_compression_mpa);
        if let Some(b) = &self.e_bending_mpa {
            line("e_bending_mpa", b);
        }
        line("poisson", &self.poisson);
        line("density_kg_m3", &self.density_kg_m3);
        if let Some(r) = &self.min_bend_radius_mm {
            line("min_bend_radius_mm", r);
        }
        self.laws.scene_lines(&mut s);
        if self.ei_n_m2.is_some() || self.gj_n_m2.is_some() {
            let mut parts = vec![
                format!("d_inner = {}", num(self.d_inner_mm)),
                format!("d_outer = {}", num(self.d_outer_mm)),
            ];
            if let Some(ei) = &self.ei_n_m2 {
                parts.push(format!("ei1_n_m2 = {0}, ei2_n_m2 = {0}", num(ei.value)));
            }
            if let Some(gj) = &self.gj_n_m2 {
                parts.push(format!("gj_n_m2 = {}", num(gj.value)));
            }
            let _ = writeln!(
                s,
                "\n# The tested section (lengths in mm, length_unit = \"mm\") with the measured stiffness given\n# directly (docs/scene-format.md, Sections){}:\n# section = {{ {} }}",
                if self.gj_held_by_material {
                    "; the material above already reproduces it for this section"
                } else {
                    "; needed for GJ: the material cannot hold it (see the warning)"
                },
                parts.join(", ")
            );
        }
        s
    }

    /// An entry in the format of the built-in library (`crates/scene/data/materials.toml`).
    pub fn library_toml(&self, origin: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# Library entry (format of crates/scene/data/materials.toml) calibrated by"
        );
        let _ = writeln!(
            s,
            "# `pliant calibrate {origin}`. The library holds no bending modulus: a bending test's"
        );
        let _ = writeln!(s, "# E_b is in material.toml (e_bending_mpa) only; without it the library's hose bends with");
        let _ = writeln!(s, "# the reduced modulus of E_t and E_c.");
        let _ = writeln!(
            s,
            "\n[{}]",
            if self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
            {
                self.name.clone()
            } else {
                toml_str(&self.name)
            }
        );
        let _ = writeln!(s, "description = {}", toml_str(&self.description));
        let geom = Derived::source(0.0, None, format!("the tested specimen, {origin}"));
        let mut entry = |k: &str, d: &Derived| {
            let (what, text) = d.provenance();
            let _ = writeln!(
                s,
                "{k} = {{ value = {}, {what} = {} }}",
                num(d.value),
                toml_str(text)
            );
        };
        entry(
            "d_inner_mm",
            &Derived {
                value: self.d_inner_mm,
                ..geom.clone()
            },
        );
        entry(
            "d_outer_mm",
            &Derived {
                value: self.d_outer_mm,
                ..geom
            },
        );
        entry("e_compression_mpa", &self.e_compression_mpa);
        entry("e_tension_mpa", &self.e_tension_mpa);
        entry("density_kg_m3", &self.density_kg_m3);
        entry("poisson", &self.poisson);
        let r_min = self.min_bend_radius_mm.clone().unwrap_or_else(|| {
            if self.d_inner_mm <= 0.0 {
                // the library needs r_min > d_outer / 2; no hose rule for a solid rod
                return Derived::assumption(
                    self.d_outer_mm,
                    "one outer diameter (a solid rod: no hose rule applies); no datasheet value".into(),
                );
            }
            Derived::assumption(
                6.0 * self.d_inner_mm + 0.5 * self.d_outer_mm,
                format!(
                    "rule 6 x d_inner to the inside of the bend (mandrel-built rubber hose) = 6 x {} + {} / 2 on the centre line; no datasheet value",
                    num(self.d_inner_mm),
                    num(self.d_outer_mm)
                ),
            )
        });
        entry("min_bend_radius_mm", &r_min);
        self.laws.library_lines(&mut s);
        s
    }
}
