//! The HTTP/WebSocket shell (axum): `GET /ws` speaks the protocol, every other path serves
//! the embedded browser viewer ([`crate::assets`]). Each connection is one task: it reads
//! the client's messages (checking size, rate, form and ownership) and sends the newest
//! snapshot at most 60 times a second, skipping stale ones. A slow client only slows its
//! own task; the simulation never waits. `load_scene` replaces the session for every
//! client: each connection notices the new generation and sends a new `welcome`.
//!
//! One bad request never takes the server down: a panic while handling one client ends that
//! client's connection only (it is caught, logged and its hands are released), a panic in
//! the scene loader is an `invalid_scene` reply, and the shared locks recover from a panic
//! of an earlier holder (`lock`).

use crate::access::{token_in_query, Access};
use crate::limits::{
    Admit, ClientScenes, RateLimiter, HARD_MAX_MESSAGE_BYTES, MAX_MESSAGE_BYTES,
    MAX_SCENE_MESSAGE_BYTES, MAX_STEPS_PER_REQUEST,
};
use crate::ownership::{ClientId, Ownership, Refusal};
use crate::protocol::{
    error_json, ClientMessage, ErrorCode, SceneSource, ServerMessage, PROTOCOL_VERSION,
};
use crate::session::{Command, Session, SessionOptions};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::{RawQuery, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use futures_util::FutureExt;
use glam::{DQuat, DVec3};
use pliant_assembly::ergonomics::ErgonomicProfile;
use pliant_assembly::Input;
use pliant_core::math::near_unit_quaternion;
use std::any::Any;
use std::net::SocketAddr;
use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};
use tokio::net::TcpListener;
use tokio::sync::watch;

/// Most snapshots sent to one client per second, as a rule.
pub const SNAPSHOT_HZ: f64 = 60.0;
/// After a client's accepted command, the first snapshot published after it goes out to
/// that client without waiting for the 60 Hz pacing, but at most this often \[Hz\]: the
/// reply to input comes sooner (lower hand-to-screen latency), and a client gets at most as
/// many extra snapshots as it sends commands.
pub const INPUT_SNAPSHOT_HZ: f64 = 240.0;

/// Where to listen.
#[derive(Clone, Debug)]
pub struct ServerConfig {
    pub host: String,
    /// 0 picks a free port.
    pub port: u16,
    /// Relative mesh paths of scenes sent with `load_scene` are resolved against this
    /// folder (the browser sends only the scene text).
    pub scene_dir: PathBuf,
    /// Sessions started by `load_scene` record into a new folder here (SPEC W2);
    /// `None`: they keep their log in memory only (a `report` is then refused).
    pub sessions_dir: Option<PathBuf>,
    /// Who may open the WebSocket ([`crate::access`]).
    pub access: Access,
    /// A connection that has not said `hello` this long after its handshake is closed.
    pub hello_timeout: Duration,
    /// Most clients at once, counting those that have said `hello` (sockets
    /// that never greet must not lock viewers out; they are closed after
    /// [`Self::hello_timeout`]). With this many, the next handshake gets 503 and a
    /// `hello` on a connection opened meanwhile gets `server_full`, until one leaves.
    pub max_clients: usize,
    /// How scenes sent with `load_scene` are loaded (sandbox, limits).
    pub client_scenes: ClientScenes,
    /// The haptic force stream's UDP port on 127.0.0.1 (0 picks a free one; `None`: no
    /// stream). Always loopback, whatever `host` is ([`crate::haptic`]).
    pub haptic_port: Option<u16>,
    /// The haptic stream solves each pose on the whole scene rather than on the part
    /// the hand can move ([`crate::haptic::mirror::Mirror::set_cutting`]): the same
    /// answers, slower; for comparing the two.
    pub haptic_whole_scene: bool,
}

