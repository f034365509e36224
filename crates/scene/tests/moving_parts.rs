//! Parts that move in the scene format: `motion` (hinge, slide, periodic, path) and
//! `parent`, converted to SI at the file boundary; broken entries name the field.

use glam::DVec3;
use pliant_assembly::{run_timeline, NoObserver, WorkcellOptions};
use pliant_core::kinematics::PartMotion;
use pliant_core::{Model, SolverKind};
use pliant_scene::{load_scene_str_in, LoadedScene, SceneError};
use pliant_testkit::scenes::{DOOR, HOSE3_300, RAISED_HOSE3_300, WEIGHTLESS_MM};
use std::path::{Path, PathBuf};

fn temp_dir(name: &str) -> PathBuf {
    pliant_testkit::files::scratch_dir("moving", name)
}

fn load_in(dir: &Path, parts: &str) -> Result<LoadedScene, SceneError> {
    load_scene_str_in(&format!("{RAISED_HOSE3_300}\n{parts}"), "scene.toml", dir)
}

const MOVING: &str = r#"
[[parts]]
name = "body"
box = { size = [100, 100, 100] }
position = [0, 500, 0]
motion = { kind = "periodic", centre = [0, 500, 0], roll = { amplitude = 2, frequency_hz = 1.5 }, z = { amplitude = 3, frequency_hz = 1.5, phase_deg = 90 } }

[[parts]]
name = "door"
box = { size = [10, 400, 600] }
position = [0, 800, 0]
parent = "body"
motion = { kind = "hinge", axis = [0, 0, 1], point = [0, 600, 0], angle_deg = { times_s = [0, 2, 4], values = [0, 70, 0] } }

[[parts]]
name = "seat"
box = { size = [100, 100, 10] }
position = [1000, 0, 0]
motion = { kind = "slide", direction = [0, 2, 0], distance = { times_s = [0, 1], values = [0, 250], smooth = false } }

[[parts]]
name = "engine"
sphere = { radius = 50 }
position = [0, 0, 500]
motion = { kind = "path", file = "engine.csv", centre = [0, 0, 500] }
"#;

#[test]
fn every_kind_loads_in_si_and_the_model_builds() {
    let dir = temp_dir("ok");
    std::fs::write(
        dir.join("engine.csv"),
        "time_s,x,y,z,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n0.5,1,0,2,1,0,0\n1,0,0,0,0,0,0\n",
    )
    .unwrap();
    let scene = load_in(&dir, MOVING).unwrap_or_else(|e| panic!("{e}"));
    let parts = &scene.world.rigid_parts;
    let Some(PartMotion::Periodic(p)) = &parts[0].motion else {
        panic!("body: {:?}", parts[0].motion)
    };
    assert!((p.centre - DVec3::new(0.0, 0.5, 0.0)).length() < 1e-12);
    assert!((p.rotation[0].amplitude - 2f64.to_radians()).abs() < 1e-15);
    assert!((p.translation[2].amplitude - 0.003).abs() < 1e-15);
    assert!((p.translation[2].phase - 90f64.to_radians()).abs() < 1e-15);
    let Some(PartMotion::Hinge(h)) = &parts[1].motion else {
        panic!("door: {:?}", parts[1].motion)
    };
    assert_eq!(parts[1].parent, Some(0));
    assert!((h.point - DVec3::new(0.0, 0.6, 0.0)).length() < 1e-12);
    assert!((h.angle.at(2.0).0 - 70f64.to_radians()).abs() < 1e-12);
    let Some(PartMotion::Slide(s)) = &parts[2].motion else {
        panic!("seat: {:?}", parts[2].motion)
    };
    assert!((s.direction - DVec3::Y).length() < 1e-15);
    assert!(
        (s.distance.at(0.5).0 - 0.125).abs() < 1e-12,
        "linear keyframes"
    );
    let Some(PartMotion::SampledPath(path)) = &parts[3].motion else {
        panic!("engine: {:?}", parts[3].motion)
    };
    assert_eq!(path.times, vec![0.0, 0.5, 1.0]);
    assert!((path.positions[1] - DVec3::new(0.001, 0.0, 0.002)).length() < 1e-15);
    let model = Model::build(&scene.world).unwrap_or_else(|e| panic!("{e}"));
    assert!(model.kinematics.any_moves());
    assert!((0..4).all(|k| model.kinematics.moves(k)));
    // the door turns with the body: at t = 2 s it is at 70° about the (moving) hinge
    let door = model
        .kinematics
        .placement_at(1, 2.0, &Default::default())
        .pose;
    let body = model
        .kinematics
        .placement_at(0, 2.0, &Default::default())
        .pose;
    let hinge_point = body.apply(DVec3::new(0.0, 0.6, 0.0));
    assert!((door.apply(DVec3::new(0.0, 0.6, 0.0)) - hinge_point).length() < 1e-12);
}

