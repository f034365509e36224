//! The haptic force stream (SPEC H1, docs/protocol.md "Haptic force stream"): answers
//! are the session's static equilibrium for the same pose, sequence numbers are echoed,
//! malformed datagrams are counted (and only requests answered), hands keep their owners, the token is
//! required when the server has one. Every wait is for a condition (with a hang guard),
//! never for a duration; nothing here depends on the machine's speed.

use futures_util::SinkExt;
use glam::DVec3;
use pliant_core::SolverKind;
use pliant_server::access::Access;
use pliant_server::haptic::datagram::{Kind, Reply, Request, Status, KEY_BYTES, REQUEST_BYTES};
use pliant_server::haptic::priority;
use pliant_server::session::SessionOptions;
use pliant_server::{start, RunningServer, ServerConfig, Session};
use std::net::UdpSocket;
use std::time::{Duration, Instant};
use tokio_tungstenite::tungstenite::Message;

/// A hang guard, not a performance expectation.
const HANG_GUARD: Duration = Duration::from_secs(300);

/// The built-in demo's scene file: a coolant hose (library hose 3), fixed at its first
/// node, its free end at [`END`] (the session runs none of its timeline's motions).
const SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/demo.toml");
/// The hose's free end \[m\].
const END: DVec3 = DVec3::new(0.4, 0.33, 0.3);

async fn server(solver: SolverKind, access: Access) -> RunningServer {
    let scene = pliant_scene::load_scene_file(std::path::Path::new(SCENE)).unwrap();
    let session = Session::start(
        &scene,
        SessionOptions {
            solver: Some(solver),
            ..SessionOptions::default()
        },
    )
    .unwrap();
    let config = ServerConfig {
        port: 0,
        haptic_port: Some(0),
        access,
        ..ServerConfig::default()
    };
    start(session, &config).await.unwrap()
}

struct Client {
    socket: UdpSocket,
    sequence: u64,
    key: [u8; KEY_BYTES],
}

impl Client {
    fn new(s: &RunningServer) -> Client {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket.connect(s.haptic_addr().unwrap()).unwrap();
        socket.set_read_timeout(Some(HANG_GUARD)).unwrap();
        Client {
            socket,
            sequence: 1 << 40, // beyond 32 bits: the echo must keep all 64
            key: [0; KEY_BYTES],
        }
    }

    /// Sends raw bytes, returns the reply.
    fn raw(&self, bytes: &[u8]) -> Reply {
        self.socket.send(bytes).unwrap();
        let mut buf = [0u8; 256];
        let n = self
            .socket
            .recv(&mut buf)
            .expect("a reply to every datagram");
        Reply::decode(&buf[..n]).expect("a well-formed reply")
    }

    fn ask(&mut self, kind: Kind, hand: u32, position: DVec3) -> Reply {
        self.sequence += 1;
        let request = Request::new(kind, hand, self.sequence, position, self.key);
        let reply = self.raw(&request.encode());
        assert_eq!(
            reply.sequence, self.sequence,
            "the sequence number is echoed"
        );
        assert_eq!(reply.hand, hand);
        reply
    }

    /// Grabs at `at` and sends that pose until the session has taken the grab.
    fn grab(&mut self, hand: u32, at: DVec3) {
        let r = self.ask(Kind::Grab(pliant_assembly::Grip::Firm), hand, at);
        assert_eq!(r.status, Status::Pending, "{r:?}");
        let deadline = Instant::now() + HANG_GUARD;
        loop {
            let r = self.ask(Kind::Pose, hand, at);
            if r.status == Status::Ok {
                return;
            }
            assert_eq!(r.status, Status::Pending, "{r:?}");
            assert!(Instant::now() < deadline, "the grab was never taken");
            std::thread::yield_now();
        }
    }
}

fn close(a: DVec3, b: DVec3, relative: f64, absolute: f64) -> bool {
    (a - b).length() <= relative * a.length().max(b.length()) + absolute
}

