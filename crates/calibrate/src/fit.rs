//! One test's fit: the curve, its linear range, the line and the stiffness with its
//! confidence interval.

use crate::csv_input::Table;
use crate::error::CalibError;
use crate::least_squares::{fit_line, LineFit};
use crate::linear_range::{self, RangeError};
use crate::mechanics::{self, Curve, Geometry, Property, TestKind};
use serde::Serialize;

/// The linear range used, as data rows, CSV lines and physical values.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RangeReport {
    /// First and last data row used (0-based, inclusive).
    pub first_row: usize,
    pub last_row: usize,
    /// Their lines in the CSV (1-based).
    pub first_line: usize,
    pub last_line: usize,
    /// Number of points in the range, and in the curve.
    pub points: usize,
    pub total_points: usize,
    /// x at the range's ends, in the plot's unit (`x_label`).
    pub x_from: f64,
    pub x_to: f64,
    /// y at the range's ends, in the plot's unit (`y_label`).
    pub y_from: f64,
    pub y_to: f64,
    pub x_label: String,
    pub y_label: String,
    /// Estimated measurement scatter in y, in the plot's unit.
    pub noise_std: f64,
}

/// One fitted test.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TestFit {
    pub kind: TestKind,
    /// The CSV file, as named in the calibration file.
    pub csv: String,
    pub geometry: Geometry,
    pub property: Property,
    /// Symbol and display unit of the stiffness (e.g. "E_t", "MPa").
    pub symbol: String,
    pub unit: String,
    /// The stiffness, in SI (Pa or N·m²).
    pub value: f64,
    /// Its standard error and 95 % confidence interval, SI.
    pub std_error: f64,
    pub ci95: [f64; 2],
    /// The same in the display unit.
    pub value_display: f64,
    pub ci95_display: [f64; 2],
    /// The line through the linear range (curve units, SI) and its statistics.
    pub line: LineFit,
    pub range: RangeReport,
    /// The formula used.
    pub formula: String,
    /// Signs flipped (the curve was recorded negative).
    pub flipped: bool,
    /// The curve that was fitted (SI), for plots.
    #[serde(skip)]
    pub curve: Curve,
}

/// Fits one test's table.
pub fn fit_test(
    kind: TestKind,
    csv_name: &str,
    table: &Table,
    g: Geometry,
) -> Result<TestFit, CalibError> {
    let curve = mechanics::prepare(kind, table, &g)?;
    let file = table.file.as_str();
    let range = linear_range::find(&curve.x, &curve.y).map_err(|e| match e {
        RangeError::TooFewPoints { points, needed } => CalibError::file(
            file,
            format!("too few points: {points} data rows, a fit needs at least {needed}"),
        ),
        RangeError::NoneLinear { min_points, noise_std } => CalibError::file(
            file,
            format!(
                "no linear range found: no run of {min_points} or more consecutive points rises along a straight line within the scatter of the data (σ ≈ {:.3e} {}); check the columns and the test kind",
                noise_std * curve.y_scale,
                curve.y_label
            ),
        ),
    })?;
    let (a, b) = (range.first, range.last);
    let line = fit_line(&curve.x[a..=b], &curve.y[a..=b]).ok_or_else(|| {
        CalibError::file(
            file,
            "the linear range's points all share one x: nothing to fit",
        )
    })?;
    let property = kind.property().ok_or_else(|| {
        CalibError::file(
            file,
            format!("a {} test measures no stiffness", kind.name()),
        )
    })?;
    let (symbol, unit, scale) = property.display();
    let f = curve.factor;
    let value = f * line.slope;
    let ci95 = [f * line.slope_ci95[0], f * line.slope_ci95[1]];
    let range = RangeReport {
        first_row: a,
        last_row: b,
        first_line: curve.lines[a],
        last_line: curve.lines[b],
        points: b - a + 1,
        total_points: curve.x.len(),
        x_from: curve.x[a] * curve.x_scale,
        x_to: curve.x[b] * curve.x_scale,
        y_from: curve.y[a] * curve.y_scale,
        y_to: curve.y[b] * curve.y_scale,
        x_label: curve.x_label.to_string(),
        y_label: curve.y_label.to_string(),
        noise_std: range.noise_std * curve.y_scale,
    };
    Ok(TestFit {
        kind,
        csv: csv_name.to_string(),
        geometry: g,
        property,
        symbol: symbol.to_string(),
        unit: unit.to_string(),
        value,
        std_error: f * line.slope_std_error,
        ci95,
        value_display: value * scale,
        ci95_display: [ci95[0] * scale, ci95[1] * scale],
        formula: curve.formula.clone(),
        flipped: curve.flipped,
        line,
        range,
        curve,
    })
}
