//! Quasi-static solution (issue 5, SPEC P5): the equilibrium under the current boundary
//! conditions — prescribed nodes where their load cases put them now, gravity, dead loads,
//! contact — found by Newton's method on the consistent tangent with a backtracking line
//! search (Nocedal & Wright, "Numerical Optimization", 2006, alg. 3.1): a step is
//! accepted when the potential energy decreases enough (Armijo, c₁ = 1e-4; dead moments
//! enter with their work along the search line), or — where the energy does not decide
//! (round-off near convergence) — when the residual decreases. Velocities are zero: what manual assembly at walking pace
//! needs, one solve per input.

use crate::newton::system::{
    apply_increment, residual_norms, rotation_limited_step, sync_bodies, NewtonSystem,
};
use crate::{Model, State};
use glam::DVec3;

/// When to stop iterating.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticOptions {
    /// Largest allowed out-of-balance force on a free node [N].
    pub force_tolerance: f64,
    /// Largest allowed out-of-balance moment on a free node [N·m].
    pub moment_tolerance: f64,
    pub max_iterations: usize,
    /// Largest translation of any node in one iteration [m], as a fraction of the
    /// smallest hose radius when contact is on (keeps contact from being jumped through).
    pub contact_step_fraction: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            force_tolerance: 1e-7,
            moment_tolerance: 1e-8,
            max_iterations: 60,
            contact_step_fraction: 0.5,
        }
    }
}

/// How a static solve ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticReport {
    pub iterations: usize,
    pub residual_force: f64,
    pub residual_moment: f64,
    pub converged: bool,
    /// Line-search steps shorter than the full Newton step.
    pub shortened_steps: usize,
}

