//! The simulation thread (SPEC I6, dissertation 5.2.3): a thin shell over the scene's
//! [`Workcell`] that steps it at its own rate — real time as the target, sleeping when
//! ahead, as fast as it can when behind — feeds it the queued input commands between
//! steps, and publishes the newest snapshot into a latest-value slot (a
//! `tokio::sync::watch` channel: publishing replaces the value and never waits for
//! readers; readers skip stale values). It never waits for clients.
//!
//! Every session is a recording (SPEC W2): with a session folder, the workcell writes
//! its input log there as it goes (a mark about once a second says how far it got), next
//! to a copy of the scene; [`Session::report`] replays the log into a fresh workcell and
//! writes the same report and CSVs as `pliant run`.

use crate::haptic::mirror::SessionCopy;
use crate::limits::MAX_STEPS_PER_REQUEST;
use crate::ownership::HandId;
use crate::reports::{record_interval_within, ReportLedger, ReportLimits};
use crate::snapshot::{
    FastenerSnapshot, HandSnapshot, HoseSnapshot, PartPose, SceneData, Snapshot,
};
use glam::{DQuat, DVec3};
use pliant_assembly::ergonomics::{colour_value, ErgonomicProfile, HandAssessment};
use pliant_assembly::fasteners::FastenerSample;
use pliant_assembly::report::{replay_with_outputs, Summary};
use pliant_assembly::workcell::log::{InputLog, LogHeader};
use pliant_assembly::workcell::LogShare;
use pliant_assembly::{
    Applied, ClipSite, Input, NoObserver, Stage, StubSite, Verdict, Workcell, WorkcellError,
    WorkcellOptions,
};
use pliant_core::SolverKind;
use pliant_runs::session::{start_session_folder, write_session_folder};
use pliant_scene::LoadedScene;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use tokio::sync::watch;

/// Most wall-clock time spent stepping before commands are looked at again.
const BATCH: Duration = Duration::from_millis(2);
/// Commands a session holds before its thread takes them; beyond, `send` refuses.
pub const COMMAND_QUEUE: usize = 256;

/// The command queue is full.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Busy;
/// Behind real time by more than this, the thread stops trying to catch up.
const MAX_LAG: f64 = 0.05;
/// How often the input log is told how far the session has got (wall clock).
const MARK_EVERY: Duration = Duration::from_secs(1);

/// An input command (already checked: finite values, allowed by ownership).
#[derive(Clone, Debug)]
pub enum Command {
    Grab {
        hand: HandId,
        position: DVec3,
        grip: pliant_assembly::Grip,
    },
    Move {
        hand: HandId,
        position: DVec3,
        orientation: Option<DQuat>,
    },
    Release {
        hand: HandId,
    },
    Pause,
    Resume,
    Step(u32),
    Reset,
    /// Judge hand loads with this profile from now on.
    SetErgonomics(ErgonomicProfile),
    /// Move or turn a part ([`Input::MovePart`], [`Input::RotatePart`]).
    MovePart(Input),
    /// The VR user's body poses the worker ([`Input::WorkerPose`]).
    WorkerPose(Input),
    /// Send back the input log so far (for a report): its sealed chunks shared, only the
    /// open chunk copied, so the simulation thread never copies the whole log.
    Log(mpsc::Sender<(LogShare, u64)>),
}

/// A session could not start.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    #[error("cannot build the model: {0}")]
    Workcell(#[from] WorkcellError),
    /// The operating system refused the simulation thread.
    #[error("cannot start the simulation thread: {0}")]
    Thread(std::io::Error),
    #[error("cannot create the session folder {path}: {reason}")]
    Folder { path: String, reason: String },
    /// What the session would keep in memory while it runs exceeds the scene's limit.
    #[error("{0}")]
    Budget(String),
    /// The scene's timeline failed while settling the session's start
    /// ([`Session::start_settled`]).
    #[error("running the scene's timeline: {0}")]
    Timeline(String),
}

/// Options of the simulation thread.
#[derive(Clone, Debug)]
pub struct SessionOptions {
    /// Most snapshots published per wall-clock second.
    pub publish_hz: f64,
    /// Start paused.
    pub paused: bool,
    /// Solver instead of the scene's `[simulation] solver`.
    pub solver: Option<SolverKind>,
    /// The session folder: the scene's copy and the input log are written there as the
    /// session goes, and reports into its subfolders. `None`: the log stays in memory.
    pub folder: Option<PathBuf>,
    /// Bounds on the session's reports (rate, size).
    pub reports: ReportLimits,
}

