//! Connector stubs (SPEC L6) and clips (SPEC L7) acting on the simulation: each step the
//! assembly layer observes the hose, advances each fastener's state machine and turns the
//! state into load cases — the stub's press-fit friction as a force on the hose end while
//! it is pushed on, an L1 fix once it is released on the stub (on the stub's axis, the end
//! turned onto it); the clip's snap force on
//! the beam crossing the clip while it snaps in, an L1 fix of that point once seated.
//! Forces on a node a hand holds end up in the hand's load, which is what the worker
//! feels.
//!
//! A fastener on a moving part goes with it: it observes the hose in the part's
//! reference placement ([`PartFrame`]), turns its forces into world axes, measures the
//! hose's sliding on the stub relative to the part, and holds what it fastens with a
//! mount (a stub's end and a fixed clip's seat; held where they are when the hold closes)
//! or a support carried with the part's pose and velocity (a rotating or sliding clip).

use crate::clip::{ClipObservation, ClipSpec, ClipState, ClipTolerance};
use crate::fastener_state::{FastenerKind, FastenerState};
use crate::part_frame::PartFrame;
use crate::stub::{
    AxialLaw, FitRelaxation, FitTerms, StubLaw, StubObservation, StubState, StubTolerance,
};
use glam::DVec3;
use pliant_core::kinematics::Pose;
use pliant_core::loads::{DeadLoad, Drive, LoadCase, LoadCaseId};
use pliant_core::math::{log_map, rotation_between};
use pliant_core::{Model, State};
use serde::Serialize;
use std::ops::Range;

/// Axial speed below which stub friction is regularised linearly \[m/s\] (a Coulomb law
/// smoothed over ±1 mm/s so that a hose held still on the stub does not chatter).
const FRICTION_SPEED: f64 = 1e-3;

/// Time over which a hose end released on a stub is carried onto the stub's axis \[s\].
/// While inserting, the hand may hold the end a little off the axis (up to the stub's
/// radius). Moved there within one step, the fix's reaction — the stub force reported —
/// was m·Δx/Δt²: in a variant of the engine-bay study 2 452 N at time-step safety 0.25,
/// 613 N at 0.5, 189 N at 0.9, against 164 N at every step now. Over 50 ms with a smooth
/// start and stop the end's inertia adds ≈ 5.8·m·Δx/T² (0.1 N for 2 mm), and the force is
/// the hose's elastic reaction.
const SEATING_TIME: f64 = 0.05;

/// A stub and the hose end meant to go onto it, or a connector's counterpart and the hose
/// end carrying the plug.
#[derive(Clone, Debug)]
pub struct StubSite {
    pub name: String,
    /// The press fit on the stub, or the connector's mating law.
    pub fit: StubLaw,
    /// Global index of the hose's end node, and of its neighbour (gives the direction).
    pub end_node: usize,
    pub inner_node: usize,
    /// The part the stub sits on (index into the model's parts), if any: it goes with it.
    pub part: Option<usize>,
}

/// A clip and the hose meant to go into it.
#[derive(Clone, Debug)]
pub struct ClipSite {
    pub name: String,
    pub spec: ClipSpec,
    pub hose: usize,
    /// The part the clip sits on (index into the model's parts), if any: it goes with it.
    pub part: Option<usize>,
    /// The clip takes the hose only when a hand presses it in through its opening (a
    /// fixing on a harness pushed into its hole): a hose drawn through it, passing by, or
    /// carried into the jaws from behind is not held.
    pub by_hand: bool,
}

/// How a fastener did over the run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct FastenerReport {
    pub name: String,
    pub kind: FastenerKind,
    /// Largest force the fastener applied to the hose \[N\] and when.
    pub max_force: f64,
    pub max_force_time: f64,
    /// State at the end of the run (e.g. fixed, seated, approach).
    pub final_state: FastenerState,
    /// Whether the fastener ended in its assembled state (stub: fixed; connector: fixed
    /// and latched; clip: seated).
    pub assembled: bool,
    /// The axial pull that would start the hose off its stub or connector at the end of
    /// the run \[N\] — a rubber hose's press fit relaxed ([`crate::stub::FitRelaxation`])
    /// — 0 off it and for clips.
    pub holding_force: f64,
}

