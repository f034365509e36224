//! A session with a junction body's shape under the static solver replays bit for bit: the
//! coolant T-piece example (`examples/coolant_tee.toml`, the heater return resting on the
//! tee's box), the heater hose's far end then raised 30 mm (and moved 10 mm along the
//! line) and lowered again, so that contact with the shape, its reaction on the body and
//! the friction anchors in the shape's frame all enter the log's replay.

use pliant_assembly::workcell::replay::replay;
use pliant_assembly::{run_timeline, NoObserver, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;

fn scene() -> String {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/coolant_tee.toml"
    );
    let example = std::fs::read_to_string(path).unwrap();
    format!(
        r#"{example}
[[timeline]]
action = "move"
hose = "heater return"
node = -1
by = [10, 0, 30]
duration_s = 0.1

[[timeline]]
action = "move"
hose = "heater return"
node = -1
by = [0, 0, -30]
duration_s = 0.1

[[timeline]]
action = "run"
duration_s = 0.05
"#
    )
}

#[test]
fn a_session_with_a_junction_shape_replays_bit_for_bit_under_the_static_solver() {
    let s = load_scene_str(&scene(), "coolant_tee.toml").unwrap();
    let options = WorkcellOptions {
        solver: Some(SolverKind::Static),
        ..Default::default()
    };
    let mut live = s.workcell(options).unwrap();
    run_timeline(&mut live, &s.timeline, &mut NoObserver).unwrap();
    let end = live.state().clone();
    // the heater return (hose 3) rests on the tee's box again at the end
    let heater = s.build_model().unwrap().hoses[3].nodes();
    let on_tee: f64 = heater.map(|i| end.contact_force[i].z).sum();
    assert!(
        on_tee > 0.05,
        "the heater hose presses the tee with {on_tee} N"
    );

    let mut again = s.workcell(options).unwrap();
    replay(
        &mut again,
        &live.log().to_vec(),
        live.tick(),
        &mut NoObserver,
    )
    .unwrap();
    let replayed = again.state();
    assert_eq!(replayed.x, end.x);
    assert_eq!(replayed.q, end.q);
    assert_eq!(replayed.contact_force, end.contact_force);
    assert_eq!(replayed.friction.anchor, end.friction.anchor);
    assert_eq!(replayed.bodies, end.bodies);
}
