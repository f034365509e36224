//! Implicit dynamics (SPEC P5; the dissertation's outlook 7.2): the HHT-α method
//! (Hilber, Hughes & Taylor 1977, "Improved numerical dissipation for time integration
//! algorithms in structural dynamics", EESD 5) with Newton iterations on the consistent
//! tangent, solved in O(N) per iteration ([`crate::newton::block_tree`]).
//!
//! With α ∈ [−⅓, 0], β = (1 − α)²/4, γ = ½ − α, per node
//!   m a_{n+1} = (1 + α) f_{n+1} − α f_n,
//!   x_{n+1} = x_n + Δt v_n + Δt² ((½ − β) a_n + β a_{n+1}),
//!   v_{n+1} = v_n + Δt ((1 − γ) a_n + γ a_{n+1}),
//! and likewise for rotations on the rotation group (Simo & Vu-Quoc 1988): q_{n+1} =
//! exp(Θ) q_n with Θ in place of x_{n+1} − x_n, the isotropic inertia I α = m (as in the
//! explicit solver, [`crate::rod::mass`]). The Jacobian of a node's equations is
//! (1 + α) K + m/(βΔt²) [𝟙, J_l⁻¹(Θ)], K from [`crate::newton::system`] including the damping
//! tangent. α < 0 damps the highest modes numerically (α = −0.1 by default); the scheme is
//! unconditionally stable for linear problems and second-order accurate, so the step is
//! chosen for accuracy — 10 ms is fine where explicit stepping needs microseconds.
//!
//! Each Newton step is shortened by halving until it lowers the norm of the residual
//! (backtracking, Nocedal & Wright 2006, §11.2 with the residual norm as merit function;
//! at most `MAX_BACKTRACKS` halvings): a full step that raises it — typically a contact
//! switching on or off between iterates — is not taken whole. With contact, no iterate
//! moves a node by more than half the smallest hose radius
//! (the static solver's step control): a first iterate that has not yet seen a contact
//! would otherwise carry a hose through the one it lands on, and Newton would balance it
//! there with the contact normal reversed. A step whose Newton iterations do not
//! converge is retried as two half steps (down to 1/16 of the step) before it is
//! reported.

use super::statics::increment_at_round_off;
use crate::math::{left_jacobian_inverse_transpose_times, log_map};
use crate::newton::block_tree::SingularBlock;
use crate::newton::convergence::Tolerance;
use crate::newton::system::{
    apply_increment, contact_translation_limit, rotation_limited_step, sync_bodies,
    translation_limited_step, NewtonSystem, TopologyError,
};
pub use crate::state::ImplicitHistory;
use crate::{Model, State};
use glam::{DQuat, DVec3};
use nalgebra::Vector6;

/// Halvings the line search may make of one Newton step.
const MAX_BACKTRACKS: usize = 10;

/// Settings of the implicit solver.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImplicitOptions {
    /// Time step \[s\].
    pub time_step: f64,
    /// HHT α ∈ [−⅓, 0].
    pub alpha: f64,
    /// Convergence: the largest out-of-balance force and moment of a node's dynamic
    /// equation, against the problem's load scale ([`Tolerance`]).
    pub tolerance: Tolerance,
    pub max_iterations: usize,
    /// How many times a step may be halved when Newton does not converge.
    pub max_halvings: u32,
    /// Largest translation of a node in one Newton iteration, as a fraction of the
    /// smallest hose radius, when the model has contact
    /// ([`crate::newton::system::contact_translation_limit`]): an iterate must not jump
    /// through a hose or part it has not yet touched. Only the path of the iterates
    /// changes, not the step's solution.
    pub contact_step_fraction: f64,
}

impl Default for ImplicitOptions {
    fn default() -> Self {
        Self {
            time_step: 0.01,
            alpha: -0.1,
            tolerance: Tolerance::default(),
            max_iterations: 25,
            max_halvings: 4,
            contact_step_fraction: 0.5,
        }
    }
}

/// How a step went.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImplicitReport {
    /// Newton iterations over all sub-steps.
    pub iterations: usize,
    /// Sub-steps taken (1 unless the step had to be halved).
    pub substeps: usize,
    pub residual_force: f64,
    pub residual_moment: f64,
    pub converged: bool,
    /// Newton steps the line search shortened.
    pub shortened_steps: usize,
}

/// Why a step failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ImplicitError {
    #[error("{0}")]
    Singular(#[from] SingularBlock),
    #[error("Newton iterations did not converge even with the step halved {0} times (residual {1:.3e} N)")]
    NotConverged(u32, f64),
}