/// A fastener's dead load and what was last written to it: a step that would write the
/// same node and the same bits again leaves the load case alone (a seated clip's and a
/// fixed stub's force stays zero for most of a run, and finding a load case by its
/// handle is a search). Only the fastener writes it.
#[derive(Clone, Copy)]
struct ForceLoad {
    id: LoadCaseId,
    node: usize,
    force: DVec3,
}

impl ForceLoad {
    /// A zero dead load on `node`, added to `state`.
    fn new(state: &mut State, node: usize) -> Self {
        let id = state.loads.add(LoadCase::DeadLoad(DeadLoad {
            node,
            force: DVec3::ZERO,
            moment: DVec3::ZERO,
            ramp: None,
        }));
        ForceLoad {
            id,
            node,
            force: DVec3::ZERO,
        }
    }

    /// Sets the dead load to `force` on `node`.
    fn set(&mut self, state: &mut State, node: usize, force: DVec3) {
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        if node == self.node && bits(force) == bits(self.force) {
            return;
        }
        if let Some(LoadCase::DeadLoad(d)) = state.loads.get_mut(self.id) {
            d.node = node;
            d.force = force;
        }
        (self.node, self.force) = (node, force);
    }
}

#[derive(Clone)]
struct StubRun {
    site: StubSite,
    /// Checked once; `None` if invalid: the stub then never acts (as
    /// [`StubState::next`] would refuse every step).
    tolerance: Option<StubTolerance>,
    state: StubState,
    /// How far the press fit has relaxed (a hose of a relaxing material).
    relaxation: FitRelaxation,
    force: ForceLoad,
    fix: Option<LoadCaseId>,
    report: FastenerReport,
    force_now: f64,
    /// The node by which a hand holds the hose at the stub this step, if one does.
    worked_at: Option<usize>,
}

#[derive(Clone)]
struct ClipRun {
    site: ClipSite,
    /// Checked once; `None` if invalid: the clip then never acts (as
    /// [`ClipState::next`] would refuse every step).
    tolerance: Option<ClipTolerance>,
    state: ClipState,
    /// Dead loads on the two nodes of the crossing beam.
    forces: [ForceLoad; 2],
    fix: Option<LoadCaseId>,
    report: FastenerReport,
    force_now: f64,
    /// The node by which a hand holds the hose at the clip this step, if one does.
    worked_at: Option<usize>,
    /// Pulled loose by more than its holding force; it seats again only after the hose
    /// has left the seat.
    loosened: bool,
    /// The hose centre's coordinate s along the opening in the last step, if it crossed
    /// the clip's plane.
    last_coordinate: Option<f64>,
    /// The pose of the clip's moving part its support was last placed at.
    carried: Option<Pose>,
}

/// All fasteners of a run.
#[derive(Clone, Default)]
pub struct Fasteners {
    stubs: Vec<StubRun>,
    clips: Vec<ClipRun>,
}

/// A fastener's force at one recorded time (index into the run's fastener reports).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FastenerSample {
    pub time: f64,
    pub fastener: usize,
    /// Magnitude of the force the fastener applies to the hose \[N\].
    pub force: f64,
}

/// Whether a hand holds `node`; `held` lists the held nodes with their hand's force.
fn held_by_hand(held: &[(usize, DVec3)], node: usize) -> bool {
    held.iter().any(|&(n, _)| n == node)
}

/// The force of the hand holding `node` (zero if none holds it).
fn hand_force(held: &[(usize, DVec3)], node: usize) -> DVec3 {
    held.iter()
        .find(|&&(n, _)| n == node)
        .map_or(DVec3::ZERO, |&(_, f)| f)
}

impl Fasteners {
    /// Sets up the fasteners; their force load cases are added to `state` (initially zero).
    /// A clip whose hose is drawn in its seat (inside its jaws) starts seated.
    pub fn new(
        model: &Model,
        state: &mut State,
        stubs: Vec<StubSite>,
        clips: Vec<ClipSite>,
    ) -> Self {
        let stubs = stubs
            .into_iter()
            .map(|site| StubRun {
                tolerance: StubTolerance::for_stub(site.fit.stub()).checked(),
                state: StubState::Approach,
                relaxation: FitRelaxation::new(
                    site.fit
                        .press_fit()
                        .map_or(FitTerms::new(&[]), |f| *f.relaxation()),
                    state.time,
                ),
                force: ForceLoad::new(state, site.end_node),
                fix: None,
                report: FastenerReport {
                    name: site.name.clone(),
                    kind: site.fit.kind(),
                    ..Default::default()
                },
                force_now: 0.0,
                worked_at: None,
                site,
            })
            .collect();
        let clips = clips
            .into_iter()
            .map(|site| ClipRun {
                tolerance: ClipTolerance::for_clip(&site.spec).checked(),
                state: if !site.by_hand && drawn_seated(model, state, &site) {
                    ClipState::Seated
                } else {
                    ClipState::Free
                },
                forces: [ForceLoad::new(state, 0), ForceLoad::new(state, 0)],
                fix: None,
                report: FastenerReport {
                    name: site.name.clone(),
                    kind: FastenerKind::Clip,
                    ..Default::default()
                },
                force_now: 0.0,
                worked_at: None,
                loosened: false,
                last_coordinate: None,
                carried: None,
                site,
            })
            .collect();
        Fasteners { stubs, clips }
    }

