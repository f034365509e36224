//! Which solver advances a simulation (SPEC P4/P5), chosen per scene
//! (`[simulation] solver = …`) or per command (`--solver …`):
//!
//! * `explicit` — the dissertation's central differences (`crate::explicit`) at the
//!   model's stable step: dynamics with contact friction, the reference behaviour;
//! * `implicit` — HHT-α with Newton (`crate::newton::implicit`) at a step chosen for
//!   accuracy (default 10 ms), for stiff hoses and tubes;
//! * `static` — the equilibrium at each input (`crate::newton::statics`): one Newton
//!   solve per input step (default 10 ms of the timeline), the way slow manual assembly
//!   and industrial cable tools see it. Velocities are reported as the displacement over
//!   the input step (so rate-dependent laws — stub friction — still see the motion). An
//!   input step whose solve does not converge is retried in 2, 4, … 16 sub-steps
//!   (adaptive load stepping); if it still does not, the load path has passed a limit
//!   point and the snap to the next stable equilibrium is followed dynamically
//!   ([`snap`]). Every equilibrium is checked for stability ([`stability`]).

use crate::health::{check_for, Divergence};
pub mod advance;
pub mod component;
pub mod cut;
pub mod explicit;
pub mod fallback;
pub mod implicit;
pub mod snap;
pub mod split;
pub mod stability;
pub mod statics;

pub use implicit::{
    ImplicitError, ImplicitHistory, ImplicitOptions, ImplicitReport, ImplicitSolver,
};
pub use stability::StabilityEvent;
pub use statics::{StaticError, StaticOptions, StaticReport, StaticSolver};

use crate::newton::TopologyError;
pub use crate::settings::{SolverKind, SolverSettings};
use crate::{Model, State};
use glam::DVec3;
use serde::Serialize;

/// Largest out-of-balance force and moment on the free nodes as the Newton solvers
/// ([`ImplicitSolver`], [`StaticSolver`]) leave the state: their `force` includes the
/// parts' contact already. After explicit steps use [`crate::relax::residual`], which
/// adds it back.
pub fn free_node_residual(state: &State) -> (f64, f64) {
    let mut f: f64 = 0.0;
    let mut m: f64 = 0.0;
    for i in 0..state.x.len() {
        if !state.held[i] {
            f = f.max(state.force[i].length());
            m = m.max(state.moment[i].length());
        }
    }
    (f, m)
}

/// What went wrong in a step.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SolverError {
    #[error("{0}")]
    Diverged(#[from] Divergence),
    #[error("implicit solver at t = {time:.6} s: {error}")]
    Implicit { time: f64, error: ImplicitError },
    #[error("static solver at t = {time:.6} s: {error}")]
    Static { time: f64, error: StaticError },
}

impl SolverError {
    /// The failure as a typed divergence reason with its numbers.
    pub fn kind(&self) -> crate::health::DivergenceKind {
        use crate::health::{finite_or_none, DivergenceKind};
        match self {
            SolverError::Diverged(d) => d.kind.clone(),
            SolverError::Implicit { error, .. } => match error {
                ImplicitError::Singular(s) => DivergenceKind::Singular {
                    solver: "implicit",
                    node: s.0,
                },
                ImplicitError::NotConverged(halvings, residual) => DivergenceKind::NotConverged {
                    solver: "implicit",
                    halvings: *halvings,
                    residual_n: finite_or_none(*residual),
                },
            },
            SolverError::Static { error, .. } => match error {
                StaticError::Singular(s) => DivergenceKind::Singular {
                    solver: "static",
                    node: s.0,
                },
                StaticError::NonFinite(iteration) => DivergenceKind::NonFiniteIteration {
                    solver: "static",
                    iteration: *iteration,
                },
            },
        }
    }

    /// The failure as a [`Divergence`] report (what callers of any solver handle).
    pub fn into_divergence(self, model: &Model, state: &State) -> Divergence {
        match self {
            SolverError::Diverged(d) => d,
            other => Divergence {
                step: state.step,
                time: state.time,
                hose: model.hoses.first().map(|h| h.name.clone()).unwrap_or_default(),
                node: 0,
                kind: other.kind(),
                what: other.to_string(),
                cause: "the Newton iterations found no equilibrium (a load beyond what the hose can carry, or a step too large for the contact); try a smaller step or the explicit solver".into(),
            },
        }
    }
}

