//! `Simulation.settle`: static equilibrium by dynamic relaxation with kinetic damping —
//! the one routine of `pliant_core::relax` (Cundall 1976; Barnes 1999, its residual
//! counting contact with parts and hoses), run on the full interactive step, so that
//! hands, stubs and clips act while the hose settles. The result is the equilibrium of
//! the same explicit model `step` advances; it is not an implicit or Newton solver.

use crate::engine::{Engine, Refusal};
use pliant_core::health::Divergence;
use pliant_core::relax::{relax_with, RelaxOptions, RelaxReport, Relaxing};
use pliant_core::{Model, State};
use std::ops::ControlFlow;

/// The engine as dynamic relaxation drives it: one workcell step a step, the velocities
/// zeroed by a logged `Arrest` input.
impl Relaxing for Engine {
    fn model(&self) -> &Model {
        Engine::model(self)
    }
    fn state(&self) -> &State {
        Engine::state(self)
    }
    fn step(&mut self) -> Result<(), Divergence> {
        self.step_once()
    }
    fn stop(&mut self) {
        self.arrest();
    }
}

impl Engine {
    /// Relaxes to static equilibrium under the current load cases and hand poses.
    /// Refused while a hand or a drive is still moving (there is no equilibrium then).
    pub fn settle(
        &mut self,
        opts: &RelaxOptions,
    ) -> Result<Result<RelaxReport, Divergence>, Refusal> {
        if self.moving() {
            return Err(Refusal::Invalid(
                "a hand or a drive is still moving; let it finish first (run() for its remaining duration)"
                    .into(),
            ));
        }
        if let Some(d) = self.diverged() {
            return Ok(Err(d.clone()));
        }
        Ok(relax_with(self, opts, |_| ControlFlow::Continue(())))
    }
}
