//! Executes a [`Timeline`] on a model: turns each action into load cases on the state and
//! advances the explicit integrator, checking health as it goes and tracking the peak
//! support loads of every held node.

use crate::ergonomics::{ErgonomicLimits, ErgonomicProfile, HandAssessment, LoadKind};
use crate::fasteners::{ClipSite, FastenerReport, FastenerSample, Fasteners, StubSite};
use crate::hand::{Hand, HandLoad};
use crate::timeline::{Action, MovePath, NodeRef, Timeline};
use glam::DVec3;
use pliant_core::curve::catmull_rom;
use pliant_core::health::{check, Divergence};
use pliant_core::loads::{DeadLoad, Drive, Fix, LoadCase};
use pliant_core::{Model, Solver, SolverKind, SolverSettings, State};
use serde::Serialize;

/// How often the state is checked for divergence, in steps.
const HEALTH_CHECK_EVERY: u64 = 16;
/// How often `Settle` looks at the kinetic energy, in steps.
const SETTLE_CHECK_EVERY: u64 = 16;

/// Sees the run as it goes. Only states that passed the divergence check reach `on_state`.
pub trait Observer {
    /// Whether the observer wants the state at simulated time `time` (e.g. a recorder
    /// sampling at an interval).
    fn wants_state(&self, _time: f64) -> bool {
        false
    }
    /// A checked state the observer asked for.
    fn on_state(&mut self, _model: &Model, _state: &State) {}
    /// An action is about to start.
    fn on_action(&mut self, _index: usize, _action: &Action, _state: &State) {}
    /// Called every step with the simulated time (for progress display); keep it cheap.
    fn on_step(&mut self, _time: f64) {}
    /// The hands' loads and their ergonomic assessment, with every state the observer
    /// asked for.
    fn on_hands(&mut self, _time: f64, _hands: &[HandRecord]) {}
}

/// One hand's load in one step and how it compares with the ergonomic limits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HandRecord {
    pub hand: usize,
    pub load: HandLoad,
    /// `None` only if the load was not finite (the step is then reported as diverged).
    pub assessment: Option<HandAssessment>,
}

/// Peak loads of one hand over the run, and its worst moment against the limits.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HandPeak {
    pub hand: usize,
    pub max_force: f64,
    pub max_force_time: f64,
    pub max_torque: f64,
    pub max_torque_time: f64,
    /// Largest load/limit ratio, its kind, magnitude, limit and time.
    pub worst_ratio: f64,
    pub worst_kind: Option<LoadKind>,
    pub worst_magnitude: f64,
    pub worst_limit: f64,
    pub worst_time: f64,
}

/// A rigid part the hoses touched, and when (SPEC I5: where contact blocked the path).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactEpisode {
    pub part: String,
    pub first_time: f64,
    pub last_time: f64,
    /// Steps with at least one contact point on this part.
    pub steps: u64,
}

/// An observer that watches nothing.
pub struct NoObserver;
impl Observer for NoObserver {}

/// Peak support loads at one node that a fix or drive held at some point.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct NodePeak {
    pub hose: usize,
    pub node: usize,
    /// Largest |F| the support applied [N] and when [s].
    pub max_force: f64,
    pub max_force_time: f64,
    /// Largest |M| the support applied [N·m] and when [s].
    pub max_moment: f64,
    pub max_moment_time: f64,
    /// Support force and moment in the last step it held the node.
    pub last_force: DVec3,
    pub last_moment: DVec3,
}

/// Outcome of one `Settle` action.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SettleOutcome {
    pub action: usize,
    pub at_rest: bool,
    pub time: f64,
    pub kinetic_energy: f64,
}

