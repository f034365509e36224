//! The history variables of the inelastic laws are part of the state (SPEC X1–X3): a
//! session with a steel line bent past yield, a rubber hose held stretched while it
//! relaxes and a bundle twisted against its wires' friction replays bit for bit from its
//! log, and a checkpoint restored mid-run brings back the plastic strains, the Prony
//! stresses, the friction moments and the laws' clock — so the rest of the run is the
//! same to the bit. Kept small (six elements a hose, static steps) so it runs in seconds.

use pliant_assembly::workcell::replay::replay;
use pliant_assembly::{run_timeline, NoObserver, Timeline, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scenes::{EPDM, WEIGHTLESS_MM};

fn scene() -> String {
    format!(
        r#"{WEIGHTLESS_MM}solver = "static"
{EPDM}relaxation = [{{ weight = 0.3, time_s = 0.5 }}, {{ weight = 0.2, time_s = 2 }}]

[materials.wires]
e_tension_mpa = 50
e_compression_mpa = 50
poisson = 0.4
density_kg_m3 = 2000
hysteresis = {{ bending_moment_n_m = 0.01, bending_curvature_1_m = 1, torsion_moment_n_m = 0.02, torsion_curvature_1_m = 0.5 }}

[[hoses]]
name = "line"
material = "steel_tube"
section = {{ d_inner = 3.35, d_outer = 4.75 }}
elements = 6
start = [0, 0, 0]
path = [{{ line = {{ to = [200, 0, 0] }} }}]

[[hoses]]
name = "rubber"
material = "epdm"
section = {{ d_inner = 10, d_outer = 16 }}
elements = 6
start = [0, 100, 0]
path = [{{ line = {{ to = [200, 100, 0] }} }}]

[[hoses]]
name = "bundle"
material = "wires"
section = {{ d_inner = 0, d_outer = 10 }}
elements = 6
start = [0, 200, 0]
path = [{{ line = {{ to = [200, 200, 0] }} }}]

[[timeline]]
action = "fix"
hose = "line"
node = 0

[[timeline]]
action = "fix"
hose = "rubber"
node = 0

[[timeline]]
action = "fix"
hose = "bundle"
node = 0

[[timeline]]
action = "move"
hose = "line"
node = -1
by = [-72.676, 0, 127.324]
rotate = {{ axis = [0, -1, 0], angle_deg = 90 }}
duration_s = 0.5

[[timeline]]
action = "move"
hose = "rubber"
node = -1
by = [2, 0, 0]
duration_s = 0.2

[[timeline]]
action = "move"
hose = "bundle"
node = -1
rotate = {{ axis = [1, 0, 0], angle_deg = 90 }}
duration_s = 0.2

[[timeline]]
action = "run"
duration_s = 0.5

[[timeline]]
action = "release"
hose = "line"
node = -1

[[timeline]]
action = "release"
hose = "bundle"
node = -1

[[timeline]]
action = "run"
duration_s = 0.5
"#
    )
}

#[test]
fn inelastic_histories_replay_and_restore_bit_for_bit() {
    let s = load_scene_str(&scene(), "inelastic.toml").unwrap();
    let options = WorkcellOptions {
        solver: Some(SolverKind::Static),
        initial_loads: false,
        ..Default::default()
    };
    let mut live = s.workcell(options).unwrap();
    // checkpoint after the bends, before the hold: every law has a history by then
    let split = 6;
    let first = Timeline {
        actions: s.timeline.actions[..split].to_vec(),
    };
    let rest = Timeline {
        actions: s.timeline.actions[split..].to_vec(),
    };
    run_timeline(&mut live, &first, &mut NoObserver).unwrap();
    let saved = live.checkpoint();
    let history = live.state().inelastic_history.clone();
    let clock = live.state().inelastic_time;
    assert!(history.iter().any(|v| *v != 0.0), "no history yet");
    run_timeline(&mut live, &rest, &mut NoObserver).unwrap();
    let end = live.state().clone();
    assert_ne!(
        end.inelastic_history, history,
        "the rest of the run changes the history"
    );
    // the line kept a bend: its end stays well above the axis once let go
    let line_end = 6;
    assert!(end.x[line_end].z > 0.1, "{:?}", end.x[line_end]);

    // replay of the log: the same state to the bit
    let mut again = s.workcell(options).unwrap();
    replay(
        &mut again,
        &live.log().to_vec(),
        live.tick(),
        &mut NoObserver,
    )
    .unwrap();
    assert_eq!(again.state().inelastic_history, end.inelastic_history);
    assert_eq!(
        again.state().inelastic_time.to_bits(),
        end.inelastic_time.to_bits()
    );
    assert_eq!(again.state().x, end.x);
    assert_eq!(again.state().q, end.q);

    // rollback: the checkpoint brings the histories and their clock back, and the rest
    // of the run is the same
    live.restore(&saved).unwrap();
    assert_eq!(live.state().inelastic_history, history);
    assert_eq!(live.state().inelastic_time.to_bits(), clock.to_bits());
    run_timeline(&mut live, &rest, &mut NoObserver).unwrap();
    assert_eq!(live.state().inelastic_history, end.inelastic_history);
    assert_eq!(live.state().x, end.x);
}
