//! The snapshot's per-beam fields for the viewer's colour modes (issue 11 item 4) and each
//! hand's grip (issue 11 item 2), over a real WebSocket connection. The session is paused
//! and advances only by `step` requests: nothing depends on the machine's speed.

use futures_util::{SinkExt, StreamExt};
use pliant_server::session::SessionOptions;
use pliant_server::{start, RunningServer, ServerConfig, Session};
use serde_json::{json, Value};
use std::time::{Duration, Instant};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

type Ws = WebSocketStream<MaybeTlsStream<TcpStream>>;
/// Stops a hung test only; no wait is a performance expectation.
const HANG_GUARD: Duration = Duration::from_secs(300);

/// A hose routed as a half circle of radius 100 mm (library hose1: minimum bend radius
/// 68 mm) in the x–y plane, no gravity, both ends fixed; and a straight one, its first
/// node fixed.
const SCENE: &str = r#"
format = "pliant-scene"
version = 1
name = "bent"
length_unit = "mm"
[simulation]
gravity = [0, 0, 0]
[[hoses]]
name = "arc"
material = "hose1"
start = [0, 0, 0]
path = [{ arc = { via = [100, 100, 0], to = [200, 0, 0] } }]
[[hoses]]
name = "straight"
material = "hose1"
start = [0, 300, 0]
path = [{ line = { to = [300, 300, 0] } }]
[[timeline]]
action = "fix"
hose = "arc"
node = 0
[[timeline]]
action = "fix"
hose = "arc"
node = -1
[[timeline]]
action = "fix"
hose = "straight"
node = 0
"#;

async fn serve() -> RunningServer {
    let dir = tempfile::tempdir().unwrap();
    let scene = pliant_scene::load_scene_str_in(SCENE, "bent.toml", dir.path()).unwrap();
    let options = SessionOptions {
        paused: true,
        ..SessionOptions::default()
    };
    let session = Session::start(&scene, options).unwrap();
    let config = ServerConfig {
        host: "127.0.0.1".into(),
        port: 0,
        ..ServerConfig::default()
    };
    start(session, &config).await.unwrap()
}

async fn send(ws: &mut Ws, v: Value) {
    ws.send(Message::text(v.to_string())).await.unwrap();
}

/// Next message of `type` satisfying `pred` (failing only after HANG_GUARD).
async fn next_where(ws: &mut Ws, ty: &str, pred: impl Fn(&Value) -> bool) -> Value {
    let deadline = Instant::now() + HANG_GUARD;
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        let msg = tokio::time::timeout(left, ws.next())
            .await
            .unwrap_or_else(|_| panic!("no {ty} message within the hang guard"))
            .expect("connection open")
            .expect("message");
        if let Message::Text(t) = msg {
            let v: Value = serde_json::from_str(t.as_str()).unwrap();
            if v["type"] == ty && pred(&v) {
                return v;
            }
        }
    }
}

async fn connect(s: &RunningServer) -> (Ws, Value) {
    let (mut ws, _) = tokio_tungstenite::connect_async_with_config(s.ws_url(), None, true)
        .await
        .unwrap();
    send(&mut ws, json!({"type": "hello", "version": 1})).await;
    let welcome = next_where(&mut ws, "welcome", |_| true).await;
    (ws, welcome)
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_hose_bent_to_a_known_radius_reports_its_ratio_to_the_minimum() {
    let s = serve().await;
    let (mut ws, welcome) = connect(&s).await;
    let hose = &welcome["session"]["hoses"][0];
    let min_radius = hose["min_bend_radius"].as_f64().unwrap();
    assert!(
        (min_radius - 0.068).abs() < 1e-9,
        "hose1: 68 mm, {min_radius}"
    );
    let twist_limit = welcome["session"]["twist_limit"].as_f64().unwrap();
    assert!((twist_limit - 10f64.to_radians()).abs() < 1e-9);
    let snap = next_where(&mut ws, "snapshot", |_| true).await;
    let arc = &snap["hoses"][0];
    let beams = arc["positions"].as_array().unwrap().len() - 1;
    let ratio = floats(&arc["bend_radius_ratio"]);
    assert_eq!(ratio.len(), beams, "one value per beam");
    // κ = 1/R of the routed arc on the inner beams (the rest length is the chord:
    // within 1 %); the end nodes' frames follow the end chords, so the two end beams
    // turn through half the angle
    for (k, r) in ratio.iter().enumerate() {
        let expected = if k == 0 || k == beams - 1 { 0.34 } else { 0.68 };
        assert!(
            (r - expected).abs() < expected * 0.01,
            "beam {k}: {r}, expected {expected}: {ratio:?}"
        );
    }
    // at rest: no twist relative to the routed hose, no axial force
    for x in floats(&arc["twist"]) {
        assert!(x.abs() < 1e-3, "twist {x} rad/m");
    }
    for f in floats(&arc["axial_force"]) {
        assert!(f.abs() < 1e-2, "axial force {f} N");
    }
    let straight = floats(&snap["hoses"][1]["bend_radius_ratio"]);
    assert!(straight.iter().all(|r| r.abs() < 1e-6), "{straight:?}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_stretched_hose_reports_tension_and_a_hand_its_grip() {
    let s = serve().await;
    let (mut ws, _) = connect(&s).await;
    // the straight hose's free end pulled 3 mm along its axis by a ball grip
    send(
        &mut ws,
        json!({"type": "grab", "hand_id": 2, "position": [0.3, 0.3, 0.0], "grip": "ball"}),
    )
    .await;
    send(
        &mut ws,
        json!({"type": "move", "hand_id": 2, "position": [0.303, 0.3, 0.0]}),
    )
    .await;
    let held = next_where(&mut ws, "snapshot", |v| {
        v["hands"].as_array().is_some_and(|h| h.len() == 1)
    })
    .await;
    assert_eq!(held["hands"][0]["grip"], "ball");
    let mut step = held["step"].as_u64().unwrap();
    let mut last = held;
    for _ in 0..50 {
        let target = [0.303, 0.3, 0.0];
        let at = &last["hands"][0]["position"];
        if (at[0].as_f64().unwrap() - target[0]).abs() < 1e-6 {
            break;
        }
        send(&mut ws, json!({"type": "step", "n": 2000})).await;
        last = next_where(&mut ws, "snapshot", |v| {
            v["step"].as_u64().is_some_and(|s| s >= step + 2000)
        })
        .await;
        step = last["step"].as_u64().unwrap();
    }
    // a few more steps for the hose to follow the hand
    send(&mut ws, json!({"type": "step", "n": 4000})).await;
    let snap = next_where(&mut ws, "snapshot", |v| {
        v["step"].as_u64().is_some_and(|s| s >= step + 4000)
    })
    .await;
    let force = floats(&snap["hoses"][1]["axial_force"]);
    let middle = force[force.len() / 2];
    // 1 % strain: E_t·A of hose1 gives well over 1 N; the sign says stretched
    assert!(middle > 1.0, "axial force {middle} N (stretched: positive)");
    assert_eq!(snap["hands"][0]["grip"], "ball");
}
