//! The `cyclic_bending` and `cyclic_torsion` tests: moment against curvature (or torque
//! against twist) cycled back and forth → the elastic stiffness K (EI or GJ) and Dahl's
//! pair (M_s, κ_s) of the simulator's hysteresis ([`pliant_core::material::DahlLaw`]).
//!
//! The law fitted: M = K κ + z, the friction moment z following Dahl's law
//! dz/dκ = (M_s/κ_s)(1 − s z/M_s), s = sgn(κ̇) (Dahl 1976, *AIAA Journal* 14(12)), in
//! its closed form between consecutive points, where κ moves one way:
//!
//! z(κ) = s M_s − (s M_s − zⁿ) e^{−s (κ − κⁿ)/κ_s},
//!
//! the form the element integrates by (docs/physics.md, "Materials with a history"). The
//! record starts from the virgin, unloaded specimen (z = 0 at the first row). The
//! twist's curvature is the angle over the grip distance.
//!
//! A curve without a loop (M_s or κ_s not identified, or the elastic line as good: ΔBIC
//! below [`crate::law_fit::BIC_MARGIN`]) is an error, never a friction law.

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit};
use crate::mechanics::{need_length, Geometry, TestKind};
use crate::nonlinear_least_squares::{Parameter, Scale};

/// The moments K κᵢ + zᵢ along the curvatures `kappa` for `p` = (K, M_s, κ_s), from a
/// virgin start (module doc).
pub fn moments(p: &[f64], kappa: &[f64]) -> Vec<f64> {
    let (k, m_s, kappa_s) = (p[0], p[1], p[2]);
    let mut z = 0.0;
    let mut out = Vec::with_capacity(kappa.len());
    for (i, x) in kappa.iter().enumerate() {
        if i > 0 {
            let delta = x - kappa[i - 1];
            if delta != 0.0 {
                let s = delta.signum();
                let target = s * m_s;
                z = target - (target - z) * (-s * delta / kappa_s).exp();
            }
        }
        out.push(k * x + z);
    }
    out
}

/// Fits a `cyclic_bending` or `cyclic_torsion` table.
pub fn fit(
    kind: TestKind,
    csv_name: &str,
    table: &Table,
    g: Geometry,
) -> Result<LawFit, CalibError> {
    let file = table.file.as_str();
    let torsion = kind == TestKind::CyclicTorsion;
    let mut c = if torsion {
        law_fit::two_columns(kind, table, Quantity::Angle, &[Quantity::Torque], false)?
    } else {
        law_fit::two_columns(kind, table, Quantity::Curvature, &[Quantity::Torque], false)?
    };
    if torsion {
        let l = need_length(kind, &g, file)?;
        c.x.iter_mut().for_each(|a| *a /= l);
    }
    let n = c.x.len();
    if n < 8 {
        return Err(CalibError::file(
            file,
            format!(
                "too few points: {n} data rows, a {} fit needs at least 8",
                kind.name()
            ),
        ));
    }
    let mut reversals = 0;
    let mut last = 0.0;
    for i in 1..n {
        let d = (c.x[i] - c.x[i - 1]).signum();
        if c.x[i] != c.x[i - 1] {
            if last != 0.0 && d != last {
                reversals += 1;
            }
            last = d;
        }
    }
    if reversals == 0 {
        return Err(CalibError::file(
            file,
            format!(
                "no reversal: the {} moves one way only; a {} test bends back and forth (load, unload, reverse) to trace a loop",
                if torsion { "twist" } else { "curvature" },
                kind.name()
            ),
        ));
    }
    let (bic_elastic, k_line) = law_fit::elastic_line_bic(&c.x, &c.y);
    let range = c.x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let width =
        c.x.iter()
            .zip(&c.y)
            .fold(0.0_f64, |m, (x, y)| m.max((y - k_line * x).abs()));
    if !(k_line > 0.0 && range > 0.0 && width > 0.0) {
        return Err(CalibError::file(
            file,
            "the moment does not rise with the curvature: check the columns and their signs",
        ));
    }
    let (k_name, m_name, s_name) = if torsion {
        ("GJ", "M_s_torsion", "kappa_s_torsion")
    } else {
        ("EI", "M_s", "kappa_s")
    };
    let starts: Vec<Vec<Parameter>> = [0.02, 0.1, 0.3]
        .iter()
        .map(|f| {
            vec![
                Parameter {
                    name: k_name,
                    start: k_line,
                    scale: Scale::Log,
                },
                Parameter {
                    name: m_name,
                    start: width,
                    scale: Scale::Log,
                },
                Parameter {
                    name: s_name,
                    start: f * range,
                    scale: Scale::Log,
                },
            ]
        })
        .collect();
    let x = &c.x;
    let model = |p: &[f64]| -> Option<Vec<f64>> {
        let m = moments(p, x);
        m.iter().all(|v| v.is_finite()).then_some(m)
    };
    let fit = law_fit::best_of(&model, &c.y, &starts).ok_or_else(|| {
        CalibError::file(file, "Dahl's law could not be evaluated along this curve")
    })?;
    let why = "the curve shows no hysteresis loop within its scatter (it retraces itself: an elastic specimen), or the loop is too narrow or too wide to separate friction from stiffness";
    if law_fit::bic(fit.ssr, n as f64, 3, &c.y) > bic_elastic - law_fit::BIC_MARGIN {
        return Err(CalibError::file(
            file,
            format!("{m_name} is not identified: {why} (the elastic line K = {k_line:.4e} N·m² explains it as well)"),
        ));
    }
    law_fit::require_identified(&fit, file, why)?;
    let v = fit.values();
    let fitted = moments(&v, &c.x);
    let unit = if torsion { "twist rate" } else { "curvature" };
    let checks = vec![format!(
            "{reversals} reversal(s); loop height 2 M_s = {:.5} N·m, friction saturates over a few κ_s = {:.5} 1/m of {unit} after each reversal (initial friction stiffness M_s/κ_s = {:.5} N·m²)",
            2.0 * v[1],
            v[2],
            v[1] / v[2]
        )];
    Ok(LawFit {
        kind,
        csv: csv_name.to_string(),
        geometry: g,
        fit,
        formula: format!(
            "M = {k_name} κ + z, dz/dκ = (M_s/κ_s)(1 − sgn(κ̇) z/M_s) (Dahl), z = 0 at the first row{}",
            if torsion {
                format!("; twist rate = angle / L, L = {:.2} mm", g.length.unwrap_or(0.0) * 1e3)
            } else {
                String::new()
            }
        ),
        x_label: if torsion { "twist rate [1/m]" } else { "curvature [1/m]" }.into(),
        y_label: if torsion { "torque [N·m]" } else { "moment [N·m]" }.into(),
        x_scale: 1.0,
        y_scale: 1.0,
        checks,
        x: c.x,
        y: c.y,
        fitted,
        lines: c.lines,
    })
}
