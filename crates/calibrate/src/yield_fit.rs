//! The `plastic_bending` test: a metal tube (or solid rod) bent past yield and unloaded,
//! moment M against curvature κ → Young's modulus E, the yield stress σ_y and the
//! kinematic hardening modulus H of the simulator's elastic–plastic law
//! ([`pliant_core::material::YieldLaw`]).
//!
//! The law fitted is the closed-form moment–curvature of the section the core implements
//! ([`pliant_core::rod::plastic_moment::hardening_bending_moment`], M_mono(κ), bilinear
//! fibres with linear hardening) on loading, and on unloading from the largest curvature
//! κ_max Masing's rule
//!
//! M(κ) = M_mono(κ_max) − 2 M_mono((κ_max − κ)/2),
//!
//! exact for linear kinematic hardening: every fibre unloads elastically and yields in
//! reverse after a stress change of 2σ_y along its own loading curve stretched by two
//! (Masing 1926; Lubliner, *Plasticity Theory*, 1990, §8.2), and the section's moment is
//! the integral of the fibres' stresses at strains κ y. The unloading branch is the
//! springback check: the curvature left at M = 0, measured and predicted, is reported
//! beside the elastic estimate κ_max − M_max/EI (1/R_after = 1/R − M/EI).
//!
//! A curve that never yields (the fitted first-yield curvature beyond the data, or an
//! elastic line explaining the curve as well: ΔBIC below [`crate::law_fit::BIC_MARGIN`])
//! is an error, never a yield stress.

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit};
use crate::mechanics::{Geometry, TestKind};
use crate::nonlinear_least_squares::{Parameter, Scale};
use pliant_core::rod::plastic_moment::{first_yield_moment, hardening_bending_moment};

/// Fewest points of the unloading branch.
pub const MIN_UNLOADING_POINTS: usize = 3;

/// The section's radii and the curve's peak: everything the law needs besides (E, σ_y, H).
#[derive(Clone, Copy, Debug)]
pub struct Bend {
    pub ri: f64,
    pub ro: f64,
    /// The largest curvature reached, where unloading starts \[1/m\].
    pub kappa_max: f64,
}

impl Bend {
    /// The moment at curvature `kappa` on loading (`unloading` false) or on unloading
    /// from `kappa_max` (module doc), for E, σ_y, H = `p`.
    pub fn moment(&self, p: [f64; 3], kappa: f64, unloading: bool) -> f64 {
        let [e, sy, h] = p;
        let mono = |k: f64| hardening_bending_moment(self.ri, self.ro, e, sy, h, k);
        if unloading {
            mono(self.kappa_max) - 2.0 * mono(0.5 * (self.kappa_max - kappa))
        } else {
            mono(kappa)
        }
    }

