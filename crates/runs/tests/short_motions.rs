//! Every prescribed motion arrives, however short against the solver's step: a hose end
//! moved 100 mm up over 2 ms — a fifth of the static solver's 10 ms input step — and then
//! 50 mm sideways ends 100 mm up and 50 mm over under every solver (it ended 100 mm too low
//! under the implicit and static solvers, which skipped the 2 ms move).

use glam::DVec3;
use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;

const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "a move shorter than a step"
length_unit = "mm"

[simulation]
gravity = [0, 0, -9.81]

[[hoses]]
name = "hose"
material = "hose3"
start = [0, 0, 300]
path = [{ line = { to = [500, 0, 300] } }]
elements = 10

[[timeline]]
action = "fix"
hose = "hose"
node = 0

[[timeline]]
action = "move"
hose = "hose"
node = -1
by = [[0, 0, 100]]
duration_s = 0.002

[[timeline]]
action = "move"
hose = "hose"
node = -1
by = [[0, 50, 0]]
duration_s = 0.2
"#;

/// Runs the scene under `solver` and checks the moved end's final position exactly (to
/// round-off).
fn arrives(solver: SolverKind) {
    let scene = load_scene_str_in(SCENE, "short.toml", std::path::Path::new(".")).unwrap();
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
