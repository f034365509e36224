//! The `pliant` Python package's native module (`pliant._pliant`): scenes, interactive
//! simulations, timeline runs and reports, on top of Pliant's Rust crates. The Python
//! package (python/pliant) re-exports everything from here and adds type stubs.

mod args;
mod arrays;
mod calibration;
mod collector;
mod engine;
mod errors;
mod hand_load;
mod load_id;
mod motion_table;
mod part_distance;
mod run_result;
mod scene;
mod settle;
mod settle_report;
mod simulation;
mod sweep_samples;

use pyo3::prelude::*;

#[pymodule]
fn _pliant(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_MAX_STEPS", pliant_scene::budget::DEFAULT_MAX_STEPS)?;
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add(
        "SimulationDiverged",
        py.get_type::<errors::SimulationDiverged>(),
    )?;
    m.add(
        "SolverNotConverged",
        py.get_type::<errors::SolverNotConverged>(),
    )?;
    m.add("SolverWarning", py.get_type::<errors::SolverWarning>())?;
    m.add(
        "CalibrationError",
        py.get_type::<calibration::CalibrationError>(),
    )?;
    m.add_class::<calibration::Calibration>()?;
    m.add_class::<calibration::CalibrationFit>()?;
    m.add_function(wrap_pyfunction!(calibration::calibrate, m)?)?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<load_id::LoadId>()?;
    m.add_class::<hand_load::HandLoad>()?;
    m.add_class::<settle_report::SettleReport>()?;
    m.add_class::<run_result::RunResult>()?;
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::demo_scene, m)?)?;
    m.add_function(wrap_pyfunction!(run_result::run_timeline, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_samples::centreline_sample_keys, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_samples::swept_voxel_keys, m)?)?;
    m.add_function(wrap_pyfunction!(part_distance::part_distances, m)?)?;
    m.add_function(wrap_pyfunction!(part_distance::part_clearance, m)?)?;
    m.add_function(wrap_pyfunction!(material_library_toml, m)?)?;
    Ok(())
}

/// The built-in material library as shipped (TOML text of crates/scene/data/materials.toml):
/// values in the units their keys name, each with its source or assumption.
#[pyfunction]
fn material_library_toml() -> &'static str {
    pliant_scene::library::LIBRARY_TOML
}