    /// The curvature left after unloading to M = 0 (Masing's branch), by bisection.
    pub fn springback_curvature(&self, p: [f64; 3]) -> f64 {
        let (mut lo, mut hi) = (-self.kappa_max, self.kappa_max);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.moment(p, mid, true) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// Fits a `plastic_bending` table.
pub fn fit(csv_name: &str, table: &Table, g: Geometry) -> Result<LawFit, CalibError> {
    let kind = TestKind::PlasticBending;
    let file = table.file.as_str();
    let c = law_fit::two_columns(kind, table, Quantity::Curvature, &[Quantity::Torque], true)?;
    let n = c.x.len();
    if n < 8 {
        return Err(CalibError::file(
            file,
            format!("too few points: {n} data rows, a plastic_bending fit needs at least 8 (loading past yield and unloading)"),
        ));
    }
    let peak = (0..n).fold(0, |best, i| if c.x[i] > c.x[best] { i } else { best });
    for i in 1..=peak {
        if c.x[i] < c.x[i - 1] {
            return Err(CalibError::line(
                file,
                c.lines[i],
                format!(
                    "not monotonic: the curvature falls from {:.6} to {:.6} 1/m before its largest value (line {}); the test loads once, then unloads",
                    c.x[i - 1], c.x[i], c.lines[peak]
                ),
            ));
        }
    }
    for i in peak + 1..n {
        if c.x[i] > c.x[i - 1] {
            return Err(CalibError::line(
                file,
                c.lines[i],
                format!(
                    "not monotonic: the curvature rises from {:.6} to {:.6} 1/m while unloading; a plastic_bending test unloads once (use cyclic_bending for loops)",
                    c.x[i - 1], c.x[i]
                ),
            ));
        }
    }
    if n - 1 - peak < MIN_UNLOADING_POINTS {
        return Err(CalibError::line(
            file,
            c.lines[peak],
            format!(
                "unloading missing: the curve ends at (or {} points after) its largest curvature {:.6} 1/m; record at least {MIN_UNLOADING_POINTS} points of the unloading branch (the springback check needs it)",
                n - 1 - peak,
                c.x[peak]
            ),
        ));
    }
    let bend = Bend {
        ri: 0.5 * g.d_inner,
        ro: 0.5 * g.d_outer,
        kappa_max: c.x[peak],
    };
    let i_sec = g.section().second_moment();
    let model = |p: &[f64]| -> Option<Vec<f64>> {
        let p = [p[0], p[1], p[2]];
        let m: Vec<f64> =
            c.x.iter()
                .enumerate()
                .map(|(i, k)| bend.moment(p, *k, i > peak))
                .collect();
        m.iter().all(|v| v.is_finite()).then_some(m)
    };
    // starts: E from the steepest secant on loading, σ_y from the peak moment
    let m_max = c.y[peak];
    let e0 = (0..=peak)
        .filter(|&i| c.x[i] >= 0.05 * bend.kappa_max && c.x[i] > 0.0)
        .map(|i| c.y[i] / (c.x[i] * i_sec))
        .fold(0.0_f64, f64::max);
    if !(e0 > 0.0 && m_max > 0.0) {
        return Err(CalibError::file(
            file,
            "the moment does not rise with the curvature: check the columns (moment_Nm, curvature_1_m) and their signs",
        ));
    }
    let z_plastic = 4.0 / 3.0 * (bend.ro.powi(3) - bend.ri.powi(3));
    let starts: Vec<Vec<Parameter>> = [0.5, 0.8, 1.0]
        .iter()
        .map(|f| {
            vec![
                Parameter {
                    name: "E",
                    start: e0,
                    scale: Scale::Log,
                },
                Parameter {
                    name: "sigma_y",
                    start: f * m_max / z_plastic,
                    scale: Scale::Log,
                },
                Parameter {
                    name: "H",
                    start: 0.01 * e0,
                    scale: Scale::Linear { non_negative: true },
                },
            ]
        })
        .collect();
    let fit = law_fit::best_of(&model, &c.y, &starts).ok_or_else(|| {
        CalibError::file(
            file,
            "the yield law could not be evaluated along this curve",
        )
    })?;
    let [e, sy, h] = [fit.values()[0], fit.values()[1], fit.values()[2]];
    let kappa_e = sy / (e * bend.ro);
    let (bic_elastic, ei_line) = law_fit::elastic_line_bic(&c.x, &c.y);
    let bic_plastic = law_fit::bic(fit.ssr, n as f64, 3, &c.y);
    if kappa_e >= bend.kappa_max || bic_plastic > bic_elastic - law_fit::BIC_MARGIN {
        return Err(CalibError::file(
            file,
            format!(
                "the curve never yields: an elastic line M = EI κ (EI = {:.4e} N·m²) explains it as well as the yield law (the largest curvature {:.5} 1/m gives a surface stress of at most E κ r_o = {:.4} MPa); σ_y is not identified — bend further past yield, or use three_point_bending for E",
                ei_line,
                bend.kappa_max,
                ei_line / i_sec * bend.kappa_max * bend.ro * 1e-6
            ),
        ));
    }
    law_fit::require_identified(
        &fit,
        file,
        "the curve does not pin the yield law down; it needs points well past first yield and the unloading branch",
    )?;
    let p = [e, sy, h];
    let fitted = model(&fit.values()).unwrap_or_default();
    let ei = e * i_sec;
    let predicted = bend.springback_curvature(p);
    let measured = (peak + 1..n).find(|&i| c.y[i] <= 0.0).map(|i| {
        let (k0, k1, m0, m1) = (c.x[i - 1], c.x[i], c.y[i - 1], c.y[i]);
        k0 + (k1 - k0) * m0 / (m0 - m1)
    });
    let mut checks = vec![
        format!(
            "first yield at κ_e = σ_y/(E r_o) = {:.5} 1/m, M_e = {:.5} N·m; the test reached κ_max = {:.5} 1/m ({:.2} κ_e), M = {:.5} N·m",
            kappa_e,
            first_yield_moment(bend.ri, bend.ro, sy),
            bend.kappa_max,
            bend.kappa_max / kappa_e,
            m_max
        ),
        format!(
            "springback: after full unloading the law leaves κ = {:.6} 1/m (the elastic estimate κ_max − M_max/EI = {:.6} 1/m)",
            predicted,
            bend.kappa_max - bend.moment(p, bend.kappa_max, false) / ei
        ),
    ];
    checks.push(match measured {
        Some(k) => format!(
            "springback measured: the curve crosses M = 0 at κ = {k:.6} 1/m ({:+.2} % of the predicted set)",
            100.0 * (k - predicted) / predicted.abs().max(f64::MIN_POSITIVE)
        ),
        None => format!(
            "springback measured: the unloading stops at M = {:.5} N·m, before M = 0",
            c.y[n - 1]
        ),
    });
    if c.flipped {
        checks.push("the curve was recorded with negative signs: magnitudes were fitted".into());
    }
    Ok(LawFit {
        kind,
        csv: csv_name.to_string(),
        geometry: g,
        fit,
        formula: format!(
            "M = M_mono(κ) on loading, M_mono(κ_max) − 2 M_mono((κ_max − κ)/2) on unloading (Masing); M_mono the elastic–plastic tube with linear hardening (pliant_core plastic_moment), r_i = {:.3} mm, r_o = {:.3} mm",
            bend.ri * 1e3,
            bend.ro * 1e3
        ),
        x_label: "curvature [1/m]".into(),
        y_label: "moment [N·m]".into(),
        x_scale: 1.0,
        y_scale: 1.0,
        checks,
        x: c.x,
        y: c.y,
        fitted,
        lines: c.lines,
    })
}
