//! What a workcell keeps account of as it steps (SPEC I2, I5): the peak support loads of
//! every node a fix or drive held, each hand's peak push, pull, twist and bending (magnitudes, so
//! that a verdict can be judged again under another ergonomic profile), the rigid parts
//! the hoses touched, and the Newton solvers' statistics. Nothing here allocates once a
//! node, hand or part has been seen.

use super::input::HandNumber;
use super::solver_doubt::{InstabilityNote, SolverDoubt};
use super::solver_record::SolverRecord;
use crate::ergonomics::{
    en1005_action, En1005Action, En1005Judgement, En1005Limit, En1005Params, ErgonomicLimits,
    ErgonomicProfile, GuideRange, HandAssessment, LoadKind, Named, Standard,
};
use crate::fasteners::{FastenerReport, FastenerSample};
use crate::hand::HandLoad;
use glam::DVec3;
use pliant_core::integrators::{StabilityEvent, StepStats};
use pliant_core::{Model, State};
use pliant_worker::PostureClass;
use serde::{Serialize, Serializer};

/// One hand's load in one step and how it compares with the ergonomic limits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HandRecord {
    pub hand: usize,
    pub load: HandLoad,
    /// The fastener the hand works this step (its index in the run's fastener
    /// reports): the stub it presses a hose end onto, the clip it presses a hose into.
    pub fastener: Option<usize>,
    /// `None` only if the load was not finite (the step is then reported as diverged).
    pub assessment: Option<HandAssessment>,
    /// The worker's posture class whose rows judged the force (SPEC E2; `None`: no
    /// worker, or not posed yet — the profile's own rows judged it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub posture_class: Option<PostureClass>,
}

/// The largest magnitude of one load kind [N or N·m] and when \[s\].
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Peak {
    pub magnitude: f64,
    pub time: f64,
    /// The fastener the hand worked then (index in the run's fastener reports).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fastener: Option<usize>,
}

impl Peak {
    fn record(&mut self, magnitude: f64, time: f64, fastener: Option<usize>) {
        if physical(magnitude) && magnitude > self.magnitude {
            self.magnitude = magnitude;
            self.time = time;
            self.fastener = fastener;
        }
    }
}

/// A hand's peak push and pull while the worker was in one posture class (`None`: no
/// worker, or not posed yet), so that a verdict can judge each against its class's rows.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ClassPeaks {
    pub class: Option<PostureClass>,
    pub push: Peak,
    pub pull: Peak,
}

/// A peak moment (twist or bending) above the upper end of its guide range: a warning,
/// or a reason for infeasibility when it exceeds the limit and moments decide.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct MomentNote {
    pub kind: LoadKind,
    /// Peak magnitude \[N·m\] and when \[s\].
    pub magnitude: f64,
    pub time: f64,
    /// Upper end of the guide range and the limit value \[N·m\] (tables 3.10 / 3.11).
    pub guide_hi: f64,
    pub limit: f64,
}

/// A peak push or pull judged by EN 1005-3: its risk zone and the
/// recommended force limit it was judged against.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ZoneNote {
    pub kind: LoadKind,
    /// Peak magnitude \[N\] and when \[s\].
    pub magnitude: f64,
    pub time: f64,
    /// The action, in the data file's words (e.g. "whole body work, standing").
    pub action: String,
    /// F_B, F_Br, the multipliers and F_R.
    pub limit: En1005Limit,
    /// m_r = F / F_R and the zone.
    pub judgement: En1005Judgement,
}

/// Peak loads of one hand over the run, and its worst moment against the limits.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HandPeak {
    pub hand: usize,
    pub max_force: f64,
    pub max_force_time: f64,
    pub max_torque: f64,
    pub max_torque_time: f64,
    /// Peak push and pull (tables 3.6–3.9), twist and bending (tables 3.10 / 3.11).
    pub push: Peak,
    pub pull: Peak,
    pub twist: Peak,
    pub bending: Peak,
    /// Largest load/limit ratio of the loads that decide feasibility under the profile
    /// the run is judged with (the force; twist and bending too when `moments_decide`),
    /// its kind, magnitude, limit and time (filled in by [`Tally::judge_hands`]).
    pub worst_ratio: f64,
    pub worst_kind: Option<LoadKind>,
    pub worst_magnitude: f64,
    pub worst_limit: f64,
    pub worst_time: f64,
    /// The worker's posture class whose rows gave the worst limit (SPEC E2; `None`: the
    /// profile's own rows, or a moment).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_class: Option<PostureClass>,
    /// The peak push and pull per posture class met (at most one entry per class and
    /// one for no class).
    #[serde(skip)]
    pub class_peaks: Vec<ClassPeaks>,
    /// The fastener the hand worked at its worst moment (index in the run's fastener
    /// reports).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_fastener: Option<usize>,
    /// Twist and bending peaks above their guide range (filled in by
    /// [`Tally::judge_hands`]).
    pub moment_notes: Vec<MomentNote>,
    /// Under EN 1005-3: the peak push and pull (those that occurred) with their risk
    /// zones (filled in by [`Tally::judge_hands`]).
    pub zones: Vec<ZoneNote>,
}

