//! A study as a user runs it (issue 10's first complaint): a straight hose clamped at
//! both ends, one end pushed to 70 % of the length under `--solver static`. Past the
//! Euler load the straight hose is an unstable equilibrium; the workcell must land on the
//! stable elastica branch (end load within 1 % of the exact value, where the straight
//! branch carries thousands of times more), and say in its summary and verdict that the
//! hose buckled — while the verdict stays certain (every solve converged).

use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use pliant_validation::elastica::clamped_column;
use pliant_validation::harness::hose1;
use std::f64::consts::PI;

const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "clamped hose pushed past buckling"
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]
solver = "static"

[[hoses]]
name = "column"
material = "hose1"
start = [0, 0, 0]
path = [{ line = { to = [1000, 0, 0] } }]
elements = 40

[[timeline]]
action = "fix"
hose = "column"
node = 0

[[timeline]]
action = "move"
hose = "column"
node = -1
to = [[700, 0, 0]]
duration_s = 1.0
"#;

#[test]
fn a_clamped_hose_pushed_past_buckling_lands_on_the_elastica_and_says_so() {
    let scene = load_scene_str_in(SCENE, "column.toml", std::path::Path::new(".")).unwrap();
    let (cell, run) = scene.run_with(Some(SolverKind::Static)).unwrap();
    // the support's end load against the exact elastica (hose 1's bending stiffness;
    // 40 elements and hose 1's own axial compliance make up the 1 %)
    let (mat, sec) = hose1();
    let ei = mat.bending_modulus() * sec.second_moment();
    let end = run
        .peaks
        .iter()
        .find(|p| p.node == 40)
        .expect("the driven end");
    let ratio = end.last_force.length() / (4.0 * PI * PI * ei);
    let exact = clamped_column(0.7).load_ratio;
    assert!(
        (ratio / exact - 1.0).abs() < 0.01,
        "end load {ratio:.4} × 4π²EI/L², exact {exact:.4}"
    );
    assert!(run.solver.instability_count >= 1, "{:?}", run.solver);
    let first = &run.solver.instabilities[0];
    assert_eq!(first.hose, 0);
    assert_eq!(first.mode.len(), 41);
    assert!(first.time > 0.0 && first.time < 1.0);
    let verdict = cell.verdict(pliant_assembly::Stage::Final);
    assert!(
        verdict
            .reasons
            .iter()
            .any(|r| r.contains("hose 'column' buckled")),
        "{:?}",
        verdict.reasons
    );
    assert!(!verdict.uncertain, "{:?}", verdict.reasons);
    assert_eq!(run.solver.unconverged_steps, 0);
}
