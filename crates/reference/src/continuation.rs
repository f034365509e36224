//! Path following (natural-parameter continuation with step halving).
//!
//! Large deformations are reached through a sequence of end conditions. Each
//! target is approached from the previous converged solution; the step from the
//! previous end condition `c_a` to the target `c_b` is first tried in one go and,
//! when Newton fails, halved (down to `2^-max_step_halvings` of the step) along the
//! interpolated path `c(t)` (positions and loads linearly in `t`, frames along the
//! SO(3) geodesic `R_a exp(t log(R_aᵀ R_b))`). After each success the step doubles
//! again. Every sub-step starts from the last converged unknowns and must pass the
//! local convergence tests of the shooting Newton iteration (which keep the path from
//! jumping to another equilibrium branch); only at the smallest step is a damped
//! Newton solve tried as a last resort.
//!
//! The path starts from the unloaded rest state (`n = m = 0`), whose end condition
//! is the rest end pose moved rigidly with the base (clamped targets) or zero end
//! loads (loaded targets); the rod's distributed load is ramped up from zero along
//! the way to the first target.

use crate::boundary::EndCondition;
use crate::error::{ReferenceError, Result};
use crate::newton::Globalization;
use crate::shooting::{ShootingSolver, Unknowns};
use crate::solution::Solution;

/// A converged point of the path.
struct PathPoint {
    condition: EndCondition,
    unknowns: Unknowns,
    load_scale: f64,
}

impl ShootingSolver {
    /// Solves each of `targets` in turn by continuation from the unloaded rest
    /// state, returning one solution per target.
    ///
    /// Consecutive targets of different kinds (clamped/loaded) cannot be
    /// interpolated: the switch is attempted as one Newton solve from the previous
    /// solution. Fails with [`ReferenceError::ContinuationFailed`] when a target
    /// cannot be reached within `max_step_halvings` halvings.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::ContinuationFailed`] when a target cannot be reached;
    /// invalid targets are reported before any work is done.
    pub fn solve_path(&self, targets: &[EndCondition]) -> Result<Vec<Solution>> {
        let Some(first) = targets.first() else {
            return Ok(Vec::new());
        };
        let condition = match first {
            EndCondition::Clamped(_) => EndCondition::Clamped(self.unloaded_end_pose()),
            EndCondition::Loaded { .. } => {
                EndCondition::loaded(nalgebra::Vector3::zeros(), nalgebra::Vector3::zeros())
            }
        };
        let start = PathPoint {
            condition,
            unknowns: Unknowns::zero(),
            load_scale: 0.0,
        };
        self.follow(start, targets)
    }

    /// Like [`ShootingSolver::solve_path`], but continuing from an existing solution of
    /// this solver (same rod, base and options).
    ///
    /// # Errors
    ///
    /// As [`ShootingSolver::solve_path`]; [`ReferenceError::InvalidBoundaryCondition`] if
    /// `start` was computed by a different solver.
    pub fn solve_path_from(
        &self,
        start: &Solution,
        targets: &[EndCondition],
    ) -> Result<Vec<Solution>> {
        if start.solver() != self {
            return Err(ReferenceError::InvalidBoundaryCondition(
                "the start solution belongs to a different problem".to_string(),
            ));
        }
        let start = PathPoint {
            condition: *start.end_condition(),
            unknowns: start.unknowns(),
            load_scale: 1.0,
        };
        self.follow(start, targets)
    }

    fn follow(&self, mut current: PathPoint, targets: &[EndCondition]) -> Result<Vec<Solution>> {
        for target in targets {
            target.validate()?;
        }
        let mut solutions = Vec::with_capacity(targets.len());
        for (index, target) in targets.iter().enumerate() {
            let interpolable = current.condition.interpolate(target, 0.5).is_some();
            let solution = follow_leg(
                self.options().max_step_halvings,
                index,
                interpolable,
                current.unknowns,
                |t, guess, globalization| {
                    let condition = if t >= 1.0 {
                        *target
                    } else {
                        current.condition.interpolate(target, t).unwrap_or(*target)
                    };
                    let load_scale = current.load_scale + (1.0 - current.load_scale) * t;
                    self.newton(&condition, guess, load_scale, globalization)
                },
                Solution::unknowns,
            )?;
            current = PathPoint {
                condition: *target,
                unknowns: solution.unknowns(),
                load_scale: 1.0,
            };
            solutions.push(solution);
        }
        Ok(solutions)
    }
}

/// Follows one leg of a path, from parameter `t = 0` (converged, with unknowns
/// `guess`) to `t = 1`, by step halving: `solve(t, guess, globalization)` solves the
/// problem at `t` from `guess`, `unknowns_of` reads a solution's unknowns (the next
/// guess). A leg that is not `interpolable` (its end points are of different kinds) is
/// tried in one step only. `target` is the leg's index, for the error.
pub(crate) fn follow_leg<S, U>(
    max_halvings: u32,
    target: usize,
    interpolable: bool,
    mut guess: U,
    mut solve: impl FnMut(f64, &U, Globalization) -> Result<S>,
    unknowns_of: impl Fn(&S) -> U,
) -> Result<S> {
    let mut t = 0.0;
    let mut halvings = 0u32;
    loop {
        let step = (-f64::from(halvings)).exp2();
        let t_next = if interpolable {
            (t + step).min(1.0)
        } else {
            1.0
        };
        let mut attempt = solve(t_next, &guess, Globalization::Local);
        if attempt.is_err() && halvings >= max_halvings {
            // Last resort at the smallest step: a damped solve (needed e.g. when the
            // path starts exactly at the kink N = 0 of a bimodular law, where the local
            // convergence tests cannot hold).
            attempt = solve(t_next, &guess, Globalization::Damped);
        }
        match attempt {
            Ok(solution) => {
                guess = unknowns_of(&solution);
                t = t_next;
                if t >= 1.0 {
                    return Ok(solution);
                }
                halvings = halvings.saturating_sub(1);
            }
            Err(error) => {
                if !interpolable || halvings >= max_halvings {
                    return Err(ReferenceError::ContinuationFailed {
                        target,
                        reached: t,
                        halvings,
                        last_error: Box::new(error),
                    });
                }
                halvings += 1;
            }
        }
    }
}
