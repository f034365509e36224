//! Resolving materials: the scene's own `[materials]` (converted from MPa to Pa and
//! checked) and the built-in library, which scene materials may not shadow.

use crate::error::FieldError;
use crate::format::MaterialEntry;
use crate::library::Library;
use crate::validate::{finite, positive, with_unit};
use pliant_core::material::{DahlLaw, Hysteresis, PronyTerm, YieldLaw};
use pliant_core::{Material, Section};
use std::collections::BTreeMap;

/// Materials a hose may name: the library's and the scene's own.
pub struct Materials<'a> {
    library: &'a Library,
    /// The scene's materials and their minimum bend radius \[m\] if given.
    user: BTreeMap<String, (Material, Option<f64>)>,
}

/// A material looked up by name, with the library's default cross-section if it has one.
pub struct Resolved {
    /// The material, SI.
    pub material: Material,
    /// Default cross-section, SI (library hoses only).
    pub default_section: Option<Section>,
    /// Minimum bend radius of the centre line \[m\], where the data gives one (library
    /// hoses; scene materials with `min_bend_radius_mm`).
    pub min_bend_radius: Option<f64>,
}

/// The minimum bend radius of the centre line \[m\] of a hose of section `s` whose
/// material gives none: 6 × d_inner to the inside of the bend, the rule for
/// mandrel-built rubber hoses (BTR hose catalogue; an assumption, see
/// `data/materials.toml`), i.e. 6 d_inner + d_outer / 2.
pub fn min_bend_radius_rule(s: &Section) -> f64 {
    6.0 * s.d_inner + 0.5 * s.d_outer
}

impl<'a> Materials<'a> {
    /// Checks and converts the scene's `[materials]`.
    pub fn build(
        raw: &BTreeMap<String, MaterialEntry>,
        library: &'a Library,
    ) -> Result<Self, FieldError> {
        let mut user = BTreeMap::new();
        for (name, entry) in raw {
            let field = format!("materials.{name}");
            if name.trim().is_empty() {
                return Err(FieldError::about(
                    field,
                    "a material name must not be empty",
                ));
            }
            if library.get(name).is_some() {
                return Err(FieldError::about(
                    field,
                    format!(
                        "the name is taken by the built-in library ({}); choose another name",
                        library.names().join(", ")
                    ),
                ));
            }
            let r_min = match entry.min_bend_radius_mm {
                Some(r) => Some(positive(&format!("{field}.min_bend_radius_mm"), r, "mm")? * 1e-3),
                None => None,
            };
            user.insert(name.clone(), (user_material(&field, entry)?, r_min));
        }
        Ok(Self { library, user })
    }

    /// Looks up `name` for the field `field` (used in the error).
    pub fn resolve(&self, field: &str, name: &str) -> Result<Resolved, FieldError> {
        if let Some(entry) = self.library.get(name) {
            return Ok(Resolved {
                material: entry.material.clone(),
                default_section: Some(entry.section),
                min_bend_radius: Some(entry.min_bend_radius),
            });
        }
        if let Some((material, r_min)) = self.user.get(name) {
            return Ok(Resolved {
                material: material.clone(),
                default_section: None,
                min_bend_radius: *r_min,
            });
        }
        let user: Vec<&str> = self.user.keys().map(String::as_str).collect();
        let scene = if user.is_empty() {
            "none".to_string()
        } else {
            user.join(", ")
        };
        Err(FieldError::new(
            field,
            format!("\"{name}\""),
            format!(
                "unknown material; library materials: {}; scene materials: {scene}",
                self.library.names().join(", ")
            ),
        ))
    }
}

/// Checks one `[materials.NAME]` entry and converts it to SI.
fn user_material(field: &str, m: &MaterialEntry) -> Result<Material, FieldError> {
    let e_tension = positive(&format!("{field}.e_tension_mpa"), m.e_tension_mpa, "MPa")?;
    let e_compression = positive(
        &format!("{field}.e_compression_mpa"),
        m.e_compression_mpa,
        "MPa",
    )?;
    let e_bending = match m.e_bending_mpa {
        Some(e) => Some(positive(&format!("{field}.e_bending_mpa"), e, "MPa")? * 1e6),
        None => None,
    };
    let poisson_field = format!("{field}.poisson");
    let poisson = finite(&poisson_field, m.poisson, "")?;
    if !(poisson > -1.0 && poisson < 0.5) {
        return Err(FieldError::new(
            poisson_field,
            with_unit(poisson, ""),
            "must lie in (−1, 0.5)",
        ));
    }
    let density = positive(&format!("{field}.density_kg_m3"), m.density_kg_m3, "kg/m³")?;
    let plasticity = yield_law(field, m)?;
    let relaxation = relaxation(field, m)?;
    if plasticity.is_some() && !relaxation.is_empty() {
        return Err(FieldError::new(
            format!("{field}.relaxation"),
            format!("{} terms", relaxation.len()),
            "a material either yields (`yield_stress_mpa`) or relaxes, not both",
        ));
    }
    let hysteresis = hysteresis(field, m)?;
    if hysteresis.is_some() && (plasticity.is_some() || !relaxation.is_empty()) {
        return Err(FieldError::new(
            format!("{field}.hysteresis"),
            "given",
            "a material has one law with a history: it yields (`yield_stress_mpa`), \
             relaxes (`relaxation`) or rubs (`hysteresis`)",
        ));
    }
    Ok(Material {
        e_tension: e_tension * 1e6,
        e_compression: e_compression * 1e6,
        e_bending,
        poisson,
        density,
        plasticity,
        relaxation,
        hysteresis,
    })
}

