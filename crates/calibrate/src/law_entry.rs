//! From the fitted laws to the material's inelastic entries, in the scene format
//! (docs/scene-format.md, `[materials.NAME]`): `yield_stress_mpa` and
//! `hardening_modulus_mpa` from the tests past yield (a bending one, a torsion one or one
//! of each: [`crate::yield_combination`]), `relaxation = [{ weight, time_s
//! }, …]` from a relaxation test, `hysteresis = { bending_moment_n_m, … }` from cyclic
//! bending (and torsion) tests — every value with its 95 % interval and source — and the
//! elastic stiffness each law fit measured (E·I, EI or GJ), which joins the stiffness
//! tests'. A material does one of yield, relax or rub (the scene's rule), so other
//! combinations are an error.

use crate::law_fit::LawFit;
use crate::material_entry::{num, Derived, Measured};
use crate::mechanics::{Property, TestKind};
use crate::nonlinear_least_squares::Estimate;
use crate::yield_combination;
use serde::Serialize;
use std::fmt::Write as _;

/// One Prony term of the material.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PronyEntry {
    pub weight: Derived,
    pub time_s: Derived,
}

/// The material's Dahl friction.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HysteresisEntry {
    pub bending_moment_n_m: Derived,
    pub bending_curvature_1_m: Derived,
    pub torsion_moment_n_m: Option<Derived>,
    pub torsion_curvature_1_m: Option<Derived>,
}

/// The inelastic entries of a calibrated material (all empty for an elastic one).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct LawEntries {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_stress_mpa: Option<Derived>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hardening_modulus_mpa: Option<Derived>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub relaxation: Vec<PronyEntry>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hysteresis: Option<HysteresisEntry>,
    /// How the entries were put together from several tests (for the material's
    /// warnings).
    #[serde(skip)]
    pub notes: Vec<String>,
}

/// A law fit described for a source line.
pub fn describe(f: &LawFit) -> String {
    let params: Vec<String> = f
        .fit
        .estimates
        .iter()
        .map(|e| {
            format!(
                "{} = {:.6e} (95% CI {:.6e}-{:.6e})",
                e.name, e.value, e.ci95[0], e.ci95[1]
            )
        })
        .collect();
    format!(
        "{} test {} (pliant calibrate; law fitted to all {} points, residual std {:.4e}): {}",
        f.kind.name(),
        f.csv,
        f.fit.points,
        f.fit.residual_std,
        params.join(", ")
    )
}

/// Whether a test measures the yield law (E or G, σ_y or τ_y, H).
pub fn is_yield_test(kind: TestKind) -> bool {
    matches!(
        kind,
        TestKind::PlasticBending
            | TestKind::PlasticTorsion
            | TestKind::PlasticCantilever
            | TestKind::PlasticThreePointBending
    )
}

/// An estimate in a display unit (`scale` from SI) with its interval and the fit as
/// source.
pub(crate) fn derived(e: &Estimate, scale: f64, f: &LawFit) -> Derived {
    Derived::source(
        e.value * scale,
        Some([e.ci95[0] * scale, e.ci95[1] * scale]),
        describe(f),
    )
}

pub(crate) fn estimate<'a>(f: &'a LawFit, name: &str) -> Result<&'a Estimate, String> {
    f.estimate(name)
        .ok_or_else(|| format!("{}: the fit has no {name}", f.csv))
}

/// The elastic stiffness a law fit measured, as a stiffness test's would be: E I of the
/// tested section from a bending test past yield (G J from torsion past yield), EI or GJ
/// from a cyclic one, E₀ from a relaxation test with its held strain.
pub fn measured(f: &LawFit) -> Option<Measured> {
    let (name, property, factor) = match f.kind {
        TestKind::PlasticBending
        | TestKind::PlasticCantilever
        | TestKind::PlasticThreePointBending => (
            "E",
            Property::BendingStiffness,
            f.geometry.section().second_moment(),
        ),
        TestKind::PlasticTorsion => (
            "G",
            Property::TorsionalStiffness,
            f.geometry.section().polar_moment(),
        ),
        TestKind::CyclicBending => ("EI", Property::BendingStiffness, 1.0),
        // E0 from the held strain (else the relaxation gives ratios only)
        TestKind::Relaxation => ("E0", Property::ETension, 1.0),
        TestKind::CyclicTorsion => ("GJ", Property::TorsionalStiffness, 1.0),
        _ => return None,
    };
    let e = f.estimate(name)?;
    // the parameter is fitted as its logarithm: se(p) ≈ p se(ln p)
    Some(Measured {
        property,
        value: e.value * factor,
        std_error: e.value * e.std_error * factor,
        ci95: [e.ci95[0] * factor, e.ci95[1] * factor],
        geometry: f.geometry,
        description: describe(f),
    })
}