impl HandPeak {
    /// The peaks with their kinds.
    pub fn each(&self) -> [(LoadKind, Peak); 4] {
        [
            (LoadKind::Push, self.push),
            (LoadKind::Pull, self.pull),
            (LoadKind::Twist, self.twist),
            (LoadKind::Bending, self.bending),
        ]
    }
}

/// The guide range and limit value of `kind` under `profile` [N or N·m].
pub fn limits_of(
    limits: &ErgonomicLimits,
    profile: &ErgonomicProfile,
    kind: LoadKind,
) -> (GuideRange, f64) {
    let (pop, duty) = (profile.population, profile.duty);
    match (kind, kind.torque_grip()) {
        (LoadKind::Push | LoadKind::Pull, _) => {
            let (guide, limit, _) = limits.force_limits(profile, kind == LoadKind::Push);
            (guide, limit)
        }
        (_, grip) => {
            let grip = grip.unwrap_or_default();
            (
                limits.torque_guide(grip, pop, duty),
                limits.torque_limit(grip, pop, duty),
            )
        }
    }
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

/// Peak support loads at one node that a fix or drive held at some point.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct NodePeak {
    pub hose: usize,
    pub node: usize,
    /// Largest |F| the support applied \[N\] and when \[s\].
    pub max_force: f64,
    pub max_force_time: f64,
    /// Largest |M| the support applied \[N·m\] and when \[s\].
    pub max_moment: f64,
    pub max_moment_time: f64,
    /// Support force and moment in the last step it held the node.
    pub last_force: DVec3,
    pub last_moment: DVec3,
}

/// Outcome of one `Settle` action ([`Workcell::settle`](super::Workcell::settle)).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SettleOutcome {
    /// The action's index in the timeline.
    pub action: usize,
    /// Converged: the residual within its tolerances, nothing moving, the kinetic energy
    /// below the threshold — before the action's maximum duration ran out.
    pub at_rest: bool,
    /// Simulated time when the settle ended \[s\].
    pub time: f64,
    /// Total kinetic energy then \[J\].
    pub kinetic_energy: f64,
    /// Largest out-of-balance force on a free node then, contact counted \[N\].
    pub residual_force: f64,
    /// Largest out-of-balance moment on a free node then \[N·m\].
    pub residual_moment: f64,
    /// A settle finished by the static solver (`finish = "static"`,
    /// [`Workcell::settle_finishing_static`](super::Workcell::settle_finishing_static)):
    /// the simulated time the static equilibrium was taken at \[s\]; `None` when no
    /// static solve was taken (a dynamic settle, or the solve refused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub static_solve_time: Option<f64>,
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
    /// Largest total contact force of the parts on the hoses \[N\] and when.
    pub max_contact_force: f64,
    pub max_contact_force_time: f64,
    /// The ergonomic profile hand loads were judged with.
    pub ergonomics: String,
    /// Whether twist and bending decided feasibility (the profile's `moments_decide`).
    pub moments_decide: bool,
    /// The standard that judged push and pull.
    pub standard: Standard,
    /// Stubs and clips and whether they ended assembled.
    pub fasteners: Vec<FastenerReport>,
    /// Their forces at the recorded times (the observer's sampling).
    pub fastener_series: Vec<FastenerSample>,
    /// Newton solvers only: iterations, steps out of balance, instabilities met.
    pub solver: SolverRecord,
    /// Why the study is uncertain ([`SolverRecord::warnings`]); empty when it is not.
    /// Serialised in words.
    #[serde(serialize_with = "in_words")]
    pub solver_warnings: Vec<SolverDoubt>,
    /// The instabilities met, hoses named. Serialised in words.
    #[serde(serialize_with = "in_words")]
    pub instability_notes: Vec<InstabilityNote>,
    /// The installation checks and their violations (SPEC V3).
    pub checks: crate::checks::ChecksSummary,
    /// What the worker did (SPEC E1–E2), if the scene has a worker.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worker: Option<crate::worker::WorkerSummary>,
}

/// Serialises `lines` as their `Display` text (the form `report.json` has always had).
fn in_words<T: std::fmt::Display, S: Serializer>(lines: &[T], out: S) -> Result<S::Ok, S::Error> {
    out.collect_seq(lines.iter().map(T::to_string))
}

