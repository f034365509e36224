//! `Simulation.settle`: static equilibrium by dynamic relaxation with kinetic damping —
//! the workcell's settle ([`pliant_assembly::Workcell::settle`]), the one routine of
//! `pliant_core::relax` (Cundall 1976; Barnes 1999, its residual counting contact with
//! parts and hoses) run on the full interactive step, so that hands, stubs and clips act
//! while the hose settles. The result is the equilibrium of the same model `step`
//! advances, with the simulation's solver.

use crate::engine::{Engine, Refusal};
use pliant_assembly::workcell::SettleOptions;
use pliant_assembly::NoObserver;
use pliant_core::health::Divergence;
use pliant_core::relax::{RelaxOptions, RelaxReport};

impl Engine {
    /// Relaxes to static equilibrium under the current load cases and hand poses (the
    /// residual alone decides: no kinetic-energy threshold).
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
        let opts = SettleOptions {
            relax: *opts,
            kinetic_energy: f64::INFINITY,
        };
        Ok(self.cell_mut().settle(&opts, &mut NoObserver))
    }
}
