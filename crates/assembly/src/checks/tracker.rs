//! The installation checks as a study runs (SPEC V3): every `interval` seconds of
//! simulated time the curvature and the twist of every beam (`strain.rs`) are compared
//! with the limits, and per hose and check the worst violation is kept with its place
//! and time; at the end the assembled state is checked for tension and for the straight
//! length behind each stub. All buffers are sized when the tracker is built: nothing is
//! allocated while checking, except the first time a check is violated on a hose.

use super::kind::{CheckKind, Violation};
use super::pictures::ScenePictures;
use super::settings::CheckSettings;
use super::strain::{axial_strain, bend_and_twist};
use crate::fasteners::StubSite;
use crate::stub::StubLaw;
use crate::sweep::MotionSweep;
use glam::DQuat;
use pliant_core::{Model, State};
use serde::Serialize;

/// One hose's curvature and twist along its length at its worst instants (for the
/// report's plots).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct HoseProfile {
    pub hose: usize,
    pub hose_name: String,
    /// Arc length of each beam's midpoint from the first node (rest length) \[m\].
    pub arc_length: Vec<f64>,
    /// The bend met furthest past its beam's minimum radius (largest κ·r_min; the
    /// smallest radius where one minimum holds throughout): that beam's radius \[m\] (∞
    /// when straight throughout), when \[s\], and that beam's minimum allowed \[m\].
    pub min_bend_radius: f64,
    pub min_bend_radius_time: f64,
    pub allowed_bend_radius: f64,
    /// That bend's ratio κ·r_min = r_min / r (above 1 it breaks the minimum).
    pub worst_bend_ratio: f64,
    /// Curvature κ per beam [1/m] at that instant.
    pub curvature: Vec<f64>,
    /// The largest curvature allowed per beam, 1/r_min [1/m] (a protected stretch has
    /// its own minimum radius).
    pub allowed_curvature: Vec<f64>,
    /// Largest twist rate relative to the routed hose met [rad/m], when \[s\], its limit.
    pub max_twist: f64,
    pub max_twist_time: f64,
    pub twist_limit: f64,
    /// Twist rate relative to the routed hose per beam [rad/m] at that instant.
    pub twist: Vec<f64>,
    /// This hose's first global node and node count.
    pub first_node: usize,
    pub node_count: usize,
}

/// The checks' account of a study.
#[derive(Clone, Debug, PartialEq)]
pub struct InstallationChecks {
    settings: CheckSettings,
    /// Per beam: its hose and its rest twist rate [rad/m].
    beam_hose: Vec<usize>,
    rest_twist: Vec<f64>,
    /// Per beam, the values at the instant being checked (scratch).
    kappa: Vec<f64>,
    dtwist: Vec<f64>,
    next_time: f64,
    /// Per hose × running check (bend radius, twist): the worst violation so far.
    running: Vec<[Option<Violation>; 2]>,
    profiles: Vec<HoseProfile>,
    /// The scene at the worst bends of the few hoses bent furthest below their limit.
    pictures: ScenePictures,
    /// The range-of-motion rows, if the study sweeps a motion.
    sweep: Option<MotionSweep>,
}

impl InstallationChecks {
    /// A tracker for `model` with `settings` (whose `hoses` must match the model's
    /// hoses; missing hoses are not checked).
    pub fn new(model: &Model, settings: CheckSettings) -> Self {
        let n = model.elements.len();
        let mut beam_hose = vec![usize::MAX; n];
        let mut rest_twist = vec![0.0; n];
        let mut profiles = Vec::with_capacity(model.hoses.len());
        for (h, info) in model.hoses.iter().enumerate() {
            let mut s = 0.0;
            let mut arc = Vec::with_capacity(info.element_count);
            for e in info.first_element..info.first_element + info.element_count {
                let el = &model.elements[e];
                beam_hose[e] = h;
                // the stress-free shape's twist (as routed, or as delivered)
                let rest = el.rest_relative_rotation();
                rest_twist[e] = bend_and_twist(DQuat::IDENTITY, rest, el.rest_length).1;
                arc.push(s + 0.5 * el.rest_length);
                s += el.rest_length;
            }
            let limits = settings.hoses.get(h);
            profiles.push(HoseProfile {
                hose: h,
                hose_name: info.name.clone(),
                curvature: vec![0.0; arc.len()],
                allowed_curvature: (0..arc.len())
                    .map(|k| limits.map_or(0.0, |l| 1.0 / l.bend_radius_at(k)))
                    .collect(),
                twist: vec![0.0; arc.len()],
                arc_length: arc,
                min_bend_radius: f64::INFINITY,
                allowed_bend_radius: limits.map_or(0.0, |l| l.min_bend_radius),
                twist_limit: settings.twist_limit,
                first_node: info.first_node,
                node_count: info.node_count,
                ..Default::default()
            });
        }
        let sweep = settings.sweep.as_ref().map(|s| {
            let allowed = model
                .hoses
                .iter()
                .enumerate()
                .map(|(h, info)| {
                    (0..info.element_count)
                        .map(|k| settings.hoses.get(h).map_or(0.0, |l| l.bend_radius_at(k)))
                        .collect()
                })
                .collect();
            MotionSweep::new(model, s, allowed, settings.twist_limit)
        });
        InstallationChecks {
            sweep,
            running: vec![[None, None]; model.hoses.len()],
            kappa: vec![0.0; n],
            dtwist: vec![0.0; n],
            beam_hose,
            rest_twist,
            next_time: 0.0,
            profiles,
            pictures: ScenePictures::default(),
            settings,
        }
    }

