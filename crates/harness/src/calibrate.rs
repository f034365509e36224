//! Calibration of a protection's coupling factors from a bending or a torsion test of a
//! bundle (SPEC N2: "`pliant calibrate` fits it from a bending test of a bundle").
//!
//! The bundle model (`bundle.rs`) puts a bundle's bending stiffness between two bounds
//! computed from its wires: the wires sliding freely (EI_slip = Σ EI_i) and bonded into one
//! section (EI_bond, parallel-axis theorem), with a factor f_ei per protection kind:
//!
//! EI = EI_slip + f_ei (EI_bond − EI_slip).
//!
//! A measured EI of a real bundle (wires and protection as in the harness) inverts this:
//!
//! f_ei = (EI_measured − EI_slip) / (EI_bond − EI_slip),
//!
//! valid only for EI_slip ≤ EI_measured ≤ EI_bond; outside, the measurement or the wire
//! data is wrong and the fit is refused. Torsion likewise: GJ = GJ_slip + f_gj (GJ_bond −
//! GJ_slip), GJ_bond with each wire's GA r² about the centroid ([`Stiffness`]).
//!
//! The EI of a three-point bending test (simply supported span L, central force F,
//! central deflection δ, small deflection, shear neglected — Euler–Bernoulli beam, e.g.
//! Gere & Goodno, *Mechanics of Materials*, table of beam deflections) is
//! EI = F L³ / (48 δ): [`three_point_bending_ei`].

use crate::bundle::{
    bundle_section, BundleData, BundleSection, SegmentBundle, Sourced, WireSection,
};
use crate::error::HarnessError;
use crate::model::{Harness, ProtectionKind};

/// Why a factor cannot be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    /// A measured quantity is zero, negative or not a number.
    #[error("{what} must be a positive number, is {value}")]
    NotPositive { what: &'static str, value: f64 },
    /// The bundle has no wire.
    #[error("the bundle has no wire: its bounds are zero")]
    NoWires,
    /// One wire (or wires all on one spot): slip and bonded bound coincide.
    #[error(
        "the slip and bonded bounds coincide ({what} {value:.4e} N·m²: a single wire): a bundle of one wire has no coupling factor to fit"
    )]
    DegenerateBounds { what: &'static str, value: f64 },
    /// Below the slip bound: softer than the wires alone.
    #[error(
        "measured {what} {measured:.4e} N·m² is below the slip bound {slip:.4e} N·m² (the wires' own stiffness, f = 0; bonded bound {bond:.4e}): \
         check the test (the linear range, the length, the supports or grips) or the wire data (insulation modulus, strand diameter in data/bundle.toml)"
    )]
    BelowSlip {
        what: &'static str,
        measured: f64,
        slip: f64,
        bond: f64,
    },
    /// Above the bonded bound: stiffer than the wires glued into one section.
    #[error(
        "measured {what} {measured:.4e} N·m² is above the bonded bound {bond:.4e} N·m² (all wires acting as one section, f = 1; slip bound {slip:.4e}): \
         check the test (a protection with stiffness of its own, e.g. a corrugated tube, is not part of the bundle model) or the wire list"
    )]
    AboveBond {
        what: &'static str,
        measured: f64,
        slip: f64,
        bond: f64,
    },
}

/// The stiffness of a bundle a test measures and a coupling factor sets: bending (EI,
/// f_ei) or torsion (GJ, f_gj).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stiffness {
    Bending,
    Torsion,
}

impl Stiffness {
    /// The stiffness a test kind measures: bending tests EI, the torsion test GJ.
    pub fn of_test(kind: pliant_calibrate::TestKind) -> Option<Stiffness> {
        use pliant_calibrate::TestKind;
        match kind {
            TestKind::ThreePointBending | TestKind::Cantilever => Some(Stiffness::Bending),
            TestKind::Torsion => Some(Stiffness::Torsion),
            _ => None,
        }
    }

    /// "EI" or "GJ".
    pub fn symbol(self) -> &'static str {
        match self {
            Stiffness::Bending => "EI",
            Stiffness::Torsion => "GJ",
        }
    }

    /// The factor's name: "f_ei" or "f_gj".
    pub fn factor(self) -> &'static str {
        match self {
            Stiffness::Bending => "f_ei",
            Stiffness::Torsion => "f_gj",
        }
    }

    /// The slip and bonded bound of a section \[N·m²\].
    pub fn bounds(self, b: &BundleSection) -> (f64, f64) {
        match self {
            Stiffness::Bending => (b.ei_slip, b.ei_bond),
            Stiffness::Torsion => (b.gj_slip, b.gj_bond),
        }
    }

    /// The effective value of a section \[N·m²\].
    pub fn of(self, b: &BundleSection) -> f64 {
        match self {
            Stiffness::Bending => b.ei,
            Stiffness::Torsion => b.gj,
        }
    }
}

