//! Every prescribed motion arrives, however short against the solver's step: a hose end
//! moved 100 mm up over 2 ms — a fifth of the static solver's 10 ms input step — and then
//! 50 mm sideways ends 100 mm up and 50 mm over under every solver (it ended 100 mm too low
//! under the implicit and static solvers, which skipped the 2 ms move).

use glam::DVec3;
use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use pliant_testkit::scene_text::{action, fix, hose, simulation, SceneText};

/// A 500 mm hose 300 mm up, fixed at its start; its end moved 100 mm up over 2 ms, then
/// 50 mm sideways over 0.2 s.
fn scene() -> String {
    let move_end = |by: &str, duration_s: f64| {
        action("move")
            .text("hose", "hose")
            .number("node", -1.0)
            .inline("by", by)
            .number("duration_s", duration_s)
    };
    let (start, end) = ([0.0, 0.0, 300.0], [500.0, 0.0, 300.0]);
    SceneText::mm_named("a move shorter than a step")
        .with(simulation().point("gravity", [0.0, 0.0, -9.81]))
        .with(hose("hose", "hose3", start, end).number("elements", 10.0))
        .with(fix("hose", 0))
        .with(move_end("[[0, 0, 100]]", 0.002))
        .with(move_end("[[0, 50, 0]]", 0.2))
        .into()
}

/// Runs the scene under `solver` and checks the moved end's final position exactly (to
/// round-off).
fn arrives(solver: SolverKind) {
    let scene = load_scene_str_in(&scene(), "short.toml", std::path::Path::new(".")).unwrap();
    let (cell, _) = pliant_runs::run_with(&scene, Some(solver)).unwrap();
    let end = cell.state().x[10];
    let expected = DVec3::new(0.5, 0.05, 0.4);
    assert!(
        (end - expected).length() < 1e-9,
        "{solver:?}: the end is at {end}, not {expected}"
    );
}

#[test]
fn a_move_shorter_than_a_step_arrives_under_the_explicit_solver() {
    arrives(SolverKind::Explicit);
}

#[test]
fn a_move_shorter_than_a_step_arrives_under_the_implicit_solver() {
    arrives(SolverKind::Implicit);
}

#[test]
fn a_move_shorter_than_a_step_arrives_under_the_static_solver() {
    arrives(SolverKind::Static);
}
