//! Shooting on a rod tree: unknown internal force and moment at the base of every
//! branch, found by Newton's method so that the trunk's clamp, force and moment
//! balance at every branch point and the dead loads at every tip all hold.
//!
//! # Unknowns and residual
//!
//! Branch `b` (a [`crate::Rod`] of length `L_b`) is integrated from its base, as the
//! chain of [`crate::shooting`] is, with the unknowns `n_b(0), m_b(0)`; its base pose
//! is the trunk's clamp (trunk) or its parent's end pose turned by the weld,
//! `r_b(0) = r_p(L_p)`, `R_b(0) = R_p(L_p) W_b` ([`Tree`]). With `F_b, M_b` the dead
//! force and moment applied at the end of branch `b` (a tip, or the branch point where
//! its children start), the residual of branch `b` is the balance of its end point,
//!
//! ```text
//! n_b(L_b) − Σ_children c n_c(0) − F_b = 0,
//! m_b(L_b) − Σ_children c m_c(0) − M_b = 0
//! ```
//!
//! (moments about the joint, where all the children start; at a tip the sums are empty
//! and this is the chain's loaded end condition). `6 B` unknowns, `6 B` equations for
//! `B` branches; scaled as the chain's by the trunk's `EI` and the tree's reach `L`
//! (longest rest arc length from the base to a tip).
//!
//! # Jacobian
//!
//! Exact, from the variational equations ([`crate::ode`]): each branch is integrated
//! with twelve variations seeded at its base — position `δr = e_i`, global spin
//! `δR = [e_i]× R`, force and moment — giving the 12 × 12 sensitivity of its end state
//! `(r, φ, n, m)` (`δφ = vee(δR Rᵀ)`) to its base state. The base state of a branch
//! depends on its own unknowns and, through the weld, on its parent's end pose, so the
//! sensitivity to all `6 B` unknowns is the product with the parent's, accumulated from
//! the trunk outwards (the chain rule along the tree).
//!
//! Large loads are reached by path following ([`crate::continuation`]): the end loads
//! (and the rods' distributed loads) grow from zero, and between consecutive targets,
//! linearly, with step halving.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use crate::boundary::Pose;
use crate::continuation::follow_leg;
use crate::error::{ReferenceError, Result};
use crate::newton::{self, Evaluation, Globalization};
use crate::ode::{integrate, Augmented, RodState};
use crate::shooting::{SolverOptions, Unknowns};
use crate::so3::{nearest_rotation, skew, vee_skew_part};
use crate::solution::{SectionState, Wrench};
use crate::tree::Tree;

/// Rows of a branch's end-state sensitivity: position, spin, force, moment.
const STATE_ROWS: usize = 12;

/// Static reference solver for a rod tree whose trunk is clamped at its base.
#[derive(Debug, Clone, PartialEq)]
pub struct TreeSolver {
    tree: Tree,
    base: Pose,
    options: SolverOptions,
}

/// A converged static equilibrium of a tree.
#[derive(Debug, Clone, PartialEq)]
pub struct TreeSolution {
    /// Scaled unknowns (the next continuation guess).
    scaled: DVector<f64>,
    trunk: usize,
    bases: Vec<SectionState>,
    ends: Vec<SectionState>,
    loads: Vec<Wrench>,
    iterations: usize,
    residual: f64,
}

/// Residual scales: forces by `EI/L²`, moments by `EI/L`.
#[derive(Debug, Clone, Copy)]
struct Scales {
    force: f64,
    moment: f64,
}

/// What one evaluation keeps of each branch: the base and end states.
type BranchStates = Vec<(RodState, RodState)>;

impl TreeSolver {
    /// A solver for `tree` with its trunk's base clamped at `base`, default options.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidBoundaryCondition`] if `base` is non-finite or its
    /// frame is not a rotation.
    pub fn new(tree: Tree, base: Pose) -> Result<Self> {
        base.validate("base")?;
        Ok(Self {
            tree,
            base,
            options: SolverOptions::default(),
        })
    }