    pub fn is_empty(&self) -> bool {
        self.stubs.is_empty() && self.clips.is_empty()
    }

    /// Whether no fastener's force law acts now: no clip snapping and no stub pushing on
    /// its hose (a stub holds a released end by a load case), so that the loads on the hoses are their load cases alone (what the
    /// quasi-static solver sees).
    pub fn quiet(&self) -> bool {
        let stub_quiet = |s: &StubRun| {
            s.fix.is_some()
                || !matches!(
                    s.state,
                    StubState::Inserting { .. } | StubState::Fixed { .. }
                )
        };
        self.stubs.iter().all(stub_quiet) && self.clips.iter().all(|c| !c.state.force_acts())
    }

    /// One step's update, before the physics step to `t_next`. `held` lists the nodes the
    /// hands hold, each with the force of the hand holding it (last step).
    pub fn update(
        &mut self,
        model: &Model,
        state: &mut State,
        held: &[(usize, DVec3)],
        t_next: f64,
    ) {
        for s in &mut self.stubs {
            let frame = PartFrame::at(model, state, s.site.part, state.time);
            update_stub(s, state, held, &frame);
        }
        for c in &mut self.clips {
            let frame = PartFrame::at(model, state, c.site.part, state.time);
            update_clip(c, model, state, held, &frame);
            if frame.moves() {
                let next = PartFrame::at(model, state, c.site.part, t_next);
                carry_support(c, state, &next);
            }
        }
    }

    /// Appends each fastener's current force (same order as [`Fasteners::reports`]).
    pub fn sample(&self, time: f64, out: &mut Vec<FastenerSample>) {
        let forces = self
            .stubs
            .iter()
            .map(|s| s.force_now)
            .chain(self.clips.iter().map(|c| c.force_now));
        out.extend(forces.enumerate().map(|(fastener, force)| FastenerSample {
            time,
            fastener,
            force,
        }));
    }

    /// The fastener (its index in [`Fasteners::reports`]) a hand holding `node` works
    /// this step: one whose hose the hand holds at the fastener while the fastener pushes
    /// back on it (a hose end being pressed onto a stub, a hose snapping into a clip).
    pub fn worked_through(&self, node: usize) -> Option<usize> {
        let stubs = self.stubs.iter().map(|s| (s.worked_at, s.force_now));
        let clips = self.clips.iter().map(|c| (c.worked_at, c.force_now));
        stubs
            .chain(clips)
            .position(|(at, force)| at == Some(node) && force > 0.0)
    }

    /// Reports at the end of the run (the final states are set here, not every step).
    pub fn reports(&self) -> Vec<FastenerReport> {
        let stubs = self.stubs.iter().map(|s| FastenerReport {
            final_state: stub_final_state(s),
            ..s.report.clone()
        });
        let clips = self.clips.iter().map(|c| FastenerReport {
            final_state: c.state.into(),
            ..c.report.clone()
        });
        stubs.chain(clips).collect()
    }
}

/// A stub's state as reports give it; a connector released on its counterpart is
/// latched or half mated.
fn stub_final_state(s: &StubRun) -> FastenerState {
    match (s.state, &s.site.fit) {
        (StubState::Fixed { depth }, StubLaw::Mating(m)) if m.latched(depth) => {
            FastenerState::Latched
        }
        (StubState::Fixed { .. }, StubLaw::Mating(_)) => FastenerState::HalfMated,
        (state, _) => state.into(),
    }
}

