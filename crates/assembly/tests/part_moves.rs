//! Parts moved by inputs (`move_part`, `rotate_part`): a hose mounted at both ends on a
//! moved part goes with it rigidly under every solver (the closed form: every node at the
//! part's pose applied to where it was); a hose lying on a plate that is lifted rises with
//! it; a study with part moves replays bit for bit, through its log's text too, and
//! continues bit for bit from a checkpoint taken mid-move; bad moves are refused with
//! the reason.

use glam::{DQuat, DVec3};
use pliant_assembly::workcell::log::{line_text, InputLog, LogHeader, LogLine};
use pliant_assembly::workcell::replay::replay;
use pliant_assembly::{
    Input, NoObserver, NodeRef, Refusal, Stage, Workcell, WorkcellOptions, WorkcellSetup,
};
use pliant_core::kinematics::{Hinge, PartMotion, Profile};
use pliant_core::{HoseSpec, Model, RigidPartSpec, SimSettings, SolverKind, WorldSpec};
use pliant_testkit::hose3;
use std::sync::Arc;

/// A flat square plate of half-size `h` at height `z`, centred on (cx, 0).
fn plate(name: &str, cx: f64, z: f64, h: f64, movable: bool) -> RigidPartSpec {
    RigidPartSpec {
        name: name.into(),
        vertices: vec![
            DVec3::new(cx - h, -h, z),
            DVec3::new(cx + h, -h, z),
            DVec3::new(cx + h, h, z),
            DVec3::new(cx - h, h, z),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        friction_static: 0.5,
        friction_sliding: 0.4,
        movable,
        ..Default::default()
    }
}

/// Hose 3 in 12 beams of 25 mm along X at height `z`, with these parts and gravity.
fn model(z: f64, parts: Vec<RigidPartSpec>, gravity: DVec3) -> Arc<Model> {
    let (material, section) = hose3();
    Arc::new(
        Model::build(&WorldSpec {
            hoses: vec![HoseSpec {
                name: "h".into(),
                material,
                nodes: (0..=12)
                    .map(|i| DVec3::new(0.025 * i as f64, 0.0, z))
                    .collect(),
                sections: vec![section],
                normal_hint: Some(DVec3::Y),
            }],
            rigid_parts: parts,
            settings: SimSettings {
                gravity,
                ..Default::default()
            },
        })
        .unwrap(),
    )
}

fn workcell(model: Arc<Model>, solver: SolverKind) -> Workcell {
    Workcell::new(
        WorkcellSetup::bare(model),
        WorkcellOptions {
            solver: Some(solver),
            ..Default::default()
        },
    )
    .unwrap()
}

fn node(k: usize) -> NodeRef {
    NodeRef { hose: 0, node: k }
}

/// Far below the hose, out of its reach: it only carries the mounted ends.
fn carrier() -> Vec<RigidPartSpec> {
    vec![
        plate("floor", 0.15, -1.0, 0.5, false),
        plate("tray", 0.15, -0.5, 0.2, true),
    ]
}

const TURN: f64 = 1.0; // rad
const PIVOT: DVec3 = DVec3::new(0.15, 0.0, 0.0);
const LIFT: DVec3 = DVec3::new(0.0, 0.02, 0.05);

/// Mounts both ends of the hose on the tray, turns it by [`TURN`] about Z through
/// [`PIVOT`] and lifts it by [`LIFT`], each over 0.4 s, then waits 0.4 s.
fn carry(cell: &mut Workcell) {
    for k in [0, 12] {
        cell.apply(Input::Mount {
            node: node(k),
            part: "tray".into(),
        })
        .unwrap();
    }
    cell.apply(Input::RotatePart {
        part: "tray".into(),
        axis: DVec3::Z * 3.0,
        point: Some(PIVOT),
        by: Some(TURN),
        to: None,
        duration: 0.4,
    })
    .unwrap();
    let n = cell.steps_until_done(0.4);
    cell.steps(n, &mut NoObserver).unwrap();
    cell.apply(Input::MovePart {
        part: "tray".into(),
        by: Some(LIFT),
        to: None,
        duration: 0.4,
    })
    .unwrap();
    let n = cell.steps_until_done(0.4) + cell.steps_in(0.4);
    cell.steps(n, &mut NoObserver).unwrap();
}

/// The closed form of the carry: x ↦ R (x − p) + p + d.
fn carried(x: DVec3) -> DVec3 {
    DQuat::from_rotation_z(TURN) * (x - PIVOT) + PIVOT + LIFT
}

#[test]
fn a_hose_mounted_on_a_moved_part_goes_with_it_rigidly_under_every_solver() {
    for solver in SolverKind::ALL {
        let m = model(0.0, carrier(), DVec3::ZERO);
        let mut cell = workcell(m.clone(), solver);
        let start = cell.state().x.clone();
        carry(&mut cell);
        assert!(!cell.moving(), "{solver}: the moves have ended");
        // the part's pose is the closed form, to rounding
        let pose = m
            .kinematics
            .placement_at(1, cell.state().time, &cell.state().part_moves)
            .pose;
        let probe = DVec3::new(0.3, -0.1, 0.2);
        assert!((pose.apply(probe) - carried(probe)).length() < 1e-12);
        // every node of the hose at the carried place: the hose moved rigidly
        let worst = start
            .iter()
            .zip(&cell.state().x)
            .map(|(x0, x)| (carried(*x0) - *x).length())
            .fold(0.0, f64::max);
        eprintln!("{solver}: hose off the rigid carry by {worst:.2e} m");
        assert!(worst < 2e-5, "{solver}: {worst} m off the rigid carry");
        let strain = cell.state().strain_energy(&m);
        assert!(strain < 1e-6, "{solver}: strain energy {strain} J");
    }
}

#[test]
fn a_hose_lying_on_a_lifted_plate_rises_with_it() {
    for solver in SolverKind::ALL {
        // the hose (radius 17.5 mm) lying on the plate
        let parts = vec![plate("plate", 0.15, 0.0, 0.3, true)];
        let m = model(0.0175, parts, DVec3::new(0.0, 0.0, -9.81));
        let mut cell = workcell(m.clone(), solver);
        let n = cell.steps_in(0.5);
        cell.steps(n, &mut NoObserver).unwrap();
        let mean_z = |c: &Workcell| c.state().x.iter().map(|x| x.z).sum::<f64>() / 13.0;
        let before = mean_z(&cell);
        cell.apply(Input::MovePart {
            part: "plate".into(),
            by: None,
            to: Some(DVec3::Z * 0.04),
            duration: 0.5,
        })
        .unwrap();
        let n = cell.steps_until_done(0.5) + cell.steps_in(0.5);
        cell.steps(n, &mut NoObserver).unwrap();
        let rise = mean_z(&cell) - before;
        eprintln!("{solver}: resting at z {before:.5} m, rose by {rise:.5} m");
        assert!(
            (before - 0.0175).abs() < 2e-4,
            "{solver}: rests on the plate, z {before}"
        );
        assert!((rise - 0.04).abs() < 2e-4, "{solver}: rose by {rise} m");
    }
}

/// A study whose log has part moves, for replays.
fn study(solver: SolverKind) -> Workcell {
    let mut cell = workcell(model(0.0, carrier(), DVec3::ZERO), solver);
    carry(&mut cell);
    // a turn interrupted by another (the second starts from where the first got to)
    cell.apply(Input::RotatePart {
        part: "tray".into(),
        axis: DVec3::X,
        point: None,
        by: Some(-0.3),
        to: None,
        duration: 0.3,
    })
    .unwrap();
    let n = cell.steps_in(0.1);
    cell.steps(n, &mut NoObserver).unwrap();
    cell
}

fn assert_same(a: &Workcell, b: &Workcell) {
    assert_eq!(a.tick(), b.tick());
    let bits = |v: &[DVec3]| {
        v.iter()
            .flat_map(|p| p.to_array())
            .map(f64::to_bits)
            .collect::<Vec<_>>()
    };
    assert_eq!(bits(&a.state().x), bits(&b.state().x), "positions");
    assert_eq!(bits(&a.state().v), bits(&b.state().v), "velocities");
    assert_eq!(a.state().part_moves, b.state().part_moves, "part moves");
    assert_eq!(a.summary(), b.summary());
    assert_eq!(a.verdict(Stage::Final), b.verdict(Stage::Final));
}

#[test]
fn a_study_with_part_moves_replays_bit_for_bit_through_its_log_text() {
    for solver in SolverKind::ALL {
        let mut live = study(solver);
        let n = live.steps_in(0.3);
        live.steps(n, &mut NoObserver).unwrap();
        // the log as written to a session's inputs.jsonl, and read back
        let header = LogHeader::new(
            "t",
            "t",
            "scene.toml",
            ".",
            *live.options(),
            live.time_step(),
        );
        let mut text = line_text(&LogLine::Header { header });
        for s in live.log().iter() {
            text.push_str(&line_text(&LogLine::Input(s.clone())));
        }
        text.push_str(&line_text(&LogLine::Mark { tick: live.tick() }));
        assert!(text.contains("\"rotate_part\"") && text.contains("\"move_part\""));
        let log = InputLog::parse(&text, "inputs.jsonl").unwrap();
        assert_eq!(log.inputs, live.log().to_vec());
        let mut again = workcell(live.model().clone(), solver);
        replay(&mut again, &log.inputs, log.end_tick, &mut NoObserver).unwrap();
        assert_same(&live, &again);
    }
}

#[test]
fn a_checkpoint_mid_move_continues_bit_for_bit_and_a_reset_puts_the_part_back() {
    for solver in SolverKind::ALL {
        let mut cell = study(solver);
        let saved = cell.checkpoint();
        assert!(cell.moving(), "{solver}: saved mid-turn");
        let n = cell.steps_in(0.3);
        cell.steps(n, &mut NoObserver).unwrap();
        let end = cell.state().clone();
        cell.restore(&saved).unwrap();
        cell.steps(n, &mut NoObserver).unwrap();
        assert_eq!(cell.state().x, end.x);
        assert_eq!(cell.state().part_moves, end.part_moves);
        cell.apply(Input::Reset).unwrap();
        assert!(!cell.state().part_moves.any());
        let pose = cell
            .model()
            .kinematics
            .placement_at(1, 0.0, &cell.state().part_moves)
            .pose;
        assert_eq!(pose, pliant_core::kinematics::Pose::IDENTITY);
    }
}

#[test]
fn a_turn_to_an_angle_counts_from_where_the_scene_placed_the_part() {
    let m = model(0.0, carrier(), DVec3::ZERO);
    let mut cell = workcell(m.clone(), SolverKind::Static);
    let turn = |cell: &mut Workcell, by: Option<f64>, to: Option<f64>, axis: DVec3| {
        cell.apply(Input::RotatePart {
            part: "tray".into(),
            axis,
            point: Some(PIVOT),
            by,
            to,
            duration: 0.05,
        })
    };
    let rest = |cell: &mut Workcell| {
        let n = cell.steps_until_done(0.05);
        cell.steps(n, &mut NoObserver).unwrap();
    };
    let angle_of = |cell: &Workcell| {
        let pose = m
            .kinematics
            .placement_at(1, cell.state().time, &cell.state().part_moves)
            .pose;
        let (axis, angle) = pose.rotation.to_axis_angle();
        angle * axis.z.signum()
    };
    turn(&mut cell, Some(0.5), None, DVec3::Z).unwrap();
    rest(&mut cell);
    // about the opposite axis, to 2.0 rad about it: a turn of −2.5 about +Z
    turn(&mut cell, None, Some(2.0), -DVec3::Z).unwrap();
    rest(&mut cell);
    assert!((angle_of(&cell) + 2.0).abs() < 1e-12, "{}", angle_of(&cell));
    turn(&mut cell, None, Some(0.0), DVec3::Z).unwrap();
    rest(&mut cell);
    assert!(angle_of(&cell).abs() < 1e-12);
    // once turned about another axis, an angle `to` is not defined
    turn(&mut cell, Some(0.2), None, DVec3::X).unwrap();
    rest(&mut cell);
    let e = turn(&mut cell, None, Some(1.0), DVec3::Z).unwrap_err();
    assert!(e.to_string().contains("another axis"), "{e}");
    // `to` of move_part: the centre back where the scene placed it
    cell.apply(Input::MovePart {
        part: "tray".into(),
        by: Some(DVec3::X),
        to: None,
        duration: 0.05,
    })
    .unwrap();
    rest(&mut cell);
    turn(&mut cell, Some(-0.2), None, DVec3::X).unwrap();
    rest(&mut cell);
    cell.apply(Input::MovePart {
        part: "tray".into(),
        by: None,
        to: Some(DVec3::ZERO),
        duration: 0.05,
    })
    .unwrap();
    rest(&mut cell);
    let pose = m
        .kinematics
        .placement_at(1, cell.state().time, &cell.state().part_moves)
        .pose;
    let centre = DVec3::new(0.15, 0.0, -0.5);
    assert!((pose.apply(centre) - centre).length() < 1e-12);
}

#[test]
fn bad_part_moves_are_refused_with_the_reason_and_change_nothing() {
    let mut parts = carrier();
    parts.push(RigidPartSpec {
        motion: Some(PartMotion::Hinge(Hinge {
            point: DVec3::ZERO,
            axis: DVec3::Z,
            angle: Profile::ramp(0.0, 1.0, 0.0, 1.0),
        })),
        ..plate("door", 2.0, 0.0, 0.1, false)
    });
    let mut cell = workcell(model(0.0, parts, DVec3::ZERO), SolverKind::Explicit);
    let shift = |part: &str, by: Option<DVec3>, to: Option<DVec3>, duration: f64| Input::MovePart {
        part: part.into(),
        by,
        to,
        duration,
    };
    let turn = |axis: DVec3, by: f64, point: Option<DVec3>| Input::RotatePart {
        part: "tray".into(),
        axis,
        point,
        by: Some(by),
        to: None,
        duration: 1.0,
    };
    let cases: Vec<(Input, &str)> = vec![
        (
            shift("lid", Some(DVec3::X), None, 1.0),
            "no part named \"lid\" (parts: floor, tray, door)",
        ),
        (
            shift("door", Some(DVec3::X), None, 1.0),
            "scripted motion (hinge)",
        ),
        (shift("floor", Some(DVec3::X), None, 1.0), "movable = true"),
        (
            shift("tray", Some(DVec3::X), Some(DVec3::X), 1.0),
            "not both",
        ),
        (shift("tray", None, None, 1.0), "not neither"),
        (shift("tray", Some(DVec3::NAN), None, 1.0), "must be finite"),
        (
            shift("tray", Some(DVec3::X * 5e3), None, 1.0),
            "farther than a part moves",
        ),
        (
            shift("tray", Some(DVec3::X), None, 0.0),
            "a part does not jump",
        ),
        (
            shift("tray", Some(DVec3::X), None, f64::INFINITY),
            "duration",
        ),
        (turn(DVec3::ZERO, 1.0, None), "axis must not be zero"),
        (turn(DVec3::Z, f64::NAN, None), "angle must be finite"),
        (turn(DVec3::Z, 1e6, None), "ten turns"),
        (
            turn(DVec3::Z, 1.0, Some(DVec3::splat(f64::INFINITY))),
            "point must be finite",
        ),
    ];
    let before = cell.state().clone();
    for (input, says) in cases {
        let what = format!("{input:?}");
        match cell.apply(input) {
            Err(Refusal::Invalid(e)) => assert!(e.contains(says), "{what}: {e}"),
            other => panic!("{what}: {other:?}"),
        }
    }
    assert!(cell.log().is_empty(), "refused inputs are not logged");
    assert_eq!(cell.state().part_moves, before.part_moves);
}
