//! The workcell (SPEC W1): one object that owns everything that happens in an assembly
//! study — the model, the state, the solver, the hands, the stubs and clips, the load
//! cases inputs added, the ergonomic profile, the peaks and the running verdict — with
//! one [`Workcell::step`] and one set of inputs ([`Input`]). The timeline runner,
//! `pliant serve` and the Python `Simulation` are thin shells that feed it inputs; none
//! of them steps the physics itself, so the same inputs give the same numbers bit for
//! bit in each of them.
//!
//! Every input taken is logged with its tick (steps since the workcell was built), to
//! memory and, when asked, to a sink as it happens (SPEC W2, [`log`]); replaying the log
//! into a fresh workcell of the same scene reproduces the study exactly.

pub mod chunked_log;
pub mod error;
mod hand_inputs;
pub mod hands;
pub mod input;
pub mod log;
pub mod log_reading;
mod node_inputs;
pub mod observer;
pub mod part_inputs;
pub mod reason;
pub mod recovery;
pub mod replay;
pub mod settle;
pub mod solver_doubt;
pub mod solver_record;
mod state_inputs;
pub mod tally;
pub mod verdict;

pub use chunked_log::{ChunkedLog, LogShare};
pub use error::WorkcellError;
pub use hands::{Aim, Feel, HandLimits, HeldHand};
pub use input::{HandNumber, InitialLoad, Input, Refusal, StampedInput};
pub use observer::{NoObserver, Observer};
pub use reason::{Reason, WorkedFastener};
pub use settle::{SettleOptions, StaticFinish};
pub use solver_doubt::{InstabilityNote, SolverDoubt};
pub use solver_record::{Instability, SolverRecord, Unconverged};
pub use tally::{
    limits_of, ContactEpisode, HandPeak, HandRecord, MomentNote, NodePeak, Peak, RunSummary,
    SettleOutcome, Tally, ZoneNote,
};
pub use verdict::{Findings, Stage, Verdict};

use crate::checks::{CheckSettings, ChecksSummary, InstallationChecks};
use crate::ergonomics::{ErgonomicLimits, ErgonomicProfile};
use crate::fasteners::{ClipSite, FastenerReport, FastenerSample, Fasteners, StubSite};
use crate::hand::{Hand, HandLoad, RELEASE_TIME};
use crate::timeline::NodeRef;
use crate::worker::{WorkerSample, WorkerSettings, WorkerTrack};
use glam::{DQuat, DVec3};
use hands::{holder, Hands};
use pliant_core::health::{check_for, Divergence};
use pliant_core::integrators::StaticReport;
use pliant_core::loads::{LoadCase, LoadCaseId};
use pliant_core::{Model, Solver, SolverKind, SolverSettings, State};
use recovery::Recovery;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;
use std::sync::Arc;

/// How often the state is checked for divergence, in steps.
pub const HEALTH_CHECK_EVERY: u64 = 16;

/// What a scene gives a workcell: the model, the stubs' and clips' sites on it, the
/// scene's initial load cases (its timeline's leading fixes, mounts and dead loads) and
/// its ergonomic profile. `pliant_scene::LoadedScene::workcell_setup` makes one.
#[derive(Clone, Debug)]
pub struct WorkcellSetup {
    pub model: Arc<Model>,
    pub stubs: Vec<StubSite>,
    pub clips: Vec<ClipSite>,
    pub initial: Vec<InitialLoad>,
    pub profile: ErgonomicProfile,
    /// The installation checks and their limits (SPEC V3; [`CheckSettings::none`] for
    /// none).
    pub checks: CheckSettings,
    /// The worker who does the study (SPEC E1; `None`: nobody is modelled).
    pub worker: Option<WorkerSettings>,
}

impl WorkcellSetup {
    /// A workcell of `model` alone: no stubs, clips or initial load cases, the default
    /// ergonomic profile, no installation checks, no worker.
    pub fn bare(model: Arc<Model>) -> WorkcellSetup {
        WorkcellSetup {
            model,
            stubs: Vec::new(),
            clips: Vec::new(),
            initial: Vec::new(),
            profile: ErgonomicProfile::default(),
            checks: CheckSettings::none(),
            worker: None,
        }
    }
}