impl Default for SessionOptions {
    fn default() -> Self {
        SessionOptions {
            publish_hz: 240.0,
            paused: false,
            solver: None,
            folder: None,
            reports: ReportLimits::default(),
        }
    }
}

/// A running simulation. Dropping it stops the thread.
pub struct Session {
    commands: mpsc::SyncSender<Command>,
    /// Commands queued so far (counted under the lock, in queue order).
    sent: Mutex<u64>,
    snapshots: watch::Receiver<Arc<Snapshot>>,
    /// Copies of the state for the haptic stream's mirror, published while wanted.
    copies: watch::Receiver<Option<Arc<SessionCopy>>>,
    copies_wanted: Arc<AtomicBool>,
    scene: Arc<SceneData>,
    loaded: Arc<LoadedScene>,
    header: LogHeader,
    folder: Option<PathBuf>,
    report_limits: ReportLimits,
    reports: ReportLedger,
    epoch: Arc<AtomicU64>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Session {
    /// Builds the workcell of `scene` and starts its simulation thread.
    pub fn start(scene: &LoadedScene, options: SessionOptions) -> Result<Session, SessionError> {
        Self::start_with(scene, options, false)
    }

    /// As [`Session::start`], with the scene's timeline run to its end first (its inputs
    /// in the session's log): a live session on the scene as the timeline leaves it —
    /// an imported harness with its fixings pressed in, an engine bay with its clips
    /// seated. A reset goes back to the scene's start, before the timeline.
    pub fn start_settled(
        scene: &LoadedScene,
        options: SessionOptions,
    ) -> Result<Session, SessionError> {
        Self::start_with(scene, options, true)
    }

    fn start_with(
        scene: &LoadedScene,
        options: SessionOptions,
        settle: bool,
    ) -> Result<Session, SessionError> {
        scene.check_live_session().map_err(SessionError::Budget)?;
        let (mut cell, sites, cell_options) = live_workcell(scene, options.solver)?;
        if let Some(dir) = &options.folder {
            let file =
                start_session_folder(dir, scene, &cell).map_err(|e| SessionError::Folder {
                    path: dir.display().to_string(),
                    reason: e.to_string(),
                })?;
            cell.log_to(Box::new(file));
        }
        if settle {
            pliant_assembly::run_timeline(&mut cell, &scene.timeline, &mut NoObserver)
                .map_err(|e| SessionError::Timeline(e.reason))?;
        }
        let header = LogHeader::new(
            &scene.name,
            &scene.source,
            "",
            &scene.base_dir.display().to_string(),
            cell_options,
            cell.time_step(),
        );
        let data = Arc::new(SceneData::new(scene, cell.model(), &sites, 60.0));
        let (tx, rx) = mpsc::sync_channel(COMMAND_QUEUE);
        let epoch = Arc::new(AtomicU64::new(0));
        let stop = Arc::new(AtomicBool::new(false));
        let copies_wanted = Arc::new(AtomicBool::new(false));
        let (copy_tx, copy_rx) = watch::channel(None);
        let mut sim = Sim::new(cell, epoch.clone(), options.paused);
        sim.copies = Some((copy_tx, copies_wanted.clone()));
        let (snap_tx, snap_rx) = watch::channel(Arc::new(sim.snapshot(0.0)));
        let publish_every = Duration::from_secs_f64(1.0 / options.publish_hz.max(1.0));
        let stop2 = stop.clone();
        let thread = std::thread::Builder::new()
            .name("pliant-sim".into())
            .spawn(move || sim.run(rx, snap_tx, stop2, publish_every))
            .map_err(SessionError::Thread)?;
        Ok(Session {
            commands: tx,
            sent: Mutex::new(0),
            snapshots: snap_rx,
            copies: copy_rx,
            copies_wanted,
            scene: data,
            loaded: Arc::new(scene.clone()),
            header,
            folder: options.folder,
            report_limits: options.reports,
            reports: ReportLedger::default(),
            epoch,
            stop,
            thread: Some(thread),
        })
    }

    /// Queues a command; it is applied before the next step. `Err(Busy)` when the queue
    /// holds [`COMMAND_QUEUE`] commands the simulation thread has not taken yet (the
    /// command is dropped; the sender is told).
    pub fn send(&self, command: Command) -> Result<(), Busy> {
        self.send_counted(command).map(|_| ())
    }

    /// [`Self::send`], returning the command's place in the queue's order (1, 2, …): the
    /// session has applied it once a [`SessionCopy::taken`] reaches that number.
    pub fn send_counted(&self, command: Command) -> Result<u64, Busy> {
        let mut sent = self.sent.lock().unwrap_or_else(PoisonError::into_inner);
        match self.commands.try_send(command) {
            Err(mpsc::TrySendError::Full(_)) => Err(Busy),
            // a stopped thread takes nothing; the session is being replaced
            Ok(()) | Err(mpsc::TrySendError::Disconnected(_)) => {
                *sent += 1;
                Ok(*sent)
            }
        }
    }

    /// Queues a command the server itself must not lose (a leaving client's releases, a
    /// log request), waiting for room: the thread empties the queue every loop.
    pub fn send_waiting(&self, command: Command) {
        let mut sent = self.sent.lock().unwrap_or_else(PoisonError::into_inner);
        if self.commands.send(command).is_ok() {
            *sent += 1;
        }
    }

    /// The newest copy of the state for the haptic mirror; the first call asks the
    /// simulation thread to publish copies from now on (at the snapshot rate), so it
    /// returns `None` until the first one.
    pub fn state_copy(&self) -> Option<Arc<SessionCopy>> {
        self.copies_wanted.store(true, Ordering::Relaxed);
        self.copies.borrow().clone()
    }

    /// A receiver of the newest snapshot.
    pub fn subscribe(&self) -> watch::Receiver<Arc<Snapshot>> {
        self.snapshots.clone()
    }

    /// The newest snapshot.
    pub fn latest(&self) -> Arc<Snapshot> {
        self.snapshots.borrow().clone()
    }

    /// The scene as loaded (its file's text included).
    pub fn loaded(&self) -> &Arc<LoadedScene> {
        &self.loaded
    }

    /// The static scene data.
    pub fn scene(&self) -> &Arc<SceneData> {
        &self.scene
    }

    /// The session folder, if the session records into one.
    pub fn folder(&self) -> Option<&Path> {
        self.folder.as_deref()
    }

    /// Resets so far (ownership entries of older epochs are void).
    pub fn epoch(&self) -> u64 {
        self.epoch.load(Ordering::SeqCst)
    }

    /// Counts a reset requested by a client (the command follows through the queue).
    pub(crate) fn bump_epoch(&self) -> u64 {
        self.epoch.fetch_add(1, Ordering::SeqCst) + 1
    }

    /// The input log so far as the simulation thread hands it over (shared chunks, see
    /// [`Command::Log`]) and the tick the session has reached.
    pub fn log_share(&self) -> Result<(LogShare, u64), String> {
        let (tx, rx) = mpsc::channel();
        self.send_waiting(Command::Log(tx));
        rx.recv()
            .map_err(|_| "the simulation thread has stopped".to_string())
    }

    /// The input log so far (inputs and the tick the session has reached), put together
    /// on the caller's thread.
    pub fn input_log(&self) -> Result<InputLog, String> {
        let (share, end_tick) = self.log_share()?;
        Ok(InputLog {
            header: self.header.clone(),
            inputs: share.to_vec(),
            end_tick,
        })
    }

    /// Writes the session's report so far into `out` — `report.html`, `report.json`,
    /// `summary.json` and the CSVs of `pliant run` — by replaying its input log into a
    /// fresh workcell (the one verdict implementation, bit for bit the live session),
    /// with the log and the scene's copy beside them (so `pliant replay out` works too).
    /// The time series are recorded at the scene's interval, or coarser if a long session
    /// would otherwise pass [`ReportLimits::max_report_bytes`]; returns that interval
    /// \[s\] too. Blocks for the replay: call it off the async runtime.
    pub fn report(&self, out: &Path) -> Result<(Verdict, Summary, f64), String> {
        self.report_observed(out, &mut NoObserver)
    }

    /// [`Self::report`], with `observer` watching the replay.
    pub fn report_observed(
        &self,
        out: &Path,
        observer: &mut dyn pliant_assembly::Observer,
    ) -> Result<(Verdict, Summary, f64), String> {
        let log = self.input_log()?;
        let cell = self
            .loaded
            .workcell(log.header.options)
            .map_err(|e| e.to_string())?;
        write_session_folder(out, &self.loaded, &log)
            .map_err(|e| format!("writing the session's log into {}: {e}", out.display()))?;
        let nodes = self.loaded.world.hoses.iter().map(|h| h.nodes.len()).sum();
        let interval = record_interval_within(
            self.loaded.record_interval,
            log.end_tick as f64 * log.header.time_step,
            nodes,
            self.report_limits.max_report_bytes,
        );
        let (verdict, summary) =
            replay_with_outputs(out, cell, &log, &self.loaded.name, interval, observer)?;
        Ok((verdict, summary, interval))
    }

    /// Bounds on this session's reports.
    pub fn report_limits(&self) -> &ReportLimits {
        &self.report_limits
    }

    /// This session's reports so far (rate and total size, [`crate::reports`]).
    pub fn reports(&self) -> &ReportLedger {
        &self.reports
    }

    /// A new folder for a report of this session: `report-N` in the session folder, N
    /// counting up. `None` if the session records into no folder.
    pub fn next_report_folder(&self) -> Option<PathBuf> {
        let dir = self.folder.as_ref()?;
        Some(self.reports.next_folder(dir))
    }
}

/// The stub and clip sites a workcell was built with.
type FastenerSites = (Vec<StubSite>, Vec<ClipSite>);

/// The workcell of a live session on `scene`, the fastener sites it was built with and
/// its options: hoses far from the action sleep (SPEC I6), a divergence is rolled back
/// rather than reset.
fn live_workcell(
    scene: &LoadedScene,
    solver: Option<SolverKind>,
) -> Result<(Workcell, FastenerSites, WorkcellOptions), SessionError> {
    let setup = scene.workcell_setup()?;
    let sites = (setup.stubs.clone(), setup.clips.clone());
    let options = WorkcellOptions {
        solver,
        sleeping: true,
        recovery: true,
        ..Default::default()
    };
    let cell = Workcell::new(setup, options)?;
    Ok((cell, sites, options))
}

/// The mean wall-clock cost of one snapshot of a live session on `scene` (at rest,
/// paused, on the calling thread) over `count` snapshots after one warm-up: what the
/// simulation thread pays up to 240 times a second besides stepping. For `pliant bench
/// --only snapshot`; nothing asserts a time.
pub fn snapshot_cost(scene: &LoadedScene, count: u32) -> Result<Duration, SessionError> {
    let (cell, _, _) = live_workcell(scene, None)?;
    let mut sim = Sim::new(cell, Arc::new(AtomicU64::new(0)), true);
    std::hint::black_box(sim.snapshot(0.0));
    let started = Instant::now();
    for _ in 0..count {
        std::hint::black_box(sim.snapshot(0.0));
    }
    Ok(started.elapsed() / count.max(1))
}

impl Drop for Session {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

struct Sim {
    cell: Workcell,
    /// Steps asked for with `step` not yet taken; run in batches between snapshots and
    /// commands, at most [`MAX_STEPS_PER_REQUEST`] at once.
    pending_steps: u64,
    /// The command that waits for the pending steps.
    held: Option<Command>,
    /// Current force of each fastener (buffer reused for every snapshot).
    fastener_forces: Vec<FastenerSample>,
    /// Why the simulation last diverged, until the next client reset.
    diverged: Option<String>,
    /// Divergences rolled back so far (each also in the log and the notice).
    rollbacks: u64,
    paused: bool,
    epoch: Arc<AtomicU64>,
    notice: Option<String>,
    /// Real-time pacing: simulated time `anchor_sim` at wall time `anchor_wall`.
    anchor_wall: Instant,
    anchor_sim: f64,
    /// Commands applied so far (the order [`Session::send_counted`] numbers them in).
    taken: u64,
    /// Where state copies go for the haptic mirror, and whether one is wanted.
    copies: Option<(CopySender, Arc<AtomicBool>)>,
    /// Whether this thread has lowered its priority for a haptic stream
    /// ([`crate::haptic::priority`]).
    yielded: bool,
}

/// Where the simulation thread sends its state copies.
type CopySender = watch::Sender<Option<Arc<SessionCopy>>>;

impl Sim {
    fn new(cell: Workcell, epoch: Arc<AtomicU64>, paused: bool) -> Sim {
        Sim {
            cell,
            pending_steps: 0,
            held: None,
            fastener_forces: Vec::new(),
            diverged: None,
            rollbacks: 0,
            paused,
            epoch,
            notice: None,
            anchor_wall: Instant::now(),
            anchor_sim: 0.0,
            taken: 0,
            copies: None,
            yielded: false,
        }
    }

