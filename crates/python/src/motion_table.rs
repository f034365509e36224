//! A range-of-motion study's findings as Python values, the same for a finished run
//! (`RunResult.motion`) and a live simulation (`Simulation.sweep`): the columns of
//! `motion.csv` exactly as `pliant run` writes them, as numpy arrays, and the worst
//! positions.

use crate::arrays::{scalars, to_python};
use pliant_assembly::sweep::SweepSummary;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The columns of `motion.csv` (its header's names), each a numpy array with one value
/// per checked instant (NaN where the file has an empty cell); `None` without a
/// coordinate.
pub fn motion_columns<'py>(
    py: Python<'py>,
    sweep: &SweepSummary,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let csv = sweep.csv();
    let mut lines = csv.lines();
    let Some(head) = lines.next() else {
        return Ok(None);
    };
    let names: Vec<&str> = head.split(',').collect();
    let mut columns = vec![Vec::new(); names.len()];
    for line in lines {
        for (column, value) in columns.iter_mut().zip(line.split(',')) {
            column.push(value.parse::<f64>().unwrap_or(f64::NAN));
        }
    }
    let table = PyDict::new(py);
    for (name, column) in names.into_iter().zip(columns) {
        table.set_item(name, scalars(py, column))?;
    }
    Ok(Some(table))
}

/// `{"columns": motion_columns, "worst": [{what, value, time, coordinate, position}],
/// "clearance_violations": [...], "over_the_motion": the verdict's sentence}`; `None`
/// without a coordinate.
pub fn sweep_findings<'py>(
    py: Python<'py>,
    sweep: &SweepSummary,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let (Some(columns), Some(coordinate)) = (motion_columns(py, sweep)?, &sweep.coordinate) else {
        return Ok(None);
    };
    let worst: Vec<serde_json::Value> = sweep
        .worst()
        .into_iter()
        .map(|w| {
            serde_json::json!({
                "what": w.what,
                "value": w.value,
                "time": w.time,
                "coordinate": w.coordinate,
                "position": coordinate.describe(w.coordinate),
            })
        })
        .collect();
    let out = PyDict::new(py);
    out.set_item("columns", columns)?;
    out.set_item("worst", to_python(py, &worst)?)?;
    out.set_item(
        "clearance_violations",
        to_python(py, &sweep.clearance_violations())?,
    )?;
    out.set_item("over_the_motion", sweep.extremes().map(|e| e.to_string()))?;
    Ok(Some(out))
}
