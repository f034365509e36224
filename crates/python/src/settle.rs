//! Static equilibrium by dynamic relaxation with kinetic damping — the method of
//! `pliant_core::relax` (Cundall 1976; Barnes 1999) run on the full interactive step, so
//! that hands, stubs and clips act while the hose settles: the explicit step runs on, and
//! whenever the total kinetic energy passes a peak all velocities are set to zero. The
//! result is the equilibrium of the same explicit model `step` advances; it is not an
//! implicit or Newton solver.

use crate::engine::{Engine, Refusal};
use pliant_core::health::{check, Divergence};
use pliant_core::relax::{SettleOptions, SettleReport as CoreSettleReport};
use pliant_core::State;

/// How often the residual is looked at, in steps (as `pliant_core::relax`).
const CHECK_EVERY: u64 = 64;

/// Largest out-of-balance force and moment on the free nodes after the last step. As
/// `pliant_core::relax::residual`, but with the rigid parts' contact forces counted (a
/// hose resting on a part is in balance with the part's push, which the explicit step
/// applies kinematically and reports apart from `force`).
fn residual(state: &State) -> (f64, f64) {
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

impl Engine {
    /// Relaxes to static equilibrium under the current load cases and hand poses.
    /// Refused while a hand or a drive is still moving (there is no equilibrium then).
    pub fn settle(
        &mut self,
        opts: &SettleOptions,
    ) -> Result<Result<CoreSettleReport, Divergence>, Refusal> {
        if self.moving() {
            return Err(Refusal::Invalid(
                "a hand or a drive is still moving; let it finish first (run() for its remaining duration)"
                    .into(),
            ));
        }
        if let Some(d) = self.diverged() {
            return Ok(Err(d.clone()));
        }
        let mut last_energy = 0.0;
        let mut steps = 0;
        let outcome = (|| {
            while steps < opts.max_steps {
                let chunk = CHECK_EVERY.min(opts.max_steps - steps);
                for _ in 0..chunk {
                    self.step_once()?;
                    steps += 1;
                    let energy = self.state().kinetic_energy(self.model());
                    if opts.kinetic_damping && energy < last_energy {
                        self.arrest();
                        last_energy = 0.0;
                    } else {
                        last_energy = energy;
                    }
                }
                check(self.model(), self.state())?;
                let (f, m) = residual(self.state());
                if f <= opts.force_tolerance && m <= opts.moment_tolerance {
                    return Ok(CoreSettleReport {
                        steps,
                        residual_force: f,
                        residual_moment: m,
                        converged: true,
                    });
                }
            }
            check(self.model(), self.state())?;
            let (f, m) = residual(self.state());
            Ok(CoreSettleReport {
                steps,
                residual_force: f,
                residual_moment: m,
                converged: false,
            })
        })();
        Ok(outcome)
    }
}