    fn time(&self) -> f64 {
        self.cell.state().time
    }

    fn run(
        &mut self,
        commands: mpsc::Receiver<Command>,
        out: watch::Sender<Arc<Snapshot>>,
        stop: Arc<AtomicBool>,
        publish_every: Duration,
    ) {
        let mut last_publish = Instant::now() - publish_every;
        let mut last_mark = Instant::now();
        let mut dirty = true;
        // Real-time factor over windows of about half a second.
        let (mut rtf_wall, mut rtf_sim, mut rtf) = (Instant::now(), self.time(), 0.0);
        self.rebase();
        while !stop.load(Ordering::Relaxed) {
            // Commands keep their order: one after a `step` waits (held, the rest in the
            // bounded queue) until the steps are taken; snapshots go on meanwhile. Further
            // `step`s join the pending ones, up to the cap.
            loop {
                let c = match self.held.take() {
                    Some(c) => c,
                    None => match commands.try_recv() {
                        Ok(c) => c,
                        Err(_) => break,
                    },
                };
                if self.pending_steps > 0 && !matches!(c, Command::Step(_)) {
                    self.held = Some(c);
                    break;
                }
                self.apply(c);
                dirty = true;
            }
            let now = Instant::now();
            let mut wait = Duration::from_millis(5);
            if self.pending_steps > 0 {
                // requested steps, a batch at a time: commands and snapshots go on
                while self.pending_steps > 0 && now.elapsed() < BATCH {
                    self.pending_steps -= 1;
                    if !self.step() {
                        self.pending_steps = 0;
                    }
                }
                self.rebase();
                dirty = true;
                wait = Duration::ZERO;
            } else if !self.paused {
                let dt = self.cell.time_step();
                let due = self.anchor_sim + now.duration_since(self.anchor_wall).as_secs_f64();
                if due - self.time() > MAX_LAG {
                    // Cannot keep up: run flat out from here.
                    self.anchor_sim = self.time();
                    self.anchor_wall = now;
                }
                let due = self.anchor_sim + now.duration_since(self.anchor_wall).as_secs_f64();
                if self.time() + dt <= due {
                    while self.time() + dt <= due && now.elapsed() < BATCH {
                        if !self.step() {
                            break;
                        }
                    }
                    dirty = true;
                    wait = Duration::ZERO;
                } else {
                    wait = Duration::from_secs_f64((self.time() + dt - due).min(0.002));
                }
            }
            if last_mark.elapsed() >= MARK_EVERY {
                self.cell.log_mark();
                last_mark = Instant::now();
            }
            let since = rtf_wall.elapsed().as_secs_f64();
            if since >= 0.5 {
                rtf = (self.time() - rtf_sim) / since;
                rtf_wall = Instant::now();
                rtf_sim = self.time();
            }
            if dirty && last_publish.elapsed() >= publish_every {
                out.send_replace(Arc::new(self.snapshot(rtf)));
                self.publish_copy();
                last_publish = Instant::now();
                dirty = false;
            } else if dirty {
                wait = wait.min(publish_every.saturating_sub(last_publish.elapsed()));
            }
            if !wait.is_zero() {
                // Sleeping on the command queue: a command wakes the thread at once.
                match commands.recv_timeout(wait) {
                    Ok(c) => {
                        self.apply(c);
                        dirty = true;
                    }
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                    Err(mpsc::RecvTimeoutError::Disconnected) => break,
                }
            }
        }
        self.cell.log_mark();
    }