/// Newton statistics of the last step (zero for the explicit solver).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct StepStats {
    pub iterations: usize,
    pub residual_force: f64,
    pub residual_moment: f64,
    /// The residual limits of the convergence test \[N\], \[N·m\].
    pub force_limit: f64,
    pub moment_limit: f64,
    pub converged: bool,
    /// Static solver: the step ended on an equilibrium known to be unstable.
    pub unstable: bool,
    /// Static solver: sub-steps the input step took (1 unless it had to be split).
    pub substeps: usize,
    /// Implicit solver: the step did not converge even halved, and was taken instead in
    /// this many explicit steps (0: it converged) — [`Solver::step`].
    pub explicit_fallback: usize,
}

/// Most sub-steps one static input step may be split into.
pub const MAX_STATIC_SUBSTEPS: usize = 16;

/// Relaxations (each followed by a Newton solve) one snap may take ([`snap`]).
const SNAP_ROUNDS: usize = 4;

/// A solver of the chosen kind with its buffers (allocated once).
#[derive(Clone, Debug)]
pub struct Solver {
    settings: SolverSettings,
    built: Built,
    buffers: Buffers,
    pub last: StepStats,
}

/// The solver [`Solver`] was built for: the kind and the solver's own buffers in one, so
/// that the kind cannot change without them.
#[derive(Clone, Debug)]
enum Built {
    Explicit,
    Implicit(Box<ImplicitSolver>),
    Static(Box<StaticSolver>),
}

/// What every kind keeps between the parts of one step: the state at its start (to
/// restart from), the implicit fallback's targets, the static step's stability events
/// and the snap relaxation's anchor.
#[derive(Clone, Debug)]
struct Buffers {
    previous_x: Vec<DVec3>,
    previous_q: Vec<glam::DQuat>,
    previous_v: Vec<DVec3>,
    previous_w: Vec<DVec3>,
    fallback_targets: Vec<fallback::Target>,
    previous_friction: crate::contact::friction::FrictionMemory,
    /// Unstable equilibria the last step left (static solver).
    events: Vec<StabilityEvent>,
    /// Positions at the snap relaxation's last check ([`snap::relax`]).
    relax_anchor: Vec<DVec3>,
    /// Explicit steps of snap relaxation left for the run
    /// ([`SolverSettings::static_relaxation_budget`]).
    relaxation_left: u64,
}

impl Solver {
    pub fn new(model: &Model, settings: SolverSettings) -> Result<Self, TopologyError> {
        let built = match settings.kind {
            SolverKind::Explicit => Built::Explicit,
            SolverKind::Implicit => Built::Implicit(Box::new(ImplicitSolver::new(
                model,
                ImplicitOptions {
                    time_step: settings.implicit_time_step,
                    ..Default::default()
                },
            )?)),
            SolverKind::Static => {
                let mut solver = StaticSolver::new(model)?;
                solver.options.max_iterations = settings.static_max_iterations;
                Built::Static(Box::new(solver))
            }
        };
        let buffers = Buffers {
            previous_x: vec![DVec3::ZERO; model.node_count()],
            previous_q: vec![glam::DQuat::IDENTITY; model.node_count()],
            previous_v: vec![DVec3::ZERO; model.node_count()],
            previous_w: vec![DVec3::ZERO; model.node_count()],
            fallback_targets: Vec::new(),
            previous_friction: crate::contact::friction::FrictionMemory::new(&model.rest_x),
            events: Vec::new(),
            relax_anchor: Vec::with_capacity(model.node_count()),
            relaxation_left: settings.static_relaxation_budget,
        };
        Ok(Self {
            settings,
            built,
            buffers,
            last: StepStats::default(),
        })
    }

    /// The scene's choice ([`Model::solver`]).
    pub fn for_model(model: &Model) -> Result<Self, TopologyError> {
        Self::new(model, model.solver)
    }

    /// The settings it was built with.
    pub fn settings(&self) -> &SolverSettings {
        &self.settings
    }

