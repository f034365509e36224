//! The `plastic_torsion` test: a metal tube (or solid rod) twisted past yield and
//! unloaded, torque T against the angle of twist over the grip distance L → the shear
//! modulus G, the shear yield stress τ_y and the kinematic hardening modulus H of the
//! simulator's elastic–plastic law ([`pliant_core::material::YieldLaw`], von Mises:
//! σ_y = √3 τ_y).
//!
//! The law fitted is the closed-form torque of the section the core implements
//! ([`pliant_core::rod::plastic_moment::hardening_torque`], T_mono(θ′) with the yielded
//! fibres' shear tangent G H/(3G + H)) at the twist rate θ′ = angle/L on loading, and on
//! unloading Masing's rule T_mono(θ′_max) − 2 T_mono((θ′_max − θ′)/2)
//! ([`crate::load_unload`]), fitted by [`crate::yield_law_fit`]. The unloading branch
//! gives the permanent twist, measured and predicted.

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit};
use crate::load_unload;
use crate::mechanics::{need_length, Geometry, TestKind};
use crate::yield_law_fit::{Shown, YieldCurve};
use pliant_core::rod::plastic_moment::{hardening_torque, plastic_torque};

/// Fits a `plastic_torsion` table.
pub fn fit(csv_name: &str, table: &Table, g: Geometry) -> Result<LawFit, CalibError> {
    let kind = TestKind::PlasticTorsion;
    let file = table.file.as_str();
    let length = need_length(kind, &g, file)?;
    let mut c = law_fit::two_columns(kind, table, Quantity::Angle, &[Quantity::Torque], true)?;
    c.x.iter_mut().for_each(|a| *a /= length);
    let peak = load_unload::peak(kind, file, &c.x, &c.lines, ("twist rate", "rad/m"))?;
    let (ri, ro) = (0.5 * g.d_inner, 0.5 * g.d_outer);
    let j = g.section().polar_moment();
    let rate_max = c.x[peak];
    let t_max = c.y[peak];
    let g0 = (0..=peak)
        .filter(|&i| c.x[i] >= 0.05 * rate_max && c.x[i] > 0.0)
        .map(|i| c.y[i] / (c.x[i] * j))
        .fold(0.0_f64, f64::max);
    if !(g0 > 0.0 && t_max > 0.0) {
        return Err(CalibError::file(
            file,
            "the torque does not rise with the twist: check the columns (torque_Nm, angle_deg) and their signs",
        ));
    }
    let sqrt3 = 3f64.sqrt();
    let curve = YieldCurve {
        file,
        x: &c.x,
        y: &c.y,
        peak,
        names: ["G", "tau_y", "H"],
        // T_p = (2π/3) τ_y (r_o³ − r_i³) at the peak torque
        start: [g0, t_max / plastic_torque(ri, ro, sqrt3), 0.01 * g0],
        mono: |[g, tau_y, h]: [f64; 3], rate: f64| {
            hardening_torque(ri, ro, g, sqrt3 * tau_y, h, rate)
        },
    };
    let f = curve.fit(
        |[g, tau_y, _]| tau_y / (g * ro),
        |gj_line| format!(
            "the curve never yields: an elastic line T = GJ θ′ (GJ = {:.4e} N·m²) explains it as well as the yield law (the largest twist rate {:.5} rad/m gives a surface shear stress of at most G θ′ r_o = {:.4} MPa); τ_y is not identified — twist further past yield, or use torsion for GJ",
            gj_line,
            rate_max,
            gj_line / j * rate_max * ro * 1e-6
        ),
        "the curve does not pin the yield law down; it needs points well past first yield and the unloading branch",
    )?;
    let v = f.fit.values();
    let p = [v[0], v[1], v[2]];
    let rate_e = p[1] / (p[0] * ro);
    let predicted = curve.set(p);
    let mut checks = vec![
        format!(
            "first yield at θ′_e = τ_y/(G r_o) = {:.5} rad/m; the test reached θ′_max = {:.5} rad/m ({:.2} θ′_e), T = {:.5} N·m; σ_y = √3 τ_y = {:.4} MPa",
            rate_e,
            rate_max,
            rate_max / rate_e,
            t_max,
            sqrt3 * p[1] * 1e-6
        ),
        format!(
            "springback: after full unloading the law leaves a twist of {:.6} rad/m × L = {:.4}° (the elastic estimate θ′_max − T_max/GJ = {:.6} rad/m)",
            predicted,
            (predicted * length).to_degrees(),
            rate_max - curve.value(p, rate_max, false) / (p[0] * j)
        ),
    ];
    checks.push(curve.measured_set_check(predicted, ("T", "N·m", "θ′", "rad/m")));
    let shown = Shown {
        formula: format!(
            "T = T_mono(θ′) on loading, T_mono(θ′_max) − 2 T_mono((θ′_max − θ′)/2) on unloading (Masing); T_mono the von Mises tube with linear kinematic hardening (pliant_core plastic_moment), r_i = {:.3} mm, r_o = {:.3} mm; θ′ = angle / L, L = {:.2} mm",
            ri * 1e3,
            ro * 1e3,
            length * 1e3
        ),
        x_label: "twist rate [rad/m]",
        y_label: "torque [N·m]",
        y_scale: 1.0,
    };
    Ok(f.finish((kind, csv_name, g), shown, checks, c))
}
