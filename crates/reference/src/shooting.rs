//! The shooting method: damped Newton on the six unknowns `n(0), m(0)`.
//!
//! Integrating the rod equations ([`crate::ode`]) from the clamped base with
//! guessed `n(0), m(0)` gives the end state; the residual compares it with the end
//! condition ([`EndCondition`]). Residual and unknowns are made dimensionless with
//! the rod length `L` and the bending stiffness `EI`:
//!
//! | quantity            | scale     |
//! |---------------------|-----------|
//! | positions           | `L`       |
//! | rotations           | 1 (rad)   |
//! | forces (`n`, `F`)   | `EI / L²` |
//! | moments (`m`, `M`)  | `EI / L`  |
//!
//! The Jacobian of the residual is exact (variational equations, see
//! [`crate::ode`]); for the rotation residual `ψ = log(R_Lᵀ R(L))` it is
//! `dψ = J_r⁻¹(ψ) · vee(R(L)ᵀ dR(L))`.
//!
//! The Jacobian is very ill-conditioned for near-inextensible rods (condition
//! number ~ `EA L² / EI`, e.g. 1e9): a full Newton step can be excellent in the
//! unknowns yet raise the residual norm through tiny second-order terms. The steps
//! are therefore damped with Deuflhard's affine-invariant *natural monotonicity
//! test* (Deuflhard, "Newton Methods for Nonlinear Problems", 2004, §3.3): the step
//! factor α is halved until the simplified Newton correction
//! `‖J(x_k)⁻¹ F(x_k + α Δx_k)‖ ≤ (1 − α/4) ‖Δx_k‖` (norms of scaled unknowns).

use nalgebra::{Matrix6, Vector3, Vector6};

use crate::boundary::{EndCondition, Pose};
use crate::error::{ReferenceError, Result};
use crate::ode::{integrate, Augmented, RodState};
use crate::rod::Rod;
use crate::so3;
use crate::solution::{SectionState, Solution};

/// Numerical parameters of the solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// RK4 steps per rod length `L` (step `h ≤ L / steps_per_length`, at least 4
    /// steps per segment). Default 4000.
    pub steps_per_length: usize,
    /// Convergence tolerance on the max norm of the scaled residual. Default 1e-11.
    pub tolerance: f64,
    /// Maximum Newton iterations per solve. Default 40.
    pub max_iterations: usize,
    /// Maximum number of backtracking halvings of one Newton step. Default 30.
    pub max_backtracks: u32,
    /// Maximum number of halvings of a continuation step (at most 52). Default 16.
    pub max_step_halvings: u32,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            steps_per_length: 4000,
            tolerance: 1e-11,
            max_iterations: 40,
            max_backtracks: 30,
            max_step_halvings: 16,
        }
    }
}

impl SolverOptions {
    fn validate(&self) -> Result<()> {
        if self.steps_per_length == 0 {
            return Err(ReferenceError::InvalidOptions(
                "steps_per_length must be positive".to_string(),
            ));
        }
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(ReferenceError::InvalidOptions(format!(
                "tolerance must be finite and positive, got {}",
                self.tolerance
            )));
        }
        if self.max_step_halvings > 52 {
            return Err(ReferenceError::InvalidOptions(format!(
                "max_step_halvings must be at most 52 (steps below 2^-52 are void), got {}",
                self.max_step_halvings
            )));
        }
        if self.max_iterations == 0 {
            return Err(ReferenceError::InvalidOptions(
                "max_iterations must be positive".to_string(),
            ));
        }
        Ok(())
    }
}

/// The shooting unknowns: internal force and moment at the base, `n(0)`, `m(0)`
/// (global; the base support applies `−n(0)`, `−m(0)` to the rod).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unknowns {
    /// `n(0)` \[N\].
    pub force: Vector3<f64>,
    /// `m(0)` \[N m\].
    pub moment: Vector3<f64>,
}

