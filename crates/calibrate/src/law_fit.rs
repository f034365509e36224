//! One inelastic law fitted to a whole test curve (bending or torsion past yield,
//! relaxation, cyclic bending or torsion): the shared result, reading the two columns a law needs, and the
//! checks every law fit makes (enough points, identified parameters). The laws
//! themselves: [`crate::yield_fit`], [`crate::plastic_torsion_fit`],
//! [`crate::plastic_beam_fit`], [`crate::relaxation_fit`], [`crate::dahl_fit`].

use crate::csv_input::{Quantity, Table};
use crate::error::CalibError;
use crate::mechanics::{Geometry, TestKind};
use crate::nonlinear_least_squares::{Estimate, NonlinearFit};
use serde::Serialize;

/// Most data rows a law fit takes (each iteration evaluates the law along the whole
/// curve a few times per parameter): thin a longer record.
pub const MAX_LAW_POINTS: usize = 20_000;

/// ΔBIC above which a richer model is preferred ("very strong" evidence, Kass & Raftery
/// 1995, *J. Am. Stat. Assoc.* 90).
pub const BIC_MARGIN: f64 = 10.0;

/// A fitted law.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LawFit {
    pub kind: TestKind,
    /// The CSV file, as named in the calibration file.
    pub csv: String,
    pub geometry: Geometry,
    /// The parameters (SI) with their intervals, and the fit's statistics.
    pub fit: NonlinearFit,
    /// The law fitted, for the report.
    pub formula: String,
    /// Axis labels with display units, and factors from SI to them.
    pub x_label: String,
    pub y_label: String,
    pub x_scale: f64,
    pub y_scale: f64,
    /// Checks and remarks for the report (e.g. the springback measured and predicted).
    pub checks: Vec<String>,
    /// The curve (SI), the law's values at its points, and each point's CSV line.
    #[serde(skip)]
    pub x: Vec<f64>,
    #[serde(skip)]
    pub y: Vec<f64>,
    #[serde(skip)]
    pub fitted: Vec<f64>,
    #[serde(skip)]
    pub lines: Vec<usize>,
}

impl LawFit {
    /// The estimate named `name`.
    pub fn estimate(&self, name: &str) -> Option<&Estimate> {
        self.fit.estimates.iter().find(|e| e.name == name)
    }
}

/// The curve of a law test: two columns in SI with the CSV line of each row, signs
/// flipped when `x` was recorded negative.
pub struct TwoColumns {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub lines: Vec<usize>,
    pub flipped: bool,
}

/// Reads columns `xq` and `yq` (or the first of `y_alternatives` present) of a `kind`
/// test, checks their size, and flips the signs of a curve recorded negative if `flip`.
pub fn two_columns(
    kind: TestKind,
    table: &Table,
    xq: Quantity,
    y_alternatives: &[Quantity],
    flip: bool,
) -> Result<TwoColumns, CalibError> {
    let file = table.file.as_str();
    let x = table.column(xq).map(|(_, v)| v.to_vec());
    let y = y_alternatives
        .iter()
        .find_map(|q| table.column(*q).map(|(_, v)| v.to_vec()));
    let (Some(mut x), Some(mut y)) = (x, y) else {
        let wanted: Vec<&str> = std::iter::once(xq)
            .chain(y_alternatives.iter().copied())
            .map(|q| q.example())
            .collect();
        let have: Vec<&str> = table.columns.iter().map(|c| c.header.as_str()).collect();
        return Err(CalibError::file(
            file,
            format!(
                "a {} test needs the columns {} and {}; found {}",
                kind.name(),
                wanted[0],
                wanted[1..].join(" or "),
                if have.is_empty() {
                    "none".to_string()
                } else {
                    have.join(", ")
                }
            ),
        ));
    };
    if x.len() > MAX_LAW_POINTS {
        return Err(CalibError::file(
            file,
            format!(
                "{} data rows: a {} fit takes at most {MAX_LAW_POINTS}; thin the record",
                x.len(),
                kind.name()
            ),
        ));
    }
    let flipped = flip && x.iter().sum::<f64>() < 0.0;
    if flipped {
        x.iter_mut().for_each(|v| *v = -*v);
        y.iter_mut().for_each(|v| *v = -*v);
    }
    Ok(TwoColumns {
        x,
        y,
        lines: table.lines.clone(),
        flipped,
    })
}