    pub fn kind(&self) -> SolverKind {
        match self.built {
            Built::Explicit => SolverKind::Explicit,
            Built::Implicit(_) => SolverKind::Implicit,
            Built::Static(_) => SolverKind::Static,
        }
    }

    /// Simulated time one [`Self::step`] advances \[s\].
    pub fn time_step(&self, model: &Model) -> f64 {
        match self.built {
            Built::Explicit => model.time_step,
            Built::Implicit(_) => self.settings.implicit_time_step,
            Built::Static(_) => self.settings.static_input_step,
        }
    }

    /// Advances `state` by [`Self::time_step`] and checks its health.
    pub fn step(&mut self, model: &Model, state: &mut State) -> Result<StepStats, SolverError> {
        let time = state.time;
        let h = self.settings.static_input_step;
        self.last = match &mut self.built {
            Built::Explicit => {
                explicit::step(model, state);
                StepStats {
                    converged: true,
                    ..Default::default()
                }
            }
            Built::Implicit(solver) => self.buffers.implicit_step(solver, model, state, time)?,
            Built::Static(solver) => self.buffers.static_step(solver, model, state, time, h)?,
        };
        let kind = self.kind();
        if kind != SolverKind::Explicit {
            check_for(kind, model, state)?;
        }
        Ok(self.last)
    }

    /// The implicit solver's options (`None` for the other kinds), e.g. to tighten them.
    pub fn implicit_options_mut(&mut self) -> Option<&mut ImplicitOptions> {
        match &mut self.built {
            Built::Implicit(s) => Some(&mut s.options),
            _ => None,
        }
    }

    /// The unstable equilibria the last [`Self::step`] left (static solver; empty
    /// otherwise).
    pub fn stability_events(&self) -> &[StabilityEvent] {
        &self.buffers.events
    }

    /// Modified factorisations the static solver skipped because their matrix was the one
    /// factorised before ([`crate::newton::factor_reuse`]; 0 for the other kinds).
    pub fn factorizations_reused(&self) -> u64 {
        match &self.built {
            Built::Static(s) => s.system.reuse.reused,
            _ => 0,
        }
    }
}

impl Buffers {
    /// One implicit step. A step Newton cannot converge even halved (a contact's active
    /// set chattering, a grip pulled hard) is taken from its start by the explicit
    /// solver instead, in ⌈h / Δt_stable⌉ equal steps — a valid dynamic solution of the
    /// same equations, only with the explicit method's step limit — and the HHT history
    /// restarts from the state it reaches. A singular tangent (an iterate far off) and a
    /// converged step that fails the health check (a jump to a distant solution) fall
    /// back the same way; a state the explicit pieces cannot mend fails the health check.
    fn implicit_step(
        &mut self,
        solver: &mut ImplicitSolver,
        model: &Model,
        state: &mut State,
        time: f64,
    ) -> Result<StepStats, SolverError> {
        self.previous_x.copy_from_slice(&state.x);
        self.previous_q.copy_from_slice(&state.q);
        self.previous_v.copy_from_slice(&state.v);
        self.previous_w.copy_from_slice(&state.w);
        self.previous_friction.clone_from(&state.friction);
        let (step, h) = (state.step, solver.options.time_step);
        let outcome = solver.step(model, state);
        match outcome {
            // a converged step that moves a node faster than the hose's wave speed has
            // jumped to a far-off solution of its equations (a step too large for what
            // the hands did): taken explicitly as well
            Ok(r) if crate::health::check(model, state).is_ok() => Ok(StepStats {
                iterations: r.iterations,
                residual_force: r.residual_force,
                residual_moment: r.residual_moment,
                converged: r.converged,
                substeps: r.substeps,
                ..Default::default()
            }),
            failed => {
                let residual = match failed {
                    Err(ImplicitError::NotConverged(_, r)) => r,
                    _ => 0.0,
                };
                state.x.copy_from_slice(&self.previous_x);
                state.q.copy_from_slice(&self.previous_q);
                state.v.copy_from_slice(&self.previous_v);
                state.w.copy_from_slice(&self.previous_w);
                state.friction.clone_from(&self.previous_friction);
                state.time = time;
                let pieces = fallback::explicit_pieces(model, state, h, &mut self.fallback_targets);
                state.time = time + h; // the implicit grid, free of the pieces' rounding
                state.step = step + 1;
                state.implicit.restart();
                Ok(StepStats {
                    residual_force: residual,
                    converged: true,
                    substeps: pieces,
                    explicit_fallback: pieces,
                    ..Default::default()
                })
            }
        }
    }