    /// Replaces the numerical options (see [`crate::ShootingSolver::with_options`]).
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidOptions`] for options out of range.
    pub fn with_options(mut self, options: SolverOptions) -> Result<Self> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// The tree.
    pub fn tree(&self) -> &Tree {
        &self.tree
    }

    /// Solves each of `targets` in turn by path following from the unloaded rest
    /// state. A target lists, for every branch, the dead force and moment (global,
    /// moment about the point) applied at the branch's end: its tip, or the branch
    /// point where its children start.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidBoundaryCondition`] for a target without one load per
    /// branch or with non-finite values (before any work is done);
    /// [`ReferenceError::ContinuationFailed`] when a target cannot be reached.
    pub fn solve_path(&self, targets: &[Vec<Wrench>]) -> Result<Vec<TreeSolution>> {
        for loads in targets {
            self.validate_loads(loads)?;
        }
        let count = self.tree.branch_count();
        let zero = Wrench {
            force: Vector3::zeros(),
            moment: Vector3::zeros(),
        };
        let mut previous = vec![zero; count];
        let mut previous_scale = 0.0;
        let mut guess = DVector::zeros(6 * count);
        let mut solutions = Vec::with_capacity(targets.len());
        for (index, target) in targets.iter().enumerate() {
            let solution = follow_leg(
                self.options.max_step_halvings,
                index,
                true,
                guess,
                |t, guess: &DVector<f64>, globalization| {
                    let loads: Vec<Wrench> = previous
                        .iter()
                        .zip(target)
                        .map(|(a, b)| Wrench {
                            force: a.force + (b.force - a.force) * t,
                            moment: a.moment + (b.moment - a.moment) * t,
                        })
                        .collect();
                    let load_scale = previous_scale + (1.0 - previous_scale) * t;
                    self.newton(loads, guess, load_scale, globalization)
                },
                |s: &TreeSolution| s.scaled.clone(),
            )?;
            previous.clone_from(target);
            previous_scale = 1.0;
            guess = solution.scaled.clone();
            solutions.push(solution);
        }
        Ok(solutions)
    }

    fn validate_loads(&self, loads: &[Wrench]) -> Result<()> {
        let count = self.tree.branch_count();
        if loads.len() != count {
            return Err(ReferenceError::InvalidBoundaryCondition(format!(
                "a tree target needs one end load per branch: {count} expected, {} given",
                loads.len()
            )));
        }
        if let Some(b) = loads
            .iter()
            .position(|w| !w.force.iter().chain(w.moment.iter()).all(|v| v.is_finite()))
        {
            return Err(ReferenceError::InvalidBoundaryCondition(format!(
                "the end load of tree branch {b} contains non-finite values"
            )));
        }
        Ok(())
    }

    fn scales(&self) -> Scales {
        let length = self.tree.reach();
        let trunk = self.tree.trunk();
        let bending = self
            .tree
            .rod(trunk)
            .map_or(1.0, |rod| rod.stiffness().bending());
        Scales {
            force: bending / (length * length),
            moment: bending / length,
        }
    }

    /// Newton's method ([`newton::solve`]) from the scaled unknowns `guess`.
    fn newton(
        &self,
        loads: Vec<Wrench>,
        guess: &DVector<f64>,
        load_scale: f64,
        globalization: Globalization,
    ) -> Result<TreeSolution> {
        let converged = newton::solve(guess.clone(), &self.options, globalization, |x| {
            self.evaluate(x, &loads, load_scale)
        })?;
        let section = |b: usize, at_end: bool, y: &RodState| SectionState {
            arc_length: if at_end {
                self.tree.rod(b).map_or(0.0, |rod| rod.length())
            } else {
                0.0
            },
            position: y.r,
            frame: nearest_rotation(&y.frame),
            force: y.n,
            moment: y.m,
        };
        let states = &converged.evaluation.detail;
        Ok(TreeSolution {
            bases: (0..states.len())
                .map(|b| section(b, false, &states[b].0))
                .collect(),
            ends: (0..states.len())
                .map(|b| section(b, true, &states[b].1))
                .collect(),
            scaled: converged.x,
            trunk: self.tree.trunk(),
            loads,
            iterations: converged.iterations,
            residual: converged.residual,
        })
    }

    /// Residual and exact Jacobian at the scaled unknowns `x` (see the module
    /// documentation), with each branch's base and end states.
    pub(crate) fn evaluate(
        &self,
        x: &DVector<f64>,
        loads: &[Wrench],
        load_scale: f64,
    ) -> Result<Evaluation<BranchStates>> {
        let sc = self.scales();
        let count = self.tree.branch_count();
        let size = 6 * count;
        let mut states: Vec<Option<(RodState, RodState)>> = vec![None; count];
        let mut sensitivities: Vec<DMatrix<f64>> = vec![DMatrix::zeros(0, 0); count];
        for &b in self.tree.order() {
            let rod = self.tree.branch_rod(b);
            // base pose and its sensitivity to all unknowns (6 × size)
            let (position, frame, pose_sensitivity) = match self.tree.parent(b) {
                None => (
                    self.base.position,
                    *self.base.frame.matrix(),
                    DMatrix::zeros(6, size),
                ),
                Some(p) => {
                    let (_, end) = states[p].as_ref().ok_or_else(|| unordered(b))?;
                    (
                        end.r,
                        end.frame * self.tree.weld(b).matrix(),
                        sensitivities[p].rows(0, 6).into_owned(),
                    )
                }
            };
            let base = RodState {
                r: position,
                frame,
                n: Vector3::new(x[6 * b], x[6 * b + 1], x[6 * b + 2]) * sc.force,
                m: Vector3::new(x[6 * b + 3], x[6 * b + 4], x[6 * b + 5]) * sc.moment,
            };
            let seeds: [RodState; STATE_ROWS] = std::array::from_fn(|j| {
                let unit = Vector3::ith(j % 3, 1.0);
                let mut seed = RodState::zero();
                match j / 3 {
                    0 => seed.r = unit,
                    1 => seed.frame = skew(&unit) * frame,
                    2 => seed.n = unit * sc.force,
                    _ => seed.m = unit * sc.moment,
                }
                seed
            });
            let out = integrate(
                rod,
                load_scale,
                self.options.steps_per_length,
                Augmented {
                    state: base,
                    variations: seeds,
                },
                &[],
                |_, _| {},
            )?;
            let end = out.state;
            let end_frame_t: Matrix3<f64> = end.frame.transpose();
            let mut local = DMatrix::zeros(STATE_ROWS, STATE_ROWS);
            for (j, v) in out.variations.iter().enumerate() {
                let spin = vee_skew_part(&(v.frame * end_frame_t));
                for (block, value) in [v.r, spin, v.n, v.m].iter().enumerate() {
                    local.fixed_view_mut::<3, 1>(3 * block, j).copy_from(value);
                }
            }
            let mut base_sensitivity = DMatrix::zeros(STATE_ROWS, size);
            base_sensitivity.rows_mut(0, 6).copy_from(&pose_sensitivity);
            for i in 0..6 {
                base_sensitivity[(6 + i, 6 * b + i)] = 1.0;
            }
            sensitivities[b] = local * base_sensitivity;
            states[b] = Some((base, end));
        }
        let states: BranchStates = states
            .into_iter()
            .enumerate()
            .map(|(b, s)| s.ok_or_else(|| unordered(b)))
            .collect::<Result<_>>()?;
        let mut residual = DVector::zeros(size);
        let mut jacobian = DMatrix::zeros(size, size);
        for b in 0..count {
            let end = &states[b].1;
            let mut force = end.n - loads[b].force;
            let mut moment = end.m - loads[b].moment;
            for &c in self.tree.children(b) {
                force -= states[c].0.n;
                moment -= states[c].0.m;
                for i in 0..6 {
                    jacobian[(6 * b + i, 6 * c + i)] -= 1.0;
                }
            }
            residual
                .fixed_rows_mut::<3>(6 * b)
                .copy_from(&(force / sc.force));
            residual
                .fixed_rows_mut::<3>(6 * b + 3)
                .copy_from(&(moment / sc.moment));
            let sensitivity = &sensitivities[b];
            for i in 0..3 {
                for j in 0..size {
                    jacobian[(6 * b + i, j)] += sensitivity[(6 + i, j)] / sc.force;
                    jacobian[(6 * b + 3 + i, j)] += sensitivity[(9 + i, j)] / sc.moment;
                }
            }
        }
        Ok(Evaluation {
            residual,
            jacobian,
            detail: states,
        })
    }
}

