//! The workcell's settle: the one relaxation of [`pliant_core::relax`] (dynamic relaxation,
//! Cundall 1976; Barnes 1999) run on the workcell's own step, so that hands, stubs and
//! clips act, contact counts in the residual, the tally takes every step in and a session
//! logs it. The timeline's `settle` action and Python's `Simulation.settle` both call
//! [`Workcell::settle`].

use super::{Input, Observer, Workcell};
use pliant_core::health::Divergence;
use pliant_core::relax::{relax_with, RelaxOptions, RelaxReport, Relaxing, CHECK_EVERY};
use pliant_core::{Model, SolverKind, State};
use std::ops::ControlFlow;

/// What a settle asks for besides the relaxation's tolerances.
#[derive(Clone, Copy, Debug)]
pub struct SettleOptions {
    /// The residual's tolerances, the step budget and whether velocities are zeroed at
    /// each peak of the kinetic energy (kinetic damping).
    pub relax: RelaxOptions,
    /// At rest also needs the total kinetic energy below this \[J\] (`f64::INFINITY`:
    /// the residual alone decides).
    pub kinetic_energy: f64,
}

/// The workcell as dynamic relaxation drives it: one workcell step a step (shown to
/// `obs`), the velocities zeroed by a logged [`Input::Arrest`].
struct Settling<'a> {
    cell: &'a mut Workcell,
    obs: &'a mut dyn Observer,
    kinetic_energy: f64,
}

impl Relaxing for Settling<'_> {
    fn model(&self) -> &Model {
        self.cell.model()
    }
    fn state(&self) -> &State {
        self.cell.state()
    }
    fn step(&mut self) -> Result<(), Divergence> {
        self.cell.step(self.obs)
    }
    fn stop(&mut self) {
        // refused only after a divergence, which the next step reports
        let _ = self.cell.apply(Input::Arrest);
    }
    fn solver(&self) -> SolverKind {
        self.cell.solver().kind()
    }
    fn check_every(&self) -> u64 {
        match self.solver() {
            SolverKind::Explicit => CHECK_EVERY,
            // each step is a Newton solve: worth a look every time
            SolverKind::Implicit | SolverKind::Static => 1,
        }
    }
    fn at_rest(&self) -> bool {
        !self.cell.moving()
            && self.cell.state().kinetic_energy(self.cell.model()) < self.kinetic_energy
    }
}

impl Workcell {
    /// Relaxes to static equilibrium under the current loads and hand poses: steps (each
    /// a full [`Workcell::step`]) until the largest out-of-balance force and moment on a
    /// free node, contact counted, are within `opts.relax`'s tolerances, nothing moves and
    /// the kinetic energy is below `opts.kinetic_energy` — converged — or
    /// `opts.relax.max_steps` have passed (not converged, the residual reported).
    pub fn settle(
        &mut self,
        opts: &SettleOptions,
        obs: &mut dyn Observer,
    ) -> Result<RelaxReport, Divergence> {
        if let Some(d) = self.diverged() {
            return Err(d.clone());
        }
        let mut sys = Settling {
            cell: self,
            obs,
            kinetic_energy: opts.kinetic_energy,
        };
        relax_with(&mut sys, &opts.relax, |_| ControlFlow::Continue(()))
    }
}
