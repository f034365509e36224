//! What several of this crate's tests share: a static run's outputs written to a
//! temporary folder as `pliant run` writes them.

use pliant_assembly::report::{write_outputs, Outputs};
use pliant_assembly::{RunSummary, Workcell};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;

/// Writes `summary.json`, `worker.csv`, `report.html`, … of the static run `run` of the
/// scene `text` (named `source`), ended in `cell`, into a new temporary folder.
pub fn static_outputs(
    text: &str,
    source: &str,
    cell: &Workcell,
    run: &RunSummary,
) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let s = load_scene_str(text, source).unwrap();
    let model = cell.model().clone();
    let outputs = Outputs {
        scene_name: "worker",
        source,
        model: &model,
        state: cell.state(),
        run,
        diverged: None,
        hand_series: &[],
        profile: &s.ergonomics,
        solver: SolverKind::Static,
        time_step: cell.time_step(),
        wall_time: 1.0,
        worker_series: cell.worker_series(),
    };
    write_outputs(dir.path(), &outputs).unwrap();
    dir
}