    /// One static input step: the equilibrium at t + h, solved in 1, 2, 4, …
    /// [`MAX_STATIC_SUBSTEPS`] load steps until the solves converge, and past a limit
    /// point by following the snap ([`snap`]).
    fn static_step(
        &mut self,
        solver: &mut StaticSolver,
        model: &Model,
        state: &mut State,
        time: f64,
        h: f64,
    ) -> Result<StepStats, SolverError> {
        self.previous_x.copy_from_slice(&state.x);
        self.previous_q.copy_from_slice(&state.q);
        self.previous_friction.clone_from(&state.friction);
        self.events.clear();
        let mut pieces = 1;
        // the linearised response of the pieces summed: the path-following predictor
        let mut predicted;
        let mut indefinite;
        let (mut report, mut iterations) = loop {
            let mut iterations = 0;
            let mut last = None;
            predicted = 0.0;
            indefinite = 0;
            for j in 1..=pieces {
                state.time = if j == pieces {
                    time + h
                } else {
                    time + h * j as f64 / pieces as f64
                };
                let r = solver
                    .solve(model, state)
                    .map_err(|error| SolverError::Static { time, error })?;
                iterations += r.iterations;
                predicted += r.first_increment;
                indefinite += r.indefinite_iterations;
                self.events.extend(solver.events.iter().cloned());
                last = Some(r);
                if !r.converged {
                    break;
                }
            }
            let r = last.expect("at least one piece");
            if r.converged || pieces >= MAX_STATIC_SUBSTEPS {
                break (r, iterations);
            }
            // retry from the start of the step in smaller load steps
            pieces *= 2;
            state.x.copy_from_slice(&self.previous_x);
            state.q.copy_from_slice(&self.previous_q);
            state.friction.clone_from(&self.previous_friction);
            self.events.clear();
        };
        if !report.converged {
            state.x.copy_from_slice(&self.previous_x);
            state.q.copy_from_slice(&self.previous_q);
            state.friction.clone_from(&self.previous_friction);
            state.time = time + h;
            let before = solver.system.potential_energy(model, state);
            // the failed solve may have stood on an unstable equilibrium and stepped off
            // it: the snap starts that way (from rest on the unstable state it would not)
            if let Some(e) = self.events.last() {
                for (x, m) in state.x.iter_mut().zip(&e.mode) {
                    *x += *m * e.amplitude;
                }
            }
            self.events.clear();
            // the relaxation hands over where the residual is small — near the snap's
            // saddle too, from where Newton may not converge: relax on from where it left
            // (within the run's budget: once spent, the step stays unconverged)
            for _ in 0..SNAP_ROUNDS {
                if self.relaxation_left == 0 {
                    break;
                }
                let relaxation = snap::relax(
                    model,
                    state,
                    time + h,
                    (report.force_limit, report.moment_limit),
                    self.relaxation_left,
                    &mut self.relax_anchor,
                );
                self.relaxation_left = self.relaxation_left.saturating_sub(relaxation.steps);
                if !relaxation.reached {
                    break;
                }
                state.time = time + h;
                let r = solver
                    .solve(model, state)
                    .map_err(|error| SolverError::Static { time, error })?;
                iterations += r.iterations;
                report = r;
                if r.converged {
                    let after = solver.system.potential_energy(model, state);
                    self.events.push(snap_event(
                        time + h,
                        &self.previous_x,
                        &state.x,
                        before - after,
                    ));
                    self.events.extend(solver.events.iter().cloned());
                    break;
                }
            }
        }
        state.time = time + h;
        if report.converged && self.events.is_empty() {
            self.report_jump(solver, model, state, predicted, indefinite);
        }
        for i in 0..state.x.len() {
            state.v[i] = (state.x[i] - self.previous_x[i]) / h;
        }
        state.step += 1;
        Ok(StepStats {
            iterations,
            residual_force: report.residual_force,
            residual_moment: report.residual_moment,
            force_limit: report.force_limit,
            moment_limit: report.moment_limit,
            converged: report.converged,
            unstable: report.unstable,
            substeps: pieces,
            explicit_fallback: 0,
        })
    }
}

