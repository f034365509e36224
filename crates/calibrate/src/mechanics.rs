//! The mechanics of each test: which columns it reads, how a curve becomes the straight
//! line whose slope is wanted, and the formula from that slope to the stiffness.
//!
//! | test | line fitted | stiffness from the slope k |
//! |---|---|---|
//! | tension, compression | σ = F / A against ε = ΔL / L₀ (or the stress and strain given) | E = k (Hooke: σ = E ε) |
//! | three-point bending | F against the mid-span deflection δ | EI = k L³ / 48 (δ = F L³ / (48 EI), simply supported span L, load at mid-span; Gere & Timoshenko, *Mechanics of Materials*, table G-2) |
//! | cantilever | F against the tip deflection δ | EI = k L³ / 3 (δ = F L³ / (3 EI), clamped at one end, load at the free end at distance L; ibid., table G-1) |
//! | torsion | T against the angle of twist θ | GJ = k L (θ = T L / (GJ), grips L apart; ibid., §3.3) |
//! | ISO 10619-1 (force to reach a bend radius) | F against the curvature κ = 1/R | EI = k a (M = F a = EI κ, lever arm a; see below) |
//!
//! **ISO 10619-1 model (an assumption).** Methods A2 and C2 of ISO 10619-1 press a hose,
//! bent into a U, between two plates and record the force F that brings it to a bend
//! radius. The standard reports the force only; to turn it into a bending stiffness Pliant
//! takes the moment at the apex of the bend, where the radius is measured, to be
//! M = F·a with a the lever arm from the force's line of action to the apex (given by the
//! test description, `length_mm`), and the apex to bend as a beam, M = EI/R. So F = (EI/a)·κ
//! is linear in the curvature κ = 1/R and EI = a·k. The radius is that of the centre line:
//! a `bend_radius` column is taken as such; a `plate_distance` column C (the inner bend
//! diameter of ISO 10619-1) gives R = (C + d_outer)/2. The real loop is an elastica whose
//! curvature varies along it, so EI from this test is an estimate; the three-point,
//! cantilever and torsion tests are exact within beam theory.

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which test a curve comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TestKind {
    Tension,
    Compression,
    ThreePointBending,
    Cantilever,
    Torsion,
    /// ISO 10619-1 methods A2/C2: force to reach a bend radius.
    #[serde(rename = "iso10619")]
    Iso10619,
    /// A metal line bent past yield and unloaded: moment against curvature
    /// ([`crate::yield_fit`]).
    PlasticBending,
    /// Torque against angle of twist past yield and unloaded
    /// ([`crate::plastic_torsion_fit`]).
    PlasticTorsion,
    /// Force against deflection of a cantilever bent past yield and unloaded
    /// ([`crate::plastic_beam_fit`]).
    PlasticCantilever,
    /// Force against midspan deflection in three-point bending past yield and unloaded
    /// ([`crate::plastic_beam_fit`]).
    PlasticThreePointBending,
    /// Force (or stress) against time at a held strain ([`crate::relaxation_fit`]).
    Relaxation,
    /// Moment against curvature, bent back and forth ([`crate::dahl_fit`]).
    CyclicBending,
    /// Torque against angle of twist, twisted back and forth ([`crate::dahl_fit`]).
    CyclicTorsion,
}

impl TestKind {
    pub const ALL: [TestKind; 13] = [
        TestKind::Tension,
        TestKind::Compression,
        TestKind::ThreePointBending,
        TestKind::Cantilever,
        TestKind::Torsion,
        TestKind::Iso10619,
        TestKind::PlasticBending,
        TestKind::PlasticTorsion,
        TestKind::PlasticCantilever,
        TestKind::PlasticThreePointBending,
        TestKind::Relaxation,
        TestKind::CyclicBending,
        TestKind::CyclicTorsion,
    ];

