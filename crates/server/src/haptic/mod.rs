//! The haptic force stream (SPEC H1; protocol in docs/protocol.md, "Haptic force
//! stream"): a UDP socket on the loopback interface (`pliant serve --haptic-port N`) that
//! takes a hand pose and answers that hand's force and torque, at the rate the device
//! asks (1 kHz for a haptic loop).
//!
//! One dedicated thread owns the socket and a quasi-static [`mirror::Mirror`] of the
//! session. For each pose it (1) solves the static equilibrium with the hand at that pose
//! on the mirror and answers the hand's load at once, and (2) forwards the pose to the
//! session as the hand's `move` (at most every [`FORWARD_EVERY`] per hand; the newest pose
//! always goes out), so the viewer shows the same hand and the session's verdict and log
//! record its loads. The mirror is put back on the session's newest state at the
//! session's snapshot rate (≤ 240 Hz), between poses where the time is free
//! ([`slack::SyncSlack`]), so stream and session never diverge by more than one snapshot
//! interval and [`slack::MAX_DEFER`]; with the session on the static solver, both answer the same
//! equilibrium for the same pose (server test `haptic::stream_force_equals_the_sessions`).
//!
//! Security (SPEC R1): the socket is bound to 127.0.0.1 only, whatever `--host` says, so
//! only processes on this machine reach it; when the server has a token, every datagram
//! must carry it in its key field. Hands follow the WebSocket's ownership rules: the
//! stream is one client, a hand another client holds is refused. Only a datagram of a
//! request's size with the request magic gets a reply (0–4-byte datagrams got
//! 96-byte answers, an amplifier), and it is smaller than the request; every other one
//! is counted and dropped, never a crash. A hand the stream has not heard of for [`IDLE_RELEASE`]
//! is released (a device that stops sending does not hold a hose for ever).

pub mod cut;
pub mod datagram;
pub mod mirror;
pub mod priority;
pub mod slack;

use crate::ownership::{ClientId, Refusal};
use crate::server::{lock, Shared};
use crate::session::{Command, Session};
use datagram::{hand_of, sequence_of, Kind, Reply, Request, Status, KEY_BYTES};
use glam::{DQuat, DVec3};
use mirror::{Answer, Mirror, SessionCopy};
use slack::SyncSlack;
use std::collections::HashMap;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The ownership table's client id of the haptic stream (WebSocket clients count up
/// from 1 and never reach it).
pub const HAPTIC_CLIENT: ClientId = u64::MAX;
/// Shortest interval between two poses of one hand forwarded to the session as `move`.
pub const FORWARD_EVERY: Duration = Duration::from_millis(4);
/// A haptic hand silent this long is released.
pub const IDLE_RELEASE: Duration = Duration::from_secs(2);
/// How often the thread wakes without traffic (to forward, release idle hands, stop).
const POLL: Duration = Duration::from_millis(2);

/// A running haptic stream; dropping it stops the thread.
pub struct HapticStream {
    pub addr: SocketAddr,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl HapticStream {
    /// Binds 127.0.0.1:`port` (0 picks a free port) and starts the stream's thread;
    /// `cutting`: poses are solved on the part of the scene the hand can move
    /// ([`mirror::Mirror::set_cutting`]).
    pub(crate) fn start(
        shared: Arc<Shared>,
        port: u16,
        cutting: bool,
    ) -> std::io::Result<HapticStream> {
        let socket = UdpSocket::bind(("127.0.0.1", port))?;
        socket.set_read_timeout(Some(POLL))?;
        let addr = socket.local_addr()?;
        let key = Request::key_for(shared.access.token()).ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "the haptic stream carries the token in {KEY_BYTES} bytes: use a token of \
                     at most {KEY_BYTES} characters"
                ),
            )
        })?;
        let stop = Arc::new(AtomicBool::new(false));
        let stop2 = stop.clone();
        let thread = std::thread::Builder::new()
            .name("pliant-haptic".into())
            .spawn(move || {
                let mut stream = Stream::new(shared, key, cutting);
                stream.run(&socket, &stop2);
            })?;
        Ok(HapticStream {
            addr,
            stop,
            thread: Some(thread),
        })
    }

    /// Asks the thread to stop (it does within a few milliseconds).
    pub fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
    }
}

