//! The `relaxation` test: force (or stress, or torque) against time at a held strain →
//! the Prony terms (gᵢ, τᵢ) of the simulator's relaxing law
//! ([`pliant_core::material::PronyTerm`]): y(t) = y₀ (1 − Σᵢ gᵢ (1 − e^{−t/τᵢ})), the
//! held strain's response being the modulus' relaxation E(t)/E₀ times a constant, so no
//! geometry is needed. Time counts from the moment the strain was applied (a loading ramp
//! much shorter than the first time recorded).
//!
//! **How many terms.** Each term count n = 1 … [`MAX_TERMS`] is fitted by nonlinear least
//! squares in (y₀, gᵢ, τᵢ), started from times on a log grid over the record; the count
//! kept is the smallest whose every parameter is identified (interval within a factor
//! [`crate::nonlinear_least_squares::MAX_INTERVAL_RATIO`]) and that no identified larger
//! count beats by more than [`crate::law_fit::BIC_MARGIN`] in Schwarz's criterion (BIC).
//! Why not non-negative least squares on a fixed log grid of times: it fits as well but
//! spreads each physical time over neighbouring grid terms whose weights are not
//! individually identified, so they have no meaningful interval; a short series whose
//! every term the data fix does, and BIC keeps it from fitting noise (Schwarz 1978; for
//! Prony series e.g. Park & Schapery 1999, *Int. J. Solids Struct.* 36).
//!
//! A test entry's `terms = N` forces N terms (1 … [`MAX_FORCED_TERMS`]); the fit is then
//! an error unless every one of them is identified.
//!
//! **The instantaneous modulus.** With the held strain ε given (`held_strain`), the fit's
//! first parameter is E₀ itself rather than y₀: y₀ = E₀ ε for a stress column, E₀ ε A
//! for a force over the section's area A; E₀ then joins the material as a measured
//! tensile modulus. A torque column needs a twist, not a strain, and takes no held strain.
//!
//! A curve that does not relax (no term identified) is an error, never a series.

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::law_fit::{self, LawFit, LawOptions};
use crate::mechanics::{Geometry, TestKind};
use crate::nonlinear_least_squares::{NonlinearFit, Parameter, Scale};

/// Most Prony terms tried (the scene takes up to 8; a test over a few decades of time
/// rarely identifies more than 3).
pub const MAX_TERMS: usize = 4;

/// Most Prony terms a test entry may ask for (`terms`): the scene's limit.
pub const MAX_FORCED_TERMS: usize = 8;

/// y(t) of the series `p` = (y₀, g₁, τ₁, g₂, τ₂, …), or `None` when Σ g ≥ 1.
pub fn series(p: &[f64], t: f64) -> f64 {
    let mut ratio = 1.0;
    for term in p[1..].chunks_exact(2) {
        ratio -= term[0] * (1.0 - (-t / term[1]).exp());
    }
    p[0] * ratio
}