/// The inelastic entries of `laws`, or why they cannot make one material.
pub fn entries(laws: &[LawFit]) -> Result<LawEntries, String> {
    let of = |k: TestKind| -> Result<Option<&LawFit>, String> {
        let mut it = laws.iter().filter(|f| f.kind == k);
        let first = it.next();
        match it.next() {
            Some(second) => Err(format!(
                "two {} tests ({} and {}): give one per calibration",
                k.name(),
                first.map_or("", |f| f.csv.as_str()),
                second.csv
            )),
            None => Ok(first),
        }
    };
    let yield_tests: Vec<&LawFit> = laws.iter().filter(|f| is_yield_test(f.kind)).collect();
    let bending_yield: Vec<&LawFit> = yield_tests
        .iter()
        .copied()
        .filter(|f| f.kind != TestKind::PlasticTorsion)
        .collect();
    if let [first, second, ..] = bending_yield[..] {
        return Err(format!(
            "two bending tests past yield ({} {} and {} {}): give one per calibration (the yield law has one σ_y and one H; a plastic_torsion test may join it)",
            first.kind.name(),
            first.csv,
            second.kind.name(),
            second.csv
        ));
    }
    let torsion_yield = of(TestKind::PlasticTorsion)?;
    let plastic = yield_combination::combine(bending_yield.first().copied(), torsion_yield)?;
    let relaxation = of(TestKind::Relaxation)?;
    let bending = of(TestKind::CyclicBending)?;
    let torsion = of(TestKind::CyclicTorsion)?;
    let count = [
        plastic.is_some(),
        relaxation.is_some(),
        bending.is_some() || torsion.is_some(),
    ]
    .iter()
    .filter(|b| **b)
    .count();
    if count > 1 {
        return Err("a material either yields (plastic_bending, plastic_torsion, plastic_cantilever, plastic_three_point_bending), relaxes (relaxation) or rubs (cyclic_bending, cyclic_torsion), not two of these (docs/scene-format.md): calibrate them as separate materials".into());
    }
    if torsion.is_some() && bending.is_none() {
        return Err("a cyclic_torsion test needs a cyclic_bending test too: the scene's hysteresis has a bending pair and an optional torsion pair".into());
    }
    let mut out = LawEntries::default();
    if let Some(y) = plastic {
        out.yield_stress_mpa = Some(y.yield_stress);
        out.hardening_modulus_mpa = Some(y.hardening);
        out.notes.extend(y.note);
    }
    if let Some(f) = relaxation {
        let values = &f.fit.estimates;
        for pair in values[1..].chunks_exact(2) {
            out.relaxation.push(PronyEntry {
                weight: derived(&pair[0], 1.0, f),
                time_s: derived(&pair[1], 1.0, f),
            });
        }
    }
    if let Some(b) = bending {
        out.hysteresis = Some(HysteresisEntry {
            bending_moment_n_m: derived(estimate(b, "M_s")?, 1.0, b),
            bending_curvature_1_m: derived(estimate(b, "kappa_s")?, 1.0, b),
            torsion_moment_n_m: torsion
                .map(|t| estimate(t, "M_s_torsion").map(|e| derived(e, 1.0, t)))
                .transpose()?,
            torsion_curvature_1_m: torsion
                .map(|t| estimate(t, "kappa_s_torsion").map(|e| derived(e, 1.0, t)))
                .transpose()?,
        });
    }
    Ok(out)
}