    pub fn settings(&self) -> &CheckSettings {
        &self.settings
    }

    /// Beam `e`'s twist rate in the routed, unloaded hose [rad/m].
    pub(super) fn rest_twist(&self, e: usize) -> f64 {
        self.rest_twist[e]
    }

    /// Checks the state if a checked instant is due (every `interval` seconds of
    /// simulated time, so that every shell checks the same instants).
    pub fn observe(&mut self, model: &Model, state: &State) {
        if !self.due(state.time) {
            return;
        }
        self.next_time = state.time + self.settings.interval;
        self.check_now(model, state);
    }

    /// Whether [`Self::observe`] would check a state at `time`.
    pub fn due(&self, time: f64) -> bool {
        self.settings.any_running() && time + 1e-12 >= self.next_time
    }

    /// Checks the state now (curvature and twist of every beam).
    pub fn check_now(&mut self, model: &Model, state: &State) {
        for (e, el) in model.elements.iter().enumerate() {
            let (k, t) = bend_and_twist(state.q[el.node_a], state.q[el.node_b], el.rest_length);
            self.kappa[e] = k;
            self.dtwist[e] = t - self.rest_twist[e];
        }
        if let Some(sweep) = &mut self.sweep {
            sweep.record(model, state, &self.kappa, &self.dtwist);
        }
        let time = state.time;
        for (h, info) in model.hoses.iter().enumerate() {
            let Some(limits) = self.settings.hoses.get(h) else {
                continue;
            };
            let range = info.first_element..info.first_element + info.element_count;
            // the beam bent furthest past its own minimum radius: largest κ·r_min
            let (mut worst, mut wat) = (0.0, range.start);
            let (mut tmax, mut tat) = (0.0, range.start);
            for e in range.clone() {
                let ratio = self.kappa[e] * limits.bend_radius_at(e - range.start);
                if ratio > worst {
                    (worst, wat) = (ratio, e);
                }
                if self.dtwist[e].abs() > tmax {
                    (tmax, tat) = (self.dtwist[e].abs(), e);
                }
            }
            let p = &mut self.profiles[h];
            if worst > p.worst_bend_ratio {
                p.worst_bend_ratio = worst;
                p.min_bend_radius = 1.0 / self.kappa[wat];
                p.allowed_bend_radius = limits.bend_radius_at(wat - range.start);
                p.min_bend_radius_time = time;
                p.curvature.copy_from_slice(&self.kappa[range.clone()]);
                if worst > 1.0 {
                    let poses = (0..model.environment.parts.len())
                        .map(|k| model.part_placement(state, k, time).pose);
                    self.pictures.note(h, worst, time, &state.x, poses);
                }
            }
            if tmax > p.max_twist {
                p.max_twist = tmax;
                p.max_twist_time = time;
                p.twist.copy_from_slice(&self.dtwist[range.clone()]);
            }
            let first = info.first_element;
            let arc = |e: usize| p.arc_length[e - first];
            if self.settings.bend_radius && worst > 1.0 {
                let allowed = limits.bend_radius_at(wat - first);
                note(
                    &mut self.running[h][0],
                    CheckKind::BendRadius,
                    h,
                    info,
                    arc(wat),
                    time,
                    1.0 / self.kappa[wat],
                    allowed,
                );
            }
            if self.settings.twist && tmax > self.settings.twist_limit {
                let s = arc(tat);
                note(
                    &mut self.running[h][1],
                    CheckKind::Twist,
                    h,
                    info,
                    s,
                    time,
                    tmax,
                    self.settings.twist_limit,
                );
            }
        }
    }

    /// The curvature and twist profiles of every hose at its worst instants.
    pub fn profiles(&self) -> &[HoseProfile] {
        &self.profiles
    }

    /// The range-of-motion rows, if the study sweeps a motion.
    pub fn sweep(&self) -> Option<&MotionSweep> {
        self.sweep.as_ref()
    }

