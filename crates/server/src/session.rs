//! The simulation thread (SPEC I6, dissertation 5.2.3): owns the model and state, steps at
//! its own rate — real time as the target, sleeping when ahead, as fast as it can when
//! behind — applies queued input commands between steps, and publishes the newest snapshot
//! into a latest-value slot (a `tokio::sync::watch` channel: publishing replaces the value
//! and never waits for readers; readers skip stale values). It never waits for clients.

use crate::ownership::HandId;
use crate::peaks::HandPeaks;
use crate::snapshot::{FastenerSnapshot, HandSnapshot, HoseSnapshot, SceneData, Snapshot};
use crate::verdict::RunningVerdict;
use glam::{DQuat, DVec3};
use pliant_assembly::ergonomics::{
    colour_value, ErgonomicLimits, ErgonomicProfile, HandAssessment,
};
use pliant_assembly::fasteners::{FastenerSample, Fasteners};
use pliant_assembly::{Action, ClipSite, Hand, StubSite};
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::{health, Model, Solver, SolverKind, SolverSettings, State};
use pliant_scene::LoadedScene;
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc;
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};
use tokio::sync::watch;

/// Fastest a hand's held beam is dragged towards the target of a `move` [m/s]; input
/// jumps are spread over several steps so that no step sees a large displacement.
pub const HAND_MAX_SPEED: f64 = 2.0;
/// Largest acceleration of a hand towards (and braking before) its target [m/s²] — a
/// hand does not start or stop instantly, so a `move` does not jerk the held beam (an
/// instant 2 m/s start gives inertial force spikes the worker would not feel).
pub const HAND_MAX_ACCEL: f64 = 20.0;
/// Fastest a hand turns towards its target orientation [rad/s].
pub const HAND_MAX_TURN_RATE: f64 = 4.0 * std::f64::consts::PI;
/// Most wall-clock time spent stepping before commands are looked at again.
const BATCH: Duration = Duration::from_millis(2);
/// Behind real time by more than this, the thread stops trying to catch up.
const MAX_LAG: f64 = 0.05;
/// Health check interval in steps.
const HEALTH_EVERY: u64 = 16;

/// An input command (already checked: finite values, allowed by ownership).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    Grab {
        hand: HandId,
        position: DVec3,
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
}

/// A session could not start.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    #[error("cannot build the model: {0}")]
    Model(String),
}

/// Options of the simulation thread.
#[derive(Clone, Debug)]
pub struct SessionOptions {
    /// Most snapshots published per wall-clock second.
    pub publish_hz: f64,
    /// Start paused.
    pub paused: bool,
    /// Solver instead of the scene's `[simulation] solver` (issue 5).
    pub solver: Option<SolverKind>,
}

impl Default for SessionOptions {
    fn default() -> Self {
        SessionOptions {
            publish_hz: 240.0,
            paused: false,
            solver: None,
        }
    }
}