/// What a whole run did.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RunSummary {
    pub steps: u64,
    pub simulated_time: f64,
    pub actions_completed: usize,
    pub settles: Vec<SettleOutcome>,
    pub peaks: Vec<NodePeak>,
    /// Per hand that grabbed at some point.
    pub hand_peaks: Vec<HandPeak>,
    /// Parts touched, in the order first touched.
    pub contacts: Vec<ContactEpisode>,
    /// Largest total contact force of the parts on the hoses [N] and when.
    pub max_contact_force: f64,
    pub max_contact_force_time: f64,
    /// The ergonomic profile hand loads were judged with.
    pub ergonomics: String,
    /// Stubs and clips and whether they ended assembled.
    pub fasteners: Vec<FastenerReport>,
    /// Their forces at the recorded times (the observer's sampling).
    pub fastener_series: Vec<FastenerSample>,
    /// Newton solvers only: the most iterations one step took, and how many steps ended
    /// without reaching the tolerance.
    pub newton_iterations_max: usize,
    pub newton_unconverged_steps: u64,
}

impl RunSummary {
    /// Whether every hand stayed within its limit values.
    pub fn feasible(&self) -> bool {
        self.hand_peaks.iter().all(|h| h.worst_ratio <= 1.0)
            && self.fasteners.iter().all(|f| f.assembled)
    }
}

/// A run that stopped early.
#[derive(Debug, thiserror::Error)]
#[error("{divergence}")]
pub struct RunError {
    pub divergence: Divergence,
    /// Everything up to the last healthy state.
    pub partial: RunSummary,
}

/// Executes timelines. Tracks the peak support loads of every node a fix or drive held.
pub struct Runner<'m> {
    model: &'m Model,
    /// (global node, its peaks), in the order the nodes were first held.
    peaks: Vec<(usize, NodePeak)>,
    summary: RunSummary,
    /// Hands by index; `None` while a hand holds nothing.
    hands: Vec<Option<Hand>>,
    /// Per-step hand loads (buffer reused every step).
    hand_records: Vec<HandRecord>,
    profile: ErgonomicProfile,
    limits: Option<&'static ErgonomicLimits>,
    /// Per part: index into `summary.contacts` once touched.
    contact_index: Vec<Option<usize>>,
    /// Stubs and clips to set up when the run starts, then their runtime.
    sites: Option<(Vec<StubSite>, Vec<ClipSite>)>,
    fasteners: Fasteners,
    solver: Solver,
}

impl<'m> Runner<'m> {
    pub fn new(model: &'m Model) -> Self {
        Runner {
            model,
            peaks: Vec::new(),
            summary: RunSummary::default(),
            hands: Vec::new(),
            hand_records: Vec::new(),
            profile: ErgonomicProfile::default(),
            limits: ErgonomicLimits::builtin().ok(),
            contact_index: vec![None; model.environment.parts.len()],
            sites: None,
            fasteners: Fasteners::default(),
            solver: Solver::for_model(model).expect("Model::build makes every hose a chain"),
        }
    }

    /// Advances with `kind` instead of the scene's solver (SPEC P5).
    pub fn with_solver(mut self, kind: SolverKind) -> Self {
        let settings = SolverSettings {
            kind,
            ..self.model.solver
        };
        self.solver =
            Solver::new(self.model, settings).expect("Model::build makes every hose a chain");
        self
    }

    /// The solver in use.
    pub fn solver(&self) -> &Solver {
        &self.solver
    }

    /// Adds connector stubs and clips (SPEC L6, L7).
    pub fn with_fasteners(mut self, stubs: Vec<StubSite>, clips: Vec<ClipSite>) -> Self {
        self.sites = Some((stubs, clips));
        self
    }

    /// Judges hand loads with `profile` (default: [`ErgonomicProfile::default`]).
    pub fn with_ergonomics(mut self, profile: ErgonomicProfile) -> Self {
        self.profile = profile;
        self
    }

    /// Total simulated duration the timeline asks for at most (settles counted at their
    /// maximum), for progress display.
    pub fn planned_duration(timeline: &Timeline) -> f64 {
        timeline
            .actions
            .iter()
            .map(|a| match a {
                Action::Move {
                    duration,
                    wait: true,
                    ..
                } => *duration,
                Action::MoveHand {
                    duration,
                    wait: true,
                    ..
                } => *duration,
                Action::Run { duration } => *duration,
                Action::Settle { max_duration, .. } => *max_duration,
                _ => 0.0,
            })
            .sum()
    }