impl Unknowns {
    /// `n(0) = 0`, `m(0) = 0`: the unloaded rest state.
    pub fn zero() -> Self {
        Self {
            force: Vector3::zeros(),
            moment: Vector3::zeros(),
        }
    }

    fn validate(&self) -> Result<()> {
        if self
            .force
            .iter()
            .chain(self.moment.iter())
            .all(|v| v.is_finite())
        {
            Ok(())
        } else {
            Err(ReferenceError::InvalidBoundaryCondition(
                "initial guess contains non-finite values".to_string(),
            ))
        }
    }
}

/// Static reference solver for one rod clamped at its base.
#[derive(Debug, Clone, PartialEq)]
pub struct ShootingSolver {
    rod: Rod,
    base: Pose,
    options: SolverOptions,
}

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

/// Residual scales (see the module documentation).
#[derive(Debug, Clone, Copy)]
struct Scales {
    length: f64,
    force: f64,
    moment: f64,
}

/// One evaluation of the shooting map.
struct Evaluation {
    residual: Vector6<f64>,
    jacobian: Matrix6<f64>,
    end: RodState,
}

impl ShootingSolver {
    /// A solver for `rod` with its base (`s = 0`) clamped at `base` (position and
    /// material frame; use [`Rod::rest_base_pose`] for the rest pose), default
    /// options.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidBoundaryCondition`] if `base` is non-finite or its
    /// frame is not a rotation.
    pub fn new(rod: Rod, base: Pose) -> Result<Self> {
        base.validate("base")?;
        Ok(Self {
            rod,
            base,
            options: SolverOptions::default(),
        })
    }

    /// Replaces the numerical options.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidOptions`] for a zero step count or iteration limit,
    /// a non-positive tolerance or more than 52 step halvings.
    pub fn with_options(mut self, options: SolverOptions) -> Result<Self> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// The rod.
    pub fn rod(&self) -> &Rod {
        &self.rod
    }

    /// The clamped base pose.
    pub fn base(&self) -> &Pose {
        &self.base
    }

    /// The numerical options.
    pub fn options(&self) -> &SolverOptions {
        &self.options
    }

    /// End pose of the unloaded rod (`n = m = 0`): the rest polyline moved
    /// rigidly with the base.
    pub fn unloaded_end_pose(&self) -> Pose {
        let rest_base = self.rod.rest_base_pose();
        let rotation = self.base.frame * rest_base.frame.inverse();
        let translation = self.base.position - rotation * rest_base.position;
        self.rod
            .rest_end_pose()
            .transformed(&rotation, &translation)
    }

    /// Solves the static problem for `end` by Newton's method starting from
    /// `guess` (no continuation; see [`ShootingSolver::solve_path`] for large loads).
    ///
    /// # Errors
    ///
    /// invalid input ([`ReferenceError::InvalidBoundaryCondition`]), or
    /// [`ReferenceError::NotConverged`], [`ReferenceError::SingularJacobian`],
    /// [`ReferenceError::Integration`] when Newton fails.
    pub fn solve(&self, end: &EndCondition, guess: &Unknowns) -> Result<Solution> {
        end.validate()?;
        guess.validate()?;
        self.newton(end, guess, 1.0, Globalization::Damped)
    }

    fn scales(&self) -> Scales {
        let length = self.rod.length();
        let bending = self.rod.stiffness().bending();
        Scales {
            length,
            force: bending / (length * length),
            moment: bending / length,
        }
    }

