//! Quasi-static solution (SPEC P5): the equilibrium under the current boundary
//! conditions — prescribed nodes where their load cases put them now, gravity, dead loads,
//! contact — found by Newton's method on the consistent tangent with a backtracking line
//! search (Nocedal & Wright, "Numerical Optimization", 2006, alg. 3.1): a step is
//! accepted when the potential energy decreases enough (Armijo, c₁ = 1e-4; dead moments
//! enter with their work along the search line), or — where the energy does not decide
//! (round-off near convergence) — when the residual decreases. Newton runs on a
//! positive-definite modification of the tangent, so every step descends; balance is
//! judged against the problem's load scale ([`Tolerance`]); every equilibrium found is
//! checked for stability and an unstable one is left for the stable branch nearby
//! ([`super::stability`]). Velocities are zero: what manual assembly at walking pace
//! needs, one solve per input. Only the components of the network out of balance are
//! solved — a hand's move solves the stretch between the held nodes around it — and the
//! result is checked on the whole model ([`super::split`]).

use super::component::ComponentSearch;
use super::split::{solve_out_of_balance, Outcome, Split};
use super::stability::{dead_moment_work, Escape, StabilityEvent};
use crate::newton::convergence::Tolerance;
use crate::newton::system::{
    apply_increment, contact_translation_limit, first_touch_step, largest_free, residual_norms,
    rotation_limited_step, sync_bodies, translation_limited_step, NewtonSystem,
};
use crate::{Model, State};
use glam::DVec3;

/// When to stop iterating.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticOptions {
    /// How close to balance the free nodes must come ([`Tolerance`]: relative to the
    /// problem's loads by default).
    pub tolerance: Tolerance,
    /// Newton iterations allowed per equilibrium sought (again after each step off an
    /// unstable one).
    pub max_iterations: usize,
    /// Largest translation of any node in one iteration \[m\], as a fraction of the
    /// smallest hose radius when contact — rigid parts or hose–hose — is on (keeps
    /// contact from being jumped through; [`contact_translation_limit`]).
    pub contact_step_fraction: f64,
    /// Check each equilibrium's stability and leave unstable ones ([`super::stability`]).
    pub stability: bool,
    /// Unstable equilibria one solve may step off before it reports the last one as
    /// unstable.
    pub max_escapes: usize,
    /// Solve only the components out of balance, then check the whole model
    /// ([`super::split`]); off: every solve assembles and factorises the whole model.
    pub split: bool,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            tolerance: Tolerance::default(),
            max_iterations: crate::settings::DEFAULT_STATIC_MAX_ITERATIONS,
            contact_step_fraction: 0.5,
            stability: true,
            max_escapes: 8,
            split: true,
        }
    }
}

/// How a static solve ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticReport {
    pub iterations: usize,
    pub residual_force: f64,
    pub residual_moment: f64,
    /// The residual limits the solve had to meet (from the load scale) \[N\], \[N·m\].
    pub force_limit: f64,
    pub moment_limit: f64,
    /// The free nodes are in balance.
    pub converged: bool,
    /// Line-search steps shorter than the full Newton step.
    pub shortened_steps: usize,
    /// Unstable equilibria stepped off ([`StaticSolver::events`]).
    pub escapes: usize,
    /// The equilibrium found is unstable and could not be left (`max_escapes` reached,
    /// or no step lowered the energy); only with `stability` on.
    pub unstable: bool,
    /// Largest translation of a free node in the first Newton increment δu₁ = K(u₀)⁻¹ r₀
    /// \[m\]: the linearised response to the change of loads and prescribed motions since
    /// the state the solve started from — the predictor of a path-following step, against
    /// which the solver judges whether the equilibrium it found continues the branch it
    /// started on ([`crate::integrators::Solver`], a jump to a distant branch).
    pub first_increment: f64,
    /// Newton iterations whose tangent was not positive definite (factorised with the
    /// modification): the iterates crossed a region where the potential is not convex.
    pub indefinite_iterations: usize,
    /// Nodes the Newton iterations solved: those of the components out of balance
    /// ([`super::split`]), or the whole model's.
    pub solved_nodes: usize,
}