/// The running account of a workcell.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// (global node, its peaks), in the order the nodes were first held.
    pub node_peaks: Vec<(usize, NodePeak)>,
    pub hand_peaks: Vec<HandPeak>,
    pub contacts: Vec<ContactEpisode>,
    /// Per part: index into `contacts` once touched.
    contact_index: Vec<Option<usize>>,
    pub max_contact_force: f64,
    pub max_contact_force_time: f64,
    pub fastener_series: Vec<FastenerSample>,
    pub solver: SolverRecord,
}

impl Tally {
    pub fn new(model: &Model) -> Self {
        Tally {
            contact_index: vec![None; model.environment.parts.len()],
            ..Default::default()
        }
    }

    /// Starts tracking the support loads of `node` (global) at `at`.
    pub fn track_node(&mut self, node: usize, at: crate::timeline::NodeRef) {
        if !self.node_peaks.iter().any(|(g, _)| *g == node) {
            let peak = NodePeak {
                hose: at.hose,
                node: at.node,
                ..Default::default()
            };
            self.node_peaks.push((node, peak));
        }
    }

    /// Starts a hand's peaks (once per hand number).
    pub fn track_hand(&mut self, hand: HandNumber) {
        let hand = hand as usize;
        if !self.hand_peaks.iter().any(|p| p.hand == hand) {
            self.hand_peaks.push(HandPeak {
                hand,
                ..Default::default()
            });
        }
    }

    /// Takes in one step: solver statistics and the instabilities it met, hand loads,
    /// contacts, support loads.
    pub fn record(
        &mut self,
        model: &Model,
        state: &State,
        (stats, events): (&StepStats, &[StabilityEvent]),
        hands: &[HandRecord],
    ) {
        let t = state.time;
        self.solver.record_step(t, stats);
        self.solver.record_instabilities(model, events);
        for r in hands {
            let Some(p) = self.hand_peaks.iter_mut().find(|p| p.hand == r.hand) else {
                continue;
            };
            let (f, m) = (r.load.force.length(), r.load.torque.length());
            if physical(f) && f > p.max_force {
                p.max_force = f;
                p.max_force_time = t;
            }
            if physical(m) && m > p.max_torque {
                p.max_torque = m;
                p.max_torque_time = t;
            }
            if let Some(a) = &r.assessment {
                let at = r.fastener;
                let class = match p
                    .class_peaks
                    .iter()
                    .position(|c| c.class == r.posture_class)
                {
                    Some(i) => &mut p.class_peaks[i],
                    None => {
                        p.class_peaks.push(ClassPeaks {
                            class: r.posture_class,
                            push: Peak::default(),
                            pull: Peak::default(),
                        });
                        p.class_peaks.last_mut().expect("just pushed")
                    }
                };
                match a.force.kind {
                    LoadKind::Pull => {
                        p.pull.record(a.force.magnitude, t, at);
                        class.pull.record(a.force.magnitude, t, at);
                    }
                    _ => {
                        p.push.record(a.force.magnitude, t, at);
                        class.push.record(a.force.magnitude, t, at);
                    }
                }
                p.twist.record(a.twist.magnitude, t, at);
                p.bending.record(a.bending.magnitude, t, at);
            }
        }
        self.record_contacts(model, state);
        for (i, p) in self.node_peaks.iter_mut() {
            let i = *i;
            if !state.held[i] {
                continue;
            }
            let (f, m) = (state.reaction_force[i], state.reaction_moment[i]);
            if physical(f.length()) && f.length() > p.max_force {
                p.max_force = f.length();
                p.max_force_time = t;
            }
            if physical(m.length()) && m.length() > p.max_moment {
                p.max_moment = m.length();
                p.max_moment_time = t;
            }
            // the last *physical* loads: the steps of a divergence before its health
            // check (at most 15) never reach the outputs as NaN
            if physical(f.length()) {
                p.last_force = f;
            }
            if physical(m.length()) {
                p.last_moment = m;
            }
        }
    }

    /// Which parts the hoses touch this step, and the total contact force.
    fn record_contacts(&mut self, model: &Model, state: &State) {
        if self.contact_index.is_empty() {
            return;
        }
        let t = state.time;
        for c in &state.contact.points {
            match self.contact_index[c.part] {
                Some(k) => {
                    let e = &mut self.contacts[k];
                    if e.last_time != t {
                        e.last_time = t;
                        e.steps += 1;
                    }
                }
                None => {
                    self.contact_index[c.part] = Some(self.contacts.len());
                    self.contacts.push(ContactEpisode {
                        part: model.environment.parts[c.part].name.clone(),
                        first_time: t,
                        last_time: t,
                        steps: 1,
                    });
                }
            }
        }
        let total = state.contact_force.iter().map(|f| f.length()).sum::<f64>();
        if physical(total) && total > self.max_contact_force {
            self.max_contact_force = total;
            self.max_contact_force_time = t;
        }
    }

