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
use crate::shooting::{Globalization, ShootingSolver, Unknowns};
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
        let max_halvings = self.options().max_step_halvings;
        let mut solutions = Vec::with_capacity(targets.len());
        for (index, target) in targets.iter().enumerate() {
            let mut t = 0.0;
            let mut halvings = 0u32;
            let mut guess = current.unknowns;
            loop {
                let step = (-f64::from(halvings)).exp2();
                let t_next = (t + step).min(1.0);
                let (condition, interpolable) = if t_next >= 1.0 {
                    (*target, true)
                } else {
                    match current.condition.interpolate(target, t_next) {
                        Some(c) => (c, true),
                        None => (*target, false),
                    }
                };
                let load_scale = current.load_scale + (1.0 - current.load_scale) * t_next;
                let mut attempt = self.newton(&condition, &guess, load_scale, Globalization::Local);
                if attempt.is_err() && halvings >= max_halvings {
                    // Last resort at the smallest step: a damped solve (needed e.g.
                    // when the path starts exactly at the kink N = 0 of a bimodular
                    // law, where the local convergence tests cannot hold).
                    attempt = self.newton(&condition, &guess, load_scale, Globalization::Damped);
                }
                match attempt {
                    Ok(solution) => {
                        guess = solution.unknowns();
                        t = t_next;
                        if t >= 1.0 {
                            current = PathPoint {
                                condition: *target,
                                unknowns: guess,
                                load_scale: 1.0,
                            };
                            solutions.push(solution);
                            break;
                        }
                        halvings = halvings.saturating_sub(1);
                    }
                    Err(error) => {
                        if !interpolable || halvings >= max_halvings {
                            return Err(ReferenceError::ContinuationFailed {
                                target: index,
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
        Ok(solutions)
    }
}
