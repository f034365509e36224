//! The HTTP/WebSocket shell (axum): `GET /` serves a placeholder page, `GET /ws` speaks the
//! protocol. Each connection is one task: it reads the client's messages (checking size,
//! rate, form and ownership) and sends the newest snapshot at most 60 times a second,
//! skipping stale ones. A slow client only slows its own task; the simulation never waits.

use crate::limits::{
    Admit, RateLimiter, HARD_MAX_MESSAGE_BYTES, MAX_MESSAGE_BYTES, MAX_STEPS_PER_REQUEST,
};
use crate::ownership::{ClientId, Ownership, Refusal};
use crate::protocol::{error_json, ClientMessage, ErrorCode, ServerMessage, PROTOCOL_VERSION};
use crate::session::{Command, Session};
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::extract::State;
use axum::response::{Html, IntoResponse};
use axum::routing::get;
use axum::Router;
use glam::{DQuat, DVec3};
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::net::TcpListener;

/// Most snapshots sent to one client per second.
pub const SNAPSHOT_HZ: f64 = 60.0;

/// Where to listen.
#[derive(Clone, Debug)]
pub struct ServerConfig {
    pub host: String,
    /// 0 picks a free port.
    pub port: u16,
}

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            host: "127.0.0.1".into(),
            port: 8080,
        }
    }
}

struct Shared {
    session: Session,
    ownership: Mutex<Ownership>,
    next_client: AtomicU64,
}

/// The router for one session.
pub fn router(session: Session) -> Router {
    let shared = Arc::new(Shared {
        session,
        ownership: Mutex::new(Ownership::default()),
        next_client: AtomicU64::new(1),
    });
    Router::new()
        .route("/", get(index))
        .route("/ws", get(ws_upgrade))
        .with_state(shared)
}

/// Serves `session` on `listener` until the task is dropped.
pub async fn serve(listener: TcpListener, session: Session) -> std::io::Result<()> {
    use axum::serve::ListenerExt;
    // No Nagle delay: small messages (moves, snapshots) go out at once.
    let listener = listener.tap_io(|tcp| {
        let _ = tcp.set_nodelay(true);
    });
    axum::serve(listener, router(session)).await
}

/// A server running on the current tokio runtime.
pub struct RunningServer {
    pub addr: SocketAddr,
    task: tokio::task::JoinHandle<std::io::Result<()>>,
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
    pub async fn wait(self) -> std::io::Result<()> {
        self.task.await.unwrap_or(Ok(()))
    }
    /// Stops serving (the session stops when its last connection ends).
    pub fn stop(&self) {
        self.task.abort();
    }
}

/// Binds `config.host:config.port` and serves `session` in a background task.
pub async fn start(session: Session, config: &ServerConfig) -> std::io::Result<RunningServer> {
    let listener = TcpListener::bind((config.host.as_str(), config.port)).await?;
    let addr = listener.local_addr()?;
    let task = tokio::spawn(serve(listener, session));
    Ok(RunningServer { addr, task })
}

const INDEX_HTML: &str = include_str!("index.html");

async fn index() -> Html<&'static str> {
    Html(INDEX_HTML)
}

async fn ws_upgrade(ws: WebSocketUpgrade, State(shared): State<Arc<Shared>>) -> impl IntoResponse {
    ws.max_message_size(HARD_MAX_MESSAGE_BYTES)
        .max_frame_size(HARD_MAX_MESSAGE_BYTES)
        .on_upgrade(move |socket| async move {
            let client = shared.next_client.fetch_add(1, Ordering::SeqCst);
            connection(socket, client, &shared).await;
            // A disconnecting client's hands are released.
            let epoch = shared.session.epoch();
            let mine = shared
                .ownership
                .lock()
                .unwrap()
                .release_all_of(client, epoch);
            for hand in mine {
                shared.session.send(Command::Release { hand });
            }
        })
}

