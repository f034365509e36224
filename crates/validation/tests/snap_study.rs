//! Issue 10 item 1 (limit points): a snap-through under the static solver is an
//! instability event in the run's outputs, whichever way the solver passed it.
//!
//! A hose clamped at both ends is pushed to 95 % of its length (with a 1 % lateral load,
//! removed, so that it buckles towards +y); a lateral load of 1 N against the buckle —
//! beyond the snap load of the shallow buckled arch — is then applied in one input step.
//! The buckled shape's branch ends there and the hose snaps into the mirrored shape. Newton
//! converges to it within that one step, 0.28 m away where the linearised response of the
//! step predicted 4 mm: a jump to a distant branch, not the continuation of the one it
//! stood on ([`pliant_core::integrators::JUMP_RATIO`]). Before, the step counted as
//! an ordinary converged one and nothing said the hose had snapped.
//!
//! The second test loads the deeply buckled hose (70 %) with 3 N in one step: no load
//! step of the adaptive stepping converges, the snap is followed by relaxation, whose
//! hand-over point (a small residual) can be the snap's saddle — Newton then has to
//! relax on from where it stopped rather than leave the step out of balance.

use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use serde_json::Value;

/// The scene: clamp, a named nudge at mid-span, the push to `end_mm`, the nudge removed,
/// 50 ms at rest, then `load_n` against the buckle at mid-span at once and 0.2 s more.
fn scene(end_mm: f64, load_n: f64) -> String {
    format!(
        r#"
format = "pliant-scene"
version = 1
name = "a buckled hose snapped through"
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

[[timeline]]
action = "load"
hose = "column"
node = 20
force_n = [0, 0.013, 0]
name = "nudge"

[[timeline]]
action = "move"
hose = "column"
node = -1
to = [[{end_mm}, 0, 0]]
duration_s = 1.0

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
    )
}

/// Runs the scene under the static solver; returns the final mid-span y (the buckle was
/// towards +y, the nudge's side), the run summary as `summary.json` has it, and the
/// verdict's reasons.
fn snap(end_mm: f64, load_n: f64) -> (f64, Value, Vec<String>) {
    let text = scene(end_mm, load_n);
    let scene = load_scene_str_in(&text, "snap.toml", std::path::Path::new(".")).unwrap();
    let (cell, run) = scene.run_with(Some(SolverKind::Static)).unwrap();
    let mid_y = cell.state().x[20].y;
    let verdict = cell.verdict(pliant_assembly::Stage::Final);
    (mid_y, serde_json::to_value(&run).unwrap(), verdict.reasons)
}

/// The one snap event of a run: time, hose, kind (limit point) and mode.
fn the_snap(summary: &Value) -> &Value {
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
    assert!(
        (mode[20][1].as_f64().unwrap() + 1.0).abs() < 1e-9,
        "{:?}",
        mode[20]
    );
    event
}

#[test]
fn a_snap_newton_converges_through_in_one_step_is_reported() {
    let (mid_y, summary, reasons) = snap(950.0, -1.0);
    assert!(
        mid_y < -0.1,
        "snapped into the mirrored shape: mid-span y {mid_y}"
    );
    the_snap(&summary);
    assert!(
        reasons
            .iter()
            .any(|r| r.contains("hose 'column' snapped through at t = 1.060 s")),
        "{reasons:?}"
    );
}

#[test]
fn a_snap_relaxed_past_its_saddle_converges_and_is_reported() {
    let (mid_y, summary, reasons) = snap(700.0, -3.0);
    assert!(
        mid_y < -0.3,
        "snapped into the mirrored shape: mid-span y {mid_y}"
    );
    the_snap(&summary);
    assert!(
        reasons.iter().all(|r| !r.contains("uncertain")),
        "every step converged: {reasons:?}"
    );
}