/// With the session on the static solver, the stream's force and torque for a pose are
/// the session's own equilibrium loads once the session's hand has arrived there: within
/// 0.1 % + 1 mN (and 0.1 % + 0.1 mN·m), i.e. the two solves' convergence tolerance.
/// The session's hand follows the stream's pose (the viewer sees the same hand).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn stream_force_equals_the_sessions() {
    let s = server(SolverKind::Static, Access::local()).await;
    let mut c = Client::new(&s);
    c.grab(1, END);
    // lift the end and pull it in: a bent hose, loads well above round-off
    let pose = END + DVec3::new(0.05, -0.1, 0.08);
    let deadline = Instant::now() + HANG_GUARD;
    let mut arrived: Option<f64> = None;
    // the first answer for the pose is solved from the session's state before its hand
    // moved: an equilibrium found from elsewhere
    let first = c.ask(Kind::Pose, 1, pose);
    assert_eq!(first.status, Status::Ok, "{first:?}");
    assert!(first.iterations > 0, "{first:?}");
    let (reply, snap) = loop {
        assert!(
            Instant::now() < deadline,
            "the session's hand never settled at the pose"
        );
        let reply = c.ask(Kind::Pose, 1, pose);
        assert!(reply.status.has_load(), "{reply:?}");
        let snap = s.session().latest();
        let Some(hand) = snap.hands.iter().find(|h| h.hand_id == 1) else {
            continue;
        };
        if DVec3::from_array(hand.position) != pose {
            continue;
        }
        // the hand is there: the mirror must start from a session state solved with the
        // hand at the pose, and the snapshot compared must be one as well
        let t = *arrived.get_or_insert(snap.time);
        if reply.status == Status::Ok && reply.session_time > t + 0.015 && snap.time > t + 0.015 {
            break (reply, snap);
        }
    };
    let hand = snap.hands.iter().find(|h| h.hand_id == 1).unwrap();
    let (fs, ts) = (
        DVec3::from_array(hand.force),
        DVec3::from_array(hand.torque),
    );
    eprintln!(
        "stream {} N, {} N·m; session {fs} N, {ts} N·m; differences {:.3e} N, {:.3e} N·m \
         (first answer, {} iterations from the old pose: {:.3e} N, {:.3e} N·m)",
        reply.force,
        reply.torque,
        (reply.force - fs).length(),
        (reply.torque - ts).length(),
        first.iterations,
        (first.force - fs).length(),
        (first.torque - ts).length()
    );
    assert!(
        fs.length() > 0.1,
        "a bent, lifted hose pulls on the hand: {fs}"
    );
    assert!(
        close(reply.force, fs, 1e-3, 1e-3),
        "stream force {} vs the session's {fs}",
        reply.force
    );
    assert!(
        close(reply.torque, ts, 1e-3, 1e-4),
        "stream torque {} vs the session's {ts}",
        reply.torque
    );
    assert!(
        close(first.force, fs, 1e-3, 1e-3) && close(first.torque, ts, 1e-3, 1e-4),
        "the first answer ({} N, {} N·m) is the same equilibrium",
        first.force,
        first.torque
    );
    assert_eq!(reply.hose, 0);
    session_thread_gave_way();
    // a pose elsewhere gives another answer at once (the stream solves for the pose
    // sent, not the session's lagging hand)
    let other = c.ask(Kind::Pose, 1, END + DVec3::new(0.0, -0.05, 0.0));
    assert!(other.status.has_load(), "{other:?}");
    assert!((other.force - reply.force).length() > 1e-3);
    // released: the session lets go, the stream says so
    assert_eq!(c.ask(Kind::Release, 1, pose).status, Status::Ok);
    assert_eq!(c.ask(Kind::Pose, 1, pose).status, Status::NotHeld);
}