impl Buffers {
    /// A converged static input step that landed on a distant branch: a limit point
    /// passed within the step (by Newton from the start, or by the adaptive load steps),
    /// the hose jumping to a stable equilibrium that does not continue the one it stood
    /// on. Two signs together mark it:
    ///
    /// * the step moved a free node more than [`JUMP_RATIO`] × the linearised response
    ///   K⁻¹ Δf of its load steps (the path-following predictor, summed over the pieces:
    ///   `predicted`, [`statics::StaticReport::first_increment`]) and farther than a mean
    ///   element length. On a branch the equilibrium moves by about the predictor — more
    ///   where the branch softens, by a bounded factor (twice for a step that reaches a
    ///   square-root fold);
    /// * Newton met a tangent that was not positive definite on the way (`indefinite`
    ///   iterations, [`statics::StaticReport::indefinite_iterations`]): its iterates
    ///   crossed a region where the potential is not convex — between two basins. A
    ///   small load step on a stable branch starts inside the basin of the minimum it
    ///   follows and stays there. (The first sign alone also fires where contact makes
    ///   the first increment a poor predictor: a hose dragged steadily along a part
    ///   moves 5 cm a step against a predicted 1 cm in the engine bay example.)
    ///
    /// The jump is reported as the snap it is ([`snap_event`]: limit point, the step's
    /// displacement as the mode, the potential energy released at the step's loads).
    /// With dead moments Newton runs on the unmodified tangent and reads no inertia (as
    /// the stability check does not): no jump is reported then.
    fn report_jump(
        &mut self,
        solver: &mut StaticSolver,
        model: &Model,
        state: &mut State,
        predicted: f64,
        indefinite: usize,
    ) {
        let moved = state
            .x
            .iter()
            .zip(&self.previous_x)
            .zip(&state.held)
            .filter(|(_, held)| !**held)
            .map(|((a, b), _)| (*a - *b).length())
            .fold(0.0, f64::max);
        let far = moved > JUMP_RATIO * predicted && moved > solver.system.mean_length;
        if !(far && indefinite > 0) {
            return;
        }
        let after = solver.system.potential_energy(model, state);
        std::mem::swap(&mut state.x, &mut self.previous_x);
        std::mem::swap(&mut state.q, &mut self.previous_q);
        let before = solver.system.potential_energy(model, state);
        std::mem::swap(&mut state.x, &mut self.previous_x);
        std::mem::swap(&mut state.q, &mut self.previous_q);
        self.events.push(snap_event(
            state.time,
            &self.previous_x,
            &state.x,
            before - after,
        ));
    }
}

/// A converged static step whose largest free-node motion exceeds this multiple of the
/// linearised prediction, through a region where the potential is not convex, has jumped
/// to a distant branch (`Buffers::report_jump`).
pub const JUMP_RATIO: f64 = 5.0;

/// The event of a snap from `before` to `after` (limit point passed at `time`).
fn snap_event(time: f64, before: &[DVec3], after: &[DVec3], energy_drop: f64) -> StabilityEvent {
    let mode: Vec<DVec3> = after.iter().zip(before).map(|(a, b)| *a - *b).collect();
    let (node, amplitude) = mode.iter().enumerate().fold((0, 0.0), |(n, m), (i, d)| {
        if d.length() > m {
            (i, d.length())
        } else {
            (n, m)
        }
    });
    let scale = if amplitude > 0.0 {
        1.0 / amplitude
    } else {
        0.0
    };
    StabilityEvent {
        time,
        limit_point: true,
        negative_eigenvalues: 0,
        node,
        energy_drop,
        amplitude,
        mode: mode.into_iter().map(|d| d * scale).collect(),
    }
}