/// A running simulation. Dropping it stops the thread.
pub struct Session {
    commands: mpsc::Sender<Command>,
    snapshots: watch::Receiver<Arc<Snapshot>>,
    scene: Arc<SceneData>,
    epoch: Arc<AtomicU64>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl Session {
    /// Builds the model of `scene` and starts its simulation thread.
    pub fn start(scene: &LoadedScene, options: SessionOptions) -> Result<Session, SessionError> {
        let model = Model::build(&scene.world)
            .and_then(|m| m.with_stiffened_spans(&scene.stiffened_spans()))
            .map_err(|e| SessionError::Model(e.to_string()))?;
        let sites = scene.fastener_sites(&model).map_err(SessionError::Model)?;
        let data = Arc::new(SceneData::new(scene, &model, &sites, 60.0));
        let (tx, rx) = mpsc::channel();
        let epoch = Arc::new(AtomicU64::new(0));
        let stop = Arc::new(AtomicBool::new(false));
        let initial = initial_actions(scene);
        let settings = SolverSettings {
            kind: options.solver.unwrap_or(model.solver.kind),
            ..model.solver
        };
        let solver =
            Solver::new(&model, settings).map_err(|e| SessionError::Model(e.to_string()))?;
        let mut sim = Sim::new(
            model,
            solver,
            sites,
            initial,
            scene.ergonomics.clone(),
            epoch.clone(),
            options.paused,
        );
        let (snap_tx, snap_rx) = watch::channel(Arc::new(sim.snapshot(0.0)));
        let publish_every = Duration::from_secs_f64(1.0 / options.publish_hz.max(1.0));
        let stop2 = stop.clone();
        let thread = std::thread::Builder::new()
            .name("pliant-sim".into())
            .spawn(move || sim.run(rx, snap_tx, stop2, publish_every))
            .expect("spawn simulation thread");
        Ok(Session {
            commands: tx,
            snapshots: snap_rx,
            scene: data,
            epoch,
            stop,
            thread: Some(thread),
        })
    }

    /// Queues a command; it is applied before the next step.
    pub fn send(&self, command: Command) {
        let _ = self.commands.send(command);
    }

    /// A receiver of the newest snapshot.
    pub fn subscribe(&self) -> watch::Receiver<Arc<Snapshot>> {
        self.snapshots.clone()
    }

    /// The newest snapshot.
    pub fn latest(&self) -> Arc<Snapshot> {
        self.snapshots.borrow().clone()
    }

    /// The static scene data.
    pub fn scene(&self) -> &Arc<SceneData> {
        &self.scene
    }

    /// Resets so far (ownership entries of older epochs are void).
    pub fn epoch(&self) -> u64 {
        self.epoch.load(Ordering::SeqCst)
    }

    /// Counts a reset requested by a client (the command follows through the queue).
    pub(crate) fn bump_epoch(&self) -> u64 {
        self.epoch.fetch_add(1, Ordering::SeqCst) + 1
    }
}

impl Drop for Session {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// A hand driven by messages: its pose moves towards the target at bounded speed.
struct Interactive {
    hand: Hand,
    pose: (DVec3, DQuat),
    target: (DVec3, DQuat),
    /// Current speed towards the target [m/s].
    speed: f64,
}

struct Sim {
    model: Model,
    /// Advances the state: explicit, implicit or static (issue 5).
    solver: Solver,
    state: State,
    /// Stubs and clips (SPEC L6, L7): their sites, kept for resets, and their runtime.
    sites: (Vec<StubSite>, Vec<ClipSite>),
    /// The scene's initial load cases (its timeline's leading fixes and loads), kept for
    /// resets.
    initial: Vec<Action>,
    fasteners: Fasteners,
    hand_forces: Vec<DVec3>,
    /// Current force of each fastener (buffer reused for every snapshot).
    fastener_forces: Vec<FastenerSample>,
    hands: BTreeMap<HandId, Interactive>,
    /// Peak loads of each hand id since the start or the last reset (running verdict).
    peaks: BTreeMap<HandId, HandPeaks>,
    /// Why the simulation last diverged, until the next client reset.
    diverged: Option<String>,
    paused: bool,
    epoch: Arc<AtomicU64>,
    /// Epoch as of the last reset the thread itself saw.
    profile: ErgonomicProfile,
    limits: Option<&'static ErgonomicLimits>,
    notice: Option<String>,
    steps_since_check: u64,
    /// Real-time pacing: simulated time `anchor_sim` at wall time `anchor_wall`.
    anchor_wall: Instant,
    anchor_sim: f64,
}

impl Sim {
    fn new(
        model: Model,
        solver: Solver,
        sites: (Vec<StubSite>, Vec<ClipSite>),
        initial: Vec<Action>,
        profile: ErgonomicProfile,
        epoch: Arc<AtomicU64>,
        paused: bool,
    ) -> Sim {
        let mut state = State::at_rest(&model);
        state.sleep.enabled = true; // hoses far from the action sleep (SPEC I6)
        apply_initial(&model, &mut state, &initial);
        let fasteners = Fasteners::new(&mut state, sites.0.clone(), sites.1.clone());
        Sim {
            model,
            solver,
            state,
            sites,
            initial,
            fasteners,
            hand_forces: Vec::with_capacity(16),
            fastener_forces: Vec::new(),
            hands: BTreeMap::new(),
            peaks: BTreeMap::new(),
            diverged: None,
            paused,
            epoch,
            profile,
            limits: ErgonomicLimits::builtin().ok(),
            notice: None,
            steps_since_check: 0,
            anchor_wall: Instant::now(),
            anchor_sim: 0.0,
        }
    }

