//! The output writers of `pliant run` as a library: the recorder (CSV time series, VTK
//! frames), the verdict report (`report.json`, `report.html`) and `summary.json`. The
//! `pliant` binary and the Python API (crates/python) both use them, so both write the
//! same files.

pub mod recorder;
pub mod report;
pub mod summary;
mod vtk;
