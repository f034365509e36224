//! `pliant.SettleReport`: how `Simulation.settle` ended.

use pliant_core::relax::RelaxReport;
use pyo3::prelude::*;

/// How a relaxation to static equilibrium ended.
///
/// Attributes: ``converged`` (the residuals fell below the tolerances), ``steps`` taken,
/// and the largest out-of-balance ``residual_force`` \[N\] and ``residual_moment`` \[N·m\]
/// on a free node.
#[pyclass(module = "pliant", name = "SettleReport", frozen)]
pub struct SettleReport {
    #[pyo3(get)]
    converged: bool,
    #[pyo3(get)]
    steps: u64,
    #[pyo3(get)]
    residual_force: f64,
    #[pyo3(get)]
    residual_moment: f64,
}

impl From<RelaxReport> for SettleReport {
    fn from(r: RelaxReport) -> Self {
        SettleReport {
            converged: r.converged,
            steps: r.steps,
            residual_force: r.residual_force,
            residual_moment: r.residual_moment,
        }
    }
}

#[pymethods]
impl SettleReport {
    fn __bool__(&self) -> bool {
        self.converged
    }

    fn __repr__(&self) -> String {
        format!(
            "SettleReport(converged={}, steps={}, residual_force={:.3e}, residual_moment={:.3e})",
            if self.converged { "True" } else { "False" },
            self.steps,
            self.residual_force,
            self.residual_moment
        )
    }
}