/// Once a stream has been answered from the session's state, the session thread runs
/// [`priority::SESSION_NICE_INCREMENT`] nice levels below the rest of the process, whose
/// other threads keep their priority (Linux, where the nice value is the thread's). The
/// test process may hold other tests' sessions: one `pliant-sim` thread at that value is
/// what is asserted.
fn session_thread_gave_way() {
    if !cfg!(target_os = "linux") {
        return;
    }
    let nice_of = |stat: &str| -> i32 {
        // the fields after the command's closing parenthesis start at field 3; nice is 19
        let rest = &stat[stat.rfind(')').expect("a stat line") + 2..];
        rest.split(' ').nth(19 - 3).unwrap().parse().unwrap()
    };
    // the test's own thread has the process's priority (`nice cargo test` included)
    let own = nice_of(&std::fs::read_to_string("/proc/thread-self/stat").unwrap());
    let lowered = (own + priority::SESSION_NICE_INCREMENT).min(priority::NICE_MAX);
    let mut sessions = Vec::new();
    for task in std::fs::read_dir("/proc/self/task").unwrap() {
        let dir = task.unwrap().path();
        let (Ok(name), Ok(stat)) = (
            std::fs::read_to_string(dir.join("comm")),
            std::fs::read_to_string(dir.join("stat")),
        ) else {
            continue; // a thread that ended meanwhile
        };
        if name.trim() == "pliant-sim" {
            sessions.push(nice_of(&stat));
        }
    }
    assert!(
        sessions.contains(&lowered),
        "session threads' nice values {sessions:?}, the process's {own}"
    );
}

/// Only a datagram of a request's size and magic is answered (a reply is
/// smaller than it: the port amplifies nothing; 0–4-byte datagrams used to get 96-byte
/// answers); the rest are counted and dropped. A request with a bad value — a position or
/// an orientation non-finite or absurd (\[1e200, …\]) — is answered with its status. The
/// stream answers valid poses afterwards as before. Silence is checked without waiting:
/// each dropped datagram is followed by a valid request, whose reply must come first and
/// count the dropped one.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn malformed_datagrams_are_counted_and_only_requests_answered() {
    let s = server(SolverKind::Explicit, Access::local()).await;
    let mut c = Client::new(&s);
    let valid = Request::new(Kind::Pose, 3, 77, END, [0; KEY_BYTES]).encode();
    let with = |at: usize, bytes: &[u8]| {
        let mut b = valid;
        b[at..at + bytes.len()].copy_from_slice(bytes);
        b
    };
    let absurd: Vec<u8> = (0..4).flat_map(|_| 1e200_f64.to_le_bytes()).collect();
    let dropped: Vec<Vec<u8>> = vec![
        vec![],
        vec![1, 2, 3],
        b"PLHP".to_vec(),
        valid[..REQUEST_BYTES - 1].to_vec(),
        [&valid[..], &[0]].concat(),
        with(0, b"NOPE").to_vec(), // a wrong magic
    ];
    let answered: Vec<(Vec<u8>, Status)> = vec![
        (with(4, &[9]).to_vec(), Status::UnsupportedVersion),
        (with(5, &[7]).to_vec(), Status::Malformed),
        (with(5, &[1, 9]).to_vec(), Status::InvalidValue),
        (
            with(24, &f64::NAN.to_le_bytes()).to_vec(),
            Status::InvalidValue,
        ),
        (
            with(32, &2e3_f64.to_le_bytes()).to_vec(),
            Status::InvalidValue,
        ),
        (
            with(48, &f64::INFINITY.to_le_bytes()).to_vec(),
            Status::InvalidValue,
        ),
        (with(48, &absurd).to_vec(), Status::InvalidValue),
    ];
    let mut counted = 0;
    for (k, bytes) in dropped.iter().enumerate() {
        c.socket.send(bytes).unwrap();
        counted += 1;
        // the next reply is the release's (hand 3 is not held), counting the dropped one
        let r = c.ask(Kind::Release, 3, END);
        assert_eq!(
            r.status,
            Status::NotHeld,
            "case {k}: {bytes:?} was answered"
        );
        assert_eq!(r.malformed, counted, "case {k} counted");
    }
    for (k, (bytes, status)) in answered.iter().enumerate() {
        c.socket.send(bytes).unwrap();
        let mut buf = [0u8; 256];
        let n = c.socket.recv(&mut buf).expect("a reply to a request");
        assert!(
            n < bytes.len(),
            "case {k}: a reply of {n} bytes to {}",
            bytes.len()
        );
        let r = Reply::decode(&buf[..n]).expect("a well-formed reply");
        counted += 1;
        assert_eq!(r.status, *status, "case {k}: {bytes:?}");
        assert_eq!(r.malformed, counted, "case {k} counted");
        assert!(!r.status.has_load() && r.force == DVec3::ZERO);
        assert_eq!(r.sequence, 77, "case {k}: the sequence is echoed");
    }
    // a pose for a hand never grabbed
    assert_eq!(c.ask(Kind::Pose, 3, DVec3::ZERO).status, Status::NotHeld);
    assert_eq!(c.ask(Kind::Release, 3, DVec3::ZERO).status, Status::NotHeld);
    // and the stream still works: grab, then a run of poses, each echoed
    c.grab(3, END);
    for k in 0..20 {
        let p = END + DVec3::new(0.0, -0.001 * k as f64, 0.001 * k as f64);
        let r = c.ask(Kind::Pose, 3, p);
        assert!(r.status.has_load(), "{r:?}");
        assert!(r.force.is_finite() && r.torque.is_finite());
        assert_eq!(r.malformed, counted);
    }
}

