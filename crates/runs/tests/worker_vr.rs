//! SPEC E1 ("in VR the user's headset and controllers drive it (their real
//! posture recorded in the session log and replayed bit for bit)"): a live session whose
//! worker is posed by headset and controller inputs writes them into its log, and the
//! session folder replays to the same worker — every posed instant, every score —
//! and the same state, bit for bit. The headset really poses him: the same session
//! without it gives another posture.

use glam::DVec3;
use pliant_assembly::worker::BodyPose;
use pliant_assembly::{Input, NoObserver, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_runs::session::{start_session_folder, Session};
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{fix, hose, worker, SceneText};
use pliant_worker::{body, HeadTarget, Manikin, Placement, Population, Sex, TrunkAngles};

/// The 5th-percentile woman (or, without `worker`, nobody) beside a 250 mm hose along x
/// fixed at its start.
fn vr_scene(with_worker: bool) -> String {
    let her = worker("female")
        .number("percentile", 5.0)
        .point("position", [0.0, 0.0, 0.0])
        .point("facing", [1.0, 0.0, 0.0]);
    let (start, end) = ([200.0, -250.0, 1000.0], [450.0, -250.0, 1000.0]);
    SceneText::mm()
        .with_all(with_worker.then_some(her))
        .with(hose("h", "hose3", start, end).number("elements", 10.0))
        .with(fix("h", 0))
        .into()
}

/// The 5th-percentile woman of the scene, where the scene stands her.
fn manikin() -> Manikin {
    Manikin::new(
        body(Population::new(Sex::Female, 5.0).unwrap()).unwrap(),
        Placement::new(DVec3::ZERO, DVec3::X, DVec3::Z).unwrap(),
    )
}

/// A headset bending forward (her eyes where they are at 10° + k° of trunk flexion)
/// and looking round, the left controller waving: one pose per 20 ms.
fn pose(k: usize) -> BodyPose {
    let s = k as f64 * 0.1;
    let gaze = DVec3::new(1.0, 0.3 * s.cos(), -0.6);
    let bent = TrunkAngles {
        flexion: (10.0 + k as f64).to_radians(),
        ..TrunkAngles::default()
    };
    let head = |eyes| Some(HeadTarget { eyes, gaze });
    let eyes = manikin()
        .posture_with_head(bent, [None, None], head(DVec3::ZERO))
        .joints
        .head;
    BodyPose {
        head: head(eyes),
        hands: [None, Some(DVec3::new(0.3, 0.2 + 0.05 * s.sin(), 1.0))],
    }
}

/// The headset walking forward upright, 50 mm per pose, looking ahead.
fn walking(k: usize) -> BodyPose {
    let eye = manikin().body.dims.eye_height;
    BodyPose {
        head: Some(HeadTarget {
            eyes: DVec3::new(0.05 * k as f64, 0.0, eye),
            gaze: DVec3::X,
        }),
        hands: [None, None],
    }
}

/// The live session: a hand holds the hose end, and (with `poses`) headset poses arrive.
fn live_session(
    poses: Option<fn(usize) -> BodyPose>,
    dir: &std::path::Path,
) -> pliant_assembly::Workcell {
    let scene = load_scene_str(&vr_scene(true), "vr.toml").unwrap();
    let options = WorkcellOptions {
        solver: Some(SolverKind::Explicit),
        initial_loads: false,
        ..Default::default()
    };
    let mut live = scene.workcell(options).unwrap();
    let file = start_session_folder(dir, &scene, &live).unwrap();
    live.log_to(Box::new(file));
    live.apply(Input::Fix {
        node: pliant_assembly::NodeRef { hose: 0, node: 0 },
    })
    .unwrap();
    live.apply(Input::Grab {
        hand: 0,
        at: DVec3::new(0.45, -0.25, 1.0),
        grip: pliant_assembly::Grip::Firm,
    })
    .unwrap();
    for k in 0..12 {
        if let Some(pose) = poses {
            live.apply(Input::WorkerPose { pose: pose(k) }).unwrap();
        }
        let n = live.steps_in(0.02);
        live.steps(n, &mut NoObserver).unwrap();
    }
    live.log_mark();
    assert!(live.log_error().is_none());
    live
}

#[test]
fn headset_inputs_are_logged_and_replay_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let live = live_session(Some(pose), dir.path());
    let series = live.worker_series();
    assert!(series.len() > 5, "{}", series.len());
    // the manikin's eyes are where the headset is; the left arm follows its controller
    let now = live.worker().unwrap().now().unwrap();
    let eyes = pose(11).head.unwrap().eyes;
    assert!(
        (now.posture.joints.head - eyes).length() < 2e-3,
        "eyes {} for the headset's {eyes}",
        now.posture.joints.head
    );
    let left = now.posture.arms[1];
    assert!(left.target.is_some() && left.residual < 1e-3, "{left:?}");

    let session = Session::open(dir.path()).unwrap();
    assert_eq!(session.log.inputs, live.log().to_vec());
    assert!(session
        .log
        .inputs
        .iter()
        .any(|s| matches!(s.input, Input::WorkerPose { .. })));
    let again = session.replayed().unwrap();
    assert_eq!(again.tick(), live.tick());
    assert_eq!(
        again.worker_series(),
        live.worker_series(),
        "every posed instant"
    );
    assert_eq!(again.summary().worker, live.summary().worker);
    assert_eq!(again.worker().unwrap().now(), live.worker().unwrap().now());
    assert_eq!(again.state().x, live.state().x, "positions bit for bit");

    // without the headset: another posture
    let other = tempfile::tempdir().unwrap();
    let plain = live_session(None, other.path());
    assert_ne!(plain.worker_series(), live.worker_series());
    // a headset that leans does not move the feet
    assert_eq!(live.summary().worker.unwrap().step_count, 0);
}