/// A fitted coupling factor and what it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    /// Which factor: f_ei (bending) or f_gj (torsion).
    pub stiffness: Stiffness,
    /// The factor ∈ [0, 1].
    pub factor: f64,
    /// The measured stiffness \[N·m²\].
    pub measured: f64,
    /// The bounds of the tested bundle \[N·m²\].
    pub slip: f64,
    pub bond: f64,
    /// The protection the factor belongs to (`None`: unprotected wires).
    pub kind: Option<ProtectionKind>,
    pub wire_count: usize,
}

impl Fit {
    /// The key of the factor's protection in `data/bundle.toml` (`protection.<key>.f_ei`).
    pub fn key(&self) -> &'static str {
        self.kind.map_or("none", ProtectionKind::key)
    }

    /// Put the factor into `data` (the protection kind's `f_ei` or `f_gj`, with the source).
    pub fn apply(&self, data: &mut BundleData) {
        if let Some(p) = data.protection.get_mut(self.key()) {
            let factor = match self.stiffness {
                Stiffness::Bending => &mut p.f_ei,
                Stiffness::Torsion => &mut p.f_gj,
            };
            *factor = Sourced {
                value: self.factor,
                source: format!(
                    "calibrated: {} test of a bundle of {} wires, {} = {:.4e} N·m² between the bounds {:.4e} (slip) and {:.4e} (bonded)",
                    match self.stiffness {
                        Stiffness::Bending => "bending",
                        Stiffness::Torsion => "torsion",
                    },
                    self.wire_count,
                    self.stiffness.symbol(),
                    self.measured,
                    self.slip,
                    self.bond
                ),
            };
        }
    }
}

/// EI \[N·m²\] of a three-point bending test: simply supported span `span` \[m\], central
/// force `force` \[N\], central deflection `deflection` \[m\]: EI = F L³ / (48 δ).
/// Use the slope of the loading curve in its linear range (F/δ), not a single point
/// after settling: taped bundles creep and show hysteresis.
pub fn three_point_bending_ei(
    span: f64,
    force: f64,
    deflection: f64,
) -> Result<f64, CalibrationError> {
    for (what, value) in [("span", span), ("force", force), ("deflection", deflection)] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(CalibrationError::NotPositive { what, value });
        }
    }
    Ok(force * span.powi(3) / (48.0 * deflection))
}

/// Fit the factor of protection `kind` for `stiffness` (f_ei or f_gj) from the measured
/// stiffness `measured` \[N·m²\] of a bundle of `wires` (see the module documentation).
pub fn fit_protection_factor(
    stiffness: Stiffness,
    measured: f64,
    wires: &[WireSection],
    kind: Option<ProtectionKind>,
) -> Result<Fit, CalibrationError> {
    let what = stiffness.symbol();
    if !(measured > 0.0 && measured.is_finite()) {
        return Err(CalibrationError::NotPositive {
            what: match stiffness {
                Stiffness::Bending => "measured EI",
                Stiffness::Torsion => "measured GJ",
            },
            value: measured,
        });
    }
    if wires.is_empty() {
        return Err(CalibrationError::NoWires);
    }
    // The bounds do not depend on the factors: the built-in data serve.
    let b = bundle_section(&BundleData::builtin(), wires, None);
    let (slip, bond) = stiffness.bounds(&b);
    if bond - slip <= 1e-9 * bond.abs() {
        return Err(CalibrationError::DegenerateBounds { what, value: slip });
    }
    // Within a relative 10⁻⁹ of a bound counts as on it (rounding of the inputs).
    let tol = 1e-9 * bond;
    if measured < slip - tol {
        return Err(CalibrationError::BelowSlip {
            what,
            measured,
            slip,
            bond,
        });
    }
    if measured > bond + tol {
        return Err(CalibrationError::AboveBond {
            what,
            measured,
            slip,
            bond,
        });
    }
    Ok(Fit {
        stiffness,
        factor: ((measured - slip) / (bond - slip)).clamp(0.0, 1.0),
        measured,
        slip,
        bond,
        kind,
        wire_count: wires.len(),
    })
}

