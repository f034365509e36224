//! A buckling met by the static solver in a live session reaches the
//! snapshot — time, hose, node and mode shape — as it reaches `summary.json` and Python.
//! A hose clamped at one end by a hand is pushed by another hand from the far end to
//! 70 % of its length; past the Euler load the straight hose is unstable and buckles.
//! The session runs paused and advances only by `step` commands; waits are for
//! conditions, with a hang guard only.

mod static_session;

use glam::DVec3;
use pliant_scene::load_scene_str_in;
use pliant_server::session::Command;

const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "a column pushed past buckling by hand"
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]

[[hoses]]
name = "column"
material = "hose1"
start = [0, 0, 0]
path = [{ line = { to = [1000, 0, 0] } }]
elements = 40
"#;

const STEPS: u32 = 60;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_buckling_in_a_live_static_session_reaches_the_snapshot() {
    let scene = load_scene_str_in(SCENE, "column.toml", std::path::Path::new(".")).unwrap();
    let session = static_session::start(&scene);
    let grip = Default::default();
    session
        .send(Command::Grab {
            hand: 1,
            position: DVec3::ZERO,
            grip,
        })
        .unwrap();
    session
        .send(Command::Grab {
            hand: 2,
            position: DVec3::new(1.0, 0.0, 0.0),
            grip,
        })
        .unwrap();
    session
        .send(Command::Move {
            hand: 2,
            position: DVec3::new(0.7, 0.0, 0.0),
            orientation: None,
        })
        .unwrap();
    let snapshot = static_session::step(&session, STEPS).await;
    let end = snapshot.hoses[0].positions[40];
    assert!(
        (end[0] - 0.7).abs() < 1e-6,
        "the hand pushed the end to 0.7 m: {end:?}"
    );
    assert!(
        !snapshot.instabilities.is_empty(),
        "no instability in the snapshot; verdict {:?}",
        snapshot.verdict
    );
    let first = &snapshot.instabilities[0];
    assert_eq!(first.hose, 0);
    assert!(!first.limit_point && first.negative_eigenvalues >= 1);
    assert!(first.time > 0.0 && first.time <= snapshot.time);
    assert_eq!(first.mode.len(), 41, "one mode entry per node of the hose");
    let largest = first
        .mode
        .iter()
        .map(|m| DVec3::from_array(*m).length())
        .fold(0.0, f64::max);
    assert!(
        (largest - 1.0).abs() < 1e-12,
        "the mode is scaled to 1: {largest}"
    );
    // the buckled hose left the straight line, and the verdict says it buckled
    let mid = snapshot.hoses[0].positions[20];
    assert!(mid[1].hypot(mid[2]) > 0.1, "buckled: mid-span at {mid:?}");
    assert!(
        snapshot
            .verdict
            .reasons
            .iter()
            .any(|r| r.contains("buckled")),
        "{:?}",
        snapshot.verdict.reasons
    );
    // and the JSON carries it
    let json: serde_json::Value = serde_json::from_str(snapshot.json()).unwrap();
    assert!(json["instabilities"][0]["mode"].as_array().unwrap().len() == 41);
}