/// Default [`ServerConfig::hello_timeout`].
pub const HELLO_TIMEOUT: Duration = Duration::from_secs(10);
/// Default [`ServerConfig::max_clients`].
pub const MAX_CLIENTS: usize = 64;

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            host: "127.0.0.1".into(),
            port: 8080,
            scene_dir: PathBuf::new(),
            sessions_dir: None,
            access: Access::local(),
            hello_timeout: HELLO_TIMEOUT,
            max_clients: MAX_CLIENTS,
            client_scenes: ClientScenes::default(),
            haptic_port: None,
            haptic_whole_scene: false,
        }
    }
}

/// A new folder for a session under `dir`: `session-<unix seconds>[-k]`, not yet taken.
pub fn new_session_folder(dir: &std::path::Path) -> PathBuf {
    let stamp = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let first = dir.join(format!("session-{stamp}"));
    if !first.exists() {
        return first;
    }
    (2..)
        .map(|k| dir.join(format!("session-{stamp}-{k}")))
        .find(|p| !p.exists())
        .unwrap_or(first)
}

pub(crate) struct Shared {
    /// The session every client talks to; replaced by `load_scene`.
    session: Mutex<Arc<Session>>,
    /// Counts session replacements; connections watch it to follow the new session.
    generation: watch::Sender<u64>,
    pub(crate) ownership: Mutex<Ownership>,
    next_client: AtomicU64,
    scene_dir: PathBuf,
    sessions_dir: Option<PathBuf>,
    pub(crate) access: Access,
    hello_timeout: Duration,
    max_clients: usize,
    client_scenes: ClientScenes,
    /// Clients that have said `hello` and are connected now (slots taken by
    /// [`ClientSlot`]).
    clients: AtomicUsize,
}

/// One greeted client's place under [`ServerConfig::max_clients`], taken at its `hello`
/// and given back when dropped (the connection ends).
struct ClientSlot(Arc<Shared>);

impl ClientSlot {
    fn take(shared: &Arc<Shared>) -> Option<Self> {
        let before = shared.clients.fetch_add(1, Ordering::SeqCst);
        let slot = ClientSlot(shared.clone());
        (before < shared.max_clients).then_some(slot)
    }

    /// Whether every slot is taken now.
    fn all_taken(shared: &Shared) -> bool {
        shared.clients.load(Ordering::SeqCst) >= shared.max_clients
    }
}

impl Drop for ClientSlot {
    fn drop(&mut self) {
        self.0.clients.fetch_sub(1, Ordering::SeqCst);
    }
}

impl Shared {
    fn new(session: Session, config: &ServerConfig) -> Self {
        Shared {
            session: Mutex::new(Arc::new(session)),
            generation: watch::channel(0).0,
            ownership: Mutex::new(Ownership::default()),
            next_client: AtomicU64::new(1),
            scene_dir: config.scene_dir.clone(),
            sessions_dir: config.sessions_dir.clone(),
            access: config.access.clone(),
            hello_timeout: config.hello_timeout,
            max_clients: config.max_clients,
            client_scenes: config.client_scenes,
            clients: AtomicUsize::new(0),
        }
    }

    pub(crate) fn session(&self) -> Arc<Session> {
        lock(&self.session).clone()
    }
}

/// Locks `m` even if an earlier holder panicked. A std `Mutex` is poisoned when a thread
/// panics while holding it, and `lock().unwrap()` would then panic for every later client:
/// one bad request would refuse all clients after it. Taking the data over is sound here:
/// the server's locks guard an `Arc<Session>` that is replaced in one assignment and the
/// hand [`Ownership`] table, changed by single map operations, so a panic cannot leave
/// either half-updated. Every lock of the server goes through this function.
pub(crate) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The message of a caught panic, for the log and error replies.
fn panic_message(payload: &(dyn Any + Send)) -> &str {
    payload
        .downcast_ref::<&str>()
        .copied()
        .or_else(|| payload.downcast_ref::<String>().map(String::as_str))
        .unwrap_or("no message")
}

/// The router for one session.
pub fn router(session: Session, config: &ServerConfig) -> Router {
    router_on(Arc::new(Shared::new(session, config)))
}

fn router_on(shared: Arc<Shared>) -> Router {
    Router::new()
        .route("/ws", get(ws_upgrade))
        .fallback(get(crate::assets::static_file))
        .with_state(shared)
}

