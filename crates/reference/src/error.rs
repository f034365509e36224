//! Error type of the reference solver.

use thiserror::Error;

/// Everything that can go wrong when setting up or solving a reference problem.
///
/// Invalid input is reported, never panicked on; numerical failures (a Newton
/// iteration or a continuation path that does not converge) are reported with the
/// information needed to diagnose them.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ReferenceError {
    /// The rest polyline is unusable (too few nodes, non-finite coordinates,
    /// zero-length or reversed segments, a base frame not aligned with the first
    /// segment).
    #[error("invalid rest shape: {0}")]
    InvalidRestShape(String),
    /// A stiffness or cross-section parameter is non-finite or not positive.
    #[error("invalid stiffness: {0}")]
    InvalidStiffness(String),
    /// A boundary condition or load contains non-finite values.
    #[error("invalid boundary condition: {0}")]
    InvalidBoundaryCondition(String),
    /// A tree has no branch or not exactly one root (the trunk, without a parent).
    #[error("invalid tree: {0}")]
    InvalidTree(String),
    /// A tree branch names a parent that does not exist.
    #[error(
        "tree branch {branch}: parent {parent} does not exist (the tree has {count} branches)"
    )]
    UnknownParent {
        /// The branch.
        branch: usize,
        /// The parent it names.
        parent: usize,
        /// Number of branches.
        count: usize,
    },
    /// Following the parents from a branch never reaches the trunk.
    #[error("tree branch {branch} is on a cycle of parents and never reaches the trunk")]
    TreeCycle {
        /// A branch on the cycle.
        branch: usize,
    },
    /// A branch does not start where its parent ends (branches are joined at the
    /// parent's end point).
    #[error(
        "tree branch {branch} dangles: it starts {gap:.3e} m from the end of its parent \
         {parent}; a branch must start at its parent's end"
    )]
    DanglingBranch {
        /// The branch.
        branch: usize,
        /// Its parent.
        parent: usize,
        /// Distance between the branch's first rest node and the parent's last.
        gap: f64,
    },
    /// ShootingSolver options are out of range.
    #[error("invalid solver options: {0}")]
    InvalidOptions(String),
    /// A requested sample arc length lies outside `[0, L]` or is not finite.
    #[error("invalid arc length {arc_length}: must be finite and lie in [0, {length}]")]
    InvalidArcLength {
        /// The offending arc length.
        arc_length: f64,
        /// Total reference length of the rod.
        length: f64,
    },
    /// The integration of the rod equations left the physical domain
    /// (stretch ν ≤ 0) or produced non-finite values.
    #[error("integration failed at s = {arc_length}: {reason}")]
    Integration {
        /// Reference arc length where the failure was detected.
        arc_length: f64,
        /// What went wrong.
        reason: String,
    },
    /// The shooting Jacobian could not be factorised.
    #[error("singular shooting Jacobian at Newton iteration {iteration}")]
    SingularJacobian {
        /// Newton iteration at which the factorisation failed.
        iteration: usize,
    },
    /// The damped Newton iteration stopped without reaching the tolerance.
    #[error(
        "Newton iteration did not converge after {iterations} iterations \
         (scaled residual {residual:.3e}, tolerance {tolerance:.1e})"
    )]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// Scaled residual (max norm) when the iteration stopped.
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// A continuation sub-step converged, but the Newton corrector was too large
    /// compared with the predictor (strong path curvature or a jump to another
    /// equilibrium branch); the step is halved.
    #[error(
        "continuation sub-step rejected: corrector {corrector:.3e} too large for \
         predictor {predictor:.3e} (possible branch switch)"
    )]
    StepRejected {
        /// Norm of the first Newton step (scaled unknowns).
        predictor: f64,
        /// Distance from the first Newton iterate to the solution (scaled).
        corrector: f64,
    },
    /// Path following could not reach a target even after the maximum number of
    /// step halvings.
    #[error(
        "continuation failed on the way to target {target}: stuck at fraction {reached:.6} \
         of the step after {halvings} halvings; last error: {last_error}"
    )]
    ContinuationFailed {
        /// Index of the target (in the list passed to `solve_path`) not reached.
        target: usize,
        /// Fraction of the way from the previous target that was reached.
        reached: f64,
        /// Halvings of the step size performed at the point of failure.
        halvings: u32,
        /// The error of the last failed Newton solve.
        last_error: Box<ReferenceError>,
    },
}

/// Result alias of this crate.
pub type Result<T> = std::result::Result<T, ReferenceError>;