/// The entry's friction law, SI: moments and curvature scales positive and finite, the
/// torsion pair given together.
fn hysteresis(field: &str, m: &MaterialEntry) -> Result<Option<Hysteresis>, FieldError> {
    let Some(h) = &m.hysteresis else {
        return Ok(None);
    };
    let at = |name: &str| format!("{field}.hysteresis.{name}");
    let bending = DahlLaw {
        moment: positive(&at("bending_moment_n_m"), h.bending_moment_n_m, "N·m")?,
        curvature: positive(&at("bending_curvature_1_m"), h.bending_curvature_1_m, "1/m")?,
    };
    let torsion = match (h.torsion_moment_n_m, h.torsion_curvature_1_m) {
        (None, None) => None,
        (Some(moment), Some(curvature)) => Some(DahlLaw {
            moment: positive(&at("torsion_moment_n_m"), moment, "N·m")?,
            curvature: positive(&at("torsion_curvature_1_m"), curvature, "1/m")?,
        }),
        (Some(moment), None) => {
            return Err(FieldError::new(
                at("torsion_curvature_1_m"),
                "missing",
                format!("required with torsion_moment_n_m = {moment}"),
            ))
        }
        (None, Some(curvature)) => {
            return Err(FieldError::new(
                at("torsion_moment_n_m"),
                "missing",
                format!("required with torsion_curvature_1_m = {curvature}"),
            ))
        }
    };
    Ok(Some(Hysteresis { bending, torsion }))
}

/// Most terms a relaxation may have (a Prony series fitted to a test rarely needs more
/// than one per decade of time).
const MAX_PRONY_TERMS: usize = 8;

/// The entry's Prony series, SI: every weight in (0, 1), their sum below 1, every time
/// positive and finite.
fn relaxation(field: &str, m: &MaterialEntry) -> Result<Vec<PronyTerm>, FieldError> {
    let list = format!("{field}.relaxation");
    if m.relaxation.len() > MAX_PRONY_TERMS {
        return Err(FieldError::new(
            list,
            format!("{} terms", m.relaxation.len()),
            format!("at most {MAX_PRONY_TERMS} terms"),
        ));
    }
    let mut terms = Vec::with_capacity(m.relaxation.len());
    for (i, p) in m.relaxation.iter().enumerate() {
        let weight_field = format!("{list}[{i}].weight");
        let weight = finite(&weight_field, p.weight, "")?;
        if !(weight > 0.0 && weight < 1.0) {
            return Err(FieldError::new(
                weight_field,
                with_unit(weight, ""),
                "must lie in (0, 1)",
            ));
        }
        let time = positive(&format!("{list}[{i}].time_s"), p.time_s, "s")?;
        terms.push(PronyTerm { weight, time });
    }
    let sum: f64 = terms.iter().map(|p| p.weight).sum();
    if sum >= 1.0 {
        return Err(FieldError::new(
            list,
            format!("weights summing to {sum}"),
            "the weights must sum below 1 (the long-term modulus E₀ (1 − Σ weight) stays positive)",
        ));
    }
    Ok(terms)
}

/// The entry's yield law, SI: `yield_stress_mpa` and `hardening_modulus_mpa` checked.
fn yield_law(field: &str, m: &MaterialEntry) -> Result<Option<YieldLaw>, FieldError> {
    let hardening_field = format!("{field}.hardening_modulus_mpa");
    let Some(sy) = m.yield_stress_mpa else {
        if let Some(h) = m.hardening_modulus_mpa {
            return Err(FieldError::new(
                hardening_field,
                with_unit(h, "MPa"),
                "a hardening modulus needs `yield_stress_mpa`",
            ));
        }
        return Ok(None);
    };
    let yield_stress = positive(&format!("{field}.yield_stress_mpa"), sy, "MPa")? * 1e6;
    let hardening_modulus = match m.hardening_modulus_mpa {
        Some(h) => {
            let h = finite(&hardening_field, h, "MPa")?;
            if h < 0.0 {
                return Err(FieldError::new(
                    hardening_field,
                    with_unit(h, "MPa"),
                    "must be ≥ 0",
                ));
            }
            h * 1e6
        }
        None => 0.0,
    };
    Ok(Some(YieldLaw {
        yield_stress,
        hardening_modulus,
    }))
}