/// Serves `session` on `listener` until the task is dropped.
pub async fn serve(
    listener: TcpListener,
    session: Session,
    config: ServerConfig,
) -> std::io::Result<()> {
    serve_shared(listener, Arc::new(Shared::new(session, &config))).await
}

/// A connection whose request headers have not all arrived this long after it opened
/// (or after its last request) is closed: half-sent headers hold no connection open.
pub const HEADER_READ_TIMEOUT: Duration = Duration::from_secs(10);

/// Accepts connections and serves each on its own task: HTTP/1 (with upgrades for the
/// WebSocket) or HTTP/2, with [`HEADER_READ_TIMEOUT`].
async fn serve_shared(listener: TcpListener, shared: Arc<Shared>) -> std::io::Result<()> {
    use hyper_util::rt::{TokioExecutor, TokioIo, TokioTimer};
    use hyper_util::server::conn::auto::Builder;
    use hyper_util::service::TowerToHyperService;
    let service = TowerToHyperService::new(router_on(shared));
    loop {
        let (tcp, _) = match listener.accept().await {
            Ok(conn) => conn,
            // a failed accept (e.g. out of file descriptors) ends no other connection
            Err(e) => {
                eprintln!("pliant serve: accept failed: {e}");
                tokio::time::sleep(Duration::from_millis(50)).await;
                continue;
            }
        };
        // No Nagle delay: small messages (moves, snapshots) go out at once.
        let _ = tcp.set_nodelay(true);
        let service = service.clone();
        tokio::spawn(async move {
            let mut builder = Builder::new(TokioExecutor::new());
            builder
                .http1()
                .timer(TokioTimer::new())
                .header_read_timeout(HEADER_READ_TIMEOUT);
            // a broken or timed-out connection ends only itself
            let _ = builder
                .serve_connection_with_upgrades(TokioIo::new(tcp), service)
                .await;
        });
    }
}

/// A server running on the current tokio runtime.
pub struct RunningServer {
    pub addr: SocketAddr,
    task: tokio::task::JoinHandle<std::io::Result<()>>,
    shared: Arc<Shared>,
    haptic: Option<crate::haptic::HapticStream>,
}

impl RunningServer {
    /// `http://host:port/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }
    /// `ws://host:port/ws`.
    pub fn ws_url(&self) -> String {
        format!("ws://{}/ws", self.addr)
    }
    /// Serves until the server fails.
    pub async fn wait(&mut self) -> std::io::Result<()> {
        (&mut self.task).await.unwrap_or(Ok(()))
    }
    /// Stops serving (the session stops when its last connection ends).
    pub fn stop(&self) {
        self.task.abort();
        if let Some(h) = &self.haptic {
            h.stop();
        }
    }
    /// The haptic stream's address (127.0.0.1:port), if it runs.
    pub fn haptic_addr(&self) -> Option<SocketAddr> {
        self.haptic.as_ref().map(|h| h.addr)
    }
    /// The session clients talk to now.
    pub fn session(&self) -> Arc<Session> {
        self.shared.session()
    }
}

/// Binds `config.host:config.port` and serves `session` in a background task.
pub async fn start(session: Session, config: &ServerConfig) -> std::io::Result<RunningServer> {
    let listener = TcpListener::bind((config.host.as_str(), config.port)).await?;
    let addr = listener.local_addr()?;
    let shared = Arc::new(Shared::new(session, config));
    let haptic = match config.haptic_port {
        Some(port) => Some(crate::haptic::HapticStream::start(
            shared.clone(),
            port,
            !config.haptic_whole_scene,
        )?),
        None => None,
    };
    let task = tokio::spawn(serve_shared(listener, shared.clone()));
    Ok(RunningServer {
        addr,
        task,
        shared,
        haptic,
    })
}