/// An error unless every parameter of `fit` is identified; `why` says what the data
/// lack when one is not.
pub fn require_identified(fit: &NonlinearFit, file: &str, why: &str) -> Result<(), CalibError> {
    match fit.estimates.iter().find(|e| !e.identified) {
        None => Ok(()),
        Some(e) => Err(CalibError::file(
            file,
            format!(
                "{} is not identified by this curve (fitted {:.4e}, 95 % interval {:.3e} – {:.3e}): {why}",
                e.name, e.value, e.ci95[0], e.ci95[1]
            ),
        )),
    }
}

/// The BIC of the elastic line y = k x through the origin fitted to the curve, and its
/// slope (the alternative a law must beat).
pub fn elastic_line_bic(x: &[f64], y: &[f64]) -> (f64, f64) {
    let sxx: f64 = x.iter().map(|x| x * x).sum();
    let sxy: f64 = x.iter().zip(y).map(|(x, y)| x * y).sum();
    let k = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    let ssr: f64 = x.iter().zip(y).map(|(x, y)| (y - k * x).powi(2)).sum();
    let n = x.len() as f64;
    (bic(ssr, n, 1, y), k)
}

/// Schwarz's criterion n ln(SSR/n) + p ln n with SSR floored at the rounding level of
/// `y` (relative 1e-10 per point), so that exact curves do not favour extra parameters
/// that only fit rounding.
pub fn bic(ssr: f64, n: f64, parameters: usize, y: &[f64]) -> f64 {
    let scale = y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let floor = n * (1e-10 * scale).powi(2);
    n * (ssr.max(floor).max(f64::MIN_POSITIVE) / n).ln() + parameters as f64 * n.ln()
}

/// Fits a law by the parameters, trying each start and keeping the best.
pub fn best_of<F>(
    model: &F,
    y: &[f64],
    starts: &[Vec<crate::nonlinear_least_squares::Parameter>],
) -> Option<NonlinearFit>
where
    F: Fn(&[f64]) -> Option<Vec<f64>>,
{
    starts
        .iter()
        .filter_map(|p| crate::nonlinear_least_squares::fit(model, y, p))
        .min_by(|a, b| a.ssr.total_cmp(&b.ssr))
}

/// A test's options that some laws take (from its `[[tests]]` entry).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LawOptions {
    /// Relaxation: the number of Prony terms (else chosen by BIC).
    pub terms: Option<usize>,
    /// Relaxation: the held strain, for the instantaneous modulus.
    pub held_strain: Option<f64>,
}

/// Fits the law of a `kind` test to its table.
pub fn fit_law(
    kind: TestKind,
    csv_name: &str,
    table: &Table,
    g: Geometry,
) -> Result<LawFit, CalibError> {
    fit_law_with(kind, csv_name, table, g, LawOptions::default())
}

/// [`fit_law`] with a test's options.
pub fn fit_law_with(
    kind: TestKind,
    csv_name: &str,
    table: &Table,
    g: Geometry,
    options: LawOptions,
) -> Result<LawFit, CalibError> {
    match kind {
        TestKind::PlasticBending => crate::yield_fit::fit(csv_name, table, g),
        TestKind::PlasticTorsion => crate::plastic_torsion_fit::fit(csv_name, table, g),
        TestKind::PlasticCantilever | TestKind::PlasticThreePointBending => {
            crate::plastic_beam_fit::fit(kind, csv_name, table, g)
        }
        TestKind::Relaxation => crate::relaxation_fit::fit(csv_name, table, g, options),
        TestKind::CyclicBending | TestKind::CyclicTorsion => {
            crate::dahl_fit::fit(kind, csv_name, table, g)
        }
        _ => Err(CalibError::file(
            &table.file,
            format!("a {} test has a linear range, not a law", kind.name()),
        )),
    }
}