    fn rebase(&mut self) {
        self.anchor_wall = Instant::now();
        self.anchor_sim = self.time();
    }

    /// Gives the workcell an input; a refusal becomes the notice the viewer shows.
    fn give(&mut self, input: Input) {
        if let Err(r) = self.cell.apply(input) {
            self.notice = Some(r.to_string());
        }
    }

    /// Publishes a copy of the state for the haptic mirror, if one is wanted.
    fn publish_copy(&mut self) {
        let Some((out, wanted)) = &self.copies else {
            return;
        };
        if !wanted.load(Ordering::Relaxed) {
            return;
        }
        if !self.yielded {
            // a haptic stream listens: its period comes before this thread's steps
            crate::haptic::priority::lower_this_thread();
            self.yielded = true;
        }
        let copy = SessionCopy {
            model: self.cell.model().clone(),
            state: self.cell.state().clone(),
            hands: self.cell.hands().map(|(k, h)| (k, h.clone())).collect(),
            epoch: self.epoch.load(Ordering::SeqCst),
            taken: self.taken,
        };
        out.send_replace(Some(Arc::new(copy)));
    }

    fn apply(&mut self, c: Command) {
        self.taken += 1;
        match c {
            Command::Grab {
                hand,
                position,
                grip,
            } => {
                self.notice = self
                    .cell
                    .apply(Input::Grab {
                        grip,
                        hand,
                        at: position,
                    })
                    .err()
                    .map(|r| format!("hand {hand}: {r}"));
            }
            Command::Move {
                hand,
                position,
                orientation,
            } => {
                if self.cell.hand(hand).is_ok() {
                    self.give(Input::AimHand {
                        hand,
                        position,
                        orientation,
                    });
                }
            }
            Command::Release { hand } => {
                if self.cell.hand(hand).is_ok() {
                    self.give(Input::ReleaseHand { hand });
                }
            }
            Command::Pause => self.paused = true,
            Command::Resume => {
                self.paused = false;
                self.rebase();
            }
            Command::Step(n) => {
                self.pending_steps =
                    (self.pending_steps + u64::from(n)).min(u64::from(MAX_STEPS_PER_REQUEST));
            }
            Command::Reset => {
                self.pending_steps = 0;
                self.give(Input::Reset);
                self.diverged = None;
                self.notice = None;
                self.rebase();
            }
            Command::SetErgonomics(profile) => self.give(Input::SetErgonomics { profile }),
            Command::MovePart(input) | Command::WorkerPose(input) => self.give(input),
            Command::Log(reply) => {
                let _ = reply.send((self.cell.log().share(), self.cell.tick()));
            }
        }
    }