    /// The name in calibration files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TestKind::Tension => "tension",
            TestKind::Compression => "compression",
            TestKind::ThreePointBending => "three_point_bending",
            TestKind::Cantilever => "cantilever",
            TestKind::Torsion => "torsion",
            TestKind::Iso10619 => "iso10619",
            TestKind::PlasticBending => "plastic_bending",
            TestKind::PlasticTorsion => "plastic_torsion",
            TestKind::PlasticCantilever => "plastic_cantilever",
            TestKind::PlasticThreePointBending => "plastic_three_point_bending",
            TestKind::Relaxation => "relaxation",
            TestKind::CyclicBending => "cyclic_bending",
            TestKind::CyclicTorsion => "cyclic_torsion",
        }
    }

    /// Whether the test measures an inelastic law (fitted whole by
    /// [`crate::law_fit`]) rather than a stiffness over a linear range.
    pub fn is_law(self) -> bool {
        matches!(
            self,
            TestKind::PlasticBending
                | TestKind::PlasticTorsion
                | TestKind::PlasticCantilever
                | TestKind::PlasticThreePointBending
                | TestKind::Relaxation
                | TestKind::CyclicBending
                | TestKind::CyclicTorsion
        )
    }

    /// Parses a name (as [`TestKind::name`]).
    pub fn parse(s: &str) -> Option<TestKind> {
        Self::ALL.into_iter().find(|k| k.name() == s)
    }

    /// What `length_mm` means for this test, or None when the test needs no length.
    pub fn length_meaning(self) -> &'static str {
        match self {
            TestKind::Tension | TestKind::Compression => {
                "the gauge length L0 (needed when the CSV gives force and displacement)"
            }
            TestKind::ThreePointBending | TestKind::PlasticThreePointBending => {
                "the span L between the supports"
            }
            TestKind::Cantilever | TestKind::PlasticCantilever => {
                "the free length L from the clamp to the load"
            }
            TestKind::Torsion | TestKind::PlasticTorsion => "the length L between the grips",
            TestKind::Iso10619 => {
                "the lever arm a from the force's line of action to the apex of the bend"
            }
            TestKind::PlasticBending | TestKind::CyclicBending | TestKind::Relaxation => {
                "nothing (the curve is moment against curvature, or force against time)"
            }
            TestKind::CyclicTorsion => "the length L between the grips",
        }
    }

    /// The stiffness the test measures (the relaxation test measures none: it gives
    /// ratios of moduli).
    pub fn property(self) -> Option<Property> {
        match self {
            TestKind::Tension => Some(Property::ETension),
            TestKind::Compression => Some(Property::ECompression),
            TestKind::ThreePointBending
            | TestKind::Cantilever
            | TestKind::Iso10619
            | TestKind::PlasticBending
            | TestKind::PlasticCantilever
            | TestKind::PlasticThreePointBending
            | TestKind::CyclicBending => Some(Property::BendingStiffness),
            TestKind::Torsion | TestKind::PlasticTorsion | TestKind::CyclicTorsion => {
                Some(Property::TorsionalStiffness)
            }
            TestKind::Relaxation => None,
        }
    }
}

/// A stiffness a test measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Property {
    /// E_t \[Pa\].
    ETension,
    /// E_c \[Pa\].
    ECompression,
    /// EI \[N·m²\].
    BendingStiffness,
    /// GJ \[N·m²\].
    TorsionalStiffness,
}

impl Property {
    /// Symbol, display unit and factor from SI to it.
    pub fn display(self) -> (&'static str, &'static str, f64) {
        match self {
            Property::ETension => ("E_t", "MPa", 1e-6),
            Property::ECompression => ("E_c", "MPa", 1e-6),
            Property::BendingStiffness => ("EI", "N·m²", 1.0),
            Property::TorsionalStiffness => ("GJ", "N·m²", 1.0),
        }
    }
}

/// The specimen: a tube of diameters d_inner, d_outer \[m\], and the test's length \[m\].
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Geometry {
    pub d_inner: f64,
    pub d_outer: f64,
    /// Gauge length, span, free length, grip distance or lever arm (see
    /// [`TestKind::length_meaning`]).
    pub length: Option<f64>,
}