    fn scale(&self, unknowns: &Unknowns) -> Vector6<f64> {
        let sc = self.scales();
        let f = unknowns.force / sc.force;
        let m = unknowns.moment / sc.moment;
        Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z)
    }

    fn unscale(&self, x: &Vector6<f64>) -> Unknowns {
        let sc = self.scales();
        Unknowns {
            force: Vector3::new(x[0], x[1], x[2]) * sc.force,
            moment: Vector3::new(x[3], x[4], x[5]) * sc.moment,
        }
    }

    /// Initial state at the base for the given unknowns.
    pub(crate) fn base_state(&self, unknowns: &Unknowns) -> RodState {
        RodState {
            r: self.base.position,
            frame: *self.base.frame.matrix(),
            n: unknowns.force,
            m: unknowns.moment,
        }
    }

    /// Integrates with the scaled unknowns `x` and returns residual, Jacobian and
    /// end state.
    fn evaluate(
        &self,
        x: &Vector6<f64>,
        end: &EndCondition,
        load_scale: f64,
    ) -> Result<Evaluation> {
        let sc = self.scales();
        let mut variations = [RodState::zero(); 6];
        for (j, v) in variations.iter_mut().enumerate() {
            if j < 3 {
                v.n[j] = sc.force;
            } else {
                v.m[j - 3] = sc.moment;
            }
        }
        let start = Augmented {
            state: self.base_state(&self.unscale(x)),
            variations,
        };
        let out = integrate(
            &self.rod,
            load_scale,
            self.options.steps_per_length,
            start,
            &[],
            |_, _| {},
        )?;
        let y = &out.state;
        let mut residual = Vector6::zeros();
        let mut jacobian = Matrix6::zeros();
        match end {
            EndCondition::Clamped(pose) => {
                let dr = (y.r - pose.position) / sc.length;
                let psi = so3::log(&(pose.frame.matrix().transpose() * y.frame));
                let jinv = so3::right_jacobian_inverse(&psi);
                residual.fixed_rows_mut::<3>(0).copy_from(&dr);
                residual.fixed_rows_mut::<3>(3).copy_from(&psi);
                let frame_t = y.frame.transpose();
                for (j, v) in out.variations.iter().enumerate() {
                    let dpos = v.r / sc.length;
                    let drot = jinv * so3::vee_skew_part(&(frame_t * v.frame));
                    jacobian.fixed_view_mut::<3, 1>(0, j).copy_from(&dpos);
                    jacobian.fixed_view_mut::<3, 1>(3, j).copy_from(&drot);
                }
            }
            EndCondition::Loaded { force, moment } => {
                let df = (y.n - force) / sc.force;
                let dm = (y.m - moment) / sc.moment;
                residual.fixed_rows_mut::<3>(0).copy_from(&df);
                residual.fixed_rows_mut::<3>(3).copy_from(&dm);
                for (j, v) in out.variations.iter().enumerate() {
                    jacobian
                        .fixed_view_mut::<3, 1>(0, j)
                        .copy_from(&(v.n / sc.force));
                    jacobian
                        .fixed_view_mut::<3, 1>(3, j)
                        .copy_from(&(v.m / sc.moment));
                }
            }
        }
        Ok(Evaluation {
            residual,
            jacobian,
            end: out.state,
        })
    }

    /// Newton iteration from `guess`; `load_scale` multiplies the distributed load.
    ///
    /// With [`Globalization::Local`] the solve also fails
    /// ([`ReferenceError::StepRejected`]) when the corrector is large compared with
    /// the predictor (see [`LOCAL_MAX_CORRECTOR_RATIO`]).
    pub(crate) fn newton(
        &self,
        end: &EndCondition,
        guess: &Unknowns,
        load_scale: f64,
        globalization: Globalization,
    ) -> Result<Solution> {
        let tolerance = self.options.tolerance;
        let (max_backtracks, max_contraction) = match globalization {
            Globalization::Damped => (self.options.max_backtracks, 1.0),
            Globalization::Local => (0, LOCAL_MAX_CONTRACTION),
        };
        let start = self.scale(guess);
        let mut x = start;
        let mut first_iterate: Option<Vector6<f64>> = None;
        let mut eval = self.evaluate(&x, end, load_scale)?;
        for iteration in 0..=self.options.max_iterations {
            let residual_max = eval.residual.amax();
            if residual_max <= tolerance {
                if let (Globalization::Local, Some(first)) = (globalization, first_iterate) {
                    let predictor = (first - start).norm();
                    let corrector = (x - first).norm();
                    if corrector > LOCAL_MAX_CORRECTOR_RATIO * predictor {
                        return Err(ReferenceError::StepRejected {
                            predictor,
                            corrector,
                        });
                    }
                }
                return Ok(self.solution(&x, end, &eval, iteration, residual_max, load_scale));
            }
            if iteration == self.options.max_iterations {
                break;
            }
            let lu = eval.jacobian.lu();
            let step = lu
                .solve(&(-eval.residual))
                .filter(|s| s.iter().all(|v| v.is_finite()))
                .ok_or(ReferenceError::SingularJacobian { iteration })?;
            let step_norm = step.norm();
            let mut alpha = 1.0;
            let mut accepted = None;
            for _ in 0..=max_backtracks {
                let trial = x + step * alpha;
                if let Ok(e) = self.evaluate(&trial, end, load_scale) {
                    // Natural monotonicity test (Deuflhard): the simplified Newton
                    // correction J(x_k)⁻¹ F(x_k + α Δx) must shrink.
                    let simplified = lu.solve(&(-e.residual)).map(|s| s.norm());
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
                    first_iterate.get_or_insert(x);
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
            iterations: self.options.max_iterations,
            residual: eval.residual.amax(),
            tolerance,
        })
    }

    fn solution(
        &self,
        x: &Vector6<f64>,
        end: &EndCondition,
        eval: &Evaluation,
        iterations: usize,
        residual: f64,
        load_scale: f64,
    ) -> Solution {
        let unknowns = self.unscale(x);
        let y = &eval.end;
        let end_state = SectionState {
            arc_length: self.rod.length(),
            position: y.r,
            frame: so3::nearest_rotation(&y.frame),
            force: y.n,
            moment: y.m,
        };
        Solution::new(
            self.clone(),
            *end,
            unknowns,
            end_state,
            iterations,
            residual,
            load_scale,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    /// The variational Jacobian agrees with central finite differences of the
    /// shooting map (moderate stiffness ratios, so differences are accurate).
    #[test]
    fn jacobian_matches_finite_differences() {
        let nodes = vec![
            Vector3::zeros(),
            Vector3::new(0.3, 0.05, 0.02),
            Vector3::new(0.7, -0.02, 0.1),
            Vector3::new(1.0, 0.0, 0.0),
        ];
        let stiffness = crate::Stiffness::bimodular(50.0, 30.0, 1.3, 0.9).unwrap();
        let rod = Rod::new(nodes, stiffness)
            .unwrap()
            .with_distributed_load(Vector3::new(0.1, -0.3, 0.2))
            .unwrap();
        let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
        let x = Vector6::new(0.7, -1.1, 0.4, 0.3, 0.8, -0.6);
        let pose = Pose::new(
            Vector3::new(0.8, 0.2, -0.1),
            Rotation3::new(Vector3::new(0.3, -0.9, 0.5)),
        );
        let conditions = [
            EndCondition::clamped(pose),
            EndCondition::loaded(Vector3::new(1.0, 2.0, 3.0), Vector3::new(-1.0, 0.5, 0.2)),
        ];
        for end in &conditions {
            let eval = solver.evaluate(&x, end, 1.0).unwrap();
            let h = 1e-6;
            for j in 0..6 {
                let mut xp = x;
                xp[j] += h;
                let mut xm = x;
                xm[j] -= h;
                let rp = solver.evaluate(&xp, end, 1.0).unwrap().residual;
                let rm = solver.evaluate(&xm, end, 1.0).unwrap().residual;
                let fd = (rp - rm) / (2.0 * h);
                let error = (fd - eval.jacobian.column(j)).amax();
                assert!(error < 1e-7, "column {j}: error {error:e}");
            }
        }
    }
}
