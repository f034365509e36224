//! Timeline actions that move parts (`move_part`, `rotate_part`) in the scene format: a
//! door opened and closed by the timeline carries the hose end mounted on it under
//! every solver (the closed form of the turn); the part becomes movable; bad entries name
//! the field; a session with part moves replays bit for bit from its folder and converts
//! back to a timeline that re-enacts it.

use glam::{DQuat, DVec3};
use pliant_assembly::{run_timeline, Input, NoObserver, Stage, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_runs::session::{log_to_scene, start_session_folder, Session};
use pliant_scene::{load_scene_str, load_scene_str_in};
use pliant_testkit::scene_text::{fix, mount, move_part, rotate_part, run_for, SceneText};
use pliant_testkit::scenes::{DOOR, HOSE3_300, WEIGHTLESS_MM};

/// A weightless 300 mm hose from a part "body" to a part "door" (parts[1], neither
/// moved by a motion of its own; a test may add the door's next line).
fn head() -> String {
    let body =
        "\n[[parts]]\nname = \"body\"\nbox = { size = [20, 20, 20] }\nposition = [-40, 0, -40]\n";
    format!("{WEIGHTLESS_MM}{HOSE3_300}{body}{DOOR}")
}

/// The door opened 0 → 60° about the vertical through (500, 0, 0) mm in 1 s, lifted by
/// 10 mm, then turned back to 0°.
fn timeline() -> String {
    let pin = [500.0, 0.0, 0.0];
    SceneText::piece()
        .with(fix("h", 0))
        .with(mount("h", -1, "door"))
        .with(
            rotate_part("door", [0.0, 0.0, 2.0], pin)
                .number("to_deg", 60.0)
                .number("duration_s", 1.0),
        )
        .with(
            move_part("door")
                .point("by", [0.0, 0.0, 10.0])
                .number("duration_s", 0.2),
        )
        .with(run_for(0.1))
        .with(
            rotate_part("door", [0.0, 0.0, 1.0], pin)
                .number("to_deg", 0.0)
                .number("duration_s", 0.5)
                .flag("wait", false),
        )
        .with(run_for(0.25))
        .into()
}

fn options(solver: SolverKind) -> WorkcellOptions {
    WorkcellOptions {
        solver: Some(solver),
        initial_loads: false,
        ..Default::default()
    }
}

#[test]
fn a_door_turned_by_the_timeline_carries_the_hose_end_under_every_solver() {
    let text = format!("{}{}", head(), timeline());
    let scene = load_scene_str(&text, "door.toml").unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.world.rigid_parts[1].movable, "moved by the timeline");
    assert!(!scene.world.rigid_parts[0].movable);
    for solver in SolverKind::ALL {
        let mut cell = scene.workcell(options(solver)).unwrap();
        // up to the end of the opening turn
        let opening = pliant_assembly::Timeline {
            actions: scene.timeline.actions[..3].to_vec(),
        };
        run_timeline(&mut cell, &opening, &mut NoObserver).unwrap();
        let end = *cell.state().x.last().unwrap();
        let turn = DQuat::from_rotation_z(60f64.to_radians());
        let expected = DVec3::new(0.5, 0.0, 0.0) + turn * DVec3::new(-0.2, 0.0, 0.0);
        assert!(
            (end - expected).length() < 1e-9,
            "{solver}: end at {end:?}, the door carries it to {expected:?}"
        );
        // lifted, then half-way back (the last turn does not wait): still moving
        let rest = pliant_assembly::Timeline {
            actions: scene.timeline.actions[3..].to_vec(),
        };
        run_timeline(&mut cell, &rest, &mut NoObserver).unwrap();
        assert!(cell.moving(), "{solver}: the closing turn goes on");
        let n = cell.steps_in(0.3);
        cell.steps(n, &mut NoObserver).unwrap();
        let end = *cell.state().x.last().unwrap();
        let closed = DVec3::new(0.3, 0.0, 0.01);
        assert!(
            (end - closed).length() < 1e-9,
            "{solver}: closed and lifted end at {end:?}"
        );
    }
}

/// A timeline entry moving `part` (`action`: `move_part` or `rotate_part`) with `fields`
/// (TOML lines).
fn part_move(action: &str, part: &str, fields: &str) -> String {
    format!("\n[[timeline]]\naction = \"{action}\"\npart = \"{part}\"\n{fields}\n")
}

