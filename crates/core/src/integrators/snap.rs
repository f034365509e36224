//! Passing a limit point (snap-through) in the static solver.
//!
//! Past a limit point of the load path — a buckled hose pushed sideways until it snaps into
//! the mirrored shape, a hose jumping over an edge — the equilibrium branch the solver
//! follows ends: no load step, however small, has an equilibrium nearby, and Newton cannot
//! converge. The hose then moves dynamically to a distant stable branch. This follows that
//! motion with the loads frozen at the input's time, by dynamic relaxation with kinetic
//! damping ([`crate::relax`]; Cundall 1976; Barnes 1999): explicit steps of the model's own
//! stable step, all velocities zeroed at every peak of the kinetic energy, so the state
//! walks down the energy landscape to a stable equilibrium — the one the real, damped hose
//! snaps to — from where the Newton solve finishes. Explicit steps rather than large
//! implicit ones: an implicit step longer than an unstable mode's time scale is drawn back
//! onto the unstable equilibrium (its effective stiffness 4m/Δt² − k turns negative), the
//! explicit one never is.

use super::explicit::step;
use crate::health::Divergence;
use crate::relax::{relax_with, stop, RelaxOptions, Relaxing};
use crate::{Model, State};
use glam::DVec3;
use std::ops::ControlFlow;

/// Most explicit steps one snap may take.
const MAX_RELAXATION_STEPS: u64 = 2_000_000;
/// Out-of-balance, as a multiple of the static convergence limit, from which the Newton
/// solve takes over: 1, the static limit itself — near the unstable equilibrium the snap
/// starts from the residual is small too, and a looser hand-over returns Newton to it.
const HANDOVER: f64 = 1.0;
/// Consecutive check windows in which no node moved (see [`frozen`]) after which the
/// relaxation gives up: its residual is then held by a constraint (a sticking stub or
/// contact) that explicit steps cannot move, and more steps change nothing.
const FROZEN_WINDOWS: usize = 8;
/// A node "did not move" in a window when it moved less than this fraction of the
/// shortest element's rest length (10⁻¹⁰: far below what a free node with a residual at
/// the static limit moves in one window, far above the positions' round-off).
const FROZEN_FRACTION: f64 = 1e-10;

/// Explicit steps that each end at `time`: prescribed motions stay where they are due.
struct AtTime<'a> {
    model: &'a Model,
    state: &'a mut State,
    time: f64,
    /// Steps taken.
    steps: u64,
}

impl Relaxing for AtTime<'_> {
    fn model(&self) -> &Model {
        self.model
    }
    fn state(&self) -> &State {
        self.state
    }
    fn step(&mut self) -> Result<(), Divergence> {
        self.state.time = self.time - self.model.time_step;
        step(self.model, self.state);
        self.steps += 1;
        self.state.time = self.time;
        Ok(())
    }
    fn stop(&mut self) {
        stop(self.state);
    }
}

/// How a snap relaxation ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Relaxation {
    /// Explicit steps taken (also when it failed).
    pub steps: u64,
    /// It reached the hand-over residual.
    pub reached: bool,
}

/// Relaxes `state` under its loads at time `time` ([`crate::relax::relax_with`], with
/// kinetic damping, from rest) until the largest out-of-balance force and moment on free
/// nodes ([`crate::relax::residual`], contact counted) are within `HANDOVER` ×
/// (`force_limit`, `moment_limit`), in at most `max_steps` explicit steps (and
/// `MAX_RELAXATION_STEPS`). It has not `reached` them if it diverged, stopped moving
/// short of the limits (`FROZEN_WINDOWS`) or ran out of steps (the caller then reports
/// the input step unconverged). `anchor` is scratch space for the positions at the last
/// check (resized to the nodes).
pub fn relax(
    model: &Model,
    state: &mut State,
    time: f64,
    (force_limit, moment_limit): (f64, f64),
    max_steps: u64,
    anchor: &mut Vec<DVec3>,
) -> Relaxation {
    stop(state);
    let still = FROZEN_FRACTION * shortest_element(model);
    anchor.clear();
    anchor.extend_from_slice(&state.x);
    let mut frozen_windows = 0;
    let options = RelaxOptions {
        force_tolerance: HANDOVER * force_limit,
        moment_tolerance: HANDOVER * moment_limit,
        max_steps: max_steps.min(MAX_RELAXATION_STEPS),
        kinetic_damping: true,
    };
    let mut relaxing = AtTime {
        model,
        state,
        time,
        steps: 0,
    };
    let report = relax_with(&mut relaxing, &options, |state| {
        frozen_windows = if frozen(&state.x, anchor, still) {
            frozen_windows + 1
        } else {
            0
        };
        if frozen_windows >= FROZEN_WINDOWS {
            return ControlFlow::Break(());
        }
        anchor.copy_from_slice(&state.x);
        ControlFlow::Continue(())
    });
    Relaxation {
        steps: relaxing.steps,
        reached: report.is_ok_and(|r| r.converged),
    }
}

/// Whether no node moved more than `still` since `anchor`. A free node with an
/// out-of-balance force f and mass m moves ½(f/m)T² in a window T even right after a
/// kinetic-damping reset, so a residual that moves nothing is held by a constraint.
fn frozen(x: &[DVec3], anchor: &[DVec3], still: f64) -> bool {
    let still2 = still * still;
    x.iter()
        .zip(anchor)
        .all(|(a, b)| a.distance_squared(*b) <= still2)
}

/// The shortest element's rest length \[m\].
fn shortest_element(model: &Model) -> f64 {
    model
        .elements
        .iter()
        .map(|e| e.rest_length)
        .fold(f64::INFINITY, f64::min)
}