impl LawEntries {
    /// Every value and interval bound, by key, for the finiteness check.
    pub fn values(&self) -> impl Iterator<Item = (&'static str, &Derived)> {
        let h = self.hysteresis.as_ref();
        [
            ("yield_stress_mpa", self.yield_stress_mpa.as_ref()),
            ("hardening_modulus_mpa", self.hardening_modulus_mpa.as_ref()),
            (
                "hysteresis.bending_moment_n_m",
                h.map(|h| &h.bending_moment_n_m),
            ),
            (
                "hysteresis.bending_curvature_1_m",
                h.map(|h| &h.bending_curvature_1_m),
            ),
            (
                "hysteresis.torsion_moment_n_m",
                h.and_then(|h| h.torsion_moment_n_m.as_ref()),
            ),
            (
                "hysteresis.torsion_curvature_1_m",
                h.and_then(|h| h.torsion_curvature_1_m.as_ref()),
            ),
        ]
        .into_iter()
        .filter_map(|(k, d)| d.map(|d| (k, d)))
        .chain(self.relaxation.iter().flat_map(|p| {
            [
                ("relaxation.weight", &p.weight),
                ("relaxation.time_s", &p.time_s),
            ]
        }))
    }

    /// The entries' lines of a scene's `[materials.NAME]` table, each value's source
    /// and interval in a comment above it.
    pub fn scene_lines(&self, s: &mut String) {
        let comment = |s: &mut String, k: &str, d: &Derived| {
            let (what, text) = d.provenance();
            let ci = d
                .ci95
                .map(|c| format!(" (95% CI {}-{})", num(c[0]), num(c[1])))
                .unwrap_or_default();
            let _ = writeln!(s, "# {k}{ci}, {what}: {text}");
        };
        for (k, d) in [
            ("yield_stress_mpa", &self.yield_stress_mpa),
            ("hardening_modulus_mpa", &self.hardening_modulus_mpa),
        ] {
            if let Some(d) = d {
                comment(s, k, d);
                let _ = writeln!(s, "{k} = {}", num(d.value));
            }
        }
        if !self.relaxation.is_empty() {
            let mut terms = Vec::new();
            for (i, p) in self.relaxation.iter().enumerate() {
                comment(s, &format!("relaxation[{i}].weight"), &p.weight);
                comment(s, &format!("relaxation[{i}].time_s"), &p.time_s);
                terms.push(format!(
                    "{{ weight = {}, time_s = {} }}",
                    num(p.weight.value),
                    num(p.time_s.value)
                ));
            }
            let _ = writeln!(s, "relaxation = [{}]", terms.join(", "));
        }
        if let Some(h) = &self.hysteresis {
            let mut parts = Vec::new();
            for (k, d) in [
                ("bending_moment_n_m", Some(&h.bending_moment_n_m)),
                ("bending_curvature_1_m", Some(&h.bending_curvature_1_m)),
                ("torsion_moment_n_m", h.torsion_moment_n_m.as_ref()),
                ("torsion_curvature_1_m", h.torsion_curvature_1_m.as_ref()),
            ] {
                if let Some(d) = d {
                    comment(s, &format!("hysteresis.{k}"), d);
                    parts.push(format!("{k} = {}", num(d.value)));
                }
            }
            let _ = writeln!(
                s,
                "# the friction moments are those of the tested section (use the material with it)"
            );
            let _ = writeln!(s, "hysteresis = {{ {} }}", parts.join(", "));
        }
    }

    /// The entries' lines of a library entry: the library holds a yield law
    /// (`yield_stress_mpa`, `hardening_modulus_mpa`) but no relaxation or hysteresis.
    pub fn library_lines(&self, s: &mut String) {
        for (k, d) in [
            ("yield_stress_mpa", &self.yield_stress_mpa),
            ("hardening_modulus_mpa", &self.hardening_modulus_mpa),
        ] {
            if let Some(d) = d {
                let (what, text) = d.provenance();
                let _ = writeln!(
                    s,
                    "{k} = {{ value = {}, {what} = {} }}",
                    num(d.value),
                    toml::Value::String(text.to_string())
                );
            }
        }
        if !self.relaxation.is_empty() || self.hysteresis.is_some() {
            let _ = writeln!(s, "# the library format holds no relaxation or hysteresis: they are in material.toml only");
        }
    }
}