/// The WebSocket handshake: refused with 403/401 and a plain-text reason unless
/// [`Access::check`] admits it.
async fn ws_upgrade(
    ws: WebSocketUpgrade,
    headers: HeaderMap,
    RawQuery(query): RawQuery,
    State(shared): State<Arc<Shared>>,
) -> Response {
    let header = |name: header::HeaderName| headers.get(name).and_then(|v| v.to_str().ok());
    if let Err(refusal) = shared.access.check(
        header(header::ORIGIN),
        header(header::HOST),
        token_in_query(query.as_deref()),
    ) {
        let status = StatusCode::from_u16(refusal.status()).unwrap_or(StatusCode::FORBIDDEN);
        return (status, refusal.message()).into_response();
    }
    if ClientSlot::all_taken(&shared) {
        return (StatusCode::SERVICE_UNAVAILABLE, server_full(&shared)).into_response();
    }
    ws.max_message_size(HARD_MAX_MESSAGE_BYTES)
        .max_frame_size(HARD_MAX_MESSAGE_BYTES)
        .on_upgrade(move |socket| async move {
            let client = shared.next_client.fetch_add(1, Ordering::SeqCst);
            // A panic while serving this client ends its connection only: it is caught
            // here and logged, and the client's hands are released as on a disconnect.
            // (axum runs this future in its own task, so tokio would contain the panic
            // too, but silently and with the hands still held.) Unwind safety: what the
            // connection shares with others is behind `lock`, atomics and watch channels.
            let served = AssertUnwindSafe(connection(socket, client, &shared))
                .catch_unwind()
                .await;
            if let Err(panic) = served {
                eprintln!(
                    "pliant serve: internal error while serving client {client} (panic: {}); \
                     its connection is closed, other clients carry on",
                    panic_message(&*panic)
                );
            }
            // A disconnecting client's hands are released.
            let session = shared.session();
            let epoch = session.epoch();
            let mine = lock(&shared.ownership).release_all_of(client, epoch);
            for hand in mine {
                session.send_waiting(Command::Release { hand });
            }
        })
        .into_response()
}

fn server_full(shared: &Shared) -> String {
    format!(
        "the server is full: {} clients connected (--max-clients); try again later",
        shared.max_clients
    )
}

/// What to do after a text message.
enum Reply {
    None,
    Text(String),
    /// Load this scene (slow: done off the connection's task).
    LoadScene {
        text: String,
        json: bool,
        name: String,
    },
    /// Write the session's report (slow: replays the session off the connection's task).
    Report,
}

impl From<Option<String>> for Reply {
    fn from(o: Option<String>) -> Self {
        o.map_or(Reply::None, Reply::Text)
    }
}

fn welcome(client: ClientId, session: &Session) -> String {
    ServerMessage::Welcome {
        version: PROTOCOL_VERSION,
        client_id: client,
        session: session.scene(),
    }
    .to_json()
}

