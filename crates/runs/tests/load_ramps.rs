//! Load cases tests and users need: a dead load that rises over a ramp
//! (the static solver follows it step by step — the way to take a large load in load
//! steps), and one load of several on a node removed by name, the others kept. Under
//! every solver.

use pliant_core::loads::LoadCase;
use pliant_core::SolverKind;
use pliant_scene::load_scene_str_in;

const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "ramped and named loads"
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]
damping_mass_per_s = 20.0

[[hoses]]
name = "h"
material = "hose1"
start = [0, 0, 0]
path = [{ line = { to = [300, 0, 0] } }]
elements = 10

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "load"
hose = "h"
node = -1
force_n = [0, 0, -0.2]
name = "down"
ramp_s = 0.5

[[timeline]]
action = "load"
hose = "h"
node = -1
force_n = [0, 0.1, 0]
name = "side"

[[timeline]]
action = "run"
duration_s = 0.25

[[timeline]]
action = "settle"
kinetic_energy_j = 1e-12
max_duration_s = 20

[[timeline]]
action = "unload"
hose = "h"
node = -1
name = "down"

[[timeline]]
action = "settle"
kinetic_energy_j = 1e-12
max_duration_s = 20
"#;

#[test]
fn a_ramped_load_rises_and_a_named_unload_removes_that_load_alone() {
    let scene = load_scene_str_in(SCENE, "loads.toml", std::path::Path::new(".")).unwrap();
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