    /// Runs every action of `timeline` on `state`.
    pub fn run(
        mut self,
        timeline: &Timeline,
        state: &mut State,
        obs: &mut dyn Observer,
    ) -> Result<RunSummary, RunError> {
        if let Some((stubs, clips)) = self.sites.take() {
            self.fasteners = Fasteners::new(state, stubs, clips);
        }
        for (k, action) in timeline.actions.iter().enumerate() {
            obs.on_action(k, action, state);
            if let Err(divergence) = self.apply(k, action, state, obs) {
                return Err(RunError {
                    divergence,
                    partial: self.finish(state),
                });
            }
            self.summary.actions_completed = k + 1;
        }
        Ok(self.finish(state))
    }

    fn finish(&mut self, state: &State) -> RunSummary {
        let mut s = std::mem::take(&mut self.summary);
        s.steps = state.step;
        s.simulated_time = state.time;
        s.peaks = self.peaks.iter().map(|(_, p)| p.clone()).collect();
        s.ergonomics = self.profile.to_string();
        s.fasteners = self.fasteners.reports();
        s
    }

    fn global(&self, n: NodeRef) -> usize {
        self.model.hoses[n.hose].node(n.node)
    }

    /// One action: load-case changes are instantaneous, time-taking actions step.
    pub fn apply(
        &mut self,
        index: usize,
        action: &Action,
        state: &mut State,
        obs: &mut dyn Observer,
    ) -> Result<(), Divergence> {
        let kinematic = |c: &LoadCase| !matches!(c, LoadCase::DeadLoad(_));
        match action {
            Action::Fix { node } => {
                let i = self.global(*node);
                state.loads.remove_on_node(i, kinematic);
                state.loads.add(LoadCase::Fix(Fix {
                    node: i,
                    position: state.x[i],
                    orientation: state.q[i],
                }));
                self.track(*node);
            }
            Action::Move {
                node,
                path,
                rotation,
                duration,
                wait,
            } => {
                let i = self.global(*node);
                let start = state.x[i];
                let waypoints: Vec<DVec3> = match path {
                    Some(MovePath::To(p)) => p.clone(),
                    Some(MovePath::By(p)) => p.iter().map(|d| start + *d).collect(),
                    None => Vec::new(),
                };
                let phi = rotation
                    .map(|r| r.axis.normalize_or_zero() * r.angle)
                    .unwrap_or(DVec3::ZERO);
                state.loads.remove_on_node(i, kinematic);
                let drive = Drive::new(
                    i,
                    (start, state.q[i]),
                    &waypoints,
                    phi,
                    state.time,
                    *duration,
                );
                state.loads.add(LoadCase::Drive(drive));
                self.track(*node);
                if *wait {
                    self.advance(state, *duration, obs)?;
                }
            }
            Action::Load {
                node,
                force,
                moment,
            } => {
                let i = self.global(*node);
                state.loads.add(LoadCase::DeadLoad(DeadLoad {
                    node: i,
                    force: *force,
                    moment: *moment,
                }));
            }
            Action::Unload { node } => {
                let i = self.global(*node);
                state
                    .loads
                    .remove_on_node(i, |c| matches!(c, LoadCase::DeadLoad(_)));
            }
            Action::Release { node } => {
                let i = self.global(*node);
                state.loads.remove_on_node(i, kinematic);
            }
            Action::Grab { hand, at } => {
                if let Some(old) = self.hand_slot(*hand).take() {
                    old.release(state);
                }
                let grabbed = Hand::grab(self.model, state, *at);
                if grabbed.is_some() && !self.summary.hand_peaks.iter().any(|p| p.hand == *hand) {
                    self.summary.hand_peaks.push(HandPeak {
                        hand: *hand,
                        ..Default::default()
                    });
                }
                *self.hand_slot(*hand) = grabbed;
            }
            Action::MoveHand {
                hand,
                path,
                rotation,
                duration,
                speed,
                spline,
                wait,
            } => {
                let t0 = state.time;
                let mut duration = *duration;
                if let Some(h) = self.hand_slot(*hand).as_mut() {
                    let (start, _) = h.pose_at(t0);
                    let mut waypoints: Vec<DVec3> = match path {
                        Some(MovePath::To(p)) => p.clone(),
                        Some(MovePath::By(p)) => p.iter().map(|d| start + *d).collect(),
                        None => Vec::new(),
                    };
                    if *spline && waypoints.len() >= 2 {
                        let mut through = Vec::with_capacity(waypoints.len() + 1);
                        through.push(start);
                        through.extend_from_slice(&waypoints);
                        waypoints = catmull_rom(&through, 16).split_off(1);
                    }
                    if let Some(v) = speed {
                        let mut length = 0.0;
                        let mut at = start;
                        for p in &waypoints {
                            length += (*p - at).length();
                            at = *p;
                        }
                        // the smooth step's mean speed is the given one
                        duration = (length / v).max(1e-3);
                    }
                    let phi = rotation
                        .map(|r| r.axis.normalize_or_zero() * r.angle)
                        .unwrap_or(DVec3::ZERO);
                    h.move_along(&waypoints, phi, t0, duration);
                }
                if *wait {
                    self.advance(state, duration, obs)?;
                }
            }
            Action::ReleaseHand { hand } => {
                if let Some(h) = self.hand_slot(*hand).take() {
                    h.release(state);
                }
            }
            Action::Run { duration } => self.advance(state, *duration, obs)?,
            Action::Settle {
                kinetic_energy_threshold,
                max_duration,
            } => {
                let outcome =
                    self.settle(index, state, *kinetic_energy_threshold, *max_duration, obs)?;
                self.summary.settles.push(outcome);
            }
        }
        Ok(())
    }