    /// One step; false if it diverged. The workcell then rolls back to its newest
    /// healthy recovery point, releasing only the hands on the diverging hose; with none
    /// left it is reset. Either is an input in the log, so that a replay does the same
    /// at the same tick.
    fn step(&mut self) -> bool {
        match self.cell.step(&mut NoObserver) {
            Ok(()) => true,
            Err(d) => {
                let message = d.to_string();
                match self.cell.apply(Input::Rollback) {
                    Ok(Applied::RolledBack(r)) => {
                        let hose = &r.divergence.hose;
                        let hands = match r.released.as_slice() {
                            [] => format!("no hand held hose '{hose}'"),
                            [k] => format!("hand {k} released (it held hose '{hose}')"),
                            ks => format!(
                                "hands {} released (they held hose '{hose}')",
                                ks.iter()
                                    .map(|k| k.to_string())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        };
                        self.notice = Some(format!(
                            "the simulation diverged and was rolled back to t = {:.3} s, {hands}; \
                             the rest of the session goes on: {message}",
                            r.to_time
                        ));
                        self.rollbacks += 1;
                    }
                    _ => {
                        self.give(Input::Reset);
                        self.epoch.fetch_add(1, Ordering::SeqCst);
                        self.notice = Some(format!(
                            "the simulation diverged and was reset, hands released: {message}"
                        ));
                        self.diverged = Some(message);
                    }
                }
                self.rebase();
                false
            }
        }
    }

    fn snapshot(&mut self, real_time_factor: f64) -> Snapshot {
        let (model, state) = (self.cell.model(), self.cell.state());
        let mut hoses: Vec<HoseSnapshot> = model
            .hoses
            .iter()
            .enumerate()
            .map(|(k, h)| HoseSnapshot {
                positions: h.nodes().map(|n| state.x[n].to_array()).collect(),
                colour: 0.0,
                asleep: state.sleep.hose_asleep[k],
                fields: self.cell.checks().beam_fields(model, state, k),
            })
            .collect();
        let profile = *self.cell.profile();
        let hands = self
            .cell
            .hands()
            .map(|(id, h)| {
                let record = self.cell.hand_record(id).ok();
                let load = record.map(|r| r.load).unwrap_or_default();
                let assessment: Option<HandAssessment> = record.and_then(|r| r.assessment);
                let pose = h.pose_at(state.time);
                let target = h.aim.map_or(pose.0, |a| a.target.0);
                let worst = assessment.as_ref().map(|a| *a.worst());
                let ratio = worst.map(|w| w.ratio).filter(|r| r.is_finite());
                let judged = |c: Option<pliant_assembly::ergonomics::Classification>| {
                    c.filter(|c| c.ratio.is_finite())
                };
                let force_c = judged(assessment.map(|a| a.force));
                let torque_c = judged(assessment.map(|a| *a.worst_moment()));
                let colour = colour_value(ratio.unwrap_or(f64::NAN));
                if let Some(hs) = hoses.get_mut(load.hose) {
                    hs.colour = hs.colour.max(colour);
                }
                HandSnapshot {
                    hand_id: id,
                    hose: load.hose,
                    grip: h.hand.grip(),
                    position: pose.0.to_array(),
                    orientation: pose.1.to_array(),
                    target: target.to_array(),
                    force: finite(load.force),
                    torque: finite(load.torque),
                    ratio,
                    kind: worst.map(|w| w.kind),
                    colour,
                    force_kind: force_c.map(|c| c.kind),
                    force_limit: force_c.map(|c| c.limit),
                    force_ratio: force_c.map(|c| c.ratio),
                    torque_kind: torque_c.map(|c| c.kind),
                    torque_limit: torque_c.map(|c| c.limit),
                    torque_ratio: torque_c.map(|c| c.ratio),
                }
            })
            .collect();
        self.fastener_forces.clear();
        self.cell.fastener_forces(&mut self.fastener_forces);
        let fasteners = self
            .cell
            .fastener_reports()
            .into_iter()
            .zip(&self.fastener_forces)
            .map(|(report, sample)| FastenerSnapshot {
                force: if sample.force.is_finite() {
                    sample.force
                } else {
                    0.0
                },
                report,
            })
            .collect::<Vec<_>>();
        let summary = self.cell.summary();
        let checks = summary
            .checks
            .violations
            .iter()
            .filter(|v| !v.check.at_end_only())
            .cloned()
            .collect();
        let verdict = Verdict::judge(
            &summary,
            self.diverged
                .as_ref()
                .map(|d| format!("the simulation diverged and was reset: {d}"))
                .as_deref(),
            Stage::Running,
        );
        let model = self.cell.model();
        let kinematics = &model.kinematics;
        // a junction body's shape rides on its body (pliant_core::junction_shape)
        let part_poses = (0..kinematics.len())
            .filter(|&k| model.part_moves(k))
            .map(|k| {
                let pose = model.part_placement(state, k, state.time).pose;
                PartPose {
                    part: k,
                    translation: pose.translation.to_array(),
                    rotation: pose.rotation.to_array(),
                }
            })
            .collect();
        let worker = self.cell.worker().and_then(|w| {
            w.now()
                .map(|now| crate::snapshot::WorkerSnapshot::of(w.body(), w.settings().seat, now))
        });
        Snapshot {
            time: state.time,
            step: state.step,
            part_poses,
            worker,
            paused: self.paused,
            real_time_factor,
            epoch: self.epoch.load(Ordering::SeqCst),
            hoses,
            hands,
            fasteners,
            ergonomics: profile,
            verdict,
            checks,
            instabilities: summary.solver.instabilities.clone(),
            notice: self.notice.clone(),
            rollbacks: self.rollbacks,
            ..Default::default()
        }
    }
}

/// JSON has no NaN: non-finite components are sent as 0 (the health check resets the
/// state soon after anyway).
fn finite(v: DVec3) -> [f64; 3] {
    let v = if v.is_finite() { v } else { DVec3::ZERO };
    v.to_array()
}

#[cfg(test)]
mod tests {
    use super::*;
    use pliant_assembly::report::part_outline::computed_on_this_thread;