    /// The hands' peaks with their worst ratio judged under `profile`.
    pub fn judge_hands(
        &self,
        limits: Option<&ErgonomicLimits>,
        profile: &ErgonomicProfile,
    ) -> Vec<HandPeak> {
        let mut out = self.hand_peaks.clone();
        let Some(limits) = limits else { return out };
        for p in &mut out {
            for (kind, peak) in p.each() {
                let (guide, limit) = limits_of(limits, profile, kind);
                if profile.standard == Standard::En1005_3
                    && !kind.is_moment()
                    && peak.magnitude > 0.0
                {
                    for (action, peak) in en1005_peaks(p, profile, kind, peak) {
                        let params = En1005Params {
                            action,
                            ..profile.en1005
                        };
                        let l = limits.en1005().limit(&params, kind == LoadKind::Push);
                        p.zones.push(ZoneNote {
                            kind,
                            magnitude: peak.magnitude,
                            time: peak.time,
                            action: limits.en1005().describe(action).to_string(),
                            limit: l,
                            judgement: l.judge(peak.magnitude),
                        });
                    }
                }
                if kind.is_moment() && peak.magnitude > guide.hi {
                    p.moment_notes.push(MomentNote {
                        kind,
                        magnitude: peak.magnitude,
                        time: peak.time,
                        guide_hi: guide.hi,
                        limit,
                    });
                }
                if kind.is_moment() && !profile.moments_decide {
                    continue;
                }
                if kind.is_moment() || p.class_peaks.is_empty() {
                    p.note_worst(kind, peak, limit, None);
                }
            }
            // each posture class's peak push and pull against its class's rows
            for i in 0..p.class_peaks.len() {
                let c = p.class_peaks[i];
                let judged_by = c.class.map_or(*profile, |class| profile.for_class(class));
                for (kind, peak) in [(LoadKind::Push, c.push), (LoadKind::Pull, c.pull)] {
                    let (_, limit) = limits_of(limits, &judged_by, kind);
                    p.note_worst(kind, peak, limit, c.class);
                }
            }
        }
        out
    }
}

impl HandPeak {
    /// Takes `peak` of `kind` against `limit` as the worst if its ratio is the largest yet.
    fn note_worst(&mut self, kind: LoadKind, peak: Peak, limit: f64, class: Option<PostureClass>) {
        let ratio = peak.magnitude / limit;
        if ratio.is_finite() && ratio > self.worst_ratio {
            self.worst_ratio = ratio;
            self.worst_kind = Some(kind);
            self.worst_magnitude = peak.magnitude;
            self.worst_limit = limit;
            self.worst_time = peak.time;
            self.worst_fastener = peak.fastener;
            self.worst_class = class;
        }
    }
}

/// The peak push or pull (`kind`) of hand `p` per EN 1005-3 action it was judged by, in
/// table order: the profile's own action, or a seated posture class's
/// ([`crate::ergonomics::en1005_action`]); `overall` the hand's peak when no class was met.
/// A worker who only stood gives the profile's action with the overall peak.
fn en1005_peaks(
    p: &HandPeak,
    profile: &ErgonomicProfile,
    kind: LoadKind,
    overall: Peak,
) -> Vec<(En1005Action, Peak)> {
    let mut by_action = [None::<Peak>; En1005Action::ALL.len()];
    if p.class_peaks.is_empty() {
        by_action[profile.en1005.action.index()] = Some(overall);
    }
    for c in &p.class_peaks {
        let action = c
            .class
            .and_then(en1005_action)
            .unwrap_or(profile.en1005.action);
        let peak = if kind == LoadKind::Pull {
            c.pull
        } else {
            c.push
        };
        let slot = &mut by_action[action.index()];
        if peak.magnitude > 0.0 && slot.is_none_or(|s| peak.magnitude > s.magnitude) {
            *slot = Some(peak);
        }
    }
    En1005Action::ALL
        .iter()
        .filter_map(|&a| by_action[a.index()].map(|peak| (a, peak)))
        .collect()
}

/// Whether a force \[N\] or moment \[N·m\] is a physical value and may become a peak: the
/// steps between two health checks ([`super::HEALTH_CHECK_EVERY`]) can hold the first
/// numbers of a blow-up, which must not reach the report.
fn physical(x: f64) -> bool {
    x.is_finite() && x <= pliant_core::health::MAX_FORCE
}