    fn track(&mut self, n: NodeRef) {
        let i = self.global(n);
        if !self.peaks.iter().any(|(g, _)| *g == i) {
            let peak = NodePeak {
                hose: n.hose,
                node: n.node,
                ..Default::default()
            };
            self.peaks.push((i, peak));
        }
    }

    /// One explicit step plus health check, peak tracking and observation.
    fn hand_slot(&mut self, hand: usize) -> &mut Option<Hand> {
        if self.hands.len() <= hand {
            self.hands.resize_with(hand + 1, || None);
        }
        &mut self.hands[hand]
    }

    /// Hand loads of the last step, their assessment, and the hands' peaks.
    fn track_hands(&mut self, state: &State) {
        self.hand_records.clear();
        for (k, hand) in self.hands.iter().enumerate() {
            let Some(hand) = hand else { continue };
            let load = hand.load(self.model, state);
            let assessment = self.limits.and_then(|l| {
                l.assess(&self.profile, load.force, load.torque, load.direction)
                    .ok()
            });
            self.hand_records.push(HandRecord {
                hand: k,
                load,
                assessment,
            });
        }
        for r in &self.hand_records {
            let Some(p) = self
                .summary
                .hand_peaks
                .iter_mut()
                .find(|p| p.hand == r.hand)
            else {
                continue;
            };
            let (f, t) = (r.load.force.length(), r.load.torque.length());
            if f > p.max_force {
                p.max_force = f;
                p.max_force_time = state.time;
            }
            if t > p.max_torque {
                p.max_torque = t;
                p.max_torque_time = state.time;
            }
            if let Some(a) = &r.assessment {
                let w = a.worst();
                if w.ratio > p.worst_ratio {
                    p.worst_ratio = w.ratio;
                    p.worst_kind = Some(w.kind);
                    p.worst_magnitude = w.magnitude;
                    p.worst_limit = w.limit;
                    p.worst_time = state.time;
                }
            }
        }
    }

