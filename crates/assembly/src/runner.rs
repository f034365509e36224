//! Executes a [`Timeline`]: a thin shell over the [`Workcell`] — each action becomes
//! workcell inputs, and actions that take time step the workcell. Everything that happens
//! in a step (hands, stubs and clips, the solver, the health check, the peaks) is the
//! workcell's, so a timeline gives the same numbers as the same inputs sent by a live
//! client or a Python script.

use crate::ergonomics::ErgonomicProfile;
use crate::fasteners::{ClipSite, StubSite};
use crate::report::summary::{OtherStop, Stopped};
use crate::timeline::{Action, MovePath, SettleFinish, Timeline};
use crate::workcell::{
    HandNumber, InitialLoad, Input, Observer, Refusal, RunSummary, SettleOptions, SettleOutcome,
    Workcell, WorkcellError, WorkcellOptions, WorkcellSetup,
};
use glam::DVec3;
use pliant_core::curve::catmull_rom;
use pliant_core::health::Divergence;
use pliant_core::relax::RelaxOptions;
use pliant_core::settings::DEFAULT_STATIC_MAX_ITERATIONS;
use pliant_core::{Model, SolverKind, State};
use std::sync::Arc;

pub use crate::workcell::{ContactEpisode, HandPeak, HandRecord, NoObserver, NodePeak};

/// Whether the timeline's `settle` zeroes the velocities at each peak of the kinetic
/// energy. No: a timeline is a history whose every step is tallied, judged and recorded,
/// so its motion stays the model's own; the hoses come to rest under their damping.
const SETTLE_KINETIC_DAMPING: bool = false;

/// When a `settle` action is at rest.
#[derive(Clone, Copy)]
struct Rest {
    force: f64,
    moment: f64,
    kinetic_energy: f64,
}

/// A run that stopped early.
#[derive(Debug, thiserror::Error)]
#[error("{reason}")]
pub struct RunError {
    /// The divergence, if the simulation diverged (else an action was refused).
    pub divergence: Option<Divergence>,
    pub reason: String,
    /// The same, typed (`summary.json` `diverged`).
    pub stopped: Stopped,
    /// Everything up to the last healthy state.
    pub partial: RunSummary,
}

/// Why one action stopped the run.
enum Stop {
    Diverged(Divergence),
    Refused(usize, &'static str, Refusal),
}

/// Executes timelines on a workcell.
pub struct Runner {
    setup: WorkcellSetup,
    options: WorkcellOptions,
}

impl Runner {
    /// A runner for `model` (no stubs or clips, the default ergonomic profile, the
    /// scene's solver).
    pub fn new(model: &Model) -> Self {
        Runner::from_setup(
            WorkcellSetup::bare(Arc::new(model.clone())),
            WorkcellOptions::default(),
        )
    }

    /// A runner for a scene's workcell. The timeline's own leading fixes and loads are
    /// its first actions, so the workcell does not apply the initial load cases itself.
    pub fn from_setup(setup: WorkcellSetup, options: WorkcellOptions) -> Self {
        Runner {
            setup,
            options: WorkcellOptions {
                initial_loads: false,
                ..options
            },
        }
    }

    /// Advances with `kind` instead of the scene's solver (SPEC P5).
    pub fn with_solver(mut self, kind: SolverKind) -> Self {
        self.options.solver = Some(kind);
        self
    }

    /// Adds connector stubs and clips (SPEC L6, L7).
    pub fn with_fasteners(mut self, stubs: Vec<StubSite>, clips: Vec<ClipSite>) -> Self {
        self.setup.stubs = stubs;
        self.setup.clips = clips;
        self
    }

    /// Judges hand loads with `profile` (default: [`ErgonomicProfile::default`]).
    pub fn with_ergonomics(mut self, profile: ErgonomicProfile) -> Self {
        self.setup.profile = profile;
        self
    }