/// How a workcell runs: configuration, not state (a reset keeps it).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorkcellOptions {
    /// Solver instead of the scene's `[simulation] solver`.
    pub solver: Option<SolverKind>,
    /// Hoses at rest sleep until moved or touched (SPEC I6; live sessions).
    pub sleeping: bool,
    /// Apply the scene's initial load cases at the start and on reset (a timeline run
    /// applies them itself, as its first actions).
    pub initial_loads: bool,
    /// How fast an aimed hand follows its target.
    pub hand_limits: HandLimits,
    /// Keep recent healthy checkpoints, so that a divergence can be rolled back
    /// ([`Input::Rollback`]; live sessions).
    #[serde(default)]
    pub recovery: bool,
}

impl Default for WorkcellOptions {
    fn default() -> Self {
        WorkcellOptions {
            solver: None,
            sleeping: false,
            initial_loads: true,
            hand_limits: HandLimits::default(),
            recovery: false,
        }
    }
}

/// What an input did, where there is something to tell.
#[derive(Clone, Debug, PartialEq)]
pub enum Applied {
    Done,
    /// The load case an input added (for [`Input::RemoveLoad`]).
    Load(LoadCaseId),
    /// The beam a hand grabbed.
    Grabbed {
        element: usize,
    },
    /// The static equilibrium an [`Input::SolveStatic`] reached.
    Static(StaticReport),
    /// A divergence rolled back ([`Input::Rollback`]).
    RolledBack(Rollback),
}

/// What a rollback did.
#[derive(Clone, Debug, PartialEq)]
pub struct Rollback {
    /// The divergence it undid.
    pub divergence: Divergence,
    /// The simulated time the study went back to \[s\].
    pub to_time: f64,
    /// The hands that held the diverging hose, released (the others hold on).
    pub released: Vec<HandNumber>,
}

/// Everything of a workcell that changes as it runs (SPEC W1: the state is the whole
/// state): the physics state — positions, velocities, load cases, contact memory,
/// sleeping hoses, the implicit solver's history — and the hands, the stubs' and clips'
/// state machines, the load cases inputs added, the profile, the peaks and the tick.
/// The model, the solver's scratch and the options are not in it: they do not change.
#[derive(Clone)]
pub struct Checkpoint {
    state: State,
    hands: Hands,
    hand_records: Vec<HandRecord>,
    fasteners: Fasteners,
    user_loads: BTreeSet<LoadCaseId>,
    named_loads: BTreeMap<String, LoadCaseId>,
    profile: ErgonomicProfile,
    tally: Tally,
    checks: InstallationChecks,
    worker: Option<WorkerTrack>,
    tick: u64,
    log_length: usize,
    diverged: Option<Divergence>,
}

/// One assembly study in progress.
pub struct Workcell {
    model: Arc<Model>,
    state: State,
    solver: Solver,
    options: WorkcellOptions,
    stubs: Vec<StubSite>,
    clips: Vec<ClipSite>,
    initial: Vec<InitialLoad>,
    hands: Hands,
    /// The hands' loads after the last step (buffer reused every step).
    hand_records: Vec<HandRecord>,
    /// The hands' positions this step's update set, in the hands' order (buffer reused
    /// every step: their loads after the step are taken there).
    hand_positions: Vec<DVec3>,
    /// The nodes the hands hold this step, with the hand's force of the last step
    /// (buffer reused every step: the fasteners ask about every node of their hoses).
    held_nodes: Vec<(usize, DVec3)>,
    /// When the last hand that let go has opened ([`RELEASE_TIME`] after it began): what
    /// hands left fading is taken away then.
    opening_until: Option<f64>,
    fasteners: Fasteners,
    /// Load cases added by inputs (the ones fix/drive/release/remove_load may replace).
    user_loads: BTreeSet<LoadCaseId>,
    /// Names given to dead loads that still act ([`Input::Load`]'s `name`).
    named_loads: BTreeMap<String, LoadCaseId>,
    profile: ErgonomicProfile,
    limits: Option<&'static ErgonomicLimits>,
    tally: Tally,
    /// The installation checks' account (SPEC V3).
    checks: InstallationChecks,
    /// The worker's account (SPEC E1–E2), if the scene has a worker.
    worker: Option<WorkerTrack>,
    /// Steps since the workcell was built, resets included (the stamp of inputs).
    tick: u64,
    log: chunked_log::ChunkedLog,
    sink: Option<Box<dyn Write + Send + Sync>>,
    sink_error: Option<String>,
    diverged: Option<Divergence>,
    /// Recent healthy checkpoints (with `options.recovery`).
    recovery: Recovery,
}

fn finite(v: DVec3, what: &str) -> Result<DVec3, Refusal> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refusal::Invalid(format!("{what} must be finite, got {v}")))
    }
}