async fn connection(mut socket: WebSocket, client: ClientId, shared: &Shared) {
    let mut snapshots = shared.session.subscribe();
    let mut limiter = RateLimiter::default();
    let mut welcomed = false;
    let interval = Duration::from_secs_f64(1.0 / SNAPSHOT_HZ);
    let mut next_send = tokio::time::Instant::now();
    loop {
        tokio::select! {
            incoming = socket.recv() => {
                let Some(Ok(msg)) = incoming else { return };
                let reply = match msg {
                    Message::Text(text) => match limiter.admit(Instant::now()) {
                        Admit::Yes => handle_text(text.as_str(), client, shared, &mut welcomed),
                        Admit::Drop => None,
                        Admit::DropAndReport(n) => Some(error_json(
                            ErrorCode::RateLimited,
                            format!("over {} messages per second: {n} message(s) dropped", crate::limits::MAX_MESSAGES_PER_SECOND),
                        )),
                    },
                    Message::Binary(_) => match limiter.admit(Instant::now()) {
                        Admit::Yes | Admit::DropAndReport(_) => Some(error_json(ErrorCode::BinaryNotSupported, "send JSON text messages")),
                        Admit::Drop => None,
                    },
                    Message::Close(_) => return,
                    _ => None,
                };
                if let Some(reply) = reply {
                    if socket.send(Message::Text(reply.into())).await.is_err() {
                        return;
                    }
                }
            }
            changed = async {
                tokio::time::sleep_until(next_send).await;
                snapshots.changed().await
            }, if welcomed => {
                if changed.is_err() { return }
                let snap = snapshots.borrow_and_update().clone();
                if socket.send(Message::Text(snap.json().to_owned().into())).await.is_err() {
                    return;
                }
                next_send = tokio::time::Instant::now() + interval;
            }
        }
    }
}

/// Handles one text message; returns the reply, if any.
fn handle_text(
    text: &str,
    client: ClientId,
    shared: &Shared,
    welcomed: &mut bool,
) -> Option<String> {
    if text.len() > MAX_MESSAGE_BYTES {
        return Some(error_json(
            ErrorCode::MessageTooLarge,
            format!(
                "message of {} bytes; the limit is {MAX_MESSAGE_BYTES}",
                text.len()
            ),
        ));
    }
    let msg: ClientMessage = match serde_json::from_str(text) {
        Ok(m) => m,
        Err(e) => return Some(error_json(ErrorCode::Malformed, e.to_string())),
    };
    match (msg, *welcomed) {
        (ClientMessage::Hello { version }, _) => {
            if version != PROTOCOL_VERSION {
                return Some(error_json(
                    ErrorCode::UnsupportedVersion,
                    format!(
                        "this server speaks protocol version {PROTOCOL_VERSION}, not {version}"
                    ),
                ));
            }
            *welcomed = true;
            Some(
                ServerMessage::Welcome {
                    version: PROTOCOL_VERSION,
                    client_id: client,
                    session: shared.session.scene(),
                }
                .to_json(),
            )
        }
        (_, false) => Some(error_json(ErrorCode::HelloRequired, "send hello first")),
        (msg, true) => handle_command(msg, client, shared).err(),
    }
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

fn handle_command(msg: ClientMessage, client: ClientId, shared: &Shared) -> Result<(), String> {
    let session = &shared.session;
    let command = match msg {
        ClientMessage::Hello { .. } => unreachable!("handled before"),
        ClientMessage::Grab { hand_id, position } => {
            let position = point(position)?;
            shared
                .ownership
                .lock()
                .unwrap()
                .grab(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Grab {
                hand: hand_id,
                position,
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
                Some(q) => {
                    let q = DQuat::from_array(q);
                    if !q.is_finite() || q.length() < 1e-6 {
                        return Err(error_json(
                            ErrorCode::InvalidValue,
                            "orientation must be a non-zero finite quaternion [x, y, z, w]",
                        ));
                    }
                    Some(q.normalize())
                }
            };
            shared
                .ownership
                .lock()
                .unwrap()
                .check(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Move {
                hand: hand_id,
                position,
                orientation,
            }
        }
        ClientMessage::Release { hand_id } => {
            shared
                .ownership
                .lock()
                .unwrap()
                .release(client, hand_id, session.epoch())
                .map_err(|r| refusal(r, hand_id))?;
            Command::Release { hand: hand_id }
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
            let mut o = shared.ownership.lock().unwrap();
            o.clear();
            session.bump_epoch();
            Command::Reset
        }
    };
    session.send(command);
    Ok(())
}
