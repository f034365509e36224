//! Which solver advances a simulation (issue 5, SPEC P4/P5), chosen per scene
//! (`[simulation] solver = …`) or per command (`--solver …`):
//!
//! * `explicit` — the dissertation's central differences ([`crate::explicit`]) at the
//!   model's stable step: dynamics with contact friction, the reference behaviour;
//! * `implicit` — HHT-α with Newton ([`crate::newton::implicit`]) at a step chosen for
//!   accuracy (default 10 ms), for stiff hoses and tubes;
//! * `static` — the equilibrium at each input ([`crate::newton::statics`]): one Newton
//!   solve per input step (default 10 ms of the timeline), the way slow manual assembly
//!   and industrial cable tools see it. Velocities are reported as the displacement over
//!   the input step (so rate-dependent laws — stub friction — still see the motion).

use crate::health::{check, Divergence};
pub mod explicit;
pub mod implicit;
pub mod statics;

pub use implicit::{
    ImplicitError, ImplicitHistory, ImplicitOptions, ImplicitReport, ImplicitSolver,
};
pub use statics::{StaticError, StaticOptions, StaticReport, StaticSolver};

use crate::newton::NotAChain;
use crate::{Model, State};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The solver kinds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SolverKind {
    #[default]
    Explicit,
    Implicit,
    Static,
}

impl SolverKind {
    pub const ALL: [SolverKind; 3] = [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ];

    pub fn name(self) -> &'static str {
        match self {
            SolverKind::Explicit => "explicit",
            SolverKind::Implicit => "implicit",
            SolverKind::Static => "static",
        }
    }
}

impl std::str::FromStr for SolverKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "explicit" => Ok(SolverKind::Explicit),
            "implicit" | "hht" => Ok(SolverKind::Implicit),
            "static" | "quasi-static" | "quasistatic" => Ok(SolverKind::Static),
            other => Err(format!(
                "unknown solver '{other}' (choose explicit, implicit or static)"
            )),
        }
    }
}

impl std::fmt::Display for SolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Solver choice and its step sizes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolverSettings {
    pub kind: SolverKind,
    /// Implicit time step [s] (default 10 ms).
    pub implicit_time_step: f64,
    /// Static solver: simulated time between two equilibrium solves [s] (default 10 ms).
    pub static_input_step: f64,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            kind: SolverKind::Explicit,
            implicit_time_step: 0.01,
            static_input_step: 0.01,
        }
    }
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
    /// The failure as a [`Divergence`] report (what callers of any solver handle).
    pub fn into_divergence(self, model: &Model, state: &State) -> Divergence {
        match self {
            SolverError::Diverged(d) => d,
            other => Divergence {
                step: state.step,
                time: state.time,
                hose: model.hoses.first().map(|h| h.name.clone()).unwrap_or_default(),
                node: 0,
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
    pub converged: bool,
}

/// A solver of the chosen kind with its buffers (allocated once).
#[derive(Clone, Debug)]
pub struct Solver {
    pub settings: SolverSettings,
    implicit: Option<Box<ImplicitSolver>>,
    statics: Option<Box<StaticSolver>>,
    previous_x: Vec<DVec3>,
    pub last: StepStats,
}

impl Solver {
    pub fn new(model: &Model, settings: SolverSettings) -> Result<Self, NotAChain> {
        let implicit = match settings.kind {
            SolverKind::Implicit => Some(Box::new(ImplicitSolver::new(
                model,
                ImplicitOptions {
                    time_step: settings.implicit_time_step,
                    ..Default::default()
                },
            )?)),
            _ => None,
        };
        let statics = match settings.kind {
            SolverKind::Static => Some(Box::new(StaticSolver::new(model)?)),
            _ => None,
        };
        Ok(Self {
            settings,
            implicit,
            statics,
            previous_x: vec![DVec3::ZERO; model.node_count()],
            last: StepStats::default(),
        })
    }

    /// The scene's choice ([`Model::solver`]).
    pub fn for_model(model: &Model) -> Result<Self, NotAChain> {
        Self::new(model, model.solver)
    }

    pub fn kind(&self) -> SolverKind {
        self.settings.kind
    }

    /// Simulated time one [`Self::step`] advances [s].
    pub fn time_step(&self, model: &Model) -> f64 {
        match self.settings.kind {
            SolverKind::Explicit => model.time_step,
            SolverKind::Implicit => self.settings.implicit_time_step,
            SolverKind::Static => self.settings.static_input_step,
        }
    }

    /// Advances `state` by [`Self::time_step`] and checks its health.
    pub fn step(&mut self, model: &Model, state: &mut State) -> Result<StepStats, SolverError> {
        let time = state.time;
        self.last = match self.settings.kind {
            SolverKind::Explicit => {
                explicit::step(model, state);
                StepStats {
                    converged: true,
                    ..Default::default()
                }
            }
            SolverKind::Implicit => {
                let solver = self.implicit.as_mut().expect("built for implicit");
                let r = solver
                    .step(model, state)
                    .map_err(|error| SolverError::Implicit { time, error })?;
                StepStats {
                    iterations: r.iterations,
                    residual_force: r.residual_force,
                    residual_moment: r.residual_moment,
                    converged: r.converged,
                }
            }
            SolverKind::Static => {
                let h = self.settings.static_input_step;
                self.previous_x.copy_from_slice(&state.x);
                state.time += h;
                let solver = self.statics.as_mut().expect("built for static");
                let r = solver
                    .solve(model, state)
                    .map_err(|error| SolverError::Static { time, error })?;
                for i in 0..state.x.len() {
                    state.v[i] = (state.x[i] - self.previous_x[i]) / h;
                }
                state.step += 1;
                StepStats {
                    iterations: r.iterations,
                    residual_force: r.residual_force,
                    residual_moment: r.residual_moment,
                    converged: r.converged,
                }
            }
        };
        if self.settings.kind != SolverKind::Explicit {
            check(model, state)?;
        }
        Ok(self.last)
    }
}
