//! The solver choice and its step sizes (plain data): which solver advances a simulation,
//! chosen per scene (`[simulation] solver = …`) or per command (`--solver …`). The
//! solvers themselves are in [`crate::integrators`].

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
    /// Implicit time step \[s\] (default 10 ms).
    pub implicit_time_step: f64,
    /// Static solver: simulated time between two equilibrium solves \[s\] (default 10 ms).
    pub static_input_step: f64,
    /// Static solver: Newton iterations allowed per equilibrium sought (default
    /// [`DEFAULT_STATIC_MAX_ITERATIONS`]). A route drawn far from its equilibrium — a
    /// harness from CAD springing out between its fixings — needs more for its first.
    #[serde(default = "default_static_iterations")]
    pub static_max_iterations: usize,
    /// Static solver: explicit steps the snap relaxation (the fallback of an input step
    /// Newton does not converge, [`crate::integrators::snap`]) may take over the whole run
    /// (default [`DEFAULT_STATIC_RELAXATION_BUDGET`]). Once spent, a step Newton does not
    /// converge is reported unconverged instead of relaxed again.
    #[serde(default = "default_relaxation_budget")]
    pub static_relaxation_budget: u64,
}

/// Explicit steps of snap relaxation allowed over a run, unless set: five relaxations at
/// their cap per relaxation (minutes on a harness of a thousand elements, not hours).
pub const DEFAULT_STATIC_RELAXATION_BUDGET: u64 = 10_000_000;

fn default_relaxation_budget() -> u64 {
    DEFAULT_STATIC_RELAXATION_BUDGET
}

/// Newton iterations the static solver allows per equilibrium sought, unless set.
pub const DEFAULT_STATIC_MAX_ITERATIONS: usize = 60;

fn default_static_iterations() -> usize {
    DEFAULT_STATIC_MAX_ITERATIONS
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            kind: SolverKind::Explicit,
            implicit_time_step: 0.01,
            static_input_step: 0.01,
            static_max_iterations: default_static_iterations(),
            static_relaxation_budget: default_relaxation_budget(),
        }
    }
}