    /// The workcell this runner runs the timeline on (at rest, t = 0).
    pub fn workcell(&self) -> Result<Workcell, WorkcellError> {
        Workcell::new(self.setup.clone(), self.options)
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
                Action::MovePart {
                    duration,
                    wait: true,
                    ..
                }
                | Action::RotatePart {
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

    /// Runs every action of `timeline`; `state` receives the final state.
    pub fn run(
        self,
        timeline: &Timeline,
        state: &mut State,
        obs: &mut dyn Observer,
    ) -> Result<RunSummary, RunError> {
        let mut cell = self.workcell().map_err(|e| RunError {
            divergence: None,
            stopped: Stopped::other(OtherStop::Setup, e.to_string()),
            reason: e.to_string(),
            partial: RunSummary::default(),
        })?;
        let outcome = run_timeline(&mut cell, timeline, obs);
        *state = cell.state().clone();
        outcome
    }
}

/// Runs every action of `timeline` on `cell`.
pub fn run_timeline(
    cell: &mut Workcell,
    timeline: &Timeline,
    obs: &mut dyn Observer,
) -> Result<RunSummary, RunError> {
    let mut settles = Vec::new();
    let n = timeline.actions.len();
    for k in 0..=n {
        let done = if let Some(action) = timeline.actions.get(k) {
            obs.on_action(k, action, cell.state());
            apply(cell, k, action, obs, &mut settles)
        } else {
            cell.check().map_err(Stop::Diverged)
        };
        if let Err(stop) = done {
            let (divergence, stopped) = match stop {
                Stop::Diverged(d) => (Some(d.clone()), Stopped::diverged(&d)),
                Stop::Refused(k, name, r) => (
                    None,
                    Stopped::other(
                        OtherStop::ActionRefused { action: k, name },
                        format!("timeline[{k}] ({name}): {r}"),
                    ),
                ),
            };
            let reason = stopped.message.clone();
            let mut partial = cell.summary();
            partial.actions_completed = k;
            partial.settles = settles;
            return Err(RunError {
                divergence,
                stopped,
                reason,
                partial,
            });
        }
    }
    let mut summary = cell.summary();
    summary.actions_completed = timeline.actions.len();
    summary.settles = settles;
    Ok(summary)
}

fn give(cell: &mut Workcell, index: usize, input: Input) -> Result<(), Stop> {
    let name = input.name();
    cell.apply(input)
        .map(|_| ())
        .map_err(|r| Stop::Refused(index, name, r))
}

/// Gives a motion input (a drive, a hand's or a part's move) and, with `wait`, steps
/// until it has arrived.
fn give_and_wait(
    cell: &mut Workcell,
    index: usize,
    input: Input,
    wait: bool,
    obs: &mut dyn Observer,
) -> Result<(), Stop> {
    let duration = match &input {
        Input::Drive { duration, .. }
        | Input::MoveHand { duration, .. }
        | Input::MovePart { duration, .. }
        | Input::RotatePart { duration, .. } => *duration,
        _ => 0.0,
    };
    give(cell, index, input)?;
    if wait {
        advance_until_done(cell, duration, obs)?;
    }
    Ok(())
}

/// Absolute waypoints of a path from `start`.
fn waypoints(path: &Option<MovePath>, start: DVec3) -> Vec<DVec3> {
    match path {
        Some(MovePath::To(p)) => p.clone(),
        Some(MovePath::By(p)) => p.iter().map(|d| start + *d).collect(),
        None => Vec::new(),
    }
}

fn rotation_vector(r: &Option<crate::timeline::Rotation>) -> DVec3 {
    r.map(|r| r.axis.normalize_or_zero() * r.angle)
        .unwrap_or(DVec3::ZERO)
}

/// Where a hand takes hose node `node` ([`Action::GrabNode`]): at the node, nudged a
/// millionth of the beam along the beam it takes — the one to the next node (the last
/// node: the one to the node before) — so that the nearest beam is that one and no
/// neighbour sharing the node (another hose's at a junction, the hose's own previous
/// beam when the two are in line). `None` if the model has no such node.
fn node_position(cell: &Workcell, node: crate::timeline::NodeRef) -> Option<DVec3> {
    let h = cell
        .model()
        .hoses
        .get(node.hose)
        .filter(|h| node.node < h.node_count && h.node_count > 1)?;
    let x = &cell.state().x;
    let here = x[h.node(node.node)];
    let other = if node.node + 1 < h.node_count {
        x[h.node(node.node + 1)]
    } else {
        x[h.node(node.node - 1)]
    };
    Some(here + (other - here) * 1e-6)
}

fn node_refusal(node: crate::timeline::NodeRef) -> Refusal {
    Refusal::Invalid(format!("hose {} has no node {}", node.hose, node.node))
}

/// The axis of beam `element`, pointing towards the nearer end of its hose (`None` for a
/// beam of zero length).
fn held_beam_direction(model: &Model, state: &State, element: usize) -> Option<DVec3> {
    let el = model.elements.get(element)?;
    let (a, b) = (el.node_a, el.node_b);
    let hose = model.hoses.iter().find(|h| h.nodes().contains(&a))?;
    let nodes = hose.nodes();
    // node_b lies further along the hose: towards the end when it is nearer the end
    let towards_end = (nodes.end - 1 - b) <= (a - nodes.start);
    let axis = if towards_end {
        state.x[b] - state.x[a]
    } else {
        state.x[a] - state.x[b]
    };
    axis.try_normalize()
}

/// One action: load-case changes are instantaneous, time-taking actions step.
fn apply(
    cell: &mut Workcell,
    index: usize,
    action: &Action,
    obs: &mut dyn Observer,
    settles: &mut Vec<SettleOutcome>,
) -> Result<(), Stop> {
    if let Some(load) = InitialLoad::from_action(action) {
        return give(cell, index, load.into());
    }
    match action {
        // given above, as the initial load cases they state
        Action::Fix { .. } | Action::Mount { .. } | Action::Load { .. } => {}
        Action::Tie { node, to } => give(
            cell,
            index,
            Input::Tie {
                node: *node,
                to: *to,
            },
        )?,
        Action::Move {
            node,
            path,
            rotation,
            duration,
            wait,
        } => {
            let start = cell
                .model()
                .hoses
                .get(node.hose)
                .filter(|h| node.node < h.node_count)
                .map_or(DVec3::ZERO, |h| cell.state().x[h.node(node.node)]);
            let input = Input::Drive {
                node: *node,
                waypoints: waypoints(path, start),
                rotation: rotation_vector(rotation),
                duration: *duration,
            };
            give_and_wait(cell, index, input, *wait, obs)?;
        }
        Action::Unload { node, name } => give(
            cell,
            index,
            Input::Unload {
                node: *node,
                name: name.clone(),
            },
        )?,
        Action::Release { node } => give(cell, index, Input::Release { node: *node })?,
        Action::Grab { hand, at, grip } => give(
            cell,
            index,
            Input::Grab {
                grip: *grip,
                hand: *hand as HandNumber,
                at: *at,
            },
        )?,
        Action::GrabNode { hand, node, grip } => {
            let at = node_position(cell, *node)
                .ok_or_else(|| Stop::Refused(index, "grab", node_refusal(*node)))?;
            give(
                cell,
                index,
                Input::Grab {
                    grip: *grip,
                    hand: *hand as HandNumber,
                    at,
                },
            )?
        }
        Action::AlignHand {
            hand,
            direction,
            path,
            duration,
        } => {
            let number = *hand as HandNumber;
            let held = cell
                .hand(number)
                .map_err(|r| Stop::Refused(index, "align_hand", r))?;
            let start = held.hand.pose_at(cell.state().time).0;
            let now = held_beam_direction(cell.model(), cell.state(), held.hand.element);
            let turn = match (now, direction.try_normalize()) {
                (Some(a), Some(b)) => {
                    pliant_core::math::log_map(pliant_core::math::rotation_between(a, b))
                }
                _ => DVec3::ZERO,
            };
            give(
                cell,
                index,
                Input::MoveHand {
                    hand: number,
                    waypoints: waypoints(path, start),
                    rotation: turn,
                    duration: *duration,
                },
            )?;
            advance_until_done(cell, *duration, obs)?;
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
            let number = *hand as HandNumber;
            let start = cell
                .hand(number)
                .map(|h| h.pose_at(cell.state().time).0)
                .map_err(|r| Stop::Refused(index, "move_hand", r))?;
            let mut points = waypoints(path, start);
            if *spline && points.len() >= 2 {
                let mut through = Vec::with_capacity(points.len() + 1);
                through.push(start);
                through.extend_from_slice(&points);
                points = catmull_rom(&through, 16).split_off(1);
            }
            let duration = match speed {
                Some(v) => crate::move_speed::duration_at_speed(start, &points, *v),
                None => *duration,
            };
            let input = Input::MoveHand {
                hand: number,
                waypoints: points,
                rotation: rotation_vector(rotation),
                duration,
            };
            give_and_wait(cell, index, input, *wait, obs)?;
        }
        Action::AimHand {
            hand,
            position,
            orientation,
        } => give(
            cell,
            index,
            Input::AimHand {
                hand: *hand as HandNumber,
                position: *position,
                orientation: *orientation,
            },
        )?,
        Action::ReleaseHand { hand } => give(
            cell,
            index,
            Input::ReleaseHand {
                hand: *hand as HandNumber,
            },
        )?,
        Action::MovePart {
            part,
            by,
            to,
            duration,
            wait,
        } => {
            let input = Input::MovePart {
                part: part.clone(),
                by: *by,
                to: *to,
                duration: *duration,
            };
            give_and_wait(cell, index, input, *wait, obs)?;
        }
        Action::RotatePart {
            part,
            axis,
            point,
            by,
            to,
            duration,
            wait,
        } => {
            let input = Input::RotatePart {
                part: part.clone(),
                axis: *axis,
                point: *point,
                by: *by,
                to: *to,
                duration: *duration,
            };
            give_and_wait(cell, index, input, *wait, obs)?;
        }
        Action::Run { duration } => advance(cell, *duration, obs)?,
        Action::Settle {
            kinetic_energy_threshold,
            force_tolerance,
            moment_tolerance,
            max_duration,
            finish,
        } => {
            let rest = Rest {
                force: *force_tolerance,
                moment: *moment_tolerance,
                kinetic_energy: *kinetic_energy_threshold,
            };
            let outcome = settle(cell, index, rest, (*max_duration, *finish), obs)?;
            settles.push(outcome);
        }
    }
    Ok(())
}

fn advance(cell: &mut Workcell, duration: f64, obs: &mut dyn Observer) -> Result<(), Stop> {
    steps(cell, cell.steps_in(duration), obs)
}

/// Steps until a motion of `duration` given now has arrived (at least one step for any
/// motion: every prescribed motion lands, however short against the solver's step).
fn advance_until_done(
    cell: &mut Workcell,
    duration: f64,
    obs: &mut dyn Observer,
) -> Result<(), Stop> {
    steps(cell, cell.steps_until_done(duration), obs)
}

fn steps(cell: &mut Workcell, n: u64, obs: &mut dyn Observer) -> Result<(), Stop> {
    for _ in 0..n {
        cell.step(obs).map_err(Stop::Diverged)?;
    }
    Ok(())
}

/// The action's settle: [`Workcell::settle`] (or, finished by the static solver,
/// [`Workcell::settle_finishing_static`]) for at most `max_duration`, ending with its
/// residual (the timeline's motion stays physical: no kinetic damping, see
/// [`SETTLE_KINETIC_DAMPING`]).
fn settle(
    cell: &mut Workcell,
    index: usize,
    rest: Rest,
    (max_duration, finish): (f64, SettleFinish),
    obs: &mut dyn Observer,
) -> Result<SettleOutcome, Stop> {
    let opts = SettleOptions {
        relax: RelaxOptions {
            force_tolerance: rest.force,
            moment_tolerance: rest.moment,
            max_steps: cell.steps_until_done(max_duration).max(1),
            kinetic_damping: SETTLE_KINETIC_DAMPING,
        },
        kinetic_energy: rest.kinetic_energy,
    };
    let (report, static_solve_time) = match finish {
        SettleFinish::Dynamic => cell.settle(&opts, obs).map(|r| (r, None)),
        SettleFinish::Static => cell
            .settle_finishing_static(&opts, DEFAULT_STATIC_MAX_ITERATIONS, obs)
            .map(|f| (f.relax, f.solve.map(|(_, t)| t))),
        SettleFinish::StaticEquilibrium => cell
            .settle_ending_static(&opts, DEFAULT_STATIC_MAX_ITERATIONS, obs)
            .map(|f| (f.relax, f.solve.map(|(_, t)| t))),
    }
    .map_err(Stop::Diverged)?;
    let state = cell.state();
    Ok(SettleOutcome {
        action: index,
        at_rest: report.converged,
        time: state.time,
        kinetic_energy: state.kinetic_energy(cell.model()),
        residual_force: report.residual_force,
        residual_moment: report.residual_moment,
        static_solve_time,
    })
}
