//! Why a workcell could not be built: the scene's model, its fastener sites, the solver,
//! the worker or an initial load case. Callers that speak text (the server, Python, the
//! CLI) show its `Display`, which names the scene file where there is one.

use super::Refusal;
use pliant_core::newton::TopologyError;
use pliant_core::ModelError;
use pliant_worker::WorkerError;

/// Why [`super::Workcell::new`] or a scene's workcell builder failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WorkcellError {
    /// The scene's model does not build (a hose, a span, a junction).
    #[error("{scene}: cannot build the model: {error}")]
    Model { scene: String, error: ModelError },
    /// A stub or clip of the scene is bound to nothing it can hold.
    #[error("{scene}: {reason}")]
    Fasteners { scene: String, reason: String },
    /// The solver cannot be set up for the model (the static and implicit solvers need
    /// chains of elements).
    #[error(transparent)]
    Solver(#[from] TopologyError),
    /// The worker's settings are refused.
    #[error("worker: {0}")]
    Worker(#[from] WorkerError),
    /// An initial load case is refused (a node out of range, a part that is not there).
    #[error("initial load case: {0}")]
    InitialLoad(Refusal),
    /// A session's scene gives another time step than the one its log was made with.
    #[error(
        "the scene gives a time step of {scene:e} s, the log was made with {log:e} s: the scene or this Pliant version differs from the session's"
    )]
    TimeStep { scene: f64, log: f64 },
}