impl Geometry {
    /// The tube's section (the project's formulas: A, I, J of `pliant_core::Section`).
    pub fn section(&self) -> pliant_core::Section {
        pliant_core::Section::new(self.d_inner, self.d_outer)
    }
}

/// A curve ready for the line fit, in SI, with how to show it.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// 1-based line of each point in the CSV.
    pub lines: Vec<usize>,
    /// Axis labels with display units, and factors from SI to them.
    pub x_label: &'static str,
    pub y_label: &'static str,
    pub x_scale: f64,
    pub y_scale: f64,
    /// The stiffness is `factor` × the line's slope.
    pub factor: f64,
    /// The formula used, for the report.
    pub formula: String,
    /// Whether the data's signs were flipped (compression or twist given as negative).
    pub flipped: bool,
}

/// The test's `length_mm` \[m\], or an error naming the file and what the length means.
pub(crate) fn need_length(kind: TestKind, g: &Geometry, file: &str) -> Result<f64, CalibError> {
    match g.length {
        Some(l) if l > 0.0 && l.is_finite() => Ok(l),
        _ => Err(CalibError::file(
            file,
            format!(
                "a {} test needs length_mm: {}",
                kind.name(),
                kind.length_meaning()
            ),
        )),
    }
}

fn missing(kind: TestKind, table: &Table, wanted: &str) -> CalibError {
    let have: Vec<&str> = table.columns.iter().map(|c| c.header.as_str()).collect();
    CalibError::file(
        &table.file,
        format!(
            "a {} test needs the columns {wanted}; found {}",
            kind.name(),
            if have.is_empty() {
                "none".to_string()
            } else {
                have.join(", ")
            }
        ),
    )
}

