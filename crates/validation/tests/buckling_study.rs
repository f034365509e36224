//! A study as a user runs it: a straight hose clamped at
//! both ends, one end pushed to 70 % of the length under `--solver static`. Past the
//! Euler load the straight hose is an unstable equilibrium; the workcell must land on the
//! stable elastica branch (end load within 1 % of the exact value, where the straight
//! branch carries thousands of times more), and say in its summary and verdict that the
//! hose buckled — while the verdict stays certain (every solve converged).
//!
//! A snap-through under the static solver is an
//! instability event in the run's outputs, whichever way the solver passed it. The
//! column, pushed to 95 % of its length with a 1 % lateral load (removed) so that it
//! buckles towards +y, is loaded by 1 N against the buckle in one input step — beyond the
//! snap load of the shallow buckled arch. Its branch ends there and the hose snaps into
//! the mirrored shape; Newton converges to it within that one step, 0.28 m away where the
//! linearised response of the step predicted 4 mm, through tangents that were not
//! positive definite: a jump to a distant branch, not the continuation of the one it
//! stood on ([`pliant_core::integrators::JUMP_RATIO`]).
//! Before, the step counted as an ordinary converged one and nothing said the hose had
//! snapped. Pushed to 70 % and loaded by 3 N, no load step of the adaptive stepping
//! converges and the snap is followed by relaxation, whose hand-over point (a small
//! residual) can be the snap's saddle: Newton then has to relax on from where it stopped
//! rather than leave the step out of balance.

use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use pliant_validation::elastica::clamped_column;
use pliant_validation::harness::hose1;
use std::f64::consts::PI;

/// The column (hose 1, 1 m, 40 elements, no gravity, static solver) clamped at node 0,
/// its far end driven to `end_mm` over 1 s; `before` and `after` are timeline actions
/// (TOML) before and after the push.
fn column_scene(end_mm: f64, before: &str, after: &str) -> String {
    format!(
        r#"
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
path = [{{ line = {{ to = [1000, 0, 0] }} }}]
elements = 40

[[timeline]]
action = "fix"
hose = "column"
node = 0
{before}
[[timeline]]
action = "move"
hose = "column"
node = -1
to = [[{end_mm}, 0, 0]]
duration_s = 1.0
{after}"#
    )
}

#[test]
fn a_clamped_hose_pushed_past_buckling_lands_on_the_elastica_and_says_so() {
    let text = column_scene(700.0, "", "");
    let scene = load_scene_str_in(&text, "column.toml", std::path::Path::new(".")).unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, Some(SolverKind::Static)).unwrap();
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

/// Runs the column pushed to `end_mm` and snapped by `load_n` under the static solver. It
/// must end in the mirrored shape (mid-span y below −`depth`; the buckle was towards +y,
/// the nudge's side), every step converged, with one instability in the run summary (as
/// `summary.json` has it): a snap at t = 1.06 s on hose 0, its mode the snap's
/// displacement, largest at mid-span. Returns the verdict's reasons.
fn snapped(end_mm: f64, load_n: f64, depth: f64) -> Vec<String> {
    // a named 1 % nudge at mid-span during the push, removed, 50 ms at rest, then
    // `load_n` at once against the buckle and 0.2 s more
    let nudge = r#"
[[timeline]]
action = "load"
hose = "column"
node = 20
force_n = [0, 0.013, 0]
name = "nudge"
"#;
    let after = format!(
        r#"
[[timeline]]
action = "unload"
hose = "column"
node = 20
name = "nudge"

[[timeline]]
action = "run"
duration_s = 0.05

[[timeline]]
action = "load"
hose = "column"
node = 20
force_n = [0, {load_n}, 0]

[[timeline]]
action = "run"
duration_s = 0.2
"#
    );
    let text = column_scene(end_mm, nudge, &after);
    let scene = load_scene_str_in(&text, "snap.toml", std::path::Path::new(".")).unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, Some(SolverKind::Static)).unwrap();
    let mid_y = cell.state().x[20].y;
    assert!(
        mid_y < -depth,
        "snapped into the mirrored shape: mid-span y {mid_y}"
    );
    let summary = serde_json::to_value(&run).unwrap();
    let solver = &summary["solver"];
    assert_eq!(solver["unconverged_steps"], 0, "{solver:#}");
    assert_eq!(solver["instability_count"], 1, "{solver:#}");
    let event = &solver["instabilities"][0];
    assert_eq!(
        event["limit_point"], true,
        "a snap, not a buckling: {event:#}"
    );
    assert_eq!(event["hose"], 0);
    // the load acts from t = 1.05 s; the step that snapped ends at 1.06 s
    let t = event["time"].as_f64().unwrap();
    assert!((t - 1.06).abs() < 1e-9, "snapped at t = {t}");
    assert!(event["energy_drop_j"].as_f64().unwrap() > 0.0, "{event:#}");
    // the snap's displacement, largest at mid-span, scaled to 1, one entry per node
    let mode = event["mode"].as_array().unwrap();
    assert_eq!(mode.len(), 41);
    assert_eq!(event["node"], 20);
    let across = mode[20][1].as_f64().unwrap();
    assert!((across + 1.0).abs() < 1e-9, "{:?}", mode[20]);
    cell.verdict(pliant_assembly::Stage::Final).reasons
}

#[test]
fn a_snap_newton_converges_through_in_one_step_is_reported() {
    let reasons = snapped(950.0, -1.0, 0.1);
    let said = "hose 'column' snapped through at t = 1.060 s";
    assert!(reasons.iter().any(|r| r.contains(said)), "{reasons:?}");
}

#[test]
fn a_snap_relaxed_past_its_saddle_converges_and_is_reported() {
    let reasons = snapped(700.0, -3.0, 0.3);
    let uncertain = reasons.iter().any(|r| r.contains("uncertain"));
    assert!(!uncertain, "every step converged: {reasons:?}");
}
