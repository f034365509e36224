//! The `plastic_cantilever` and `plastic_three_point_bending` tests: a metal tube (or
//! solid rod) bent past yield by a force and unloaded, force F against the deflection δ
//! at the force — what a test bench measures — → Young's modulus E, the yield stress σ_y
//! and the kinematic hardening modulus H of the simulator's elastic–plastic law
//! ([`pliant_core::material::YieldLaw`]).
//!
//! The law fitted is the deflection δ_mono(F) of the beam over the section's closed-form
//! moment–curvature law ([`crate::beam_deflection`]) on loading, and on unloading
//! Masing's rule δ_mono(F_max) − 2 δ_mono((F_max − F)/2) ([`crate::load_unload`]),
//! fitted by [`crate::yield_law_fit`] with the force as the controlled quantity and the
//! deflection as the response. Small deflections are assumed (the moment's lever is the
//! undeformed length): keep the deflection a few percent of L. The unloading branch gives
//! the permanent deflection, measured and predicted.

use crate::beam_deflection::{Beam, Support};
use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit};
use crate::load_unload;
use crate::mechanics::{need_length, Geometry, TestKind};
use crate::yield_law_fit::{Shown, YieldCurve};

/// Fits a `plastic_cantilever` or `plastic_three_point_bending` table.
pub fn fit(
    kind: TestKind,
    csv_name: &str,
    table: &Table,
    g: Geometry,
) -> Result<LawFit, CalibError> {
    let file = table.file.as_str();
    let support = match kind {
        TestKind::PlasticCantilever => Support::Cantilever,
        _ => Support::ThreePoint,
    };
    let length = need_length(kind, &g, file)?;
    let c = law_fit::two_columns(
        kind,
        table,
        Quantity::Force,
        &[Quantity::Displacement],
        true,
    )?;
    let peak = load_unload::peak(kind, file, &c.x, &c.lines, ("force", "N"))?;
    let beam = Beam {
        support,
        ri: 0.5 * g.d_inner,
        ro: 0.5 * g.d_outer,
        length,
    };
    let (lever, _) = beam.lever_and_factor();
    let (f_max, d_max) = (c.x[peak], c.y[peak]);
    // starts: E from the stiffest secant on loading, σ_y from the peak moment
    let e0 = (0..=peak)
        .filter(|&i| c.x[i] >= 0.05 * f_max && c.y[i] > 0.0)
        .map(|i| c.x[i] * beam.elastic_compliance(1.0) / c.y[i])
        .fold(0.0_f64, f64::max);
    if !(e0 > 0.0 && f_max > 0.0 && d_max > 0.0) {
        return Err(CalibError::file(
            file,
            "the deflection does not rise with the force: check the columns (force_N, deflection_mm) and their signs",
        ));
    }
    let z_plastic = 4.0 / 3.0 * (beam.ro.powi(3) - beam.ri.powi(3));
    let curve = YieldCurve {
        file,
        x: &c.x,
        y: &c.y,
        peak,
        names: ["E", "sigma_y", "H"],
        start: [e0, f_max * lever / z_plastic, 0.01 * e0],
        mono: |p: [f64; 3], force: f64| beam.deflection(p, force),
    };
    let i_sec = g.section().second_moment();
    let f = curve.fit(
        // first yield where F ℓ = M_e = σ_y I / r_o
        |[_, sy, _]| sy * i_sec / (beam.ro * lever),
        |k| format!(
            "the curve never yields: an elastic line δ = F/k (k = {:.4e} N/m, E = {:.4} MPa) explains it as well as the yield law; σ_y is not identified — bend further past yield (the force past F ℓ = σ_y I/r_o), or use {} for E",
            1.0 / k,
            beam.elastic_compliance(1.0) / k * 1e-6,
            if support == Support::Cantilever { "cantilever" } else { "three_point_bending" }
        ),
        "the curve does not pin the yield law down; it needs points well past first yield and the unloading branch",
    )?;
    let v = f.fit.values();
    let p = [v[0], v[1], v[2]];
    let f_e = p[1] * i_sec / (beam.ro * lever);
    let set = curve.value(p, 0.0, true);
    let mut checks = vec![
        format!(
            "first yield at F_e = σ_y I/(r_o ℓ) = {:.5} N (ℓ = {:.2} mm, the lever of the largest moment); the test reached F_max = {:.5} N ({:.2} F_e), δ = {:.4} mm ({:.2} % of L: small-deflection theory assumed)",
            f_e,
            lever * 1e3,
            f_max,
            f_max / f_e,
            d_max * 1e3,
            100.0 * d_max / length
        ),
        format!(
            "springback: after full unloading the law leaves a deflection of {:.5} mm (the elastic estimate δ_max − F_max/k = {:.5} mm)",
            set * 1e3,
            (d_max - f_max * beam.elastic_compliance(p[0])) * 1e3
        ),
    ];
    let last = c.y.len() - 1;
    checks.push(if c.x[last] <= 0.02 * f_max {
        format!(
            "springback measured: at F = {:.4} N the deflection is {:.5} mm ({:+.2} % of the predicted set)",
            c.x[last],
            c.y[last] * 1e3,
            100.0 * (c.y[last] - set) / set.abs().max(f64::MIN_POSITIVE)
        )
    } else {
        format!(
            "springback measured: the unloading stops at F = {:.5} N, before F = 0",
            c.x[last]
        )
    });
    if d_max > 0.05 * length {
        checks.push(format!(
            "warning: the largest deflection is {:.1} % of L; the small-deflection theory fitted loses accuracy beyond a few percent",
            100.0 * d_max / length
        ));
    }
    let shown = Shown {
        formula: format!(
            "δ = ({c}/F²) ∫ κ(M) M dM over 0 … F ℓ on loading (M(κ) the elastic–plastic tube with linear hardening, pliant_core plastic_moment; ℓ = {:.2} mm), δ_mono(F_max) − 2 δ_mono((F_max − F)/2) on unloading (Masing); r_i = {:.3} mm, r_o = {:.3} mm",
            lever * 1e3,
            beam.ri * 1e3,
            beam.ro * 1e3,
            c = beam.lever_and_factor().1
        ),
        x_label: "force [N]",
        y_label: "deflection [mm]",
        y_scale: 1e3,
    };
    Ok(f.finish((kind, csv_name, g), shown, checks, c))
}
