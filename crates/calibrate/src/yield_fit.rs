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
//! A curve that never yields is an error, never a yield stress (the shared fit:
//! [`crate::yield_law_fit`]).

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit};
use crate::load_unload;
use crate::mechanics::{Geometry, TestKind};
use crate::yield_law_fit::{Shown, YieldCurve};
use pliant_core::rod::plastic_moment::{first_yield_moment, hardening_bending_moment};

/// Fits a `plastic_bending` table.
pub fn fit(csv_name: &str, table: &Table, g: Geometry) -> Result<LawFit, CalibError> {
    let kind = TestKind::PlasticBending;
    let file = table.file.as_str();
    let c = law_fit::two_columns(kind, table, Quantity::Curvature, &[Quantity::Torque], true)?;
    let peak = load_unload::peak(kind, file, &c.x, &c.lines, ("curvature", "1/m"))?;
    let (ri, ro) = (0.5 * g.d_inner, 0.5 * g.d_outer);
    let kappa_max = c.x[peak];
    let i_sec = g.section().second_moment();
    // starts: E from the steepest secant on loading, σ_y from the peak moment
    let m_max = c.y[peak];
    let e0 = (0..=peak)
        .filter(|&i| c.x[i] >= 0.05 * kappa_max && c.x[i] > 0.0)
        .map(|i| c.y[i] / (c.x[i] * i_sec))
        .fold(0.0_f64, f64::max);
    if !(e0 > 0.0 && m_max > 0.0) {
        return Err(CalibError::file(
            file,
            "the moment does not rise with the curvature: check the columns (moment_Nm, curvature_1_m) and their signs",
        ));
    }
    let z_plastic = 4.0 / 3.0 * (ro.powi(3) - ri.powi(3));
    let curve = YieldCurve {
        file,
        x: &c.x,
        y: &c.y,
        peak,
        names: ["E", "sigma_y", "H"],
        start: [e0, m_max / z_plastic, 0.01 * e0],
        mono: |[e, sy, h]: [f64; 3], k: f64| hardening_bending_moment(ri, ro, e, sy, h, k),
    };
    let f = curve.fit(
        |[e, sy, _]| sy / (e * ro),
        |ei_line| format!(
            "the curve never yields: an elastic line M = EI κ (EI = {:.4e} N·m²) explains it as well as the yield law (the largest curvature {:.5} 1/m gives a surface stress of at most E κ r_o = {:.4} MPa); σ_y is not identified — bend further past yield, or use three_point_bending for E",
            ei_line,
            kappa_max,
            ei_line / i_sec * kappa_max * ro * 1e-6
        ),
        "the curve does not pin the yield law down; it needs points well past first yield and the unloading branch",
    )?;
    let v = f.fit.values();
    let p = [v[0], v[1], v[2]];
    let [e, sy, _] = p;
    let kappa_e = sy / (e * ro);
    let ei = e * i_sec;
    let predicted = curve.set(p);
    let mut checks = vec![
        format!(
            "first yield at κ_e = σ_y/(E r_o) = {:.5} 1/m, M_e = {:.5} N·m; the test reached κ_max = {:.5} 1/m ({:.2} κ_e), M = {:.5} N·m",
            kappa_e,
            first_yield_moment(ri, ro, sy),
            kappa_max,
            kappa_max / kappa_e,
            m_max
        ),
        format!(
            "springback: after full unloading the law leaves κ = {:.6} 1/m (the elastic estimate κ_max − M_max/EI = {:.6} 1/m)",
            predicted,
            kappa_max - curve.value(p, kappa_max, false) / ei
        ),
    ];
    checks.push(curve.measured_set_check(predicted, ("M", "N·m", "κ", "1/m")));
    let shown = Shown {
        formula: format!(
            "M = M_mono(κ) on loading, M_mono(κ_max) − 2 M_mono((κ_max − κ)/2) on unloading (Masing); M_mono the elastic–plastic tube with linear hardening (pliant_core plastic_moment), r_i = {:.3} mm, r_o = {:.3} mm",
            ri * 1e3,
            ro * 1e3
        ),
        x_label: "curvature [1/m]",
        y_label: "moment [N·m]",
        y_scale: 1.0,
    };
    Ok(f.finish((kind, csv_name, g), shown, checks, c))
}