    /// Which parts the hoses touch this step, and the total contact force.
    fn track_contacts(&mut self, state: &State) {
        if self.contact_index.is_empty() {
            return;
        }
        for c in &state.contact.points {
            let t = state.time;
            match self.contact_index[c.part] {
                Some(k) => {
                    let e = &mut self.summary.contacts[k];
                    if e.last_time != t {
                        e.last_time = t;
                        e.steps += 1;
                    }
                }
                None => {
                    self.contact_index[c.part] = Some(self.summary.contacts.len());
                    let part = self.model.environment.parts[c.part].name.clone();
                    self.summary.contacts.push(ContactEpisode {
                        part,
                        first_time: t,
                        last_time: t,
                        steps: 1,
                    });
                }
            }
        }
        let total = state.contact_force.iter().map(|f| f.length()).sum::<f64>();
        if total > self.summary.max_contact_force {
            self.summary.max_contact_force = total;
            self.summary.max_contact_force_time = state.time;
        }
    }

    fn step(&mut self, state: &mut State, obs: &mut dyn Observer) -> Result<(), Divergence> {
        let t_next = state.time + self.solver.time_step(self.model);
        for hand in self.hands.iter().flatten() {
            hand.update(state, t_next);
        }
        if !self.fasteners.is_empty() {
            let (hands, records) = (&self.hands, &self.hand_records);
            let holder = |node: usize| {
                hands
                    .iter()
                    .position(|h| h.as_ref().is_some_and(|h| h.holds(node)))
            };
            let held = |node: usize| holder(node).is_some();
            let force = |node: usize| {
                holder(node)
                    .and_then(|k| records.iter().find(|r| r.hand == k))
                    .map_or(DVec3::ZERO, |r| r.load.force)
            };
            self.fasteners.update(self.model, state, &held, &force);
        }
        match self.solver.step(self.model, state) {
            Err(e) => return Err(e.into_divergence(self.model, state)),
            Ok(stats) => {
                let s = &mut self.summary;
                s.newton_iterations_max = s.newton_iterations_max.max(stats.iterations);
                if !stats.converged {
                    s.newton_unconverged_steps += 1;
                }
            }
        }
        let wants = obs.wants_state(state.time);
        if wants || state.step % HEALTH_CHECK_EVERY == 0 {
            check(self.model, state)?;
        }
        if !self.hands.is_empty() {
            self.track_hands(state);
        }
        self.track_contacts(state);
        for (i, p) in self.peaks.iter_mut() {
            let i = *i;
            if !state.held[i] {
                continue;
            }
            let (f, m) = (state.reaction_force[i], state.reaction_moment[i]);
            if f.length() > p.max_force {
                p.max_force = f.length();
                p.max_force_time = state.time;
            }
            if m.length() > p.max_moment {
                p.max_moment = m.length();
                p.max_moment_time = state.time;
            }
            p.last_force = f;
            p.last_moment = m;
        }
        if wants {
            obs.on_state(self.model, state);
            obs.on_hands(state.time, &self.hand_records);
            if !self.fasteners.is_empty() {
                self.fasteners
                    .sample(state.time, &mut self.summary.fastener_series);
            }
        }
        obs.on_step(state.time);
        Ok(())
    }

    fn advance(
        &mut self,
        state: &mut State,
        duration: f64,
        obs: &mut dyn Observer,
    ) -> Result<(), Divergence> {
        let steps = (duration / self.solver.time_step(self.model)).round() as u64;
        for _ in 0..steps {
            self.step(state, obs)?;
        }
        Ok(())
    }

    fn settle(
        &mut self,
        index: usize,
        state: &mut State,
        threshold: f64,
        max_duration: f64,
        obs: &mut dyn Observer,
    ) -> Result<SettleOutcome, Divergence> {
        let end = state.time + max_duration;
        loop {
            self.step(state, obs)?;
            if state.step % SETTLE_CHECK_EVERY == 0
                && !state.loads.any_drive_moving(state.time)
                && !self.hands.iter().flatten().any(|h| h.moving(state.time))
            {
                let ke = state.kinetic_energy(self.model);
                if ke < threshold {
                    return Ok(SettleOutcome {
                        action: index,
                        at_rest: true,
                        time: state.time,
                        kinetic_energy: ke,
                    });
                }
            }
            if state.time >= end {
                let ke = state.kinetic_energy(self.model);
                return Ok(SettleOutcome {
                    action: index,
                    at_rest: ke < threshold,
                    time: state.time,
                    kinetic_energy: ke,
                });
            }
        }
    }
}