/// A branch reached before its parent: impossible for a [`Tree`] (its order puts
/// parents first), reported rather than panicked on.
fn unordered(branch: usize) -> ReferenceError {
    ReferenceError::InvalidTree(format!("branch {branch} was reached before its parent"))
}

impl TreeSolution {
    /// Fields at the base (`s = 0`) of `branch`; `n, m` there are the force and moment
    /// the branch exerts on its parent's end (on the clamp, for the trunk).
    pub fn base_state(&self, branch: usize) -> Option<&SectionState> {
        self.bases.get(branch)
    }

    /// Fields at the end (`s = L_b`) of `branch`.
    pub fn end_state(&self, branch: usize) -> Option<&SectionState> {
        self.ends.get(branch)
    }

    /// The shooting unknowns `n_b(0), m_b(0)` of `branch`.
    pub fn unknowns(&self, branch: usize) -> Option<Unknowns> {
        self.bases.get(branch).map(|s| Unknowns {
            force: s.force,
            moment: s.moment,
        })
    }

    /// The end loads this solution carries, one per branch.
    pub fn loads(&self) -> &[Wrench] {
        &self.loads
    }

    /// Force and moment the clamp applies to the trunk, moment about the base point.
    pub fn base_reaction(&self) -> Wrench {
        let base = &self.bases[self.trunk];
        Wrench {
            force: -base.force,
            moment: -base.moment,
        }
    }