/// A hand a WebSocket client holds cannot be moved or released through the stream, and
/// with a token every datagram must carry it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn hands_keep_their_owner_and_the_token_is_required() {
    let token = "haptic-test-token-123".to_string();
    let access = Access::for_host("127.0.0.1", Some(token.clone()), vec![]).unwrap();
    let s = server(SolverKind::Explicit, access).await;
    let mut c = Client::new(&s);
    let end = END;
    assert_eq!(c.ask(Kind::Pose, 2, end).status, Status::Unauthorised);
    let mut wrong = token.clone().into_bytes();
    wrong[0] ^= 1;
    c.key = Request::key_for(std::str::from_utf8(&wrong).ok()).unwrap();
    assert_eq!(c.ask(Kind::Pose, 2, end).status, Status::Unauthorised);
    c.key = Request::key_for(Some(&token)).unwrap();
    assert_eq!(c.ask(Kind::Pose, 2, end).status, Status::NotHeld);

    let url = format!("{}?token={token}", s.ws_url());
    let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
    let send = |v: serde_json::Value| Message::text(v.to_string());
    ws.send(send(serde_json::json!({"type": "hello", "version": 1})))
        .await
        .unwrap();
    ws.send(send(
        serde_json::json!({"type": "grab", "hand_id": 2, "position": END.to_array()}),
    ))
    .await
    .unwrap();
    // the WebSocket grab is registered when the session shows the hand
    let deadline = Instant::now() + HANG_GUARD;
    while !s.session().latest().hands.iter().any(|h| h.hand_id == 2) {
        assert!(
            Instant::now() < deadline,
            "the WebSocket grab was never taken"
        );
        tokio::time::sleep(Duration::from_millis(1)).await;
    }
    assert_eq!(c.ask(Kind::Pose, 2, end).status, Status::HandOwned);
    assert_eq!(c.ask(Kind::Release, 2, end).status, Status::HandOwned);
    let grab = c.ask(Kind::Grab(pliant_assembly::Grip::Firm), 2, end);
    assert_eq!(grab.status, Status::HandOwned);
    // another hand is the stream's to take
    c.grab(4, DVec3::new(0.3, 0.0, 0.0));
    assert!(c
        .ask(Kind::Pose, 4, DVec3::new(0.3, 0.0, 0.01))
        .status
        .has_load());
}