/// Fits `terms` terms; the first parameter is y₀ × `y0_per_first` (named `first`).
fn fit_terms(
    terms: usize,
    t: &[f64],
    y: &[f64],
    (first, y0_per_first): (&'static str, f64),
) -> Option<NonlinearFit> {
    let model = |p: &[f64]| -> Option<Vec<f64>> {
        let sum: f64 = p[1..].chunks_exact(2).map(|c| c[0]).sum();
        if sum >= 1.0 {
            return None;
        }
        let mut q = p.to_vec();
        q[0] *= y0_per_first;
        Some(t.iter().map(|t| series(&q, *t)).collect())
    };
    let t_max = t.last().copied().unwrap_or(1.0);
    let t_min = t
        .iter()
        .copied()
        .find(|t| *t > 0.0)
        .unwrap_or(t_max)
        .max(t_max * 1e-9);
    let y0 = y[0];
    let drop = (1.0 - y[y.len() - 1] / y0).clamp(0.01, 0.9);
    const NAMES: [(&str, &str); MAX_FORCED_TERMS] = [
        ("g1", "tau1"),
        ("g2", "tau2"),
        ("g3", "tau3"),
        ("g4", "tau4"),
        ("g5", "tau5"),
        ("g6", "tau6"),
        ("g7", "tau7"),
        ("g8", "tau8"),
    ];
    let starts: Vec<Vec<Parameter>> = [0.5, 0.25, 0.75]
        .iter()
        .map(|offset| {
            let mut p = vec![Parameter {
                name: first,
                start: y0 / y0_per_first,
                scale: Scale::Log,
            }];
            for (i, (g, tau)) in NAMES.iter().take(terms).enumerate() {
                let f = (i as f64 + offset) / terms as f64;
                p.push(Parameter {
                    name: g,
                    start: drop / terms as f64,
                    scale: Scale::Log,
                });
                p.push(Parameter {
                    name: tau,
                    start: t_min * (t_max / t_min).powf(f),
                    scale: Scale::Log,
                });
            }
            p
        })
        .collect();
    law_fit::best_of(&model, y, &starts)
}

/// Fits a `relaxation` table.
pub fn fit(
    csv_name: &str,
    table: &Table,
    g: Geometry,
    options: LawOptions,
) -> Result<LawFit, CalibError> {
    let kind = TestKind::Relaxation;
    let file = table.file.as_str();
    let c = law_fit::two_columns(
        kind,
        table,
        Quantity::Time,
        &[Quantity::Force, Quantity::Stress, Quantity::Torque],
        false,
    )?;
    let n = c.x.len();
    if n < 6 {
        return Err(CalibError::file(
            file,
            format!("too few points: {n} data rows, a relaxation fit needs at least 6"),
        ));
    }
    if c.x[0] < 0.0 {
        return Err(CalibError::line(
            file,
            c.lines[0],
            format!(
                "time {} s is negative: time counts from the moment the strain was applied",
                c.x[0]
            ),
        ));
    }
    for i in 1..n {
        if c.x[i] <= c.x[i - 1] {
            return Err(CalibError::line(
                file,
                c.lines[i],
                format!(
                    "not monotonic: time goes from {} s to {} s; it must increase row by row",
                    c.x[i - 1],
                    c.x[i]
                ),
            ));
        }
    }
    let (t, mut y) = (c.x, c.y);
    let flipped = y.iter().sum::<f64>() < 0.0;
    if flipped {
        y.iter_mut().for_each(|v| *v = -*v);
    }
    if let Some(i) = y.iter().position(|v| *v <= 0.0) {
        return Err(CalibError::line(
            file,
            c.lines[i],
            format!(
                "the held force changes sign ({}): a relaxation test holds one strain",
                y[i]
            ),
        ));
    }
    let force = table.column(Quantity::Force).is_some();
    let stress = !force && table.column(Quantity::Stress).is_some();
    let first = match options.held_strain {
        None => ("y0", 1.0),
        Some(strain) if force => ("E0", strain * g.section().area()),
        Some(strain) if stress => ("E0", strain),
        Some(_) => {
            return Err(CalibError::file(
                file,
                "held_strain turns a held force or stress into E0; this curve holds a torque (give a force_N or stress_MPa column, or leave held_strain out)",
            ))
        }
    };
    let nf = n as f64;
    let (terms, fit) = if let Some(terms) = options.terms {
        if n <= 2 * terms + 3 {
            return Err(CalibError::file(
                file,
                format!(
                    "too few points for terms = {terms}: {n} data rows, {} needed",
                    2 * terms + 4
                ),
            ));
        }
        let f = fit_terms(terms, &t, &y, first).ok_or_else(|| {
            CalibError::file(
                file,
                format!("{terms} Prony term(s) could not be fitted along this curve"),
            )
        })?;
        law_fit::require_identified(
            &f,
            file,
            &format!("the curve does not identify {terms} Prony term(s); ask for fewer (or leave terms out: the count is then chosen by BIC)"),
        )?;
        (terms, f)
    } else {
        let mut chosen: Option<(usize, NonlinearFit, f64)> = None;
        let mut first_failure = None;
        for terms in 1..=MAX_TERMS {
            if n <= 2 * terms + 3 {
                break;
            }
            let Some(f) = fit_terms(terms, &t, &y, first) else {
                continue;
            };
            let identified = f.estimates.iter().all(|e| e.identified);
            if !identified {
                if first_failure.is_none() {
                    first_failure = Some(f);
                }
                continue;
            }
            let b = law_fit::bic(f.ssr, nf, 2 * terms + 1, &y);
            let better = chosen
                .as_ref()
                .is_none_or(|(_, _, best)| b < best - law_fit::BIC_MARGIN);
            if better {
                chosen = Some((terms, f, b));
            }
        }
        let Some((terms, fit, _)) = chosen else {
            let why = "the curve does not relax within its scatter (a constant force is an elastic material), or the record is too short to resolve a relaxation time";
            return match first_failure {
                Some(f) => {
                    law_fit::require_identified(&f, file, why).and(Err(CalibError::file(file, why)))
                }
                None => Err(CalibError::file(file, why)),
            };
        };
        (terms, fit)
    };
    let mut values = fit.values();
    values[0] *= first.1;
    let fitted: Vec<f64> = t.iter().map(|t| series(&values, *t)).collect();
    let long_term: f64 = 1.0 - values[1..].chunks_exact(2).map(|c| c[0]).sum::<f64>();
    let how = if options.terms.is_some() {
        "asked for (terms)".to_string()
    } else {
        format!(
            "chosen by BIC (smallest count whose every parameter is identified and that no larger identified count beats by {})",
            law_fit::BIC_MARGIN
        )
    };
    let mut checks = vec![format!(
        "{terms} Prony term(s) {how}; long-term ratio E∞/E₀ = {long_term:.5}"
    )];
    if let Some(strain) = options.held_strain {
        checks.push(format!(
            "instantaneous modulus E0 = {:.4} MPa from the held strain {strain} ({})",
            values[0] / first.1 * 1e-6,
            if force {
                "force over the section's area"
            } else {
                "stress"
            }
        ));
    }
    if flipped {
        checks.push("the curve was recorded with negative signs: magnitudes were fitted".into());
    }
    let (y_label, y_scale) = if force {
        ("force [N]", 1.0)
    } else if stress {
        ("stress [MPa]", 1e-6)
    } else {
        ("torque [N·m]", 1.0)
    };
    Ok(LawFit {
        kind,
        csv: csv_name.to_string(),
        geometry: g,
        fit,
        formula: format!(
            "y(t) = y0 (1 − Σ g_i (1 − exp(−t/τ_i))): the held strain's force relaxes as the modulus E(t)/E0 (Prony series){}",
            match (options.held_strain, force) {
                (Some(e), true) => format!("; y0 = E0 ε A, ε = {e}"),
                (Some(e), false) => format!("; y0 = E0 ε, ε = {e}"),
                (None, _) => String::new(),
            }
        ),
        x_label: "time [s]".into(),
        y_label: y_label.into(),
        x_scale: 1.0,
        y_scale,
        checks,
        x: t,
        y,
        fitted,
        lines: c.lines,
    })
}
