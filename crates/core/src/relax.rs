//! Relaxing: reaching static equilibrium with the explicit step by dynamic relaxation with
//! kinetic damping (Cundall 1976; Barnes 1999, "Form finding and analysis of tension
//! structures by dynamic relaxation"): the explicit step runs on, and every time the
//! total kinetic energy passes a peak all velocities are set to zero. The state walks
//! down the energy landscape to the nearest equilibrium (optionally with viscous damping
//! only). Its answer is the explicit model's own, not another solver's.
//!
//! One routine, [`relax_with`], with one residual, [`residual_after`] (contact with parts
//! and hoses counted, whichever solver took the last step), serves every caller:
//! [`relax`] on a bare model and state (the validation suite), the static solver's
//! snap-through ([`crate::integrators::snap`]), and the workcell's settle (the timeline's
//! `settle` action and Python's `Simulation.settle`), which steps a whole workcell
//! (hands, stubs and clips acting) with its own solver. The quasi-static Newton solver
//! ([`crate::integrators::statics`]) solves for the same equilibrium directly.

use crate::health::{check_for, Divergence};
use crate::integrators::explicit::step;
use crate::integrators::free_node_residual;
use crate::{Model, SolverKind, State};
use glam::DVec3;
use std::ops::ControlFlow;

/// Steps between two looks at the residual (and health checks).
pub const CHECK_EVERY: u64 = 64;

/// When to stop relaxing.
#[derive(Clone, Copy, Debug)]
pub struct RelaxOptions {
    /// Largest allowed out-of-balance force on a free node \[N\].
    pub force_tolerance: f64,
    /// Largest allowed out-of-balance moment on a free node \[N·m\].
    pub moment_tolerance: f64,
    /// Give up after this many steps.
    pub max_steps: u64,
    /// Zero all velocities at each kinetic-energy peak. Fast for stiff, well-conditioned
    /// problems; for a very soft mode (a column near buckling) turn it off and rely on the
    /// model's viscous damping tuned near that mode's critical value instead.
    pub kinetic_damping: bool,
}

/// How relaxation ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelaxReport {
    pub steps: u64,
    pub residual_force: f64,
    pub residual_moment: f64,
    pub converged: bool,
}

/// Largest out-of-balance force and moment on the free nodes after the last explicit
/// step. Contact counts: the parts' push, which the explicit step applies kinematically
/// and reports apart from `force` (in `contact_force`), is added back; hose–hose contact
/// is part of `force` already. A hose resting on a part is thus in balance.
///
/// The Newton solvers leave `force` with the parts' contact included; for their states
/// use [`crate::integrators::free_node_residual`].
pub fn residual(state: &State) -> (f64, f64) {
    let mut f: f64 = 0.0;
    let mut m: f64 = 0.0;
    for i in 0..state.x.len() {
        if !state.held[i] {
            f = f.max((state.force[i] + state.contact_force[i]).length());
            m = m.max(state.moment[i].length());
        }
    }
    (f, m)
}

/// The [`residual`] of a state whose last step `solver` took: the explicit step reports
/// the parts' contact apart from `force`, the Newton solvers
/// ([`free_node_residual`]) inside it; either way contact counts once.
pub fn residual_after(solver: SolverKind, state: &State) -> (f64, f64) {
    match solver {
        SolverKind::Explicit => residual(state),
        SolverKind::Implicit | SolverKind::Static => free_node_residual(state),
    }
}

/// Sets every velocity to zero (nodes and stiffened bodies): kinetic damping's reset at a
/// peak of the kinetic energy.
pub fn stop(state: &mut State) {
    state.v.fill(DVec3::ZERO);
    state.w.fill(DVec3::ZERO);
    for b in state.bodies.iter_mut() {
        b.velocity = DVec3::ZERO;
        b.angular_velocity = DVec3::ZERO;
    }
}

/// What dynamic relaxation drives: a model and its state, advanced by explicit steps.
pub trait Relaxing {
    fn model(&self) -> &Model;
    fn state(&self) -> &State;
    /// One explicit step (a divergence found on the way ends the relaxation).
    fn step(&mut self) -> Result<(), Divergence>;
    /// Zeroes every velocity ([`stop`]), kinetic damping's reset.
    fn stop(&mut self);
    /// The solver that takes the steps (it decides how the [`residual_after`] is read).
    fn solver(&self) -> SolverKind {
        SolverKind::Explicit
    }
    /// Steps between two looks at the residual: [`CHECK_EVERY`] for cheap explicit steps;
    /// a system whose steps are Newton solves looks after every one.
    fn check_every(&self) -> u64 {
        CHECK_EVERY
    }
    /// A condition besides the residual that convergence needs (a settle's: nothing
    /// moving, the kinetic energy below a threshold).
    fn at_rest(&self) -> bool {
        true
    }
}

/// A bare model and state, stepped by [`crate::integrators::explicit::step`].
pub struct Explicit<'a> {
    pub model: &'a Model,
    pub state: &'a mut State,
}

impl Relaxing for Explicit<'_> {
    fn model(&self) -> &Model {
        self.model
    }
    fn state(&self) -> &State {
        self.state
    }
    fn step(&mut self) -> Result<(), Divergence> {
        step(self.model, self.state);
        Ok(())
    }
    fn stop(&mut self) {
        stop(self.state);
    }
}

/// Relaxes `state` to static equilibrium under its current load cases.
pub fn relax(
    model: &Model,
    state: &mut State,
    opts: &RelaxOptions,
) -> Result<RelaxReport, Divergence> {
    relax_with(&mut Explicit { model, state }, opts, |_| {
        ControlFlow::Continue(())
    })
}

/// The relaxation every caller runs: steps `sys`, zeroes the velocities at each peak of
/// the kinetic energy (if `opts.kinetic_damping`), and every [`Relaxing::check_every`]
/// steps and after the last checks the state's health and the [`residual_after`] its
/// solver: converged when it is within the tolerances and the system is
/// [`Relaxing::at_rest`]. Between checks that fail, `watch` sees the state and may end
/// the relaxation unconverged ([`ControlFlow::Break`]).
pub fn relax_with<R: Relaxing + ?Sized>(
    sys: &mut R,
    opts: &RelaxOptions,
    mut watch: impl FnMut(&State) -> ControlFlow<()>,
) -> Result<RelaxReport, Divergence> {
    let mut last_energy = 0.0;
    let mut steps = 0;
    let report = |steps, (f, m): (f64, f64), converged| RelaxReport {
        steps,
        residual_force: f,
        residual_moment: m,
        converged,
    };
    let every = sys.check_every().max(1);
    while steps < opts.max_steps {
        sys.step()?;
        steps += 1;
        if opts.kinetic_damping {
            let energy = sys.state().kinetic_energy(sys.model());
            if energy < last_energy {
                sys.stop();
                last_energy = 0.0;
            } else {
                last_energy = energy;
            }
        }
        if steps % every == 0 || steps == opts.max_steps {
            check_for(sys.solver(), sys.model(), sys.state())?;
            let (f, m) = residual_after(sys.solver(), sys.state());
            if f <= opts.force_tolerance && m <= opts.moment_tolerance && sys.at_rest() {
                return Ok(report(steps, (f, m), true));
            }
            if watch(sys.state()).is_break() {
                return Ok(report(steps, (f, m), false));
            }
        }
    }
    Ok(report(
        steps,
        residual_after(sys.solver(), sys.state()),
        false,
    ))
}