/// The implicit solver: its options and Newton buffers (scratch only; the history that
/// carries over between steps is the state's [`ImplicitHistory`]).
#[derive(Clone, Debug)]
pub struct ImplicitSolver {
    pub system: NewtonSystem,
    pub options: ImplicitOptions,
    /// Start-of-step state for retries.
    x0: Vec<DVec3>,
    q0: Vec<DQuat>,
    v0: Vec<DVec3>,
    w0: Vec<DVec3>,
    /// The line search's Newton increment and the iterate it starts from.
    increment: Vec<Vector6<f64>>,
    trial_x: Vec<DVec3>,
    trial_q: Vec<DQuat>,
}

impl ImplicitSolver {
    pub fn new(model: &Model, options: ImplicitOptions) -> Result<Self, TopologyError> {
        let n = model.node_count();
        let z = vec![DVec3::ZERO; n];
        Ok(Self {
            system: NewtonSystem::new(model)?,
            options,
            x0: z.clone(),
            q0: vec![DQuat::IDENTITY; n],
            v0: z.clone(),
            w0: z.clone(),
            increment: vec![Vector6::zeros(); n],
            trial_x: z,
            trial_q: vec![DQuat::IDENTITY; n],
        })
    }

    /// Advances `state` by `options.time_step`.
    pub fn step(
        &mut self,
        model: &Model,
        state: &mut State,
    ) -> Result<ImplicitReport, ImplicitError> {
        let mut report = ImplicitReport::default();
        // the history is taken out of the state for the step (no allocation) so that the
        // state can be borrowed whole while it is updated
        let mut history = std::mem::take(&mut state.implicit);
        let done = self.advance(
            model,
            state,
            &mut history,
            self.options.time_step,
            0,
            &mut report,
        );
        state.implicit = history;
        done?;
        report.converged = true;
        state.step += 1;
        Ok(report)
    }

    fn advance(
        &mut self,
        model: &Model,
        state: &mut State,
        history: &mut ImplicitHistory,
        h: f64,
        depth: u32,
        report: &mut ImplicitReport,
    ) -> Result<(), ImplicitError> {
        if !history.started {
            self.initialise(model, state, history);
        }
        self.x0.copy_from_slice(&state.x);
        self.q0.copy_from_slice(&state.q);
        self.v0.copy_from_slice(&state.v);
        self.w0.copy_from_slice(&state.w);
        let time0 = state.time;
        if self.try_step(model, state, history, h, report)? {
            report.substeps += 1;
            return Ok(());
        }
        if depth >= self.options.max_halvings {
            return Err(ImplicitError::NotConverged(depth, report.residual_force));
        }
        state.x.copy_from_slice(&self.x0);
        state.q.copy_from_slice(&self.q0);
        state.v.copy_from_slice(&self.v0);
        state.w.copy_from_slice(&self.w0);
        state.time = time0;
        self.advance(model, state, history, 0.5 * h, depth + 1, report)?;
        self.advance(model, state, history, 0.5 * h, depth + 1, report)
    }

    /// Accelerations and loads of the initial state (m a₀ = f₀).
    fn initialise(&mut self, model: &Model, state: &mut State, history: &mut ImplicitHistory) {
        let n = state.x.len();
        for v in [
            &mut history.acc,
            &mut history.ang_acc,
            &mut history.f_prev,
            &mut history.m_prev,
        ] {
            v.resize(n, DVec3::ZERO); // allocates once per state
        }
        let sys = &mut self.system;
        // which nodes are prescribed; they are moved onto their targets by the first step
        sys.set_prescribed(model, state, state.time);
        for i in 0..state.x.len() {
            if sys.prescribed[i] {
                state.v[i] = DVec3::ZERO;
                state.w[i] = DVec3::ZERO;
            }
        }
        sys.assemble(model, state, 0.0);
        for i in 0..state.x.len() {
            let free = !sys.prescribed[i] && !history.zero_acceleration;
            history.f_prev[i] = sys.force[i];
            history.m_prev[i] = sys.moment[i];
            history.acc[i] = if free {
                sys.force[i] / model.mass[i]
            } else {
                DVec3::ZERO
            };
            history.ang_acc[i] = if free {
                sys.moment[i] / model.inertia[i]
            } else {
                DVec3::ZERO
            };
        }
        history.started = true;
    }

