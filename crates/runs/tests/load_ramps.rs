//! Load cases tests and users need: a dead load that rises over a ramp
//! (the static solver follows it step by step — the way to take a large load in load
//! steps), and one load of several on a node removed by name, the others kept. Under
//! every solver.

use pliant_core::loads::LoadCase;
use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;
use pliant_testkit::scene_text::{action, fix, hose, load, run_for, settle, simulation, SceneText};

/// A weightless, damped 300 mm hose fixed at its start; its end loaded down (ramped over
/// 0.5 s, "down") and sideways ("side"), settled, "down" removed, settled again.
fn scene() -> String {
    let damped = simulation()
        .point("gravity", [0.0; 3])
        .number("damping_mass_per_s", 20.0);
    let hose = hose("h", "hose1", [0.0; 3], [300.0, 0.0, 0.0]).number("elements", 10.0);
    SceneText::mm_named("ramped and named loads")
        .with(damped)
        .with(hose)
        .with(fix("h", 0))
        .with(
            load("h", -1)
                .point("force_n", [0.0, 0.0, -0.2])
                .text("name", "down")
                .number("ramp_s", 0.5),
        )
        .with(
            load("h", -1)
                .point("force_n", [0.0, 0.1, 0.0])
                .text("name", "side"),
        )
        .with(run_for(0.25))
        .with(settle(1e-12, 20.0))
        .with(
            action("unload")
                .text("hose", "h")
                .number("node", -1.0)
                .text("name", "down"),
        )
        .with(settle(1e-12, 20.0))
        .into()
}

#[test]
fn a_ramped_load_rises_and_a_named_unload_removes_that_load_alone() {
    let scene = load_scene_str_in(&scene(), "loads.toml", std::path::Path::new(".")).unwrap();
    for solver in [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ] {
        // up to the end of the first run: the ramp is half way (t = 0.25 s of 0.5 s)
        let mut first = scene.clone();
        first.timeline.actions.truncate(4);
        let (cell, _) = pliant_runs::run_with(&first, Some(solver)).unwrap();
        let t = cell.state().time;
        let down = cell
            .state()
            .loads
            .iter()
            .find_map(|(_, c)| match c {
                LoadCase::DeadLoad(d) if d.force.z < 0.0 => Some(d.at(t).0.z),
                _ => None,
            })
            .expect("the ramped load acts");
        assert!(
            (down + 0.2 * t / 0.5).abs() < 1e-12,
            "{solver:?}: at t = {t} s the ramped load is {down} N"
        );
        // the whole timeline: the support ends up carrying the side load alone
        let (cell, run) = pliant_runs::run_with(&scene, Some(solver)).unwrap();
        let clamp = run.peaks.iter().find(|p| p.node == 0).unwrap();
        let f = clamp.last_force;
        assert!(
            (f.y + 0.1).abs() < 1e-4 && f.z.abs() < 1e-4,
            "{solver:?}: the clamp carries {f} N, not the side load alone"
        );
        let dead_loads = cell
            .state()
            .loads
            .iter()
            .filter(|(_, c)| matches!(c, LoadCase::DeadLoad(_)))
            .count();
        assert_eq!(dead_loads, 1, "{solver:?}");
    }
}