    /// A hose above a ball of 1280 triangles.
    const SCENE: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[[parts]]
name = "ball"
sphere = { radius = 100, subdivisions = 3 }
position = [250, 0, -200]

[[hoses]]
name = "hose"
material = "hose1"
start = [0, 0, 0]
path = [{ line = { to = [500, 0, 0] } }]
elements = 10
"#;

    fn scene() -> LoadedScene {
        pliant_scene::load_scene_str_in(SCENE, "ball.toml", Path::new(".")).unwrap()
    }

    /// The parts' outlines are presentation: a snapshot (the live path) never computes
    /// them, a report computes them once.
    #[test]
    fn snapshots_never_compute_part_outlines_and_a_report_computes_them_once() {
        let scene = scene();
        let (cell, _, _) = live_workcell(&scene, None).unwrap();
        let mut sim = Sim::new(cell, Arc::new(AtomicU64::new(0)), false);
        let before = computed_on_this_thread();
        for _ in 0..5 {
            assert!(sim.step());
            let snapshot = sim.snapshot(1.0);
            assert_eq!(snapshot.hoses.len(), 1);
        }
        assert_eq!(
            computed_on_this_thread(),
            before,
            "a snapshot computed outlines"
        );

        let dir = tempfile::tempdir().unwrap();
        let session = Session::start(
            &scene,
            SessionOptions {
                paused: true,
                ..Default::default()
            },
        )
        .unwrap();
        session.send(Command::Step(3)).unwrap();
        session.report(dir.path()).unwrap();
        assert_eq!(computed_on_this_thread(), before + 1);
        assert!(dir.path().join("report.html").is_file());
    }