/// Checks a motion's waypoints, rotation vector and duration; returns the duration.
fn checked_motion(waypoints: &[DVec3], rotation: DVec3, duration: f64) -> Result<f64, Refusal> {
    for p in waypoints {
        finite(*p, "a waypoint")?;
    }
    finite(rotation, "the rotation")?;
    if duration.is_finite() && duration >= 0.0 {
        Ok(duration)
    } else {
        Err(Refusal::Invalid(format!(
            "duration must be finite and ≥ 0 s, got {duration}"
        )))
    }
}

impl Workcell {
    /// A workcell at rest in the rest shape at t = 0, stubs and clips set up, the
    /// initial load cases applied (unless `options.initial_loads` is false).
    pub fn new(setup: WorkcellSetup, options: WorkcellOptions) -> Result<Workcell, WorkcellError> {
        let model = setup.model;
        let settings = SolverSettings {
            kind: options.solver.unwrap_or(model.solver.kind),
            ..model.solver
        };
        let solver = Solver::new(&model, settings)?;
        let recovery = Recovery::new(solver.time_step(&model), HEALTH_CHECK_EVERY);
        let mut cell = Workcell {
            state: State::at_rest(&model),
            tally: Tally::new(&model),
            checks: InstallationChecks::new(&model, setup.checks),
            worker: setup.worker.map(WorkerTrack::new).transpose()?,
            model,
            solver,
            options,
            stubs: setup.stubs,
            clips: setup.clips,
            initial: setup.initial,
            hands: Hands::new(),
            hand_records: Vec::with_capacity(4),
            hand_positions: Vec::with_capacity(4),
            held_nodes: Vec::with_capacity(8),
            opening_until: None,
            fasteners: Fasteners::default(),
            user_loads: BTreeSet::new(),
            named_loads: BTreeMap::new(),
            profile: setup.profile,
            limits: ErgonomicLimits::builtin().ok(),
            tick: 0,
            log: Default::default(),
            sink: None,
            sink_error: None,
            diverged: None,
            recovery,
        };
        cell.start()?;
        Ok(cell)
    }

    /// Rest state, fasteners, initial loads: the start of a study (and of every reset).
    fn start(&mut self) -> Result<(), WorkcellError> {
        self.state = State::at_rest(&self.model);
        self.opening_until = None;
        self.state.sleep.enabled = self.options.sleeping;
        self.fasteners = Fasteners::new(
            &self.model,
            &mut self.state,
            self.stubs.clone(),
            self.clips.clone(),
        );
        self.hands.clear();
        self.hand_records.clear();
        self.user_loads.clear();
        self.named_loads.clear();
        self.tally = Tally::new(&self.model);
        self.checks = InstallationChecks::new(&self.model, self.checks.settings().clone());
        if let Some(w) = &mut self.worker {
            w.reset();
        }
        self.diverged = None;
        self.recovery.clear();
        if self.options.initial_loads {
            for load in self.initial.clone() {
                self.perform(&load.into())
                    .map_err(WorkcellError::InitialLoad)?;
            }
        }
        Ok(())
    }

