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
//! The Newton iteration itself is damped by Deuflhard's natural monotonicity test
//! (Deuflhard, "Newton Methods for Nonlinear Problems", 2004, §3.3).

use nalgebra::{DMatrix, DVector, Vector3};

use crate::boundary::{EndCondition, Pose};
use crate::error::{ReferenceError, Result};
use crate::newton::{self, Converged, Evaluation, Globalization};
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
    pub(crate) fn validate(&self) -> Result<()> {
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

/// Residual scales (see the module documentation).
#[derive(Debug, Clone, Copy)]
struct Scales {
    length: f64,
    force: f64,
    moment: f64,
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

    fn scale(&self, unknowns: &Unknowns) -> DVector<f64> {
        let sc = self.scales();
        let f = unknowns.force / sc.force;
        let m = unknowns.moment / sc.moment;
        DVector::from_column_slice(&[f.x, f.y, f.z, m.x, m.y, m.z])
    }

    fn unscale(&self, x: &DVector<f64>) -> Unknowns {
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
        x: &DVector<f64>,
        end: &EndCondition,
        load_scale: f64,
    ) -> Result<Evaluation<RodState>> {
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
        let mut residual = DVector::zeros(6);
        let mut jacobian = DMatrix::zeros(6, 6);
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
            detail: out.state,
        })
    }

    /// Newton iteration ([`newton::solve`]) from `guess`; `load_scale` multiplies
    /// the distributed load.
    pub(crate) fn newton(
        &self,
        end: &EndCondition,
        guess: &Unknowns,
        load_scale: f64,
        globalization: Globalization,
    ) -> Result<Solution> {
        let converged = newton::solve(self.scale(guess), &self.options, globalization, |x| {
            self.evaluate(x, end, load_scale)
        })?;
        Ok(self.solution(&converged, end, load_scale))
    }

    fn solution(
        &self,
        converged: &Converged<RodState>,
        end: &EndCondition,
        load_scale: f64,
    ) -> Solution {
        let unknowns = self.unscale(&converged.x);
        let y = &converged.evaluation.detail;
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
            converged.iterations,
            converged.residual,
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
        let x = DVector::from_column_slice(&[0.7, -1.1, 0.4, 0.3, 0.8, -0.6]);
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
                let mut xp = x.clone();
                xp[j] += h;
                let mut xm = x.clone();
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