    /// The testkit's tee whose body's shape is a box, falling freely under gravity (mm).
    fn shaped_tee() -> String {
        use pliant_testkit::scenes::{HEAD_MM, TEE_MM};
        format!(
            "{HEAD_MM}{TEE_MM}body = {{ mass_kg = 0.02, centre_of_mass = [210, 0, 0], \
             inertia_kg_m2 = [3e-7, 8e-7, 8e-7], part = \"tee_box\" }}\n\
             [[parts]]\nname = \"tee_box\"\nbox = {{ size = [20, 10, 10] }}\nposition = [210, 0, 0]\n"
        )
    }

    /// The welcome names a junction body's shape, and every snapshot poses it where the
    /// body is: its rest mesh carried by the pose puts the outlets on the outlet nodes.
    #[test]
    fn a_junction_shape_is_posed_where_its_body_is() {
        let scene =
            pliant_scene::load_scene_str_in(&shaped_tee(), "tee.toml", Path::new(".")).unwrap();
        let (cell, _, _) = live_workcell(&scene, None).unwrap();
        let model = cell.model().clone();
        let data = crate::snapshot::SceneData::new(&scene, &model, &(Vec::new(), Vec::new()), 30.0);
        assert_eq!(data.junction_bodies.len(), 1);
        assert_eq!(data.junction_bodies[0].shape, Some(0));
        let mut sim = Sim::new(cell, Arc::new(AtomicU64::new(0)), false);
        for _ in 0..200 {
            assert!(sim.step());
        }
        let snapshot = sim.snapshot(1.0);
        let pose = snapshot
            .part_poses
            .iter()
            .find(|p| p.part == 0)
            .expect("the shape is posed");
        let (rotation, translation) = (
            glam::DQuat::from_array(pose.rotation),
            glam::DVec3::from_array(pose.translation),
        );
        assert!(translation.length() > 1e-6, "the body fell: {translation}");
        for (hose, node) in [(0, 4), (1, 0)] {
            let rest = model.rest_x[model.hoses[hose].node(node)];
            let now = glam::DVec3::from_array(snapshot.hoses[hose].positions[node]);
            let carried = rotation * rest + translation;
            assert!((carried - now).length() < 1e-9, "{carried} vs {now}");
        }
    }