async fn connection(mut socket: WebSocket, client: ClientId, shared: &Arc<Shared>) {
    let mut generation = shared.generation.subscribe();
    generation.mark_unchanged();
    let mut session = shared.session();
    let mut snapshots = session.subscribe();
    let mut limiter = RateLimiter::default();
    let mut welcomed = false;
    // taken at hello: a connection that never greets holds no client slot
    let mut slot: Option<ClientSlot> = None;
    let interval = Duration::from_secs_f64(1.0 / SNAPSHOT_HZ);
    let fast_interval = Duration::from_secs_f64(1.0 / INPUT_SNAPSHOT_HZ);
    let mut last_send = tokio::time::Instant::now() - interval;
    // a command of this client was accepted since the last snapshot sent to it
    let mut input_pending = false;
    let hello_deadline = tokio::time::Instant::now() + shared.hello_timeout;
    loop {
        tokio::select! {
            _ = tokio::time::sleep_until(hello_deadline), if !welcomed => {
                // a connection that says nothing holds a slot and a task: closed
                let reason = format!("no hello within {:?}", shared.hello_timeout);
                let close = axum::extract::ws::CloseFrame { code: 1008, reason: reason.into() };
                let _ = socket.send(Message::Close(Some(close))).await;
                return;
            }
            incoming = socket.recv() => {
                let Some(Ok(msg)) = incoming else { return };
                // The reply to a command is the first snapshot published after it, so the
                // snapshots published so far are marked seen *before* the command reaches
                // the simulation: marked after, a snapshot published in between (at once,
                // for a `step` while paused) would be taken for an old one and, paused,
                // nothing newer would ever come. Restored if the message is refused.
                let track = welcomed && !input_pending;
                let unsent = track && snapshots.has_changed().unwrap_or(false);
                if track {
                    snapshots.mark_unchanged();
                }
                let reply = match msg {
                    Message::Text(text) => match limiter.admit(Instant::now()) {
                        Admit::Yes => handle_text(text.as_str(), client, shared, &mut welcomed, &mut slot),
                        Admit::Drop => Reply::None,
                        Admit::DropAndReport(n) => Reply::Text(error_json(
                            ErrorCode::RateLimited,
                            format!("over {} messages per second: {n} message(s) dropped", crate::limits::MAX_MESSAGES_PER_SECOND),
                        )),
                    },
                    Message::Binary(_) => match limiter.admit(Instant::now()) {
                        Admit::Yes | Admit::DropAndReport(_) => Reply::Text(error_json(ErrorCode::BinaryNotSupported, "send JSON text messages")),
                        Admit::Drop => Reply::None,
                    },
                    Message::Close(_) => return,
                    _ => Reply::None,
                };
                let accepted = matches!(reply, Reply::None | Reply::LoadScene { .. } | Reply::Report);
                if track && accepted {
                    // wait for a snapshot published after this command, and send it soon
                    input_pending = true;
                } else if unsent {
                    snapshots.mark_changed();
                }
                let reply = match reply {
                    Reply::None => None,
                    Reply::Text(t) => Some(t),
                    Reply::LoadScene { text, json, name } => {
                        let shared = shared.clone();
                        // on success the new welcome follows through `generation`
                        off_task(client, "the scene loader", ErrorCode::InvalidScene, move || {
                            load_scene(&shared, &text, json, &name).err()
                        })
                        .await
                    }
                    Reply::Report => {
                        let session = session.clone();
                        off_task(client, "writing the report", ErrorCode::ReportFailed, move || {
                            Some(write_report(&session))
                        })
                        .await
                    }
                };
                if let Some(reply) = reply {
                    if socket.send(Message::Text(reply.into())).await.is_err() {
                        return;
                    }
                }
            }
            changed = async {
                let wait = if input_pending { fast_interval } else { interval };
                tokio::time::sleep_until(last_send + wait).await;
                snapshots.changed().await
            }, if welcomed => {
                if changed.is_err() { return }
                let snap = snapshots.borrow_and_update().clone();
                if socket.send(Message::Text(snap.json().to_owned().into())).await.is_err() {
                    return;
                }
                last_send = tokio::time::Instant::now();
                input_pending = false;
            }
            changed = generation.changed() => {
                if changed.is_err() { return }
                generation.mark_unchanged();
                // The scene was replaced: follow the new session (dropping ours; the old
                // simulation stops when its last reader lets go).
                session = shared.session();
                snapshots = session.subscribe();
                snapshots.mark_changed();
                if welcomed && socket.send(Message::Text(welcome(client, &session).into())).await.is_err() {
                    return;
                }
            }
        }
    }
}

/// Runs slow work (loading a scene, writing a report) off the connection's task and
/// returns its reply; a panic in it fails this request only, with a `code` error reply.
async fn off_task(
    client: ClientId,
    what: &str,
    code: ErrorCode,
    work: impl FnOnce() -> Option<String> + Send + 'static,
) -> Option<String> {
    match tokio::task::spawn_blocking(work).await {
        Ok(reply) => reply,
        Err(e) => {
            let why = match e.try_into_panic() {
                Ok(panic) => format!("{what} failed (panic: {})", panic_message(&*panic)),
                Err(_) => format!("{what} was cancelled"),
            };
            eprintln!("pliant serve: {what} for client {client}: {why}");
            Some(error_json(code, why))
        }
    }
}