    /// The scene at the worst bends of the hoses bent furthest below their limit.
    pub fn pictures(&self) -> &ScenePictures {
        &self.pictures
    }

    /// The violations of the running checks so far (bend radius, twist), hose by hose.
    pub fn running_violations(&self) -> impl Iterator<Item = &Violation> {
        self.running.iter().flat_map(|r| r.iter().flatten())
    }

    /// The checks of the assembled state `state` (the end of a study): no axial
    /// tension at rest; a straight length behind each stub.
    pub fn end_violations(
        &self,
        model: &Model,
        state: &State,
        stubs: &[StubSite],
    ) -> Vec<Violation> {
        let mut out = Vec::new();
        let time = state.time;
        for (h, info) in model.hoses.iter().enumerate() {
            let Some(limits) = self.settings.hoses.get(h) else {
                continue;
            };
            let profile = &self.profiles[h];
            if self.settings.tension_at_rest {
                let mut worst: Option<(f64, f64, f64)> = None; // (force, strain limit force, s)
                for (k, e) in
                    (info.first_element..info.first_element + info.element_count).enumerate()
                {
                    let el = &model.elements[e];
                    let strain = axial_strain(model, state, e);
                    let force = el.axial_stiffness_tension * strain.max(0.0);
                    let limit = el.axial_stiffness_tension * self.settings.rest_strain_limit;
                    if strain > self.settings.rest_strain_limit
                        && worst.is_none_or(|w| force / limit > w.0 / w.1)
                    {
                        worst = Some((force, limit, profile.arc_length[k]));
                    }
                }
                if let Some((force, limit, s)) = worst {
                    out.push(end_violation(
                        CheckKind::TensionAtRest,
                        h,
                        info,
                        s,
                        time,
                        force,
                        limit,
                        None,
                    ));
                }
            }
            if self.settings.straight_behind_stub {
                let straight = self.settings.straight_radius_factor * limits.min_bend_radius;
                let length = self.settings.straight_length_factor * limits.d_outer;
                // the hose-line rule behind a hose's stub; a connector's bundle is not a hose
                let on_stub = |s: &&StubSite| matches!(s.fit, StubLaw::PressFit(_));
                for stub in stubs
                    .iter()
                    .filter(on_stub)
                    .filter(|s| info.nodes().contains(&s.end_node))
                {
                    let from_start = stub.end_node == info.first_node;
                    let mut worst: Option<(f64, f64)> = None; // (radius, s)
                    let mut s0 = 0.0;
                    for k in 0..info.element_count {
                        // beams in order away from the stub end
                        let k_el = if from_start {
                            k
                        } else {
                            info.element_count - 1 - k
                        };
                        if s0 >= length {
                            break;
                        }
                        let el = &model.elements[info.first_element + k_el];
                        s0 += el.rest_length;
                        let (kappa, _) =
                            bend_and_twist(state.q[el.node_a], state.q[el.node_b], el.rest_length);
                        let radius = 1.0 / kappa;
                        if radius < straight && worst.is_none_or(|w| radius < w.0) {
                            worst = Some((radius, profile.arc_length[k_el]));
                        }
                    }
                    if let Some((radius, s)) = worst {
                        out.push(end_violation(
                            CheckKind::StraightBehindStub,
                            h,
                            info,
                            s,
                            time,
                            radius,
                            straight,
                            Some(stub.name.clone()),
                        ));
                    }
                }
            }
        }
        out
    }
}

/// Records a violation of a running check: worst value, its place and time, first and
/// last instant.
#[allow(clippy::too_many_arguments)]
fn note(
    slot: &mut Option<Violation>,
    check: CheckKind,
    hose: usize,
    info: &pliant_core::HoseInfo,
    arc_length: f64,
    time: f64,
    value: f64,
    limit: f64,
) {
    match slot {
        Some(v) => {
            v.last_time = time;
            v.instants += 1;
            let worse = if check.lower_bound() {
                value < v.value
            } else {
                value > v.value
            };
            if worse {
                (v.value, v.arc_length, v.time) = (value, arc_length, time);
            }
        }
        None => {
            *slot = Some(end_violation(
                check, hose, info, arc_length, time, value, limit, None,
            ))
        }
    }
}

/// A violation seen at one instant (a first one, or one of the assembled state).
#[allow(clippy::too_many_arguments)]
fn end_violation(
    check: CheckKind,
    hose: usize,
    info: &pliant_core::HoseInfo,
    arc_length: f64,
    time: f64,
    value: f64,
    limit: f64,
    at: Option<String>,
) -> Violation {
    Violation {
        check,
        hose,
        hose_name: info.name.clone(),
        arc_length,
        time,
        value,
        limit,
        first_time: time,
        last_time: time,
        instants: 1,
        at,
    }
}