    /// Waits until `done` holds, looking again whenever the thread is scheduled (a
    /// condition, not a duration; the guard only fails a hung test).
    fn wait_until(what: &str, mut done: impl FnMut() -> bool) {
        let guard = std::time::Instant::now() + Duration::from_secs(300);
        while !done() {
            assert!(std::time::Instant::now() < guard, "hung waiting for {what}");
            std::thread::yield_now();
        }
    }

    /// Holds the report's replay at its first step until the test lets it go.
    struct HeldReplay {
        started: mpsc::Sender<()>,
        go: mpsc::Receiver<()>,
        held: bool,
    }

    impl pliant_assembly::Observer for HeldReplay {
        fn on_step(&mut self, _time: f64) {
            if !self.held {
                self.held = true;
                let _ = self.started.send(());
                let _ = self.go.recv();
            }
        }
    }

    /// A report of a long session does not stall the simulation thread: the thread hands
    /// its log over in shared chunks — copying at most the open chunk, however long the
    /// log — and the session steps and publishes snapshots while the report is written.
    #[test]
    fn a_report_of_a_long_log_leaves_the_simulation_running() {
        use pliant_assembly::workcell::chunked_log::CHUNK;
        let scene = scene();
        let session = Session::start(
            &scene,
            SessionOptions {
                paused: true,
                ..Default::default()
            },
        )
        .unwrap();
        let profile = session.latest().ergonomics;
        let inputs = 40 * CHUNK + 3;
        for _ in 0..inputs {
            session.send_waiting(Command::SetErgonomics(profile));
        }
        let (first, _) = session.log_share().unwrap();
        assert_eq!(first.len(), inputs);
        session.send_waiting(Command::SetErgonomics(profile));
        let (second, _) = session.log_share().unwrap();
        assert_eq!(second.len(), inputs + 1);
        // the handoff copied only the open chunk; the sealed ones are shared, not copied
        assert!(first.copied() < CHUNK && second.copied() < CHUNK);
        assert!((0..inputs / CHUNK).all(|k| first.shares_chunk_with(&second, k)));

        // steps for the report to replay
        session.send_waiting(Command::Step(5));
        wait_until("the first steps", || session.latest().step >= 5);

        let dir = tempfile::tempdir().unwrap();
        let (started_tx, started) = mpsc::channel();
        let (go, go_rx) = mpsc::channel();
        std::thread::scope(|s| {
            let writer = s.spawn(|| {
                let mut held = HeldReplay {
                    started: started_tx,
                    go: go_rx,
                    held: false,
                };
                session.report_observed(dir.path(), &mut held)
            });
            // the report has its log and is replaying it: the session still steps and
            // publishes a snapshot of every step asked for
            started.recv().unwrap();
            for _ in 0..3 {
                let before = session.latest().step;
                session.send_waiting(Command::Step(1));
                wait_until("a snapshot of the next step", || {
                    session.latest().step > before
                });
            }
            assert!(!writer.is_finished(), "the replay is held until now");
            go.send(()).unwrap();
            let (_, summary, _) = writer.join().unwrap().unwrap();
            assert!(summary.diverged.is_none());
        });
        assert!(dir.path().join("report.html").is_file());
    }
}