    fn run(
        &mut self,
        commands: mpsc::Receiver<Command>,
        out: watch::Sender<Arc<Snapshot>>,
        stop: Arc<AtomicBool>,
        publish_every: Duration,
    ) {
        let mut last_publish = Instant::now() - publish_every;
        let mut dirty = true;
        // Real-time factor over windows of about half a second.
        let (mut rtf_wall, mut rtf_sim, mut rtf) = (Instant::now(), self.state.time, 0.0);
        self.rebase();
        while !stop.load(Ordering::Relaxed) {
            while let Ok(c) = commands.try_recv() {
                self.apply(c);
                dirty = true;
            }
            let now = Instant::now();
            let mut wait = Duration::from_millis(5);
            if !self.paused {
                let dt = self.solver.time_step(&self.model);
                let due = self.anchor_sim + now.duration_since(self.anchor_wall).as_secs_f64();
                if due - self.state.time > MAX_LAG {
                    // Cannot keep up: run flat out from here.
                    self.anchor_sim = self.state.time;
                    self.anchor_wall = now;
                }
                let due = self.anchor_sim + now.duration_since(self.anchor_wall).as_secs_f64();
                if self.state.time + dt <= due {
                    while self.state.time + dt <= due && now.elapsed() < BATCH {
                        self.step();
                    }
                    dirty = true;
                    wait = Duration::ZERO;
                } else {
                    wait = Duration::from_secs_f64((self.state.time + dt - due).min(0.002));
                }
            }
            let since = rtf_wall.elapsed().as_secs_f64();
            if since >= 0.5 {
                rtf = (self.state.time - rtf_sim) / since;
                rtf_wall = Instant::now();
                rtf_sim = self.state.time;
            }
            if dirty && last_publish.elapsed() >= publish_every {
                out.send_replace(Arc::new(self.snapshot(rtf)));
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
    }

    fn rebase(&mut self) {
        self.anchor_wall = Instant::now();
        self.anchor_sim = self.state.time;
    }

    fn apply(&mut self, c: Command) {
        match c {
            Command::Grab { hand, position } => {
                // a grab or a release changes what holds the hoses: let them all move
                self.state.sleep.wake_all(&self.model);
                if let Some(old) = self.hands.remove(&hand) {
                    old.hand.release(&mut self.state);
                }
                match Hand::grab(&self.model, &mut self.state, position) {
                    Some(h) => {
                        let pose = (position, DQuat::IDENTITY);
                        self.hands.insert(
                            hand,
                            Interactive {
                                hand: h,
                                pose,
                                target: pose,
                                speed: 0.0,
                            },
                        );
                    }
                    None => self.notice = Some(format!("hand {hand}: nothing to grab")),
                }
            }
            Command::Move {
                hand,
                position,
                orientation,
            } => {
                if let Some(h) = self.hands.get_mut(&hand) {
                    h.target = (position, orientation.unwrap_or(h.target.1));
                }
            }
            Command::Release { hand } => {
                self.state.sleep.wake_all(&self.model);
                if let Some(h) = self.hands.remove(&hand) {
                    h.hand.release(&mut self.state);
                }
            }
            Command::Pause => self.paused = true,
            Command::Resume => {
                self.paused = false;
                self.rebase();
            }
            Command::Step(n) => {
                for _ in 0..n {
                    if !self.step() {
                        break;
                    }
                }
                self.rebase();
            }
            Command::Reset => self.reset(None),
            Command::SetErgonomics(profile) => self.profile = profile,
        }
    }

    /// Back to rest, hands released. A client's `reset` has counted the epoch already.
    fn reset(&mut self, divergence: Option<String>) {
        self.state = State::at_rest(&self.model);
        self.state.sleep.enabled = true;
        self.solver.restart();
        apply_initial(&self.model, &mut self.state, &self.initial);
        self.fasteners =
            Fasteners::new(&mut self.state, self.sites.0.clone(), self.sites.1.clone());
        self.hands.clear();
        self.peaks.clear();
        self.steps_since_check = 0;
        self.diverged = divergence.clone();
        if let Some(message) = divergence {
            self.epoch.fetch_add(1, Ordering::SeqCst);
            self.notice = Some(format!(
                "the simulation diverged and was reset, hands released: {message}"
            ));
        } else {
            self.notice = None;
        }
        self.rebase();
    }

    /// One step; false if it diverged (the state is then reset).
    fn step(&mut self) -> bool {
        let dt = self.solver.time_step(&self.model);
        let t = self.state.time + dt;
        for h in self.hands.values_mut() {
            // accelerate at most HAND_MAX_ACCEL, and brake so as to stop on the target
            let to_go = (h.target.0 - h.pose.0).length();
            let braking = (2.0 * HAND_MAX_ACCEL * to_go).sqrt();
            h.speed = (h.speed + HAND_MAX_ACCEL * dt)
                .min(HAND_MAX_SPEED)
                .min(braking);
            h.pose.0 = h.pose.0.move_towards(h.target.0, h.speed * dt);
            h.pose.1 = h.pose.1.rotate_towards(h.target.1, HAND_MAX_TURN_RATE * dt);
            h.hand.set_pose(h.pose.0, h.pose.1);
            h.hand.update(&mut self.state, t);
        }
        if !self.fasteners.is_empty() {
            // the hands' loads of the last step (buffer reused: no allocation per step)
            self.hand_forces.clear();
            for h in self.hands.values() {
                self.hand_forces
                    .push(h.hand.load(&self.model, &self.state).force);
            }
            let (hands, forces) = (&self.hands, &self.hand_forces);
            let holder = |node: usize| hands.values().position(|h| h.hand.holds(node));
            let held = |node: usize| holder(node).is_some();
            let force = |node: usize| holder(node).map_or(DVec3::ZERO, |k| forces[k]);
            self.fasteners
                .update(&self.model, &mut self.state, &held, &force);
        }
        if let Err(e) = self.solver.step(&self.model, &mut self.state) {
            let d = e.into_divergence(&self.model, &self.state);
            self.reset(Some(d.to_string()));
            return false;
        }
        self.track_peaks();
        self.steps_since_check += 1;
        if self.steps_since_check >= HEALTH_EVERY {
            self.steps_since_check = 0;
            if let Err(d) = health::check(&self.model, &self.state) {
                self.reset(Some(d.to_string()));
                return false;
            }
        }
        true
    }

    /// Updates each hand's peak push, pull and torque after a step (no allocation once a
    /// hand id has been seen).
    fn track_peaks(&mut self) {
        let Some(limits) = self.limits else { return };
        let t = self.state.time;
        for (&id, h) in &self.hands {
            let load = h.hand.load(&self.model, &self.state);
            if let Ok(a) = limits.assess(&self.profile, load.force, load.torque, load.direction) {
                self.peaks.entry(id).or_default().record(&a, t);
            }
        }
    }

    fn snapshot(&mut self, real_time_factor: f64) -> Snapshot {
        let mut hoses: Vec<HoseSnapshot> = self
            .model
            .hoses
            .iter()
            .enumerate()
            .map(|(k, h)| HoseSnapshot {
                positions: h.nodes().map(|n| self.state.x[n].to_array()).collect(),
                colour: 0.0,
                asleep: self.state.sleep.hose_asleep[k],
            })
            .collect();
        let hands = self
            .hands
            .iter()
            .map(|(&id, h)| {
                let load = h.hand.load(&self.model, &self.state);
                let assessment: Option<HandAssessment> = self.limits.and_then(|l| {
                    l.assess(&self.profile, load.force, load.torque, load.direction)
                        .ok()
                });
                let worst = assessment.as_ref().map(|a| *a.worst());
                let ratio = worst.map(|w| w.ratio).filter(|r| r.is_finite());
                let judged = |c: Option<pliant_assembly::ergonomics::Classification>| {
                    c.filter(|c| c.ratio.is_finite())
                };
                let force_c = judged(assessment.map(|a| a.force));
                let torque_c = judged(assessment.map(|a| a.torque));
                let colour = colour_value(ratio.unwrap_or(f64::NAN));
                if let Some(hs) = hoses.get_mut(load.hose) {
                    hs.colour = hs.colour.max(colour);
                }
                HandSnapshot {
                    hand_id: id,
                    hose: load.hose,
                    position: h.pose.0.to_array(),
                    orientation: h.pose.1.to_array(),
                    target: h.target.0.to_array(),
                    force: finite(load.force),
                    torque: finite(load.torque),
                    ratio,
                    kind: worst.map(|w| w.kind),
                    colour,
                    force_kind: force_c.map(|c| c.kind),
                    force_limit: force_c.map(|c| c.limit),
                    force_ratio: force_c.map(|c| c.ratio),
                    torque_limit: torque_c.map(|c| c.limit),
                    torque_ratio: torque_c.map(|c| c.ratio),
                }
            })
            .collect();
        self.fastener_forces.clear();
        self.fasteners
            .sample(self.state.time, &mut self.fastener_forces);
        let fasteners = self
            .fasteners
            .reports()
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
        let verdict = RunningVerdict::judge(
            &self.peaks,
            self.limits,
            &self.profile,
            &fasteners,
            self.diverged.as_deref(),
        );
        Snapshot {
            time: self.state.time,
            step: self.state.step,
            paused: self.paused,
            real_time_factor,
            epoch: self.epoch.load(Ordering::SeqCst),
            hoses,
            hands,
            fasteners,
            ergonomics: self.profile,
            verdict,
            notice: self.notice.clone(),
            ..Default::default()
        }
    }
}

/// A scene's initial load cases (SPEC §5): the leading instantaneous actions of its
/// timeline — fixes and dead loads — up to the first action that takes time or involves a
/// hand. A live session starts from them; the rest of the timeline is the script of
/// `pliant run`, not of an interactive session.
fn initial_actions(scene: &LoadedScene) -> Vec<Action> {
    scene
        .timeline
        .actions
        .iter()
        .take_while(|a| matches!(a, Action::Fix { .. } | Action::Load { .. }))
        .cloned()
        .collect()
}

fn apply_initial(model: &Model, state: &mut State, actions: &[Action]) {
    for a in actions {
        match a {
            Action::Fix { node } => {
                let i = model.hoses[node.hose].node(node.node);
                state.loads.add(LoadCase::Fix(Fix {
                    node: i,
                    position: state.x[i],
                    orientation: state.q[i],
                }));
            }
            Action::Load {
                node,
                force,
                moment,
            } => {
                let i = model.hoses[node.hose].node(node.node);
                state.loads.add(LoadCase::DeadLoad(DeadLoad {
                    node: i,
                    force: *force,
                    moment: *moment,
                }));
            }
            _ => {}
        }
    }
}

/// JSON has no NaN: non-finite components are sent as 0 (the health check resets the
/// state soon after anyway).
fn finite(v: DVec3) -> [f64; 3] {
    let v = if v.is_finite() { v } else { DVec3::ZERO };
    v.to_array()
}