fn update_stub(s: &mut StubRun, state: &mut State, held: &[(usize, DVec3)], frame: &PartFrame) {
    let (e, n) = (s.site.end_node, s.site.inner_node);
    let stub = s.site.fit.stub();
    // the stub's axis in world axes (the stub is given in its part's reference placement)
    let axis = frame.direction_to_world(stub.axis());
    let grabbed = held_by_hand(held, e) || held_by_hand(held, n);
    s.worked_at = [e, n].into_iter().find(|&k| held_by_hand(held, k));
    let obs = StubObservation {
        end_position: frame.point_to_part(state.x[e]),
        end_direction: frame.direction_to_part(state.x[e] - state.x[n]),
        axial_force: hand_force(held, e).dot(axis),
        grabbed,
    };
    let Some(tolerance) = &s.tolerance else {
        return;
    };
    s.relaxation.advance(state.time, s.state.depth());
    let fit = s.site.fit.relaxed(s.relaxation.ratio());
    let Ok(next) = s.state.next_within(&fit, tolerance, &obs) else {
        return;
    };
    s.state = next;
    let mut force = DVec3::ZERO;
    match next {
        StubState::Fixed { depth } if !grabbed => {
            if s.fix.is_none() && frame.moves() {
                // on a moving part: held where it was released, carried with the part
                s.fix = Some(state.loads.add(frame.hold(e, state.x[e], state.q[e])));
            } else if s.fix.is_none() {
                // the end sits on the stub: on its axis at the insertion depth, its tangent
                // turned onto the axis (SPEC L6: the hose end is aligned with the stub),
                // carried there smoothly from where the hand left it (see SEATING_TIME)
                let seat = stub.origin() + axis * depth;
                let tangent = (state.x[e] - state.x[n]).normalize_or(axis);
                let turn = log_map(rotation_between(tangent, axis));
                s.fix = Some(state.loads.add(LoadCase::Drive(Drive::new(
                    e,
                    (state.x[e], state.q[e]),
                    &[seat],
                    turn,
                    state.time,
                    SEATING_TIME,
                ))));
            }
        }
        StubState::Inserting { .. } | StubState::Fixed { .. } => {
            if let Some(id) = s.fix.take() {
                state.loads.remove(id);
            }
            // friction opposing the axial motion (regularised Coulomb), and the stub's
            // base stopping the end at the stub's length
            let v = (state.v[e] - frame.velocity_at(state.x[e])).dot(axis);
            let sense = if v >= 0.0 {
                crate::stub::Sense::On
            } else {
                crate::stub::Sense::Off
            };
            let resist = next.resisting_force_moving(&fit, sense);
            force -= axis * resist * (v / FRICTION_SPEED).clamp(-1.0, 1.0);
            let over = stub.axial_coordinate(frame.point_to_part(state.x[e])) - stub.length();
            if over > 0.0 {
                force -= axis * over * 1e3 * s.site.fit.stop_force() / stub.length();
            }
        }
        _ => {
            if let Some(id) = s.fix.take() {
                state.loads.remove(id);
            }
        }
    }
    s.force.set(state, e, force);
    let f = if s.fix.is_some() {
        state.reaction_force[e].length()
    } else {
        force.length()
    };
    s.force_now = f;
    if f > s.report.max_force {
        s.report.max_force = f;
        s.report.max_force_time = state.time;
    }
    s.report.holding_force = match next {
        StubState::Inserting { depth } | StubState::Fixed { depth } => {
            fit.holding_force_moving(depth, crate::stub::Sense::Off)
        }
        _ => 0.0,
    };
    s.report.assembled = match next {
        StubState::Fixed { depth } => s.site.fit.assembled_at(depth),
        _ => false,
    };
}

