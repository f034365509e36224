//! Damped Newton iteration on the scaled shooting unknowns, shared by the chain
//! ([`crate::shooting`]) and tree ([`crate::tree_shooting`]) solvers.
//!
//! The Jacobian of a shooting map is very ill-conditioned for near-inextensible rods
//! (condition number ~ `EA L² / EI`, e.g. 1e9): a full Newton step can be excellent in
//! the unknowns yet raise the residual norm through tiny second-order terms. The steps
//! are therefore damped with Deuflhard's affine-invariant *natural monotonicity test*
//! (Deuflhard, "Newton Methods for Nonlinear Problems", 2004, §3.3): the step factor α
//! is halved until the simplified Newton correction
//! `‖J(x_k)⁻¹ F(x_k + α Δx_k)‖ ≤ (1 − α/4) ‖Δx_k‖` (norms of scaled unknowns).

use nalgebra::{DMatrix, DVector};

use crate::error::{ReferenceError, Result};
use crate::shooting::SolverOptions;

/// How a Newton iteration is kept on track far from the solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Globalization {
    /// Halve the step until the natural monotonicity test holds (single solves).
    Damped,
    /// Full steps only, each contracting the simplified correction by at least
    /// [`LOCAL_MAX_CONTRACTION`]; otherwise fail. Used by continuation: a guess that
    /// is not inside the quadratic convergence region of the nearby solution is
    /// rejected (and the step halved) instead of being allowed to wander onto
    /// another equilibrium branch.
    Local,
}

/// Largest accepted contraction `‖Δx̄_{k+1}‖ / ‖Δx_k‖` in [`Globalization::Local`].
const LOCAL_MAX_CONTRACTION: f64 = 0.5;

/// Largest accepted ratio, in [`Globalization::Local`], between the distance from
/// the first Newton iterate to the converged solution (corrector) and the first
/// Newton step (Euler predictor). The ratio is `O(Δt)` along a smooth path, so
/// small steps always pass; a larger ratio flags strong path curvature or a jump
/// to another branch, and the continuation step is halved.
const LOCAL_MAX_CORRECTOR_RATIO: f64 = 0.1;

/// One evaluation of a shooting map at scaled unknowns: residual, its exact Jacobian
/// and whatever else the solver keeps of the integration (`detail`).
pub(crate) struct Evaluation<E> {
    pub residual: DVector<f64>,
    pub jacobian: DMatrix<f64>,
    pub detail: E,
}

/// A converged Newton iteration.
pub(crate) struct Converged<E> {
    /// Scaled unknowns.
    pub x: DVector<f64>,
    /// The evaluation at `x`.
    pub evaluation: Evaluation<E>,
    /// Newton iterations used.
    pub iterations: usize,
    /// Max norm of the scaled residual at `x`.
    pub residual: f64,
}

/// Newton iteration on the map `evaluate` from the scaled unknowns `start`.
///
/// With [`Globalization::Local`] the solve also fails
/// ([`ReferenceError::StepRejected`]) when the corrector is large compared with the
/// predictor (see [`LOCAL_MAX_CORRECTOR_RATIO`]).
pub(crate) fn solve<E>(
    start: DVector<f64>,
    options: &SolverOptions,
    globalization: Globalization,
    mut evaluate: impl FnMut(&DVector<f64>) -> Result<Evaluation<E>>,
) -> Result<Converged<E>> {
    let tolerance = options.tolerance;
    let (max_backtracks, max_contraction) = match globalization {
        Globalization::Damped => (options.max_backtracks, 1.0),
        Globalization::Local => (0, LOCAL_MAX_CONTRACTION),
    };
    let mut x = start.clone();
    let mut first_iterate: Option<DVector<f64>> = None;
    let mut eval = evaluate(&x)?;
    for iteration in 0..=options.max_iterations {
        let residual_max = eval.residual.amax();
        if residual_max <= tolerance {
            if let (Globalization::Local, Some(first)) = (globalization, &first_iterate) {
                let predictor = (first - &start).norm();
                let corrector = (&x - first).norm();
                if corrector > LOCAL_MAX_CORRECTOR_RATIO * predictor {
                    return Err(ReferenceError::StepRejected {
                        predictor,
                        corrector,
                    });
                }
            }
            return Ok(Converged {
                x,
                evaluation: eval,
                iterations: iteration,
                residual: residual_max,
            });
        }
        if iteration == options.max_iterations {
            break;
        }
        let lu = eval.jacobian.clone().lu();
        let step = lu
            .solve(&(-&eval.residual))
            .filter(|s| s.iter().all(|v| v.is_finite()))
            .ok_or(ReferenceError::SingularJacobian { iteration })?;
        let step_norm = step.norm();
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..=max_backtracks {
            let trial = &x + &step * alpha;
            if let Ok(e) = evaluate(&trial) {
                // Natural monotonicity test (Deuflhard): the simplified Newton
                // correction J(x_k)⁻¹ F(x_k + α Δx) must shrink.
                let simplified = lu.solve(&(-&e.residual)).map(|s| s.norm());
                let bound = (1.0 - 0.25 * alpha).min(max_contraction) * step_norm;
                let monotone = simplified.is_some_and(|norm| norm <= bound);
                if monotone || e.residual.amax() <= tolerance {
                    accepted = Some((trial, e));
                    break;
                }
            }
            alpha *= 0.5;
        }
        match accepted {
            Some((trial, e)) => {
                x = trial;
                eval = e;
                if first_iterate.is_none() {
                    first_iterate = Some(x.clone());
                }
            }
            None => {
                return Err(ReferenceError::NotConverged {
                    iterations: iteration + 1,
                    residual: residual_max,
                    tolerance,
                })
            }
        }
    }
    Err(ReferenceError::NotConverged {
        iterations: options.max_iterations,
        residual: eval.residual.amax(),
        tolerance,
    })
}