    // ---- reading ---------------------------------------------------------------------

    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }
    pub fn state(&self) -> &State {
        &self.state
    }
    pub fn solver(&self) -> &Solver {
        &self.solver
    }
    pub fn options(&self) -> &WorkcellOptions {
        &self.options
    }
    /// Simulated time one step advances \[s\].
    pub fn time_step(&self) -> f64 {
        self.solver.time_step(&self.model)
    }
    /// Steps since the workcell was built, resets included.
    pub fn tick(&self) -> u64 {
        self.tick
    }
    pub fn profile(&self) -> &ErgonomicProfile {
        &self.profile
    }
    pub fn limits(&self) -> Option<&'static ErgonomicLimits> {
        self.limits
    }
    /// The divergence that stopped the study, until a reset.
    pub fn diverged(&self) -> Option<&Divergence> {
        self.diverged.as_ref()
    }
    /// Every input taken so far, with its tick (in shared chunks: [`ChunkedLog::share`]
    /// hands it to another thread without copying it).
    pub fn log(&self) -> &chunked_log::ChunkedLog {
        &self.log
    }
    /// The first error writing the log to its sink, if any (the log stays in memory).
    pub fn log_error(&self) -> Option<&str> {
        self.sink_error.as_deref()
    }
    /// The hands holding a beam, by number.
    pub fn hands(&self) -> impl Iterator<Item = (HandNumber, &HeldHand)> {
        self.hands.iter().map(|(k, h)| (*k, h))
    }
    pub fn hand(&self, hand: HandNumber) -> Result<&HeldHand, Refusal> {
        self.hands
            .get(&hand)
            .ok_or_else(|| Refusal::Invalid(format!("hand {hand} holds nothing; grab first")))
    }
    /// The hands' loads after the last step and their ergonomic assessment.
    pub fn hand_records(&self) -> &[HandRecord] {
        &self.hand_records
    }
    /// The load hand `hand` applies now (computed from the last step's reactions) and
    /// its assessment under the current profile.
    pub fn hand_record(&self, hand: HandNumber) -> Result<HandRecord, Refusal> {
        let h = self.hand(hand)?;
        Ok(self.assess(hand, h.hand.load(&self.model, &self.state)))
    }
    /// The hand's load judged under the profile, its push and pull rows those of the
    /// worker's posture class as last posed (SPEC E2; the profile's own rows without a
    /// worker or before the first posed instant).
    fn assess(&self, number: HandNumber, load: HandLoad) -> HandRecord {
        let posture_class = self.worker.as_ref().and_then(WorkerTrack::posture_class);
        let profile = posture_class.map_or(self.profile, |c| self.profile.for_class(c));
        let assessment = self.limits.and_then(|l| {
            l.assess(&profile, load.force, load.torque, load.direction)
                .ok()
        });
        let fastener = self.hands.get(&number).and_then(|h| {
            h.hand
                .held_nodes()
                .find_map(|node| self.fasteners.worked_through(node))
        });
        HandRecord {
            hand: number as usize,
            load,
            assessment,
            fastener,
            posture_class,
        }
    }
    /// Whether a hand, a drive or a part moved by an input is still moving, or a load
    /// still rising or falling.
    pub fn moving(&self) -> bool {
        let t = self.state.time;
        self.state.loads.any_changing(t)
            || self.hands.values().any(|h| h.moving(t))
            || self.state.part_moves.any_moving(t)
    }
    /// The load cases inputs added that are still active.
    pub fn user_loads(&self) -> impl Iterator<Item = (LoadCaseId, &LoadCase)> {
        self.state
            .loads
            .iter()
            .filter(|(id, _)| self.user_loads.contains(id))
            .map(|(id, c)| (*id, c))
    }
    /// The stubs' and clips' states now.
    pub fn fastener_reports(&self) -> Vec<FastenerReport> {
        self.fasteners.reports()
    }
    /// Appends each fastener's force now (same order as the reports).
    pub fn fastener_forces(&self, out: &mut Vec<FastenerSample>) {
        self.fasteners.sample(self.state.time, out);
    }
    /// The peak tables so far, hand peaks judged under the current profile.
    pub fn summary(&self) -> RunSummary {
        let t = &self.tally;
        RunSummary {
            steps: self.state.step,
            simulated_time: self.state.time,
            actions_completed: 0,
            settles: Vec::new(),
            peaks: t.node_peaks.iter().map(|(_, p)| p.clone()).collect(),
            hand_peaks: t.judge_hands(self.limits, &self.profile),
            contacts: t.contacts.clone(),
            max_contact_force: t.max_contact_force,
            max_contact_force_time: t.max_contact_force_time,
            ergonomics: self.profile.to_string(),
            moments_decide: self.profile.moments_decide,
            standard: self.profile.standard,
            fasteners: self.fasteners.reports(),
            fastener_series: t.fastener_series.clone(),
            solver: t.solver.clone(),
            solver_warnings: t.solver.warnings(),
            instability_notes: t
                .solver
                .instability_notes(|h| self.model.hoses[h].name.clone()),
            checks: ChecksSummary::of(
                &self.checks,
                self.checks
                    .end_violations(&self.model, &self.state, &self.stubs),
            ),
            worker: self.worker.as_ref().map(WorkerTrack::summary),
        }
    }
    /// The worker's account so far (SPEC E1–E2), if the scene has a worker.
    pub fn worker(&self) -> Option<&WorkerTrack> {
        self.worker.as_ref()
    }
    /// The worker's posed instants so far (empty without a worker).
    pub fn worker_series(&self) -> &[WorkerSample] {
        self.worker.as_ref().map_or(&[], |w| w.series())
    }
    /// The installation checks' account so far (SPEC V3).
    pub fn checks(&self) -> &InstallationChecks {
        &self.checks
    }
    /// The verdict so far ([`Stage::Running`]) or of the finished study.
    pub fn verdict(&self, stage: Stage) -> Verdict {
        let message = self.diverged.as_ref().map(|d| d.to_string());
        Verdict::judge(&self.summary(), message.as_deref(), stage)
    }
    /// The running account (peaks per hand as magnitudes, contacts, …).
    pub fn tally(&self) -> &Tally {
        &self.tally
    }

    // ---- checkpoints ---------------------------------------------------------------

    /// A copy of everything that changes, to continue from later ([`Self::restore`]).
    pub fn checkpoint(&self) -> Checkpoint {
        Checkpoint {
            state: self.state.clone(),
            hands: self.hands.clone(),
            hand_records: self.hand_records.clone(),
            fasteners: self.fasteners.clone(),
            user_loads: self.user_loads.clone(),
            named_loads: self.named_loads.clone(),
            profile: self.profile,
            tally: self.tally.clone(),
            checks: self.checks.clone(),
            worker: self.worker.clone(),
            tick: self.tick,
            log_length: self.log.len(),
            diverged: self.diverged.clone(),
        }
    }

    /// Goes back to `checkpoint` (taken from this workcell): the study continues from
    /// there bit for bit as it did the first time, and the in-memory log is cut back to
    /// it. Refused while the log is written to a sink — a session's log is append-only.
    pub fn restore(&mut self, checkpoint: &Checkpoint) -> Result<(), Refusal> {
        if self.sink.is_some() {
            return Err(Refusal::Invalid(
                "this workcell writes its input log as it goes; it cannot go back".into(),
            ));
        }
        if checkpoint.state.x.len() != self.state.x.len() || checkpoint.log_length > self.log.len()
        {
            return Err(Refusal::Invalid(
                "the checkpoint is not one of this workcell's".into(),
            ));
        }
        let c = checkpoint.clone();
        self.profile = c.profile;
        self.tick = c.tick;
        self.log.truncate(c.log_length);
        self.diverged = c.diverged.clone();
        self.put_back(c);
        Ok(())
    }

    /// The physics state, hands, fasteners, load cases and account of `c` (not its
    /// tick, log, profile or divergence: [`Self::restore`] and a rollback differ there).
    fn put_back(&mut self, c: Checkpoint) {
        self.state = c.state;
        self.opening_until = self.state.loads.latest_release_end();
        self.hands = c.hands;
        self.hand_records = c.hand_records;
        self.fasteners = c.fasteners;
        self.user_loads = c.user_loads;
        self.named_loads = c.named_loads;
        self.checks = c.checks;
        self.worker = c.worker;
        self.tally = c.tally;
    }

    // ---- the log -------------------------------------------------------------------

    /// From now on every input is also written to `sink` as one JSON line and flushed
    /// at once (a crash loses nothing taken before it). The caller writes the header.
    pub fn log_to(&mut self, sink: Box<dyn Write + Send + Sync>) {
        self.sink = Some(sink);
    }

    /// Writes a line that only says how far the study has got (the replay then runs to
    /// this tick); a live session calls it about once a second.
    pub fn log_mark(&mut self) {
        let line = log::LogLine::Mark { tick: self.tick };
        self.write_line(&line);
    }

    fn write_line(&mut self, line: &log::LogLine) {
        let Some(sink) = &mut self.sink else { return };
        let text = log::line_text(line);
        let written = sink
            .write_all(text.as_bytes())
            .and_then(|_| sink.flush())
            .map_err(|e| e.to_string());
        if let Err(e) = written {
            self.sink_error.get_or_insert(e);
            self.sink = None;
        }
    }

    // ---- inputs --------------------------------------------------------------------

    /// Takes one input, between two steps. A refused input changes nothing and is not
    /// logged; a taken one is logged with the current tick.
    pub fn apply(&mut self, input: Input) -> Result<Applied, Refusal> {
        if let Some(d) = &self.diverged {
            if !matches!(
                input,
                Input::Reset | Input::Rollback | Input::SetErgonomics { .. }
            ) {
                return Err(Refusal::Diverged(d.to_string()));
            }
        }
        let applied = self.perform(&input)?;
        let stamped = StampedInput {
            tick: self.tick,
            input,
        };
        self.write_line(&log::LogLine::Input(stamped.clone()));
        self.log.push(stamped);
        Ok(applied)
    }

    fn global(&self, n: NodeRef) -> Result<usize, Refusal> {
        let hose = self.model.hoses.get(n.hose).ok_or_else(|| {
            Refusal::Invalid(format!(
                "hose {} does not exist (the scene has {})",
                n.hose,
                self.model.hoses.len()
            ))
        })?;
        if n.node >= hose.node_count {
            return Err(Refusal::Invalid(format!(
                "hose '{}' has nodes 0 to {}, not {}",
                hose.name,
                hose.node_count - 1,
                n.node
            )));
        }
        Ok(hose.node(n.node))
    }

    /// A hand lets go: over [`RELEASE_TIME`] under a dynamic solver ([`Hand::let_go`]), at
    /// once under the static one (each of its inputs is an equilibrium, with no time for a
    /// hand to open in).
    fn let_go(&mut self, hand: Hand) {
        match self.solver.kind() {
            SolverKind::Static => hand.release(&mut self.state),
            SolverKind::Explicit | SolverKind::Implicit => {
                hand.let_go(&mut self.state, RELEASE_TIME);
                let open = self.state.time + RELEASE_TIME;
                self.opening_until = Some(self.opening_until.map_or(open, |t| t.max(open)));
            }
        }
    }

    /// Refuses a node a hand holds, else removes the fixes and drives inputs put on it.
    fn take_node(&mut self, node: usize) -> Result<(), Refusal> {
        if let Some(k) = holder(&self.hands, node) {
            return Err(Refusal::Invalid(format!(
                "hand {k} holds this node; release the hand first"
            )));
        }
        self.remove_user_loads(node, |c| !matches!(c, LoadCase::DeadLoad(_)));
        // and what a hand that let go left fading there
        self.state.loads.remove_on_node(
            node,
            |c| matches!(c, LoadCase::DeadLoad(d) if d.is_release()),
        );
        Ok(())
    }

    /// Removes the loads inputs put on `node` that `which` selects — never a tie (a fix,
    /// release or grab of a tied node does not cut it; only its handle does).
    fn remove_user_loads(&mut self, node: usize, which: impl Fn(&LoadCase) -> bool) {
        let user = &mut self.user_loads;
        let gone: Vec<LoadCaseId> = self
            .state
            .loads
            .iter()
            .filter(|(id, c)| {
                !matches!(c, LoadCase::Tie(_)) && c.node() == node && which(c) && user.contains(id)
            })
            .map(|(id, _)| *id)
            .collect();
        for id in gone {
            self.state.loads.remove(id);
            user.remove(&id);
        }
        self.forget_removed_names();
    }

    /// Drops the names of loads no longer acting.
    fn forget_removed_names(&mut self) {
        let user = &self.user_loads;
        self.named_loads.retain(|_, id| user.contains(id));
    }

    fn add_user_load(&mut self, case: LoadCase) -> LoadCaseId {
        let id = self.state.loads.add(case);
        self.user_loads.insert(id);
        id
    }

    /// Takes one input: each has its own method (the node inputs in [`node_inputs`], the
    /// hand inputs in [`hand_inputs`], the part moves in [`part_inputs`], the state inputs
    /// in [`state_inputs`]).
    fn perform(&mut self, input: &Input) -> Result<Applied, Refusal> {
        match input {
            Input::Fix { node } => self.fix(*node),
            Input::Mount { node, part } => self.mount(*node, part),
            Input::Drive {
                node,
                waypoints,
                rotation,
                duration,
            } => self.drive(*node, waypoints, *rotation, *duration),
            Input::Load {
                node,
                force,
                moment,
                ramp,
                name,
            } => self.load(*node, *force, *moment, *ramp, name.as_deref()),
            Input::Unload { node, name } => self.unload(*node, name.as_deref()),
            Input::Release { node } => self.release(*node),
            Input::Tie { node, to } => self.tie(*node, *to),
            Input::RemoveLoad { id } => self.remove_load(LoadCaseId(*id)),
            Input::Grab { hand, at, grip } => self.grab(*hand, *at, *grip),
            Input::MoveHand {
                hand,
                waypoints,
                rotation,
                duration,
            } => self.move_hand(*hand, waypoints, *rotation, *duration),
            Input::AimHand {
                hand,
                position,
                orientation,
            } => self.aim_hand(*hand, *position, *orientation),
            Input::ReleaseHand { hand } => self.release_hand(*hand),
            Input::MovePart {
                part,
                by,
                to,
                duration,
            } => {
                part_inputs::move_part(&self.model, &mut self.state, part, *by, *to, *duration)?;
                Ok(Applied::Done)
            }
            Input::RotatePart {
                part,
                axis,
                point,
                by,
                to,
                duration,
            } => {
                part_inputs::rotate_part(
                    &self.model,
                    &mut self.state,
                    part,
                    *axis,
                    *point,
                    *by,
                    *to,
                    *duration,
                )?;
                Ok(Applied::Done)
            }
            Input::SetErgonomics { profile } => {
                self.profile = *profile;
                Ok(Applied::Done)
            }
            Input::WorkerPose { pose } => {
                pose.check().map_err(Refusal::Invalid)?;
                let worker = self
                    .worker
                    .as_mut()
                    .ok_or_else(|| Refusal::Invalid("the scene has no [worker] to pose".into()))?;
                worker.set_body_pose(*pose);
                Ok(Applied::Done)
            }
            Input::Arrest => self.arrest(),
            Input::SolveStatic {
                force_tolerance,
                moment_tolerance,
                max_iterations,
                stable_only,
            } => self.solve_static(
                (*force_tolerance, *moment_tolerance),
                *max_iterations,
                *stable_only,
            ),
            Input::Reset => {
                self.start().map_err(|e| Refusal::Invalid(e.to_string()))?;
                Ok(Applied::Done)
            }
            Input::Rollback => self.roll_back().map(Applied::RolledBack),
        }
    }

    /// Goes back from a divergence to the newest recovery point ([`recovery`]) and
    /// releases the hands that held the diverging hose; the tick and the log go on (the
    /// rollback is an input like any other, so a replay rolls back the same way).
    fn roll_back(&mut self) -> Result<Rollback, Refusal> {
        let Some(divergence) = self.diverged.clone() else {
            return Err(Refusal::Invalid(
                "nothing to roll back: the simulation has not diverged".into(),
            ));
        };
        let Some(point) = self.recovery.take_newest(divergence.step) else {
            return Err(Refusal::Missing(
                "no healthy checkpoint to roll back to; reset instead".into(),
            ));
        };
        // the rollbacks so far stay on record, whatever the recovery point had
        let record = std::mem::take(&mut self.tally.solver);
        self.put_back(point);
        self.tally.solver.rollback_count = record.rollback_count;
        self.tally.solver.rollbacks = record.rollbacks;
        self.diverged = None;
        let hose = self
            .model
            .hoses
            .iter()
            .position(|h| h.name == divergence.hose);
        let released: Vec<HandNumber> = self
            .hands
            .iter()
            .filter(|(_, h)| Some(h.hand.hose) == hose)
            .map(|(k, _)| *k)
            .collect();
        for k in &released {
            if let Some(h) = self.hands.remove(k) {
                h.hand.release(&mut self.state);
            }
        }
        self.state.sleep.wake_all(&self.model);
        self.tally
            .solver
            .record_rollback(solver_record::RolledBack {
                diverged_at: divergence.time,
                back_to: self.state.time,
                hose: divergence.hose.clone(),
                reason: format!("node {}: {}", divergence.node, divergence.what),
                released: released.clone(),
            });
        Ok(Rollback {
            to_time: self.state.time,
            divergence,
            released,
        })
    }

    // ---- stepping ------------------------------------------------------------------

    /// One step: hands move their held nodes, stubs and clips act, the solver advances
    /// the state, the state is checked every [`HEALTH_CHECK_EVERY`] steps, the peaks are
    /// taken in. After a divergence every call fails until a reset.
    pub fn step(&mut self, obs: &mut dyn Observer) -> Result<(), Divergence> {
        if let Some(d) = &self.diverged {
            return Err(d.clone());
        }
        let dt = self.solver.time_step(&self.model);
        let t_next = self.state.time + dt;
        let limits = self.options.hand_limits;
        self.hand_positions.clear();
        for h in self.hands.values_mut() {
            let (position, _) = h.update(&self.model, &mut self.state, t_next, dt, &limits);
            self.hand_positions.push(position);
        }
        if !self.fasteners.is_empty() {
            self.held_nodes.clear();
            for (&k, h) in &self.hands {
                let force = self
                    .hand_records
                    .iter()
                    .find(|r| r.hand == k as usize)
                    .map_or(DVec3::ZERO, |r| r.load.force);
                self.held_nodes
                    .extend(h.hand.held_nodes().map(|node| (node, force)));
            }
            self.fasteners
                .update(&self.model, &mut self.state, &self.held_nodes, t_next);
        }
        self.tick += 1;
        let stats = match self.solver.step(&self.model, &mut self.state) {
            Ok(stats) => stats,
            Err(e) => {
                let d = e.into_divergence(&self.model, &self.state);
                return Err(self.fail(d));
            }
        };
        if self.opening_until.is_some_and(|t| self.state.time >= t) {
            self.state.loads.remove_finished_releases(self.state.time);
            self.opening_until = None;
        }
        // Divergence is declared at fixed steps only, so that it happens at the same
        // tick whoever watches (a replay with a recorder, a live session without);
        // an observer is shown checked states only.
        let checked = self.state.step % HEALTH_CHECK_EVERY == 0;
        if checked {
            if let Err(d) = check_for(self.solver.kind(), &self.model, &self.state) {
                return Err(self.fail(d));
            }
        }
        // states shown to the observer or judged by the checks are checked ones (a
        // blow-up between two health checks is neither), checked once for both (and not
        // again on a health-check step, which got here healthy)
        let (shown, judged) = (
            obs.wants_state(self.state.time),
            self.checks.due(self.state.time),
        );
        let posed = self.worker.as_ref().is_some_and(|w| w.due(self.state.time));
        let healthy = (shown || judged || posed)
            && (checked || check_for(self.solver.kind(), &self.model, &self.state).is_ok());
        let wants = shown && healthy;
        self.hand_records.clear();
        let on_grid = self.state.time == t_next; // else the solver's grid moved the time
        for ((&k, h), &position) in self.hands.iter().zip(&self.hand_positions) {
            let load = if on_grid {
                h.hand.load_at(&self.model, &self.state, position)
            } else {
                h.hand.load(&self.model, &self.state)
            };
            let r = self.assess(k, load);
            self.hand_records.push(r);
        }
        // the worker posed before the tally takes the hands in: a new posture class
        // judges this step's forces already
        if posed && healthy {
            if let Some(w) = &mut self.worker {
                let class = w.posture_class();
                let static_work = self.profile.duty == crate::ergonomics::Duty::Continuous;
                w.observe(&self.model, &self.state, &self.hand_records, static_work);
                if w.posture_class() != class {
                    let mut records = std::mem::take(&mut self.hand_records);
                    for r in &mut records {
                        *r = self.assess(r.hand as HandNumber, r.load);
                    }
                    self.hand_records = records;
                }
            }
        }
        self.tally.record(
            &self.model,
            &self.state,
            (&stats, self.solver.stability_events()),
            &self.hand_records,
        );
        if judged && healthy {
            self.checks.observe(&self.model, &self.state);
        }
        if wants {
            obs.on_state(&self.model, &self.state);
            obs.on_hands(self.state.time, &self.hand_records);
            if !self.fasteners.is_empty() {
                self.fasteners
                    .sample(self.state.time, &mut self.tally.fastener_series);
            }
        }
        obs.on_step(self.state.time);
        // a recovery point on a health-checked step, once its hands and peaks are in
        if self.options.recovery
            && self.state.step % HEALTH_CHECK_EVERY == 0
            && self.recovery.due(self.state.step)
        {
            let point = self.checkpoint();
            self.recovery.keep(point);
        }
        Ok(())
    }

    fn fail(&mut self, d: Divergence) -> Divergence {
        self.diverged = Some(d.clone());
        d
    }

    /// Checks the state now; a divergence found stops the study (as in [`Self::step`]).
    /// A study's shell calls it at the end, so that no non-finite state is reported.
    pub fn check(&mut self) -> Result<(), Divergence> {
        if let Some(d) = &self.diverged {
            return Err(d.clone());
        }
        check_for(self.solver.kind(), &self.model, &self.state).map_err(|d| self.fail(d))
    }

    /// `n` steps, then a health check, so that a successful call never leaves
    /// non-finite values behind.
    pub fn steps(&mut self, n: u64, obs: &mut dyn Observer) -> Result<(), Divergence> {
        for _ in 0..n {
            self.step(obs)?;
        }
        check_for(self.solver.kind(), &self.model, &self.state).map_err(|d| self.fail(d))
    }

    /// Steps in a duration \[s\] (rounded to whole steps).
    pub fn steps_in(&self, duration: f64) -> u64 {
        (duration / self.time_step()).round().max(0.0) as u64
    }

    /// Steps until a motion of `duration` \[s\] starting now has ended (rounded up, so
    /// that a motion shorter than a step — 2 ms against the static solver's 10 ms —
    /// still arrives before the next one starts from where it ended).
    pub fn steps_until_done(&self, duration: f64) -> u64 {
        (duration / self.time_step() - 1e-9).ceil().max(0.0) as u64
    }
}

/// The global node's (hose, node) reference.
pub fn node_ref(model: &Model, global: usize) -> Option<NodeRef> {
    model.hoses.iter().enumerate().find_map(|(hose, h)| {
        h.nodes().contains(&global).then(|| NodeRef {
            hose,
            node: global - h.first_node,
        })
    })
}

/// The rotation vector that turns `from` into `to` the shorter way.
pub fn rotation_between_poses(from: DQuat, to: DQuat) -> DVec3 {
    let mut d = (to * from.conjugate()).normalize();
    if d.w < 0.0 {
        d = -d;
    }
    d.to_scaled_axis()
}