#[test]
fn bad_part_moves_in_a_timeline_name_the_field() {
    // (action, part, its other fields, the field named, what the message says)
    let cases: &[(&str, &str, &str, &str, &str)] = &[
        (
            "move_part",
            "lid",
            "by = [0, 0, 1]\nduration_s = 1",
            "timeline[0].part",
            "names no part; parts are: body, door",
        ),
        (
            "move_part",
            "door",
            "by = [0, 0, 1]\nto = [0, 0, 1]\nduration_s = 1",
            "timeline[0]",
            "either `by`",
        ),
        (
            "move_part",
            "door",
            "by = [0, 0, 1e9]\nduration_s = 1",
            "timeline[0].by",
            "out of range",
        ),
        (
            "rotate_part",
            "door",
            "axis = [0, 0, 0]\nby_deg = 10\nduration_s = 1",
            "timeline[0].axis",
            "zero",
        ),
        (
            "rotate_part",
            "door",
            "axis = [0, 0, 1]\nby_deg = 10\nduration_s = 0",
            "timeline[0].duration_s",
            "",
        ),
        (
            "rotate_part",
            "door",
            "axis = [0, 0, 1]\nby_deg = 1e7\nduration_s = 1",
            "timeline[0].by_deg",
            "out of range",
        ),
    ];
    for (action, part, fields, field, message) in cases {
        let entry = part_move(action, part, fields);
        let text = format!("{}{entry}", head());
        let e = match load_scene_str(&text, "scene.toml") {
            Ok(_) => panic!("{entry}: loaded"),
            Err(e) => e,
        };
        let said = e.to_string();
        assert_eq!(e.field(), Some(*field), "{entry}: {said}");
        assert!(said.contains(message), "{entry}: {said}");
    }
    // a part with a motion is not moved by a timeline, nor declared movable
    let hinge = r#"motion = { kind = "hinge", axis = [0, 0, 1], point = [0, 0, 0], angle_deg = { times_s = [0], values = [0] } }"#;
    let entry = part_move("move_part", "door", "by = [0, 0, 1]\nduration_s = 1");
    let text = format!("{}{hinge}\n{entry}", head());
    let e = load_scene_str(&text, "scene.toml").unwrap_err();
    assert_eq!(e.field(), Some("timeline[0].part"), "{e}");
    assert!(e.to_string().contains("has a `motion`"), "{e}");
    let e = load_scene_str(
        &format!("{}{hinge}\nmovable = true\n", head()),
        "scene.toml",
    )
    .unwrap_err();
    assert_eq!(e.field(), Some("parts[1].movable"), "{e}");
}

#[test]
fn a_live_session_moving_a_part_replays_bit_for_bit_and_converts_to_a_timeline() {
    // the door movable for live inputs (no timeline moves it)
    let text = format!("{}movable = true\n", head());
    let scene = load_scene_str(&text, "door.toml").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let opts = options(SolverKind::Explicit);
    let mut live = scene.workcell(opts).unwrap();
    let file = start_session_folder(dir.path(), &scene, &live).unwrap();
    live.log_to(Box::new(file));
    live.apply(Input::Mount {
        node: pliant_assembly::NodeRef { hose: 0, node: 6 },
        part: "door".into(),
    })
    .unwrap();
    live.steps(40, &mut NoObserver).unwrap();
    live.apply(Input::RotatePart {
        part: "door".into(),
        axis: DVec3::Z,
        point: Some(DVec3::new(0.5, 0.0, 0.0)),
        by: None,
        to: Some(0.5),
        duration: 0.1,
    })
    .unwrap();
    live.steps(30, &mut NoObserver).unwrap();
    live.apply(Input::MovePart {
        part: "door".into(),
        by: Some(DVec3::new(0.0, 0.0, 0.01)),
        to: None,
        duration: 0.05,
    })
    .unwrap();
    let n = live.steps_in(0.15);
    live.steps(n, &mut NoObserver).unwrap();
    live.log_mark();
    assert!(live.log_error().is_none());

    let session = Session::open(dir.path()).unwrap();
    assert_eq!(session.log.inputs, live.log().to_vec());
    let again = session.replayed().unwrap();
    assert_eq!(again.tick(), live.tick());
    assert_eq!(again.state().x, live.state().x, "positions bit for bit");
    assert_eq!(again.state().v, live.state().v, "velocities bit for bit");
    assert_eq!(again.state().part_moves, live.state().part_moves);
    assert_eq!(again.verdict(Stage::Final), live.verdict(Stage::Final));

    // the log as an editable scene with `rotate_part` and `move_part` actions
    let converted = log_to_scene(&scene, &session.log, live.time_step()).unwrap();
    assert!(converted.contains("rotate_part") && converted.contains("move_part"));
    let rerun_scene = load_scene_str_in(&converted, "converted.toml", &scene.base_dir).unwrap();
    let mut rerun = rerun_scene.workcell(opts).unwrap();
    run_timeline(&mut rerun, &rerun_scene.timeline, &mut NoObserver).unwrap();
    assert_eq!(rerun.tick(), live.tick());
    let worst = (0..live.state().x.len())
        .map(|i| (live.state().x[i] - rerun.state().x[i]).length())
        .fold(0.0, f64::max);
    // through the scene's millimetres and degrees and back: not bitwise, but close
    assert!(worst < 1e-6, "re-enacted positions differ by {worst} m");
}