    /// The HHT residual r = (1+α) f_{n+1} − α f_n − m a_{n+1} at the current iterate
    /// (Newmark kinematics of the free nodes from their positions) into `system.rhs`, and
    /// its Jacobian (1+α) K + m/(βh²) [𝟙, J_l⁻¹(Θ)] into `system.matrix`. Returns the
    /// largest force and moment residual on a free node, and the residual's norm
    /// √(Σ |r_f|² + Σ |r_m|²/ℓ²) (ℓ the mean element length) that the line search
    /// compares.
    fn evaluate(
        &mut self,
        model: &Model,
        state: &mut State,
        history: &ImplicitHistory,
        h: f64,
    ) -> (f64, f64, f64) {
        let alpha = self.options.alpha;
        let beta = 0.25 * (1.0 - alpha) * (1.0 - alpha);
        let gamma = 0.5 - alpha;
        let c_acc = 1.0 / (beta * h * h);
        let c_vel = gamma / (beta * h);
        let n = state.x.len();
        let sys = &mut self.system;
        for i in 0..n {
            if sys.prescribed[i] {
                continue;
            }
            let (a, alp) = (history.acc[i], history.ang_acc[i]);
            let a_new =
                c_acc * (state.x[i] - self.x0[i] - h * self.v0[i]) - (0.5 - beta) / beta * a;
            let theta = log_map(state.q[i] * self.q0[i].conjugate());
            let alp_new = c_acc * (theta - h * self.w0[i]) - (0.5 - beta) / beta * alp;
            state.v[i] = self.v0[i] + h * ((1.0 - gamma) * a + gamma * a_new);
            state.w[i] = self.w0[i] + h * ((1.0 - gamma) * alp + gamma * alp_new);
        }
        sys.assemble(model, state, c_vel);
        for i in 0..n {
            let a_new = c_acc * (state.x[i] - self.x0[i] - h * self.v0[i])
                - (0.5 - beta) / beta * history.acc[i];
            let theta = log_map(state.q[i] * self.q0[i].conjugate());
            let alp_new =
                c_acc * (theta - h * self.w0[i]) - (0.5 - beta) / beta * history.ang_acc[i];
            let rf =
                (1.0 + alpha) * sys.force[i] - alpha * history.f_prev[i] - model.mass[i] * a_new;
            let rm = (1.0 + alpha) * sys.moment[i]
                - alpha * history.m_prev[i]
                - model.inertia[i] * alp_new;
            sys.rhs[i] = Vector6::new(rf.x, rf.y, rf.z, rm.x, rm.y, rm.z);
            let d = &mut sys.matrix.diag[i];
            *d *= 1.0 + alpha;
            let (cm, ci) = (model.mass[i] * c_acc, model.inertia[i] * c_acc);
            for k in 0..3 {
                d[(k, k)] += cm;
                // J_l⁻¹(Θ): row k is (J_l⁻ᵀ e_k)ᵀ
                let mut e = DVec3::ZERO;
                e[k] = 1.0;
                let row = left_jacobian_inverse_transpose_times(theta, e);
                for c in 0..3 {
                    d[(3 + k, 3 + c)] += ci * row[c];
                }
            }
        }
        // a junction body's own inertia, on its master (the master's Newmark accelerations)
        let (x0, v0, w0, q0) = (&self.x0, &self.v0, &self.w0, &self.q0);
        crate::newton::body_terms::add_body_inertia(
            model,
            state,
            |m| {
                let a =
                    c_acc * (state.x[m] - x0[m] - h * v0[m]) - (0.5 - beta) / beta * history.acc[m];
                let theta = log_map(state.q[m] * q0[m].conjugate());
                let alp = c_acc * (theta - h * w0[m]) - (0.5 - beta) / beta * history.ang_acc[m];
                (a, alp)
            },
            &mut sys.rhs,
            &mut sys.matrix.diag,
            c_acc,
        );
        // the off-diagonal blocks and the contact pairs' coupling outside the band (the
        // diagonal blocks were scaled above, before the mass term)
        sys.scale_off_diagonal_tangent(1.0 + alpha);
        sys.fold_rhs();
        let (mut rf, mut rm, mut sum) = (0.0_f64, 0.0_f64, 0.0);
        let l2 = sys.mean_length * sys.mean_length;
        for i in 0..n {
            if !sys.prescribed[i] {
                let (f, m) = (
                    sys.rhs[i].fixed_rows::<3>(0).norm_squared(),
                    sys.rhs[i].fixed_rows::<3>(3).norm_squared(),
                );
                rf = rf.max(f);
                rm = rm.max(m);
                sum += f + m / l2;
            }
        }
        (rf.sqrt(), rm.sqrt(), sum.sqrt())
    }