/// Turns a test's table into the curve to fit.
pub fn prepare(kind: TestKind, table: &Table, g: &Geometry) -> Result<Curve, CalibError> {
    let file = table.file.as_str();
    let col = |q| table.column(q).map(|(_, v)| v.to_vec());
    let (x, y, x_label, y_label, x_scale, y_scale, factor, formula) = match kind {
        TestKind::Tension | TestKind::Compression => {
            let sym = if kind == TestKind::Tension {
                "E_t"
            } else {
                "E_c"
            };
            if let (Some(e), Some(s)) = (col(Quantity::Strain), col(Quantity::Stress)) {
                (
                    e,
                    s,
                    "strain [%]",
                    "stress [MPa]",
                    100.0,
                    1e-6,
                    1.0,
                    format!("{sym} = dσ/dε (σ, ε as measured)"),
                )
            } else if let (Some(d), Some(f)) = (col(Quantity::Displacement), col(Quantity::Force)) {
                let l0 = need_length(kind, g, file)?;
                let a = g.section().area();
                if !(a > 0.0) {
                    return Err(CalibError::file(
                        file,
                        "the specimen's section has no area (d_outer must exceed d_inner)",
                    ));
                }
                (
                    d.iter().map(|d| d / l0).collect(),
                    f.iter().map(|f| f / a).collect(),
                    "strain [%]",
                    "stress [MPa]",
                    100.0,
                    1e-6,
                    1.0,
                    format!(
                        "{sym} = dσ/dε with σ = F/A, ε = ΔL/L0; A = π/4 (d_a² − d_i²) = {:.4} mm², L0 = {:.2} mm",
                        a * 1e6,
                        l0 * 1e3
                    ),
                )
            } else {
                return Err(missing(kind, table, "stress and strain (stress_MPa,strain) or force and displacement (force_N,displacement_mm)"));
            }
        }
        TestKind::ThreePointBending | TestKind::Cantilever => {
            let (Some(d), Some(f)) = (col(Quantity::Displacement), col(Quantity::Force)) else {
                return Err(missing(
                    kind,
                    table,
                    "force and deflection (force_N,deflection_mm)",
                ));
            };
            let l = need_length(kind, g, file)?;
            let (c, what) = if kind == TestKind::ThreePointBending {
                (48.0, "δ = F L³ / (48 EI), span")
            } else {
                (3.0, "δ = F L³ / (3 EI), free length")
            };
            (
                d,
                f,
                "deflection [mm]",
                "force [N]",
                1e3,
                1.0,
                l.powi(3) / c,
                format!("EI = (dF/dδ) L³ / {c}: {what} L = {:.2} mm", l * 1e3),
            )
        }
        TestKind::Torsion => {
            let (Some(t), Some(th)) = (col(Quantity::Torque), col(Quantity::Angle)) else {
                return Err(missing(
                    kind,
                    table,
                    "torque and angle of twist (torque_Nm,angle_deg)",
                ));
            };
            let l = need_length(kind, g, file)?;
            (
                th,
                t,
                "angle of twist [°]",
                "torque [N·m]",
                180.0 / PI,
                1.0,
                l,
                format!(
                    "GJ = (dT/dθ) L: θ = T L / (GJ), grips L = {:.2} mm apart",
                    l * 1e3
                ),
            )
        }
        TestKind::Iso10619 => {
            let Some(f) = col(Quantity::Force) else {
                return Err(missing(kind, table, "force and bend radius (force_N with bend_radius_mm, plate_distance_mm or curvature_1_m)"));
            };
            let a = need_length(kind, g, file)?;
            let (kappa, how) = if let Some(k) = col(Quantity::Curvature) {
                (k, "κ as measured".to_string())
            } else {
                let (r, how) = if let Some(r) = col(Quantity::BendRadius) {
                    (r, "κ = 1/R, R the centre line's bend radius".to_string())
                } else if let Some(c) = col(Quantity::PlateDistance) {
                    (
                        c.iter().map(|c| 0.5 * (c + g.d_outer)).collect(),
                        format!(
                            "κ = 1/R, R = (C + d_a)/2 from the plate distance C, d_a = {:.2} mm",
                            g.d_outer * 1e3
                        ),
                    )
                } else {
                    return Err(missing(kind, table, "a bend radius (bend_radius_mm, plate_distance_mm or curvature_1_m) with force_N"));
                };
                let mut k = Vec::with_capacity(r.len());
                for (i, r) in r.iter().enumerate() {
                    if !(*r > 0.0) {
                        return Err(CalibError::line(
                            file,
                            table.lines[i],
                            format!("bend radius {:.4} mm must be positive", r * 1e3),
                        ));
                    }
                    k.push(1.0 / r);
                }
                (k, how)
            };
            (
                kappa,
                f,
                "curvature 1/R [1/m]",
                "force [N]",
                1.0,
                1.0,
                a,
                format!("EI = (dF/dκ) a: F a = EI κ (assumed model, docs/calibration.md), {how}, lever arm a = {:.2} mm", a * 1e3),
            )
        }
        TestKind::PlasticBending
        | TestKind::PlasticTorsion
        | TestKind::PlasticCantilever
        | TestKind::PlasticThreePointBending
        | TestKind::Relaxation
        | TestKind::CyclicBending
        | TestKind::CyclicTorsion => {
            return Err(CalibError::file(
                file,
                format!(
                    "a {} test is fitted as a whole law, not over a linear range: run it through a calibration file (calibrate_file) or `pliant calibrate`",
                    kind.name()
                ),
            ))
        }
    };
    let mut x = x;
    let mut y = y;
    // compression (or a twist, a deflection) recorded with negative signs: use magnitudes
    let flipped = x.iter().sum::<f64>() < 0.0;
    if flipped {
        x.iter_mut().for_each(|v| *v = -*v);
        y.iter_mut().for_each(|v| *v = -*v);
    }
    for i in 1..x.len() {
        if x[i] < x[i - 1] {
            return Err(CalibError::line(
                file,
                table.lines[i],
                format!(
                    "not monotonic: {} falls from {:.6} to {:.6} (the fit needs the loading branch only, in order; cut the unloading part)",
                    x_label,
                    x[i - 1] * x_scale,
                    x[i] * x_scale
                ),
            ));
        }
    }
    Ok(Curve {
        x,
        y,
        lines: table.lines.clone(),
        x_label,
        y_label,
        x_scale,
        y_scale,
        factor,
        formula,
        flipped,
    })
}