#[test]
fn broken_motions_name_the_field() {
    let dir = temp_dir("bad");
    std::fs::write(dir.join("short.csv"), "0,0,0,0\n").unwrap();
    let cases: &[(&str, &str, &str)] = &[
        (
            r#"motion = { kind = "spin" }"#,
            "parts[0].motion.kind",
            "must be one of",
        ),
        (
            r#"motion = { kind = "hinge", point = [0, 0, 0], angle_deg = { times_s = [0], values = [0] } }"#,
            "parts[0].motion.axis",
            "needs `axis`",
        ),
        (
            r#"motion = { kind = "hinge", axis = [0, 0, 0], point = [0, 0, 0], angle_deg = { times_s = [0], values = [0] } }"#,
            "parts[0].motion.axis",
            "zero vector",
        ),
        (
            r#"motion = { kind = "slide", direction = [1, 0, 0], distance = { times_s = [0, 0], values = [0, 1] } }"#,
            "parts[0].motion.distance.times_s[1]",
            "increase",
        ),
        (
            r#"motion = { kind = "slide", direction = [1, 0, 0], distance = { times_s = [0, 1], values = [0] } }"#,
            "parts[0].motion.distance.values",
            "one value per time",
        ),
        (
            r#"motion = { kind = "periodic", pitch = { amplitude = 1, frequency_hz = -1 } }"#,
            "parts[0].motion.pitch.frequency_hz",
            "negative",
        ),
        (
            r#"motion = { kind = "path", file = "short.csv" }"#,
            "parts[0].motion.file",
            "line 1",
        ),
        (
            r#"motion = { kind = "path", file = "missing.csv" }"#,
            "parts[0].motion.file",
            "missing.csv",
        ),
        (r#"parent = "nobody""#, "parts[0].parent", "names no part"),
        (r#"parent = "a""#, "parts[0].parent", "own parent"),
    ];
    for (entry, field, message) in cases {
        let parts = format!("[[parts]]\nname = \"a\"\nbox = {{ size = [10, 10, 10] }}\n{entry}\n");
        let e = match load_in(&dir, &parts) {
            Ok(_) => panic!("{entry}: loaded"),
            Err(e) => e,
        };
        let text = e.to_string();
        assert_eq!(e.field(), Some(*field), "{entry}: {text}");
        assert!(text.contains(message), "{entry}: {text}");
        assert!(text.contains("scene.toml"), "{entry}: {text}");
    }
    // a cycle of parents
    let cycle = "[[parts]]\nname = \"a\"\nbox = { size = [10, 10, 10] }\nparent = \"b\"\n\
                 [[parts]]\nname = \"b\"\nbox = { size = [10, 10, 10] }\nparent = \"a\"\n";
    let text = load_in(&dir, cycle).unwrap_err().to_string();
    assert!(text.contains("cycle"), "{text}");
}

/// A hose from a fixed body to a door: the door turns 0 → 60° about a vertical hinge in
/// 1 s; the hose end mounted on it goes along, under every solver.
fn door() -> String {
    let rest = r#"motion = { kind = "hinge", axis = [0, 0, 1], point = [500, 0, 0], angle_deg = { times_s = [0, 1], values = [0, 60] } }

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "mount"
hose = "h"
node = -1
part = "door"

[[timeline]]
action = "run"
duration_s = 1.2
"#;
    format!("{WEIGHTLESS_MM}{HOSE3_300}{DOOR}{rest}")
}

#[test]
fn a_hose_end_mounted_on_a_door_goes_with_it_under_every_solver() {
    let scene =
        pliant_scene::load_scene_str(&door(), "door.toml").unwrap_or_else(|e| panic!("{e}"));
    for solver in SolverKind::ALL {
        let options = WorkcellOptions {
            solver: Some(solver),
            initial_loads: false, // the runner gives the timeline's fix and mount
            ..Default::default()
        };
        let mut cell = scene.workcell(options).unwrap();
        run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
            .unwrap_or_else(|e| panic!("{solver}: {e}"));
        let state = cell.state();
        let end = *state.x.last().unwrap();
        // (0.3, 0, 0) turned by 60° about the vertical through (0.5, 0, 0)
        let turn = glam::DQuat::from_rotation_z(60f64.to_radians());
        let expected = DVec3::new(0.5, 0.0, 0.0) + turn * DVec3::new(-0.2, 0.0, 0.0);
        assert!(
            (end - expected).length() < 1e-9,
            "{solver}: end at {end:?}, door carries it to {expected:?}"
        );
        assert!(state.x.iter().all(|x| x.is_finite()));
    }
    // a part the scene has not is refused with its name
    let mut cell = scene.workcell(WorkcellOptions::default()).unwrap();
    let node = pliant_assembly::NodeRef { hose: 0, node: 3 };
    let e = cell
        .apply(pliant_assembly::Input::Mount {
            node,
            part: "hood".into(),
        })
        .unwrap_err();
    assert!(format!("{e}").contains("hood"), "{e}");
}

/// A hose fixed at both ends to one moving part is carried rigidly, under every solver.
#[test]
fn a_hose_fixed_at_both_ends_to_a_moving_part_moves_rigidly_under_every_solver() {
    // the door scene with both ends fixed to the door: `fix` with `part` (a mount) at each end
    let text = door()
        .replacen("node = 0\n", "node = 0\npart = \"door\"\n", 1)
        .replace("action = \"mount\"", "action = \"fix\"");
    let scene = pliant_scene::load_scene_str(&text, "door.toml").unwrap_or_else(|e| panic!("{e}"));
    let turn = glam::DQuat::from_rotation_z(60f64.to_radians());
    let hinge = DVec3::new(0.5, 0.0, 0.0);
    for solver in SolverKind::ALL {
        let options = WorkcellOptions {
            solver: Some(solver),
            initial_loads: false,
            ..Default::default()
        };
        let mut cell = scene.workcell(options).unwrap();
        let rest: Vec<DVec3> = cell.state().x.clone();
        run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
            .unwrap_or_else(|e| panic!("{solver}: {e}"));
        let x = &cell.state().x;
        let worst = rest
            .iter()
            .zip(x)
            .map(|(&r, &now)| (hinge + turn * (r - hinge) - now).length())
            .fold(0.0, f64::max);
        // every node where the door carries it: no strain, no sag (no gravity); the
        // dynamic solvers keep a little of the swing's inertial load (µm over 0.3 m)
        eprintln!("{solver}: {worst:.3e} m from the carried shape");
        assert!(worst < 1e-5, "{solver}: {worst} m from the carried shape");
        let strain = x
            .windows(2)
            .zip(rest.windows(2))
            .map(|(a, b)| ((a[1] - a[0]).length() / (b[1] - b[0]).length() - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!("{solver}: strain {strain:.3e}");
        assert!(strain < 1e-5, "{solver}: strain {strain}");
    }
    // `fix` with `part` is a mount
    assert!(matches!(
        &scene.timeline.actions[0],
        pliant_assembly::Action::Mount { part, .. } if part == "door"
    ));
}