/// The bundle of the segment a user names: its KBL id (`Segment_12`) or its `<Id>` text.
pub fn bundle_of_segment(
    h: &Harness,
    data: &BundleData,
    segment_id: &str,
) -> Result<SegmentBundle, HarnessError> {
    let id = segment_id.trim();
    let i = h
        .segments
        .iter()
        .position(|s| s.kbl_id == id)
        .or_else(|| {
            h.segments
                .iter()
                .position(|s| s.name.as_deref().map(str::trim) == Some(id))
        })
        .ok_or_else(|| HarnessError::UnknownSegment {
            file: h.source.clone(),
            id: id.to_string(),
            example: h
                .segments
                .first()
                .map_or("Segment_1".to_string(), |s| s.kbl_id.clone()),
        })?;
    Ok(crate::bundle::segment_bundle(data, h, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    #[test]
    fn three_point_bending_by_hand() {
        // F = 1 N, L = 200 mm, δ = 5 mm: EI = 1 · 0.008 / (48 · 0.005) = 1/30 N·m².
        let ei = three_point_bending_ei(0.2, 1.0, 5e-3).unwrap();
        assert!(rel(ei, 1.0 / 30.0) < 1e-12);
        let e = three_point_bending_ei(0.2, 1.0, 0.0).unwrap_err();
        assert_eq!(e.to_string(), "deflection must be a positive number, is 0");
    }

    #[test]
    fn fit_inverts_the_bundle_model() {
        let mut data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, None);
        let wires = vec![w; 7];
        let b = bundle_section(&data, &wires, None);
        let measured = b.ei_slip + 0.3 * (b.ei_bond - b.ei_slip);
        let fit = fit_protection_factor(
            Stiffness::Bending,
            measured,
            &wires,
            Some(ProtectionKind::Tape),
        )
        .unwrap();
        assert!((fit.factor - 0.3).abs() < 1e-12);
        assert_eq!(fit.key(), "tape");
        // Put into the data, the model gives the measured EI back.
        fit.apply(&mut data);
        assert!(data.protection["tape"]
            .f_ei
            .source
            .starts_with("calibrated"));
        let cover = crate::bundle::ProtectionCover {
            kind: ProtectionKind::Tape,
            coverage: 1.0,
            outer_diameter: None,
            mass_per_length: None,
        };
        let taped = bundle_section(&data, &wires, Some(cover));
        assert!(rel(taped.ei, measured) < 1e-12);
        // The bounds themselves: f = 0 and f = 1.
        let lo = fit_protection_factor(Stiffness::Bending, b.ei_slip, &wires, None).unwrap();
        assert_eq!((lo.factor, lo.key()), (0.0, "none"));
        assert_eq!(
            fit_protection_factor(Stiffness::Bending, b.ei_bond, &wires, None)
                .unwrap()
                .factor,
            1.0
        );
    }

    #[test]
    fn out_of_bounds_is_refused_with_the_bounds() {
        let data = BundleData::builtin();
        let w = WireSection::new(&data, 1.6e-3, 0.5e-6, None, None);
        let wires = vec![w; 3];
        let b = bundle_section(&data, &wires, None);
        let e =
            fit_protection_factor(Stiffness::Bending, 0.5 * b.ei_slip, &wires, None).unwrap_err();
        assert!(matches!(e, CalibrationError::BelowSlip { .. }));
        assert!(e.to_string().contains("below the slip bound"), "{e}");
        let e =
            fit_protection_factor(Stiffness::Bending, 2.0 * b.ei_bond, &wires, None).unwrap_err();
        assert!(matches!(e, CalibrationError::AboveBond { .. }));
        assert!(e.to_string().contains("above the bonded bound"), "{e}");
        assert!(matches!(
            fit_protection_factor(Stiffness::Bending, 1e-3, &[w], None),
            Err(CalibrationError::DegenerateBounds { .. })
        ));
        assert_eq!(
            fit_protection_factor(Stiffness::Bending, 1e-3, &[], None),
            Err(CalibrationError::NoWires)
        );
        assert!(matches!(
            fit_protection_factor(Stiffness::Bending, f64::NAN, &wires, None),
            Err(CalibrationError::NotPositive { .. })
        ));
    }
}