/// Why the solve failed outright (not just "not converged").
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StaticError {
    #[error("{0}")]
    Singular(#[from] crate::newton::block_tridiagonal::SingularBlock),
    #[error("the static solve produced non-finite values at iteration {0}")]
    NonFinite(usize),
}

/// The quasi-static solver: its Newton buffers and options.
#[derive(Clone, Debug)]
pub struct StaticSolver {
    pub system: NewtonSystem,
    pub options: StaticOptions,
    /// Configuration before a trial step (line search).
    saved_x: Vec<DVec3>,
    saved_q: Vec<glam::DQuat>,
}

impl StaticSolver {
    pub fn new(model: &Model) -> Result<Self, crate::newton::system::NotAChain> {
        let n = model.node_count();
        Ok(Self {
            system: NewtonSystem::new(model)?,
            options: StaticOptions::default(),
            saved_x: vec![DVec3::ZERO; n],
            saved_q: vec![glam::DQuat::IDENTITY; n],
        })
    }

    /// Moves `state` to the equilibrium under its load cases at `state.time`. Writes
    /// forces, reactions (support loads on prescribed nodes), contact forces and `held`
    /// as the explicit step does; velocities are zero.
    pub fn solve(&mut self, model: &Model, state: &mut State) -> Result<StaticReport, StaticError> {
        let sys = &mut self.system;
        sys.set_prescribed(state, state.time);
        state.v.fill(DVec3::ZERO);
        state.w.fill(DVec3::ZERO);
        let min_radius = model.radius.iter().cloned().fold(f64::INFINITY, f64::min);
        let mut report = StaticReport {
            iterations: 0,
            residual_force: f64::INFINITY,
            residual_moment: f64::INFINITY,
            converged: false,
            shortened_steps: 0,
        };
        loop {
            sys.assemble(model, state, 0.0);
            let (rf, rm) = residual_norms(&sys.force, &sys.moment, &sys.prescribed);
            report.residual_force = rf;
            report.residual_moment = rm;
            if !(rf.is_finite() && rm.is_finite()) {
                return Err(StaticError::NonFinite(report.iterations));
            }
            let pending = sys.pending();
            if !pending && rf <= self.options.force_tolerance && rm <= self.options.moment_tolerance
            {
                report.converged = true;
                break;
            }
            if report.iterations >= self.options.max_iterations {
                break;
            }
            report.iterations += 1;
            for i in 0..sys.rhs.len() {
                let (f, m) = (sys.force[i], sys.moment[i]);
                sys.rhs[i] = nalgebra::Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z);
            }
            if pending {
                sys.add_prescribed_coupling(state);
            }
            sys.eliminate_prescribed();
            sys.solve_linear()?;
            if pending {
                // the prescribed motion and the free nodes' linear response to it, taken
                // whole (the energy before and after the supports moved is not comparable)
                let s = rotation_limited_step(&sys.rhs, &sys.prescribed);
                apply_increment(state, &sys.rhs, &sys.prescribed, s);
                sys.move_prescribed(state);
                continue;
            }
            if increment_at_round_off(&sys.rhs, &sys.prescribed, model) {
                // the residual left is round-off of the stiff (rigid-factor) elements
                report.converged = true;
                break;
            }
            // −dΠ/ds along the step = (f, m)·δu (the loads are −∇Π)
            let mut directional = 0.0;
            for i in 0..sys.rhs.len() {
                if !sys.prescribed[i] {
                    let d = sys.rhs[i];
                    directional += sys.force[i].dot(DVec3::new(d[0], d[1], d[2]))
                        + sys.moment[i].dot(DVec3::new(d[3], d[4], d[5]));
                }
            }
            let mut s: f64 = rotation_limited_step(&sys.rhs, &sys.prescribed);
            if !model.environment.is_empty() {
                let longest = sys
                    .rhs
                    .iter()
                    .map(|d| d.fixed_rows::<3>(0).norm())
                    .fold(0.0, f64::max);
                let cap = self.options.contact_step_fraction * min_radius;
                if longest > cap {
                    s = cap / longest;
                }
            }
            // dead moments have no global potential; along this search line their work is
            // s Σ M·δθ (exact for a fixed axis, first order otherwise)
            let mut moment_work = 0.0;
            for (_, case) in state.loads.iter() {
                if let crate::loads::LoadCase::DeadLoad(d) = case {
                    let r = sys.rhs[d.node];
                    moment_work += d.moment.dot(DVec3::new(r[3], r[4], r[5]));
                }
            }
            let energy0 = sys.potential_energy(model, state);
            let residual0 = rf.max(rm);
            self.saved_x.copy_from_slice(&state.x);
            self.saved_q.copy_from_slice(&state.q);
            let mut tries = 0;
            loop {
                apply_increment(state, &sys.rhs, &sys.prescribed, s);
                let energy = sys.potential_energy(model, state) - s * moment_work;
                let descent = directional > 0.0;
                let enough = energy <= energy0 - 1e-4 * s * directional;
                let accept = if descent && enough {
                    true
                } else {
                    // the energy does not decide: compare residuals
                    sys.assemble(model, state, 0.0);
                    let (f, m) = residual_norms(&sys.force, &sys.moment, &sys.prescribed);
                    f.max(m) < residual0
                };
                if accept || tries >= 12 {
                    break;
                }
                tries += 1;
                s *= 0.5;
                state.x.copy_from_slice(&self.saved_x);
                state.q.copy_from_slice(&self.saved_q);
            }
            if s < 1.0 {
                report.shortened_steps += 1;
            }
        }
        finish(model, state, &self.system);
        Ok(report)
    }
}

/// Whether a Newton increment is below what f64 can resolve for this model: no node
/// moves by more than 1e-12 of the model's size or turns by more than 1e-12 rad.
pub(crate) fn increment_at_round_off(
    rhs: &[nalgebra::Vector6<f64>],
    prescribed: &[bool],
    model: &Model,
) -> bool {
    let size = model
        .rest_x
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs().max_element()))
        .max(1.0);
    rhs.iter().zip(prescribed).all(|(d, p)| {
        *p || (d.fixed_rows::<3>(0).norm() <= 1e-12 * size && d.fixed_rows::<3>(3).norm() <= 1e-12)
    })
}

/// Writes the converged loads into the state: forces, support reactions (−f on a
/// prescribed node, so that support + loads balance), contact forces, body states.
fn finish(model: &Model, state: &mut State, sys: &NewtonSystem) {
    for i in 0..state.x.len() {
        state.force[i] = sys.force[i];
        state.moment[i] = sys.moment[i];
        state.contact_force[i] = sys.contact_force[i];
        state.held[i] = sys.prescribed[i];
        if sys.prescribed[i] {
            state.reaction_force[i] = -sys.force[i];
            state.reaction_moment[i] = -sys.moment[i];
        } else {
            state.reaction_force[i] = DVec3::ZERO;
            state.reaction_moment[i] = DVec3::ZERO;
        }
    }
    sync_bodies(model, state);
}
