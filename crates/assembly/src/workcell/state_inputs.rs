//! The inputs on the whole state ([`Input::Arrest`](super::Input::Arrest), [`Input::SolveStatic`](super::Input::SolveStatic)): velocities
//! stopped, or the state moved to the static equilibrium under its loads.

use super::{Applied, Workcell};
use crate::workcell::Refusal;
use pliant_core::integrators::StaticSolver;
use pliant_core::newton::Tolerance;

impl Workcell {
    /// [`Input::Arrest`](super::Input::Arrest): every velocity, of nodes and of free bodies, set to zero.
    pub(super) fn arrest(&mut self) -> Result<Applied, Refusal> {
        pliant_core::relax::stop(&mut self.state);
        Ok(Applied::Done)
    }

    /// [`Input::SolveStatic`](super::Input::SolveStatic): the static equilibrium under the current loads by Newton's
    /// method to the given residual tolerances \[N, N·m\]; the state is left as it was if
    /// the solve fails, and with `stable_only` also if it ends unconverged or on an
    /// unstable equilibrium (the input is then refused).
    pub(super) fn solve_static(
        &mut self,
        (force_tolerance, moment_tolerance): (f64, f64),
        max_iterations: usize,
        stable_only: bool,
    ) -> Result<Applied, Refusal> {
        let mut solver =
            StaticSolver::new(&self.model).map_err(|e| Refusal::Invalid(e.to_string()))?;
        solver.options.tolerance = Tolerance::absolute(force_tolerance, moment_tolerance);
        solver.options.max_iterations = max_iterations;
        let before = self.state.clone();
        match solver.solve(&self.model, &mut self.state) {
            Ok(r) if stable_only && (!r.converged || r.unstable) => {
                self.state = before;
                Err(Refusal::Invalid(format!(
                    "static solve kept only at a stable equilibrium: {} after {} iterations \
                     (residual {:.3e} N, {:.3e} N·m)",
                    if r.unstable {
                        "unstable"
                    } else {
                        "unconverged"
                    },
                    r.iterations,
                    r.residual_force,
                    r.residual_moment
                )))
            }
            Ok(r) => Ok(Applied::Static(r)),
            Err(e) => {
                self.state = before;
                Err(Refusal::Invalid(format!("static solve failed: {e}")))
            }
        }
    }
}