/// Loads a scene sent by a client and makes it the session of every client. On error the
/// old session keeps running and the error (with the loader's message) is returned.
fn load_scene(shared: &Shared, text: &str, json: bool, name: &str) -> Result<(), String> {
    #[cfg(test)]
    if name == tests::PANIC_IN_LOADER {
        let _held = shared.session.lock(); // poisons it
        panic!("test hook: the loader panics");
    }
    let invalid = |m: String| error_json(ErrorCode::InvalidScene, m);
    let options = &shared.client_scenes.options;
    let scene = if json {
        pliant_scene::load_scene_json_str_with(text, name, &shared.scene_dir, options)
    } else {
        pliant_scene::load_scene_str_with(text, name, &shared.scene_dir, options)
    }
    .map_err(|e| invalid(e.to_string()))?;
    let options = SessionOptions {
        folder: shared.sessions_dir.as_deref().map(new_session_folder),
        ..SessionOptions::default()
    };
    let session = Session::start(&scene, options).map_err(|e| invalid(e.to_string()))?;
    let old = {
        let mut current = lock(&shared.session);
        lock(&shared.ownership).clear();
        std::mem::replace(&mut *current, Arc::new(session))
    };
    shared.generation.send_modify(|g| *g += 1);
    drop(old);
    Ok(())
}

/// Writes the report of `session` into its next report folder; the `report` reply or an
/// error, as JSON. Bounded per session ([`crate::reports`]): one at a time and one per
/// interval (else `rate_limited`), the oldest reports removed to keep their total size
/// (listed in the reply).
fn write_report(session: &Session) -> String {
    if session.folder().is_none() {
        return error_json(
            ErrorCode::ReportFailed,
            "this session records into no folder (start pliant serve with a sessions folder)",
        );
    }
    let limits = *session.report_limits();
    let _ticket = match session.reports().begin(&limits, Instant::now()) {
        Ok(t) => t,
        Err(why) => return error_json(ErrorCode::RateLimited, why),
    };
    let removed = session
        .reports()
        .make_room(&limits, limits.max_report_bytes);
    let Some(out) = session.next_report_folder() else {
        return error_json(
            ErrorCode::ReportFailed,
            "this session records into no folder",
        );
    };
    let result = session.report(&out);
    let bytes = session.reports().written(&out);
    match result {
        Ok((verdict, _, interval)) => ServerMessage::Report {
            folder: out.display().to_string(),
            verdict: &verdict,
            bytes,
            record_interval_s: interval,
            removed: removed.iter().map(|p| p.display().to_string()).collect(),
        }
        .to_json(),
        Err(e) => error_json(ErrorCode::ReportFailed, e),
    }
}

/// Handles one text message; returns the reply, if any.
fn handle_text(
    text: &str,
    client: ClientId,
    shared: &Arc<Shared>,
    welcomed: &mut bool,
    slot: &mut Option<ClientSlot>,
) -> Reply {
    let too_large = || {
        Reply::Text(error_json(
            ErrorCode::MessageTooLarge,
            format!(
                "message of {} bytes; the limit is {MAX_MESSAGE_BYTES} ({MAX_SCENE_MESSAGE_BYTES} for load_scene)",
                text.len()
            ),
        ))
    };
    if text.len() > MAX_SCENE_MESSAGE_BYTES {
        return too_large();
    }
    #[cfg(test)]
    if text == tests::PANIC_HOLDING_LOCKS {
        let _held = (shared.session.lock(), shared.ownership.lock()); // poisons both
        panic!("test hook: a handler panics");
    }
    let msg: ClientMessage = match serde_json::from_str(text) {
        Ok(m) => m,
        Err(_) if text.len() > MAX_MESSAGE_BYTES => return too_large(),
        Err(e) => return Reply::Text(error_json(ErrorCode::Malformed, e.to_string())),
    };
    if text.len() > MAX_MESSAGE_BYTES && !matches!(msg, ClientMessage::LoadScene { .. }) {
        return too_large();
    }
    match (msg, *welcomed) {
        (ClientMessage::Hello { version }, _) => {
            if version != PROTOCOL_VERSION {
                return Reply::Text(error_json(
                    ErrorCode::UnsupportedVersion,
                    format!(
                        "this server speaks protocol version {PROTOCOL_VERSION}, not {version}"
                    ),
                ));
            }
            if slot.is_none() {
                match ClientSlot::take(shared) {
                    Some(s) => *slot = Some(s),
                    None => {
                        return Reply::Text(error_json(ErrorCode::ServerFull, server_full(shared)))
                    }
                }
            }
            *welcomed = true;
            Reply::Text(welcome(client, &shared.session()))
        }
        (_, false) => Reply::Text(error_json(ErrorCode::HelloRequired, "send hello first")),
        (ClientMessage::LoadScene { text, format, name }, true) => {
            let json = match format.as_deref().map(str::to_ascii_lowercase).as_deref() {
                None | Some("toml") => false,
                Some("json") => true,
                Some(other) => {
                    return Reply::Text(error_json(
                        ErrorCode::InvalidValue,
                        format!("format must be \"toml\" or \"json\", not {other:?}"),
                    ))
                }
            };
            Reply::LoadScene {
                text,
                json,
                name: name.unwrap_or_else(|| "scene from the viewer".into()),
            }
        }
        (ClientMessage::Report, true) => Reply::Report,
        (ClientMessage::SceneSource {}, true) => {
            let source = SceneSource::of(shared.session().loaded());
            Reply::Text(ServerMessage::SceneSource(&source).to_json())
        }
        (msg, true) => handle_command(msg, client, shared).err().into(),
    }
}