/// The beam of hose `hose` crossing the clip's plane nearest to its seat: (a, b, t, centre),
/// the centre in the clip's part's reference placement (`frame`). A hose's beam k joins
/// its nodes k and k + 1 (as the model builds it), so each node's distance from the plane
/// is measured once, for both beams that share it.
fn crossing(
    model: &Model,
    state: &State,
    clip: &ClipSpec,
    hose: usize,
    frame: &PartFrame,
) -> Option<(usize, usize, f64, DVec3)> {
    let info = &model.hoses[hose];
    debug_assert_eq!(info.element_count + 1, info.node_count);
    let xs = &state.x[info.nodes()];
    let mut distances = xs
        .iter()
        .map(|&p| clip.plane_distance(frame.point_to_part(p)));
    let mut da = distances.next()?;
    let mut best: Option<(usize, usize, f64, DVec3, f64)> = None;
    for (k, db) in distances.enumerate() {
        if ClipSpec::crosses(da, db) {
            let (a, b) = (frame.point_to_part(xs[k]), frame.point_to_part(xs[k + 1]));
            let m = ClipSpec::crossing_point(a, b, da, db);
            let d = (m - clip.origin()).length();
            if best.is_none_or(|x| d < x.4) {
                let t = ((m - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                let node = info.first_node + k;
                best = Some((node, node + 1, t, m, d));
            }
        }
        da = db;
    }
    best.map(|(a, b, t, m, _)| (a, b, t, m))
}

/// Whether the clip's hose is drawn in its seat: its centre line crosses the clip's plane
/// in line with the opening and nearer the seat than the opening (|s| < |n|: inside the
/// jaws; a route of straight beams through a curved one misses the seat by up to
/// l²κ/8), and it is thicker than the opening — the route of an installed harness or
/// hose. Such a clip holds from the first step where the hose lies, as it does once a
/// hose has snapped in.
fn drawn_seated(model: &Model, state: &State, site: &ClipSite) -> bool {
    let spec = &site.spec;
    let Some(tolerance) = ClipTolerance::for_clip(spec).checked() else {
        return false;
    };
    let frame = PartFrame::at(model, state, site.part, state.time);
    let Some((a, _, _, centre)) = crossing(model, state, spec, site.hose, &frame) else {
        return false;
    };
    spec.first_touch(model.radius[a]).is_some()
        && spec.lateral_offset(centre) <= tolerance.lateral
        && spec.opening_coordinate(centre).abs() < spec.opening_distance()
}

/// Whether a hand holds the hose at the clip: a node of the beam crossing the clip's
/// plane (nodes `a`, `b` = a + 1 of the hose's `nodes`) or of the beams on either side
/// of it. A hand pressing the hose into another clip further along does not lift this
/// one's seat.
fn held_at_clip(held: &[(usize, DVec3)], nodes: &Range<usize>, a: usize, b: usize) -> bool {
    held_node_at_clip(held, nodes, a, b).is_some()
}

/// The node by which a hand holds the hose at the clip ([`held_at_clip`]), if any.
fn held_node_at_clip(
    held: &[(usize, DVec3)],
    nodes: &Range<usize>,
    a: usize,
    b: usize,
) -> Option<usize> {
    held.iter()
        .map(|&(n, _)| n)
        .find(|&n| nodes.contains(&n) && n + 1 >= a && n <= b + 1)
}

fn update_clip(
    c: &mut ClipRun,
    model: &Model,
    state: &mut State,
    held: &[(usize, DVec3)],
    frame: &PartFrame,
) {
    let cross = crossing(model, state, &c.site.spec, c.site.hose, frame);
    let nodes = model.hoses[c.site.hose].nodes();
    let radius = cross.map_or(model.radius[nodes.start], |(a, ..)| model.radius[a]);
    let grabbed = cross.is_some_and(|(a, b, ..)| held_at_clip(held, &nodes, a, b));
    c.worked_at = cross.and_then(|(a, b, ..)| held_node_at_clip(held, &nodes, a, b));
    let coordinate = cross.map(|x| c.site.spec.opening_coordinate(x.3));
    let crossed_seat = matches!((c.last_coordinate, coordinate), (Some(a), Some(b)) if a * b < 0.0);
    let previous = c.last_coordinate;
    c.last_coordinate = coordinate;
    let obs = ClipObservation {
        centre: cross.map(|x| x.3),
        radius,
        grabbed,
        crossed_seat,
    };
    let Some(tolerance) = c.tolerance else {
        return;
    };
    let Ok(mut next) = c.state.next_within(&c.site.spec, &tolerance, &obs) else {
        return;
    };
    // a clip pressed in by hand takes the hose only from a hand pressing it in through the
    // opening: not a hose that hangs or is drawn through it, nor one carried into the
    // jaws from behind (last step's centre not in front of them)
    if c.site.by_hand && c.state == ClipState::Free && next != ClipState::Free {
        let from_front = previous
            .zip(c.site.spec.first_touch(radius))
            .is_some_and(|(s, touch)| s >= touch);
        if !grabbed || !from_front {
            next = ClipState::Free;
        }
    }
    // pulled out of its seat harder than the clip holds (the support pulling the hose
    // back along −Z): it comes loose and the snap law acts again
    let spec = &c.site.spec;
    if let (ClipState::Seated, Some(id), Some(hold)) = (next, c.fix, spec.holding_force()) {
        let node = state
            .loads
            .iter()
            .find(|(i, _)| *i == id)
            .map(|(_, l)| l.node());
        let opening = frame.direction_to_world(spec.opening());
        if node.is_some_and(|n| -state.reaction_force[n].dot(opening) > hold) {
            next = ClipState::Snapping;
            c.loosened = true;
        }
    }
    if c.loosened && cross.is_some_and(|x| spec.opening_coordinate(x.3) > tolerance.seat) {
        c.loosened = false; // out of the seat: it may snap in again
    }
    if c.loosened && next == ClipState::Seated {
        next = ClipState::Snapping;
    }
    c.state = next;
    let force = frame.direction_to_world(next.force(&c.site.spec, &obs));
    match (next, cross) {
        (ClipState::Seated, Some((a, b, t, _))) => {
            let node = if t < 0.5 { a } else { b };
            if c.fix.is_none() && frame.moves() {
                c.fix = Some(
                    state
                        .loads
                        .add(seat_hold_on_part(&c.site.spec, frame, node, state)),
                );
                c.carried = Some(frame.pose());
            } else if c.fix.is_none() {
                c.fix = Some(state.loads.add(c.site.spec.seat_hold(
                    node,
                    state.x[node],
                    state.q[node],
                )));
            }
        }
        _ => {
            if let Some(id) = c.fix.take() {
                state.loads.remove(id);
            }
            c.carried = None;
        }
    }
    let (a, b, t) = cross.map_or((0, 0, 0.0), |(a, b, t, _)| (a, b, t));
    c.forces[0].set(state, a, force * (1.0 - t));
    c.forces[1].set(state, b, force * t);
    c.force_now = force.length();
    if force.length() > c.report.max_force {
        c.report.max_force = force.length();
        c.report.max_force_time = state.time;
    }
    c.report.assembled = next == ClipState::Seated;
}

/// A clip's hold of its seated `node` on a moving part (`frame` now): a mount for a clip
/// that holds all six degrees of freedom, else its support with the clip's frame turned
/// with the part ([`carry_support`] keeps it with the part).
fn seat_hold_on_part(spec: &ClipSpec, frame: &PartFrame, node: usize, state: &State) -> LoadCase {
    let (x, q) = (state.x[node], state.q[node]);
    match spec.seat_hold(node, x, q) {
        LoadCase::Support(mut s) => {
            s.frame = (frame.pose().rotation * s.frame).normalize();
            s.velocity = frame.velocity_at(x);
            s.spin = frame.spin();
            LoadCase::Support(s)
        }
        _ => frame.hold(node, x, q),
    }
}

/// Carries a seated clip's support on a moving part from the pose it was placed at to the
/// part's pose `next` (at the step's end): its held pose, frame and slip anchor by the
/// part's rigid motion between the two, its velocity the part's there.
fn carry_support(c: &mut ClipRun, state: &mut State, next: &PartFrame) {
    let (Some(id), Some(before)) = (c.fix, c.carried) else {
        return;
    };
    let Some(LoadCase::Support(s)) = state.loads.get_mut(id) else {
        return;
    };
    let after = next.pose();
    let turn = (after.rotation * before.rotation.conjugate()).normalize();
    let carry = |x: DVec3| after.apply(before.inverse_apply(x));
    s.position = carry(s.position);
    s.anchor = carry(s.anchor);
    s.orientation = (turn * s.orientation).normalize();
    s.frame = (turn * s.frame).normalize();
    s.velocity = next.velocity_at(s.position);
    s.spin = next.spin();
    s.moved = true;
    c.carried = Some(after);
}

#[cfg(test)]
mod tests {
    use super::held_at_clip;
    use glam::DVec3;

    #[test]
    fn only_a_hand_at_the_clip_counts_as_holding_the_hose_there() {
        let hose = 10..30; // nodes of the clip's hose; the crossing beam joins 15 and 16
        let hand = |n: usize| [(n, DVec3::ZERO)];
        for n in 14..=17 {
            assert!(held_at_clip(&hand(n), &hose, 15, 16), "node {n}");
        }
        for n in [13, 18, 25] {
            assert!(!held_at_clip(&hand(n), &hose, 15, 16), "node {n}");
        }
        // a node of the next hose right after this hose's last crossing beam
        assert!(!held_at_clip(&hand(30), &hose, 28, 29));
        assert!(!held_at_clip(&[], &hose, 15, 16));
    }
}