impl Drop for HapticStream {
    fn drop(&mut self) {
        self.stop();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// What the stream knows of one of its hands.
struct StreamHand {
    /// The grab's place in the session's command order ([`Session::send_counted`]):
    /// answers are `pending` until a state copy has taken it.
    grab: u64,
    /// The newest pose not yet forwarded to the session.
    unsent: Option<(DVec3, Option<DQuat>)>,
    last_forward: Instant,
    last_heard: Instant,
}

struct Stream {
    shared: Arc<Shared>,
    /// The token's bytes, zero-padded; all zero without a token.
    key: [u8; KEY_BYTES],
    token: bool,
    session: Option<Arc<Session>>,
    mirror: Option<Mirror>,
    /// Whether the mirror solves the hand's component alone.
    cutting: bool,
    hands: HashMap<u32, StreamHand>,
    malformed: u32,
    /// When the mirror's re-synchronisation fits between poses.
    slack: SyncSlack,
}

/// Compares two keys in time independent of where they differ.
fn same_key(a: &[u8; KEY_BYTES], b: &[u8; KEY_BYTES]) -> bool {
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

impl Stream {
    fn new(shared: Arc<Shared>, key: [u8; KEY_BYTES], cutting: bool) -> Stream {
        let token = shared.access.token().is_some();
        Stream {
            shared,
            key,
            token,
            session: None,
            mirror: None,
            cutting,
            hands: HashMap::new(),
            malformed: 0,
            slack: SyncSlack::default(),
        }
    }

    fn run(&mut self, socket: &UdpSocket, stop: &AtomicBool) {
        // one byte more than a request: a longer datagram is seen as too long
        let mut buf = [0u8; datagram::REQUEST_BYTES + 1];
        while !stop.load(Ordering::Relaxed) {
            match socket.recv_from(&mut buf) {
                Ok((n, from)) => {
                    let bytes = &buf[..n];
                    if !datagram::is_request_sized(bytes) {
                        // not a request: counted, never answered
                        self.malformed = self.malformed.saturating_add(1);
                    } else {
                        self.slack.pose_arrived(Instant::now());
                        let reply = self.handle(bytes).encode();
                        debug_assert!(reply.len() <= n);
                        // a reply that cannot go out (the client is gone) is its loss
                        let _ = socket.send_to(&reply, from);
                        if self.slack.fits(Instant::now()) {
                            self.sync_mirror();
                        }
                    }
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                    ) =>
                {
                    // no pose for a while: nothing to keep the time free for
                    self.sync_mirror();
                }
                // e.g. ICMP port unreachable of an earlier reply: nothing to do
                Err(_) => {}
            }
            self.housekeeping();
        }
    }

    /// The session now; a new one (a scene loaded) drops the mirror and the hands.
    fn current_session(&mut self) -> Arc<Session> {
        let session = self.shared.session();
        if !self
            .session
            .as_ref()
            .is_some_and(|s| Arc::ptr_eq(s, &session))
        {
            self.session = Some(session.clone());
            self.mirror = None;
            self.hands.clear();
        }
        session
    }

    fn handle(&mut self, bytes: &[u8]) -> Reply {
        let (hand, sequence) = (hand_of(bytes), sequence_of(bytes));
        let request = match Request::decode(bytes) {
            Ok(r) => r,
            Err(status) => {
                self.malformed = self.malformed.saturating_add(1);
                return Reply::status(status, hand, sequence, self.malformed);
            }
        };
        let malformed = self.malformed;
        let reply = |s: Status| Reply::status(s, request.hand, request.sequence, malformed);
        if self.token && !same_key(&request.key, &self.key) {
            return reply(Status::Unauthorised);
        }
        let session = self.current_session();
        let epoch = session.epoch();
        let now = Instant::now();
        match request.kind {
            Kind::Grab(grip) => {
                if let Err(r) = lock(&self.shared.ownership).grab(HAPTIC_CLIENT, hand, epoch) {
                    return reply(refusal(r));
                }
                let command = Command::Grab {
                    hand,
                    position: request.position,
                    grip,
                };
                match session.send_counted(command) {
                    Ok(grab) => {
                        self.hands.insert(
                            hand,
                            StreamHand {
                                grab,
                                unsent: None,
                                last_forward: now,
                                last_heard: now,
                            },
                        );
                        reply(Status::Pending)
                    }
                    Err(_) => reply(Status::Busy),
                }
            }
            Kind::Release => {
                if let Err(r) = lock(&self.shared.ownership).release(HAPTIC_CLIENT, hand, epoch) {
                    return reply(refusal(r));
                }
                self.hands.remove(&hand);
                session.send_waiting(Command::Release { hand });
                reply(Status::Ok)
            }
            Kind::Pose => {
                if let Err(r) = lock(&self.shared.ownership).check(HAPTIC_CLIENT, hand, epoch) {
                    return reply(refusal(r));
                }
                let Some(h) = self.hands.get_mut(&hand) else {
                    return reply(Status::NotHeld);
                };
                h.last_heard = now;
                h.unsent = Some((request.position, request.orientation));
                let grab = h.grab;
                forward(&session, hand, h);
                let answer = self.answer(&session, grab, hand, &request);
                Reply {
                    status: answer.status,
                    iterations: answer.iterations,
                    hand,
                    hose: answer.hose,
                    sequence: request.sequence,
                    force: answer.force,
                    torque: answer.torque,
                    session_time: answer.session_time,
                    solve_seconds: answer.solve_seconds,
                    malformed: self.malformed,
                }
            }
        }
    }

    /// Puts the mirror on the session's newest state copy between poses (after a reply
    /// has gone out, where [`SyncSlack`] finds the time, or while no pose comes), so a
    /// pose's answer does not wait for it: on a harness a re-synchronisation — the state
    /// copied, the hand's component searched again, the cut refreshed — costs several
    /// times a pose's solve.
    fn sync_mirror(&mut self) {
        let (Some(session), Some(mirror)) = (&self.session, &mut self.mirror) else {
            return;
        };
        if let Some(copy) = session.state_copy() {
            if mirror.same_model(&copy) && !mirror.synced_with(&copy) {
                sync_timed(mirror, copy, &mut self.slack);
            }
        }
    }

    /// The mirror's answer to a pose. The mirror is put on the session's newest state
    /// copy first only where it must be: it does not hold the hand yet, the session was
    /// reset, or a due re-synchronisation has found no slack for [`slack::MAX_DEFER`].
    fn answer(&mut self, session: &Session, grab: u64, hand: u32, request: &Request) -> Answer {
        let pending = Answer {
            status: Status::Pending,
            force: DVec3::ZERO,
            torque: DVec3::ZERO,
            hose: u32::MAX,
            iterations: 0,
            session_time: 0.0,
            solve_seconds: 0.0,
        };
        let Some(copy) = session.state_copy() else {
            return pending;
        };
        if copy.taken < grab {
            return pending; // the session has not taken the grab yet
        }
        match &mut self.mirror {
            Some(m) if m.same_model(&copy) => {
                let must =
                    !m.holds(hand) || m.epoch() != copy.epoch || self.slack.overdue(Instant::now());
                if must && !m.synced_with(&copy) {
                    sync_timed(m, copy, &mut self.slack);
                }
            }
            _ => match Mirror::new(copy) {
                Ok(mut m) => {
                    m.set_cutting(self.cutting);
                    self.mirror = Some(m)
                }
                Err(_) => {
                    return Answer {
                        status: Status::SolveFailed,
                        ..pending
                    }
                }
            },
        }
        let mirror = self.mirror.as_mut().expect("set above");
        mirror.answer(hand, request.position, request.orientation)
    }

    /// Forwards poses held back by [`FORWARD_EVERY`] and releases idle hands.
    fn housekeeping(&mut self) {
        let Some(session) = &self.session else {
            return;
        };
        let ownership = &self.shared.ownership;
        self.hands.retain(|&hand, h| {
            forward(session, hand, h);
            if h.last_heard.elapsed() < IDLE_RELEASE {
                return true;
            }
            if lock(ownership)
                .release(HAPTIC_CLIENT, hand, session.epoch())
                .is_ok()
            {
                session.send_waiting(Command::Release { hand });
            }
            false
        });
    }
}

/// Puts `mirror` on `copy`, telling `slack` what it cost.
fn sync_timed(mirror: &mut Mirror, copy: Arc<SessionCopy>, slack: &mut SyncSlack) {
    let start = Instant::now();
    mirror.sync(copy);
    slack.synced(start.elapsed());
}

/// Sends the hand's newest pose to the session as its `move`, unless one went out less
/// than [`FORWARD_EVERY`] ago.
fn forward(session: &Session, hand: u32, h: &mut StreamHand) {
    let Some((position, orientation)) = h.unsent else {
        return;
    };
    if h.last_forward.elapsed() < FORWARD_EVERY {
        return;
    }
    let command = Command::Move {
        hand,
        position,
        orientation,
    };
    // a full queue drops this pose; the next one goes out in its place
    if session.send(command).is_ok() {
        h.unsent = None;
        h.last_forward = Instant::now();
    }
}

fn refusal(r: Refusal) -> Status {
    match r {
        Refusal::OwnedByOther(_) => Status::HandOwned,
        Refusal::NotHeld => Status::NotHeld,
        Refusal::TooManyHands => Status::TooManyHands,
    }
}