    /// One HHT step of size h from the saved start state; Ok(false) if Newton did not
    /// converge (the caller retries with smaller steps).
    fn try_step(
        &mut self,
        model: &Model,
        state: &mut State,
        history: &mut ImplicitHistory,
        h: f64,
        report: &mut ImplicitReport,
    ) -> Result<bool, ImplicitError> {
        let o = self.options;
        let alpha = o.alpha;
        let beta = 0.25 * (1.0 - alpha) * (1.0 - alpha);
        let t_next = state.time + h;
        let n = state.x.len();
        // predictor: constant velocity for the free nodes (an acceleration predictor
        // overshoots badly when a load case has just changed the forces); prescribed nodes
        // stay where they are until the first iteration carries their motion
        // (NewtonSystem::set_prescribed)
        let sys = &mut self.system;
        sys.set_prescribed(model, state, t_next);
        for i in 0..n {
            if sys.prescribed[i] {
                let (dx, dth) = sys.prescribed_increment(state, i);
                state.v[i] = dx / h;
                state.w[i] = dth / h;
            } else {
                state.x[i] = self.x0[i] + h * self.v0[i];
                state.q[i] = (crate::math::exp_map(h * self.w0[i]) * self.q0[i]).normalize();
            }
        }
        let c_acc = 1.0 / (beta * h * h);
        let mut converged = false;
        let (mut rf, mut rm, mut merit) = self.evaluate(model, state, history, h);
        for _ in 0..o.max_iterations {
            report.residual_force = rf;
            report.residual_moment = rm;
            if !(rf.is_finite() && rm.is_finite()) {
                return Ok(false);
            }
            let sys = &mut self.system;
            let pending = sys.pending();
            if !pending && o.tolerance.met(sys.scale, rf, rm) {
                converged = true;
                break;
            }
            if pending {
                sys.add_prescribed_coupling(state);
            }
            sys.eliminate_prescribed();
            sys.solve_linear(false)?;
            let mut s = rotation_limited_step(&sys.rhs, &sys.prescribed);
            report.iterations += 1;
            if pending {
                apply_increment(state, &sys.rhs, &sys.prescribed, s);
                sys.move_prescribed(state);
                (rf, rm, merit) = self.evaluate(model, state, history, h);
                continue;
            }
            if let Some(limit) = contact_translation_limit(model, state, o.contact_step_fraction) {
                s = s.min(translation_limited_step(&sys.rhs, &sys.prescribed, limit));
            }
            if increment_at_round_off(&sys.rhs, &sys.prescribed, model) {
                apply_increment(state, &sys.rhs, &sys.prescribed, s);
                converged = true;
                break;
            }
            // backtracking on the residual's norm: a full step that raises it (a contact
            // switching on or off between iterates) is halved until it does not
            self.increment.copy_from_slice(&sys.rhs);
            self.trial_x.copy_from_slice(&state.x);
            self.trial_q.copy_from_slice(&state.q);
            let mut tries = 0;
            loop {
                apply_increment(state, &self.increment, &self.system.prescribed, s);
                let trial = self.evaluate(model, state, history, h);
                if trial.2 < merit || tries >= MAX_BACKTRACKS {
                    (rf, rm, merit) = trial;
                    if tries > 0 {
                        report.shortened_steps += 1;
                    }
                    break;
                }
                tries += 1;
                s *= 0.5;
                state.x.copy_from_slice(&self.trial_x);
                state.q.copy_from_slice(&self.trial_q);
            }
        }
        if !converged {
            return Ok(false);
        }
        let sys = &mut self.system;
        // accept: store a_{n+1}, f_{n+1}; reactions on prescribed nodes m a − f
        for i in 0..n {
            let a_new = if sys.prescribed[i] {
                (state.v[i] - self.v0[i]) / h
            } else {
                c_acc * (state.x[i] - self.x0[i] - h * self.v0[i])
                    - (0.5 - beta) / beta * history.acc[i]
            };
            let alp_new = if sys.prescribed[i] {
                (state.w[i] - self.w0[i]) / h
            } else {
                let theta = log_map(state.q[i] * self.q0[i].conjugate());
                c_acc * (theta - h * self.w0[i]) - (0.5 - beta) / beta * history.ang_acc[i]
            };
            history.acc[i] = a_new;
            history.ang_acc[i] = alp_new;
            history.f_prev[i] = sys.force[i];
            history.m_prev[i] = sys.moment[i];
            state.force[i] = sys.force[i];
            state.moment[i] = sys.moment[i];
            state.contact_force[i] = sys.contact_force[i];
            state.held[i] = sys.prescribed[i];
            if sys.prescribed[i] {
                state.reaction_force[i] = model.mass[i] * a_new - sys.force[i];
                state.reaction_moment[i] = model.inertia[i] * alp_new - sys.moment[i];
            } else {
                state.reaction_force[i] = DVec3::ZERO;
                state.reaction_moment[i] = DVec3::ZERO;
            }
        }
        crate::loads::support_reactions(model, state, true);
        sys.commit_friction(state);
        sys.commit_inelastic(model, state);
        sync_bodies(model, state);
        state.time = t_next;
        Ok(true)
    }
}