    /// Newton iterations of the final solve.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// Final scaled residual (max norm).
    pub fn residual(&self) -> f64 {
        self.residual
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Rod, Stiffness};

    /// The chained variational Jacobian agrees with central finite differences of the
    /// tree's shooting map (a trunk, a kinked branch and a branch on that branch).
    #[test]
    fn jacobian_matches_finite_differences() {
        let stiffness = Stiffness::bimodular(50.0, 30.0, 1.3, 0.9).unwrap();
        let trunk = Rod::new(
            vec![Vector3::zeros(), Vector3::new(0.5, 0.1, 0.0)],
            stiffness,
        )
        .unwrap();
        let end = Vector3::new(0.5, 0.1, 0.0);
        let side = Rod::new(
            vec![
                end,
                end + Vector3::new(0.1, 0.4, 0.1),
                end + Vector3::new(0.3, 0.5, 0.0),
            ],
            stiffness,
        )
        .unwrap()
        .with_distributed_load(Vector3::new(0.1, -0.3, 0.2))
        .unwrap();
        let onward = Rod::new(vec![end, end + Vector3::new(0.4, -0.2, 0.1)], stiffness).unwrap();
        let far = end + Vector3::new(0.3, 0.5, 0.0);
        let twig = Rod::new(vec![far, far + Vector3::new(0.0, 0.0, 0.3)], stiffness).unwrap();
        let tree = Tree::new(vec![
            (trunk, None),
            (side, Some(0)),
            (onward, Some(0)),
            (twig, Some(1)),
        ])
        .unwrap();
        let base = tree.rod(0).unwrap().rest_base_pose();
        let solver = TreeSolver::new(tree, base).unwrap();
        let loads: Vec<Wrench> = (0..4)
            .map(|b| Wrench {
                force: Vector3::new(0.3, -0.2, 0.1) * b as f64,
                moment: Vector3::new(-0.1, 0.05, 0.2),
            })
            .collect();
        let x = DVector::from_fn(24, |i, _| ((i * 7 % 11) as f64 - 5.0) * 0.05);
        let eval = solver.evaluate(&x, &loads, 1.0).unwrap();
        let h = 1e-6;
        for j in 0..24 {
            let mut xp = x.clone();
            xp[j] += h;
            let mut xm = x.clone();
            xm[j] -= h;
            let rp = solver.evaluate(&xp, &loads, 1.0).unwrap().residual;
            let rm = solver.evaluate(&xm, &loads, 1.0).unwrap().residual;
            let fd = (rp - rm) / (2.0 * h);
            let error = (fd - eval.jacobian.column(j)).amax();
            assert!(error < 1e-7, "column {j}: error {error:e}");
        }
    }
}