/// Why the solve failed outright (not just "not converged").
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StaticError {
    #[error("{0}")]
    Singular(#[from] crate::newton::block_tree::SingularBlock),
    #[error("the static solve produced non-finite values at iteration {0}")]
    NonFinite(usize),
}

/// The quasi-static solver: its Newton buffers and options.
#[derive(Clone, Debug)]
pub struct StaticSolver {
    pub system: NewtonSystem,
    pub options: StaticOptions,
    /// Unstable equilibria left by the last solve.
    pub events: Vec<StabilityEvent>,
    escape: Escape,
    /// Configuration before a trial step (line search).
    saved_x: Vec<DVec3>,
    saved_q: Vec<glam::DQuat>,
    /// The component solved last on its own ([`super::split`]).
    pub(super) split: Option<Box<Split>>,
    /// Scratch of the split: the nodes out of balance, the component search.
    seeds: Vec<usize>,
    search: ComponentSearch,
}

impl StaticSolver {
    pub fn new(model: &Model) -> Result<Self, crate::newton::TopologyError> {
        let n = model.node_count();
        let mut system = NewtonSystem::new(model)?;
        // without inertia, a hose slipping at every node has no stiffness along the slip
        system.regularise_slip = true;
        Ok(Self {
            system,
            options: StaticOptions::default(),
            events: Vec::new(),
            escape: Escape::new(n),
            saved_x: vec![DVec3::ZERO; n],
            saved_q: vec![glam::DQuat::IDENTITY; n],
            split: None,
            seeds: Vec::with_capacity(n),
            search: ComponentSearch::default(),
        })
    }

    /// Moves `state` to a stable equilibrium under its load cases at `state.time`.
    /// Writes forces, reactions (support loads on prescribed nodes), contact forces and
    /// `held` as the explicit step does; velocities are zero. Newton runs on a
    /// positive-definite modification of the tangent (so every step descends in energy);
    /// at balance the tangent's inertia is checked and an unstable equilibrium is left
    /// along its unstable mode ([`super::stability`]), each time recorded in
    /// [`Self::events`].
    pub fn solve(&mut self, model: &Model, state: &mut State) -> Result<StaticReport, StaticError> {
        self.events.clear();
        self.system.set_prescribed(model, state, state.time);
        state.v.fill(DVec3::ZERO);
        state.w.fill(DVec3::ZERO);
        let mut report = StaticReport {
            iterations: 0,
            residual_force: f64::INFINITY,
            residual_moment: f64::INFINITY,
            force_limit: 0.0,
            moment_limit: 0.0,
            converged: false,
            shortened_steps: 0,
            escapes: 0,
            unstable: false,
            first_increment: 0.0,
            indefinite_iterations: 0,
            solved_nodes: model.node_count(),
        };
        if self.options.split {
            let mut seeds = std::mem::take(&mut self.seeds);
            let mut search = std::mem::take(&mut self.search);
            let outcome = solve_out_of_balance(self, model, state, (&mut seeds, &mut search));
            self.seeds = seeds;
            self.search = search;
            match outcome? {
                Outcome::Solved(r) => return Ok(r),
                Outcome::Whole(None) => {}
                Outcome::Whole(Some(part)) => {
                    // the component's solve is the start of this one
                    report.iterations = part.iterations;
                    report.shortened_steps = part.shortened_steps;
                    report.first_increment = part.first_increment;
                    report.indefinite_iterations = part.indefinite_iterations;
                }
            }
        }
        let mut budget = report.iterations + self.options.max_iterations;
        // Dead moments have no potential (their load stiffness is not symmetric): the
        // symmetric part of the tangent then says nothing sure about stability, and Newton
        // runs on the tangent as it is.
        let conservative = !has_dead_moments(state);
        let check_stability = self.options.stability && conservative;
        loop {
            let sys = &mut self.system;
            sys.assemble(model, state, 0.0);
            let (rf, rm) = residual_norms(&sys.force, &sys.moment, &sys.prescribed);
            report.residual_force = rf;
            report.residual_moment = rm;
            (report.force_limit, report.moment_limit) = self.options.tolerance.limits(sys.scale);
            if !(rf.is_finite() && rm.is_finite()) {
                return Err(StaticError::NonFinite(report.iterations));
            }
            let pending = sys.pending();
            // a node within its round-off floor is as balanced as it can be
            let (above_f, above_m) = sys.residuals_above_noise(state);
            let mut balanced = !pending && self.options.tolerance.met(sys.scale, above_f, above_m);
            let mut inertia = None;
            if !balanced && report.iterations < budget {
                report.iterations += 1;
                for i in 0..sys.rhs.len() {
                    let (f, m) = (sys.force[i], sys.moment[i]);
                    sys.rhs[i] = nalgebra::Vector6::new(f.x, f.y, f.z, m.x, m.y, m.z);
                }
                if pending {
                    sys.add_prescribed_coupling(state);
                }
                sys.eliminate_prescribed();
                let inertia_here = sys.solve_linear(conservative)?;
                if report.iterations == 1 {
                    report.first_increment = largest_free(&sys.rhs, &sys.prescribed, 0);
                }
                if !inertia_here.positive_definite() {
                    report.indefinite_iterations += 1;
                }
                if pending {
                    // the prescribed motion and the free nodes' linear response to it,
                    // taken whole (the energy before and after the supports moved is not
                    // comparable)
                    let s = rotation_limited_step(&sys.rhs, &sys.prescribed);
                    // (rigid parts only: with hose–hose contact alone, the tip of a line
                    // bent into a curl was sent off its path)
                    let parts = !model.environment.is_empty();
                    let near_contact =
                        contact_translation_limit(model, state, self.options.contact_step_fraction)
                            .filter(|_| parts)
                            .map_or(1.0, |limit| {
                                translation_limited_step(&sys.rhs, &sys.prescribed, limit)
                            });
                    if near_contact < 1.0 {
                        // the whole response would carry free nodes farther than contact
                        // allows in one iteration — through a part's surface, balanced
                        // then on its far side: the supports and the free nodes go that
                        // part of the way, and the next iteration continues from there
                        let s = s.min(near_contact);
                        apply_increment(state, &sys.rhs, &sys.prescribed, s);
                        sys.move_prescribed_part(state, s);
                        continue;
                    }
                    apply_increment(state, &sys.rhs, &sys.prescribed, s);
                    sys.move_prescribed(state);
                    continue;
                }
                if increment_at_round_off(&sys.rhs, &sys.prescribed, model) {
                    // the residual left is round-off of the stiff (rigid-factor) elements
                    balanced = true;
                    inertia = Some(inertia_here);
                } else {
                    let s = self.line_search(model, state, rf.max(rm));
                    if s < 1.0 {
                        report.shortened_steps += 1;
                    }
                    continue;
                }
            }
            if !balanced {
                break; // out of iterations
            }
            report.converged = true;
            if !check_stability {
                break;
            }
            let sys = &mut self.system;
            let inertia = match inertia {
                Some(i) => i,
                None => {
                    // the tangent at this very state (the last one factorised was the
                    // previous iterate's)
                    sys.eliminate_prescribed();
                    sys.factor_modified()?
                }
            };
            if inertia.positive_definite() {
                break;
            }
            if report.escapes >= self.options.max_escapes {
                report.unstable = true;
                break;
            }
            match self.escape.step_off(model, state, sys, &inertia) {
                Some(event) => {
                    self.events.push(event);
                    report.escapes += 1;
                    report.converged = false;
                    budget = report.iterations + self.options.max_iterations;
                }
                None => break, // no direction lowers the energy: round-off, not a mode
            }
        }
        finish(model, state, &self.system, report.converged);
        Ok(report)
    }

    /// Backtracking along the Newton increment in `system.rhs` (Armijo on the potential
    /// energy, the residual where the energy does not decide); returns the step taken.
    /// While a node slips, the friction potential is taken at the normal forces of the
    /// step's start ([`NewtonSystem::lag_friction_normal`]), and a full step along which
    /// the energy still falls at its initial rate is extended to the kink ahead
    /// ([`Self::extend_to_kink`]).
    fn line_search(&mut self, model: &Model, state: &mut State, residual0: f64) -> f64 {
        self.system.lag_friction_normal(true);
        let s = self.backtrack(model, state, residual0);
        self.system.lag_friction_normal(false);
        s
    }

    fn backtrack(&mut self, model: &Model, state: &mut State, residual0: f64) -> f64 {
        let sys = &mut self.system;
        let slipping = sys.friction.iter().flatten().any(|r| r.slipping);
        // −dΠ/ds along the step = (f, m)·δu (the loads are −∇Π)
        let directional = -slope_along(sys);
        let mut s: f64 = rotation_limited_step(&sys.rhs, &sys.prescribed);
        // the longest step contact allows (beyond the full Newton step too)
        let mut longest = f64::INFINITY;
        if let Some(limit) =
            contact_translation_limit(model, state, self.options.contact_step_fraction)
        {
            let largest = largest_free(&sys.rhs, &sys.prescribed, 0);
            if largest > 0.0 {
                longest = limit / largest;
            }
            s = s.min(translation_limited_step(&sys.rhs, &sys.prescribed, limit));
        }
        let full = s == 1.0;
        // a trial past twice the step at which two hoses apart now touch would land them
        // in or through each other: halved before it is tried (such trials were most of
        // the halvings of a hand's move on a harness)
        let touch = first_touch_step(model, state, &sys.rhs, &sys.prescribed);
        let mut tries = 0;
        while s > 2.0 * touch && tries < MAX_BACKTRACKS {
            s *= 0.5;
            tries += 1;
        }
        // dead moments have no global potential; along this search line their work is
        // s Σ M·δθ (exact for a fixed axis, first order otherwise)
        let moment_work = dead_moment_work(state, &sys.rhs);
        let energy0 = sys.potential_energy(model, state);
        self.saved_x.copy_from_slice(&state.x);
        self.saved_q.copy_from_slice(&state.q);
        loop {
            apply_increment(state, &sys.rhs, &sys.prescribed, s);
            let energy = sys.potential_energy(model, state) - s * moment_work;
            let descent = directional > 0.0;
            let enough = energy <= energy0 - 1e-4 * s * directional;
            let accept = if descent && enough {
                true
            } else {
                // the energy does not decide: compare residuals (no tangent needed)
                sys.assemble_loads(model, state, 0.0);
                let (f, m) = residual_norms(&sys.force, &sys.moment, &sys.prescribed);
                f.max(m) < residual0
            };
            if accept {
                if slipping && full && tries == 0 && descent && enough && moment_work == 0.0 {
                    let line = Line {
                        directional,
                        energy0,
                        longest,
                    };
                    return self.extend_to_kink(model, state, line);
                }
                return s;
            }
            if tries >= MAX_BACKTRACKS {
                // the shortest trial is past the minimum along the line (the energy rises
                // there): a kink closer than the halvings reach — a slipping node passing
                // its friction anchor, where the energy bends by 2 μ f_n over the width of
                // its stick ball. Find the minimum inside the bracket.
                if descent && slope_along(sys) > 0.0 {
                    let high = (s, slope_along(sys));
                    return self.bracketed_minimum(
                        model,
                        state,
                        (0.0, -directional),
                        high,
                        directional,
                    );
                }
                return s;
            }
            tries += 1;
            s *= 0.5;
            state.x.copy_from_slice(&self.saved_x);
            state.q.copy_from_slice(&self.saved_q);
        }
    }

    /// After a full Newton step was accepted while nodes slip: where the energy still
    /// falls at more than half its initial rate at the step's end, the step met no
    /// curvature — the slip's friction is constant along it — and the minimum along the
    /// line lies beyond, where a slipping node reaches the stick ball of its anchor (the
    /// energy's kink). The step is doubled while the energy keeps falling that fast
    /// (within the contact step limit) and the minimum found in the bracket
    /// ([`Self::bracketed_minimum`]). Returns the step taken, the state moved there.
    ///
    /// The extension is kept only where it leaves the free nodes farther from balance
    /// than the full step did (residuals relative to their limits, [`Self::imbalance`]):
    /// where the increment also moves nodes that do not slip — a stiff structure the full
    /// Newton step brought to balance along with a slipping node — every step beyond 1
    /// takes that part past its minimum again (at s = 2 it is reflected: as far out of
    /// balance as before the step), while the slip's constant friction still lets the
    /// energy fall along the line. Taking such steps, Newton alternates between two
    /// states and never converges; the full step is taken instead.
    fn extend_to_kink(&mut self, model: &Model, state: &mut State, line: Line) -> f64 {
        self.system.assemble(model, state, 0.0);
        let at_full_step = self.imbalance(state);
        let s = self.extend_along_slip(model, state, line);
        if s == 1.0 {
            return s;
        }
        self.system.assemble(model, state, 0.0);
        if self.imbalance(state) <= at_full_step {
            return s;
        }
        state.x.copy_from_slice(&self.saved_x);
        state.q.copy_from_slice(&self.saved_q);
        apply_increment(state, &self.system.rhs, &self.system.prescribed, 1.0);
        1.0
    }

    /// How far the last assembly is from balance: the larger of the force and moment
    /// residuals over the free nodes, each relative to its limit ([`Tolerance`]; a node
    /// within its round-off floor counting as balanced), so that 1 is the convergence
    /// limit.
    fn imbalance(&self, state: &State) -> f64 {
        let sys = &self.system;
        let (f, m) = sys.residuals_above_noise(state);
        let (f_limit, m_limit) = self.options.tolerance.limits(sys.scale);
        let relative = |r: f64, limit: f64| if r > 0.0 { r / limit } else { 0.0 };
        relative(f, f_limit).max(relative(m, m_limit))
    }

    /// The doubling and bracketing of [`Self::extend_to_kink`], from the full step with
    /// the system assembled there.
    fn extend_along_slip(&mut self, model: &Model, state: &mut State, line: Line) -> f64 {
        let sys = &mut self.system;
        let mut s = 1.0;
        let mut slope = slope_along(sys);
        while slope < -0.5 * line.directional && 2.0 * s <= line.longest {
            let before = (s, slope);
            s *= 2.0;
            state.x.copy_from_slice(&self.saved_x);
            state.q.copy_from_slice(&self.saved_q);
            apply_increment(state, &sys.rhs, &sys.prescribed, s);
            let energy = sys.potential_energy(model, state);
            if energy > line.energy0 - 1e-4 * s * line.directional {
                // the energy rose again within the doubling: the minimum is inside
                sys.assemble(model, state, 0.0);
                let after = (s, slope_along(sys));
                if after.1 > 0.0 {
                    return self.bracketed_minimum(model, state, before, after, line.directional);
                }
                s = before.0;
                state.x.copy_from_slice(&self.saved_x);
                state.q.copy_from_slice(&self.saved_q);
                apply_increment(state, &sys.rhs, &sys.prescribed, s);
                return s;
            }
            sys.assemble(model, state, 0.0);
            slope = slope_along(sys);
            if slope > 0.0 {
                return self.bracketed_minimum(model, state, before, (s, slope), line.directional);
            }
        }
        s
    }

    /// The minimum of the energy along the Newton increment in `system.rhs` between the
    /// steps `low` and `high` (each with the energy's slope φ'(s) = −(f, m)·δu there),
    /// where the slope changes sign: φ'(low) < 0 < φ'(high). Regula falsi with the
    /// Illinois modification (Dowell & Jarratt, BIT 11, 1971) on φ', which is continuous
    /// where the energy is smooth and jumps (upwards: φ' increasing) where a node's
    /// friction turns — the bracket then closes on the jump. Stops at the strong Wolfe
    /// curvature condition |φ'(s)| ≤ 0.1 φ'(0)| (`directional` = −φ'(0); Nocedal &
    /// Wright, 2006, eq. 3.7b); returns the step taken, the state moved there (the
    /// bracket's descending end if the budget runs out).
    fn bracketed_minimum(
        &mut self,
        model: &Model,
        state: &mut State,
        low: (f64, f64),
        high: (f64, f64),
        directional: f64,
    ) -> f64 {
        let sys = &mut self.system;
        let ((mut lo, mut slope_lo), (mut hi, mut slope_hi)) = (low, high);
        let mut side = 0i8;
        for _ in 0..MAX_BRACKET_EVALUATIONS {
            let s = (lo * slope_hi - hi * slope_lo) / (slope_hi - slope_lo);
            // a secant point on an end (round-off): halve instead
            let s = if s > lo && s < hi { s } else { 0.5 * (lo + hi) };
            state.x.copy_from_slice(&self.saved_x);
            state.q.copy_from_slice(&self.saved_q);
            apply_increment(state, &sys.rhs, &sys.prescribed, s);
            sys.assemble_loads(model, state, 0.0);
            let slope = slope_along(sys);
            if slope.abs() <= 0.1 * directional {
                return s;
            }
            if slope < 0.0 {
                (lo, slope_lo) = (s, slope);
                if side < 0 {
                    slope_hi *= 0.5;
                }
                side = -1;
            } else {
                (hi, slope_hi) = (s, slope);
                if side > 0 {
                    slope_lo *= 0.5;
                }
                side = 1;
            }
            if hi - lo <= f64::EPSILON * hi {
                break;
            }
        }
        state.x.copy_from_slice(&self.saved_x);
        state.q.copy_from_slice(&self.saved_q);
        apply_increment(state, &sys.rhs, &sys.prescribed, lo);
        lo
    }
}

/// A line search's start: −φ'(0), the energy there, and the longest step contact allows.
#[derive(Clone, Copy, Debug)]
struct Line {
    directional: f64,
    energy0: f64,
    longest: f64,
}

/// Halvings of a static Newton step before the line search gives up shortening it.
const MAX_BACKTRACKS: usize = 12;
/// Energy slopes evaluated to find the minimum in a bracket along a Newton step
/// ([`StaticSolver::bracketed_minimum`]).
const MAX_BRACKET_EVALUATIONS: usize = 60;

/// The energy's slope along the Newton increment in `system.rhs` at the last assembly:
/// dΠ/ds = −Σ (f, m)·δu over the free nodes (the loads are −∇Π).
fn slope_along(sys: &NewtonSystem) -> f64 {
    let mut slope = 0.0;
    for i in 0..sys.rhs.len() {
        if !sys.prescribed[i] {
            let d = sys.rhs[i];
            slope -= sys.force[i].dot(DVec3::new(d[0], d[1], d[2]))
                + sys.moment[i].dot(DVec3::new(d[3], d[4], d[5]));
        }
    }
    slope
}

/// Whether any dead load carries a moment (a load without a potential).
fn has_dead_moments(state: &State) -> bool {
    state.loads.iter().any(
        |(_, case)| matches!(case, crate::loads::LoadCase::DeadLoad(d) if d.moment != DVec3::ZERO),
    )
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
/// Friction anchors move with the accepted configuration; plastic strains with a
/// converged one.
pub(super) fn finish(model: &Model, state: &mut State, sys: &NewtonSystem, converged: bool) {
    sys.commit_friction(state);
    if converged {
        // an equilibrium: yielding elements keep their plastic strains
        sys.commit_inelastic(model, state);
    }
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
    crate::loads::support_reactions(model, state, true);
    sync_bodies(model, state);
}
