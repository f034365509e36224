//! The workcell's settle: the one relaxation of [`pliant_core::relax`] (dynamic relaxation,
//! Cundall 1976; Barnes 1999) run on the workcell's own step, so that hands, stubs and
//! clips act, contact counts in the residual, the tally takes every step in and a session
//! logs it. The timeline's `settle` action and Python's `Simulation.settle` both call
//! [`Workcell::settle`]; a `settle` with `finish = "static"` calls
//! [`Workcell::settle_finishing_static`], which lets the quasi-static solver
//! ([`pliant_core::integrators::StaticSolver`]) take the last, slow stretch to rest, and
//! one with `finish = "static_equilibrium"` [`Workcell::settle_ending_static`], which
//! ends at rest on that solver's equilibrium.

use super::{Applied, Input, Observer, Workcell};
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

/// How a settle finished by the static solver went ([`Workcell::settle_finishing_static`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticFinish {
    /// The relaxation as a whole: steps (both dynamic stretches), residual, at rest.
    pub relax: RelaxReport,
    /// The static solve taken (converged to a stable equilibrium) and the simulated time
    /// it was taken at \[s\], or `None`: the hands, drives or fasteners were never done
    /// within the budget, or the solve was refused (unconverged, unstable or failed) and
    /// the settle stayed dynamic.
    pub solve: Option<(pliant_core::integrators::StaticReport, f64)>,
}

/// Whether the static equilibrium a settle takes is confirmed by the scene's solver.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Confirm {
    /// Relaxation goes on from it until the settle's rest criterion holds.
    BySolver,
    /// It is the rest.
    No,
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

    /// A settle whose last stretch the quasi-static solver takes. Dynamic relaxation as in
    /// [`Workcell::settle`] (checked every [`CHECK_EVERY`] steps) until the hands, drives
    /// and loads have stopped changing and no fastener's force law acts
    /// ([`Workcell::moving`], a clip seated or free, a stub's end held or off it): from
    /// then on the loads on the hoses are their load cases alone, so the static
    /// equilibrium the Newton solver finds from the state reached (velocities zeroed) is an
    /// equilibrium of the explicit model. It is taken as one logged
    /// [`Input::SolveStatic`] kept only at a stable, converged equilibrium (to the
    /// settle's own force and moment tolerances), and dynamic relaxation goes on from
    /// there with the rest of the step budget: it confirms rest at its first check when
    /// the equilibrium is the explicit model's, and relaxes on when not (a clip loosened
    /// by the static load, contact the explicit step resolves differently). A refused
    /// solve leaves the state untouched: the settle is then the dynamic one. If rest comes
    /// before the hands are done, no solve is taken.
    pub fn settle_finishing_static(
        &mut self,
        opts: &SettleOptions,
        max_iterations: usize,
        obs: &mut dyn Observer,
    ) -> Result<StaticFinish, Divergence> {
        self.settle_with_static_solve(opts, max_iterations, Confirm::BySolver, obs)
    }

    /// [`Workcell::settle_finishing_static`] up to the static solve, and at rest there
    /// when the solve is taken: a converged, stable equilibrium of the quasi-static model
    /// within the settle's own force and moment tolerances, velocities zero. The scene's
    /// solver does not confirm it (under mass scaling the explicit step's contact can keep
    /// a small oscillation about it that never meets the tolerances); the report's
    /// residual is the static solve's. A refused solve leaves the settle dynamic, as there.
    pub fn settle_ending_static(
        &mut self,
        opts: &SettleOptions,
        max_iterations: usize,
        obs: &mut dyn Observer,
    ) -> Result<StaticFinish, Divergence> {
        self.settle_with_static_solve(opts, max_iterations, Confirm::No, obs)
    }

    /// The settle of [`Workcell::settle_finishing_static`], its static equilibrium
    /// confirmed by the scene's solver or not.
    fn settle_with_static_solve(
        &mut self,
        opts: &SettleOptions,
        max_iterations: usize,
        confirm: Confirm,
        obs: &mut dyn Observer,
    ) -> Result<StaticFinish, Divergence> {
        let budget = opts.relax.max_steps;
        let mut steps = 0;
        // the dynamic stretch, in chunks of one check each: the same steps and checks as
        // the dynamic settle's until the hands and fasteners are done
        while !self.ready_for_static() {
            let chunk = RelaxOptions {
                max_steps: CHECK_EVERY.min(budget - steps),
                ..opts.relax
            };
            let r = self.settle(
                &SettleOptions {
                    relax: chunk,
                    ..*opts
                },
                obs,
            )?;
            steps += r.steps;
            if r.converged || steps >= budget {
                return Ok(StaticFinish {
                    relax: RelaxReport { steps, ..r },
                    solve: None,
                });
            }
        }
        let solve = match self.apply(Input::SolveStatic {
            force_tolerance: opts.relax.force_tolerance,
            moment_tolerance: opts.relax.moment_tolerance,
            max_iterations,
            stable_only: true,
        }) {
            Ok(Applied::Static(r)) => Some((r, self.state.time)),
            _ => None,
        };
        if let (Some((r, _)), Confirm::No) = (solve, confirm) {
            return Ok(StaticFinish {
                relax: RelaxReport {
                    steps,
                    residual_force: r.residual_force,
                    residual_moment: r.residual_moment,
                    converged: true,
                },
                solve,
            });
        }
        let rest = RelaxOptions {
            max_steps: budget - steps,
            ..opts.relax
        };
        let r = self.settle(
            &SettleOptions {
                relax: rest,
                ..*opts
            },
            obs,
        )?;
        Ok(StaticFinish {
            relax: RelaxReport {
                steps: steps + r.steps,
                ..r
            },
            solve,
        })
    }

    /// Whether the loads on the hoses are their load cases alone and stay so: nothing
    /// moving or changing ([`Workcell::moving`]), no hand opening, no fastener's force law
    /// acting.
    fn ready_for_static(&self) -> bool {
        !self.moving() && self.opening_until.is_none() && self.fasteners.quiet()
    }
}