/// The feet walk with the user: a headset walking 0.55 m forward upright moves the
/// stance under it in steps just longer than a lean reaches (the head's length above
/// the shoulders, upright), reported, and replayed bit for bit.
#[test]
fn the_feet_walk_with_the_headset_and_replay_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let live = live_session(Some(walking), dir.path());
    let w = live.summary().worker.unwrap();
    let b = manikin().body;
    let head = b.dims.eye_height - b.dims.shoulder_height;
    assert!(w.step_count >= 2, "{:?}", w.steps);
    for s in &w.steps {
        assert_eq!(s.cause, pliant_assembly::worker::StepCause::Walk);
        assert!(s.length > head && s.length <= head + 0.05 + 1e-12, "{s:?}");
        assert!(s.words.ends_with(" m forward"), "{s:?}");
        assert_eq!(s.to.y, 0.0);
        assert_eq!(s.to.z, 0.0);
    }
    // the last step put the pelvis under the headset then: within one lean of the last pose
    let last = w.placement.unwrap().position;
    assert!(0.55 - last.x <= head, "{last}");
    let v = pliant_assembly::Verdict::judge(&live.summary(), None, pliant_assembly::Stage::Final);
    assert!(
        v.worker
            .iter()
            .any(|l| l.starts_with("the 5th-percentile woman steps ")
                && l.ends_with("(with the VR user)")),
        "{:?}",
        v.worker
    );
    let session = Session::open(dir.path()).unwrap();
    let again = session.replayed().unwrap();
    assert_eq!(again.worker_series(), live.worker_series());
    assert_eq!(again.summary().worker, live.summary().worker);
    assert_eq!(again.worker().unwrap().now(), live.worker().unwrap().now());
}

#[test]
fn a_body_pose_is_refused_without_a_worker_or_with_bad_values() {
    let scene = load_scene_str(&vr_scene(true), "vr.toml").unwrap();
    let mut cell = scene.workcell(WorkcellOptions::default()).unwrap();
    let logged = cell.log().to_vec().len();
    let bad = BodyPose {
        head: Some(HeadTarget {
            eyes: DVec3::new(0.0, 0.0, 1.6),
            gaze: DVec3::ZERO,
        }),
        hands: [None, None],
    };
    let e = cell.apply(Input::WorkerPose { pose: bad }).unwrap_err();
    assert!(e.to_string().contains("head gaze"), "{e}");
    let nan = BodyPose {
        head: None,
        hands: [Some(DVec3::new(f64::NAN, 0.0, 1.0)), None],
    };
    let e = cell.apply(Input::WorkerPose { pose: nan }).unwrap_err();
    assert!(e.to_string().contains("right hand position"), "{e}");
    assert_eq!(
        cell.log().to_vec().len(),
        logged,
        "refused inputs are not logged"
    );
    let without = load_scene_str(&vr_scene(false), "plain.toml").unwrap();
    let mut cell = without.workcell(WorkcellOptions::default()).unwrap();
    let e = cell.apply(Input::WorkerPose { pose: pose(0) }).unwrap_err();
    assert!(e.to_string().contains("no [worker]"), "{e}");
}