/// Applies a `set_ergonomics` message on top of `profile` (omitted fields keep theirs; a
/// `whole` profile text replaces it first).
fn ergonomics(
    mut profile: ErgonomicProfile,
    whole: Option<&str>,
    posture: Option<&str>,
    population: Option<&str>,
    duty: Option<&str>,
    moments_decide: Option<bool>,
) -> Result<ErgonomicProfile, String> {
    if let Some(text) = whole {
        profile = text
            .parse()
            .map_err(|e: pliant_assembly::ergonomics::ErgonomicsError| {
                error_json(ErrorCode::InvalidValue, e.to_string())
            })?;
    }
    let moments = moments_decide.map(|b| b.to_string());
    let given = [
        ("posture", posture),
        ("population", population),
        ("duty", duty),
        ("moments_decide", moments.as_deref()),
    ];
    for (key, value) in given {
        if let Some(v) = value {
            profile
                .set(key, v)
                .map_err(|e| error_json(ErrorCode::InvalidValue, e.to_string()))?;
        }
    }
    Ok(profile)
}

fn refusal(r: Refusal, hand: u32) -> String {
    match r {
        Refusal::OwnedByOther(c) => error_json(
            ErrorCode::HandOwned,
            format!("hand {hand} belongs to client {c}"),
        ),
        Refusal::NotHeld => error_json(
            ErrorCode::HandNotHeld,
            format!("hand {hand} holds nothing; grab first"),
        ),
        Refusal::TooManyHands => error_json(
            ErrorCode::TooManyHands,
            format!("at most {} hands at once", crate::ownership::MAX_HANDS),
        ),
    }
}

fn point(p: [f64; 3]) -> Result<DVec3, String> {
    let v = DVec3::from_array(p);
    if v.is_finite() && v.abs().max_element() < 1e3 {
        Ok(v)
    } else {
        Err(error_json(
            ErrorCode::InvalidValue,
            format!("position {p:?} is not finite or beyond 1 km"),
        ))
    }
}

fn finite_number(x: f64, what: &str) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(error_json(
            ErrorCode::InvalidValue,
            format!("{what} {x} is not finite"),
        ))
    }
}

