//! A scene's whole timeline run, as `pliant run` runs it but writing nothing.

use pliant_assembly::{run_timeline, NoObserver, RunSummary, Workcell, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_scene::budget::DEFAULT_MAX_STEPS;
use pliant_scene::LoadedScene;

/// `scene`'s whole timeline run with `solver` (the scene's own if `None`): the workcell
/// at the end and the summary. Refused beyond the default step limit ([`run_within`]).
pub fn run_with(
    scene: &LoadedScene,
    solver: Option<SolverKind>,
) -> Result<(Workcell, RunSummary), String> {
    run_within(scene, solver, DEFAULT_MAX_STEPS)
}

/// [`run_with`], refused before it starts when planned beyond `max_steps`
/// ([`LoadedScene::check_planned_steps`]).
pub fn run_within(
    scene: &LoadedScene,
    solver: Option<SolverKind>,
    max_steps: u64,
) -> Result<(Workcell, RunSummary), String> {
    let mut cell = scene
        .workcell(WorkcellOptions {
            solver,
            initial_loads: false,
            ..Default::default()
        })
        .map_err(|e| e.to_string())?;
    scene.check_planned_steps(cell.time_step(), max_steps)?;
    let run = run_timeline(&mut cell, &scene.timeline, &mut NoObserver).map_err(|e| e.reason)?;
    Ok((cell, run))
}
