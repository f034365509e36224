//! One bad request never takes the server down: a panic while serving one client
//! — with both shared locks held, so that they are poisoned — ends that client's connection
//! only, its hands are released, and a later client is served as usual; a panic in the
//! scene loader is an `invalid_scene` reply and the connection lives on.
//!
//! The panics are injected through hooks compiled only into this crate's unit-test build
//! (`#[cfg(test)]` in `server.rs`, keyed on the constants below). That is why these tests
//! live here and not in `crates/server/tests/`: integration tests link the ordinary library,
//! and a cargo feature for the hooks would be unified into the `pliant` binary that
//! `cargo test --workspace` builds (and the viewer's end-to-end tests then run).

use super::*;
use futures_util::{SinkExt, StreamExt};
use serde_json::{json, Value};
use tokio_tungstenite::tungstenite::Message as WsMessage;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

/// Test hook: this exact text message makes the handler panic holding both locks.
pub(super) const PANIC_HOLDING_LOCKS: &str = "test hook: panic holding the locks";
/// Test hook: a `load_scene` with this name makes the loader panic holding the session lock.
pub(super) const PANIC_IN_LOADER: &str = "test hook: panic in the loader";

/// Only against hangs: every wait below is for a condition, and this bound is far above
/// any machine's time for it (it is not a performance expectation).
const HANG_GUARD: Duration = Duration::from_secs(300);

type Ws = WebSocketStream<MaybeTlsStream<tokio::net::TcpStream>>;

/// A server on an ephemeral port whose shared state the test can inspect.
async fn serve_shared() -> (Arc<Shared>, SocketAddr) {
    let scene = pliant_scene::demo_scene().unwrap();
    let session = Session::start(&scene, SessionOptions::default()).unwrap();
    let shared = Arc::new(Shared::new(session, &ServerConfig::default()));
    let listener = TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let app = router_on(shared.clone());
    tokio::spawn(async move { axum::serve(listener, app).await });
    (shared, addr)
}

async fn connect(addr: SocketAddr) -> Ws {
    tokio_tungstenite::connect_async(format!("ws://{addr}/ws"))
        .await
        .unwrap()
        .0
}

async fn send(ws: &mut Ws, v: Value) {
    ws.send(WsMessage::text(v.to_string())).await.unwrap();
}

/// The next message of type `ty` satisfying `pred`; an unexpected `error` fails the test.
async fn next(ws: &mut Ws, ty: &str, pred: impl Fn(&Value) -> bool) -> Value {
    tokio::time::timeout(HANG_GUARD, async {
        loop {
            let msg = ws.next().await.expect("connection open").expect("message");
            if let WsMessage::Text(t) = msg {
                let v: Value = serde_json::from_str(t.as_str()).unwrap();
                assert!(v["type"] != "error" || ty == "error", "unexpected {v}");
                if v["type"] == ty && pred(&v) {
                    return v;
                }
            }
        }
    })
    .await
    .unwrap_or_else(|_| panic!("no {ty} message within the hang guard"))
}

async fn hello(ws: &mut Ws) {
    send(ws, json!({"type": "hello", "version": 1})).await;
    next(ws, "welcome", |_| true).await;
}

/// Waits until the server closes `ws`.
async fn closed(ws: &mut Ws) {
    tokio::time::timeout(HANG_GUARD, async {
        while let Some(Ok(_)) = ws.next().await {}
    })
    .await
    .expect("the connection is closed");
}

fn hand_ids(snap: &Value) -> Vec<u64> {
    snap["hands"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| h["hand_id"].as_u64().unwrap())
        .collect()
}

fn node(snap: &Value, i: usize) -> Value {
    snap["hoses"][0]["positions"][i].clone()
}

#[test]
fn lock_recovers_a_poisoned_mutex() {
    let m = Mutex::new(7);
    std::thread::scope(|s| {
        s.spawn(|| {
            let _g = m.lock().unwrap();
            panic!("poison it");
        })
        .join()
        .unwrap_err();
    });
    assert!(m.is_poisoned());
    *lock(&m) += 1;
    assert_eq!(*lock(&m), 8);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_panic_serving_one_client_leaves_the_server_to_the_others() {
    let (shared, addr) = serve_shared().await;
    let mut a = connect(addr).await;
    hello(&mut a).await;
    let snap = next(&mut a, "snapshot", |_| true).await;
    let p = node(&snap, 3);
    send(&mut a, json!({"type": "grab", "hand_id": 3, "position": p})).await;
    next(&mut a, "snapshot", |v| hand_ids(v) == [3]).await;
    a.send(WsMessage::text(PANIC_HOLDING_LOCKS)).await.unwrap();
    closed(&mut a).await;
    assert!(shared.session.is_poisoned() && shared.ownership.is_poisoned());
    // a later client gets its welcome and snapshots, a's hand is released, and the same
    // hand id is free to grab
    let mut b = connect(addr).await;
    hello(&mut b).await;
    next(&mut b, "snapshot", |v| hand_ids(v).is_empty()).await;
    send(&mut b, json!({"type": "grab", "hand_id": 3, "position": p})).await;
    next(&mut b, "snapshot", |v| hand_ids(v) == [3]).await;
    send(&mut b, json!({"type": "release", "hand_id": 3})).await;
    next(&mut b, "snapshot", |v| hand_ids(v).is_empty()).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_panic_in_the_scene_loader_is_an_error_reply() {
    let (shared, addr) = serve_shared().await;
    let mut a = connect(addr).await;
    hello(&mut a).await;
    send(
        &mut a,
        json!({"type": "load_scene", "text": "", "name": PANIC_IN_LOADER}),
    )
    .await;
    let e = next(&mut a, "error", |_| true).await;
    assert_eq!(e["code"], "invalid_scene");
    let message = e["message"].as_str().unwrap();
    assert!(message.contains("the loader panics"), "{message}");
    assert!(shared.session.is_poisoned());
    // the connection and the old session carry on, and a new client is served
    let t0 = next(&mut a, "snapshot", |_| true).await["time"]
        .as_f64()
        .unwrap();
    next(&mut a, "snapshot", |v| v["time"].as_f64().unwrap() > t0).await;
    let mut b = connect(addr).await;
    hello(&mut b).await;
    next(&mut b, "snapshot", |_| true).await;
}