fn handle_command(msg: ClientMessage, client: ClientId, shared: &Shared) -> Result<(), String> {
    let session = &shared.session();
    let command = match msg {
        ClientMessage::Hello { .. }
        | ClientMessage::LoadScene { .. }
        | ClientMessage::Report
        | ClientMessage::SceneSource {} => {
            return Ok(()); // handled in handle_text
        }
        ClientMessage::SetErgonomics {
            profile,
            posture,
            population,
            duty,
            moments_decide,
        } => Command::SetErgonomics(ergonomics(
            session.latest().ergonomics,
            profile.as_deref(),
            posture.as_deref(),
            population.as_deref(),
            duty.as_deref(),
            moments_decide,
        )?),
        ClientMessage::Grab {
            hand_id,
            position,
            grip,
        } => {
            let position = point(position)?;
            lock(&shared.ownership)
                .grab(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Grab {
                hand: hand_id,
                position,
                grip,
            }
        }
        ClientMessage::Move {
            hand_id,
            position,
            orientation,
        } => {
            let position = point(position)?;
            let orientation = match orientation {
                None => None,
                Some(q) => Some(near_unit_quaternion(DQuat::from_array(q)).map_err(|e| {
                    error_json(
                        ErrorCode::InvalidValue,
                        format!("orientation {q:?} {e}: it must be a unit quaternion [x, y, z, w]"),
                    )
                })?),
            };
            lock(&shared.ownership)
                .check(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Move {
                hand: hand_id,
                position,
                orientation,
            }
        }
        ClientMessage::Release { hand_id } => {
            lock(&shared.ownership)
                .release(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Release { hand: hand_id }
        }
        ClientMessage::MovePart {
            part,
            by,
            to,
            duration_s,
        } => Command::MovePart(Input::MovePart {
            part,
            by: by.map(point).transpose()?,
            to: to.map(point).transpose()?,
            duration: finite_number(duration_s, "duration_s")?,
        }),
        ClientMessage::RotatePart {
            part,
            axis,
            point: pivot,
            by_deg,
            to_deg,
            duration_s,
        } => {
            let angle = |a: Option<f64>, what| {
                a.map(|a| finite_number(a, what).map(f64::to_radians))
                    .transpose()
            };
            Command::MovePart(Input::RotatePart {
                part,
                axis: finite_number(axis[0], "axis")
                    .and(finite_number(axis[1], "axis"))
                    .and(finite_number(axis[2], "axis"))
                    .map(|_| DVec3::from_array(axis))?,
                point: pivot.map(point).transpose()?,
                by: angle(by_deg, "by_deg")?,
                to: angle(to_deg, "to_deg")?,
                duration: finite_number(duration_s, "duration_s")?,
            })
        }
        ClientMessage::WorkerPose { head, hands } => {
            if session.scene().worker.is_none() {
                return Err(error_json(
                    ErrorCode::InvalidValue,
                    "worker_pose: the scene has no [worker] to pose",
                ));
            }
            let head = match head {
                None => None,
                Some(h) => {
                    let gaze = DVec3::from_array(h.gaze);
                    if !gaze.is_finite() || gaze.length_squared() < 1e-18 {
                        return Err(error_json(
                            ErrorCode::InvalidValue,
                            format!(
                                "head.gaze {:?} must be a finite, non-zero direction",
                                h.gaze
                            ),
                        ));
                    }
                    Some(pliant_worker::HeadTarget {
                        eyes: point(h.position)?,
                        gaze,
                    })
                }
            };
            let [right, left] = hands;
            Command::WorkerPose(Input::WorkerPose {
                pose: pliant_assembly::worker::BodyPose {
                    head,
                    hands: [right.map(point).transpose()?, left.map(point).transpose()?],
                },
            })
        }
        ClientMessage::Pause => Command::Pause,
        ClientMessage::Resume => Command::Resume,
        ClientMessage::Step { n } => {
            if n == 0 || n > MAX_STEPS_PER_REQUEST {
                return Err(error_json(
                    ErrorCode::InvalidValue,
                    format!("n must be 1 to {MAX_STEPS_PER_REQUEST}"),
                ));
            }
            Command::Step(n)
        }
        ClientMessage::Reset => {
            let mut o = lock(&shared.ownership);
            o.clear();
            session.bump_epoch();
            Command::Reset
        }
    };
    session.send(command).map_err(|_| {
        error_json(
            ErrorCode::Busy,
            format!(
                "the session is busy ({} commands waiting); this one was dropped, send it again",
                crate::session::COMMAND_QUEUE
            ),
        )
    })
}

#[cfg(test)]
mod tests;
