//! What the Newton solvers' record means for a study, as typed values worded by
//! `Display`: why its numbers are uncertain ([`SolverDoubt`]) and the instabilities it
//! met ([`InstabilityNote`]). The verdict puts the doubts first among its reasons and the
//! notes after them; `summary.json` and `report.json` carry their words.

use super::solver_record::{RolledBack, Unconverged};
use serde::Serialize;
use std::fmt;

/// Why a study's numbers are uncertain.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "doubt", rename_all = "snake_case")]
pub enum SolverDoubt {
    /// `steps` steps ended out of balance; the first and the worst of them.
    OutOfBalance {
        steps: u64,
        first: Unconverged,
        worst: Unconverged,
    },
    /// `steps` steps ended on an equilibrium known to be unstable.
    Unstable { steps: u64 },
    /// The simulation diverged `count` times and was rolled back; the first rollback.
    RolledBack { count: u64, first: RolledBack },
}

impl fmt::Display for SolverDoubt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SolverDoubt::OutOfBalance {
                steps,
                first,
                worst,
            } => write!(
                f,
                "uncertain: the Newton solver did not reach balance in {} step(s), first at t = {:.3} s; \
                 worst at t = {:.3} s, residual {:.3e} N / {:.3e} N·m against the limits {:.1e} N / {:.1e} N·m — \
                 forces at those steps are not trustworthy",
                steps,
                first.time,
                worst.time,
                worst.residual_force,
                worst.residual_moment,
                worst.force_limit,
                worst.moment_limit,
            ),
            SolverDoubt::Unstable { steps } => write!(
                f,
                "uncertain: {steps} step(s) ended on an unstable equilibrium the static solver could not leave"
            ),
            SolverDoubt::RolledBack { count, first } => write!(
                f,
                "uncertain: the simulation diverged {} time(s) and was rolled back, each time releasing the \
                 hands on the diverging hose; first at t = {:.3} s (hose '{}', back to t = {:.3} s, hands {:?} \
                 released): {}",
                count, first.diverged_at, first.hose, first.back_to, first.released, first.reason
            ),
        }
    }
}

/// An instability a study met, or its implicit steps taken explicitly: information, not
/// a failure.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "note", rename_all = "snake_case")]
pub enum InstabilityNote {
    /// The hose's equilibrium branch ended (a limit point) and the static solver followed
    /// the snap to the next stable equilibrium; `node` moved most.
    SnappedThrough {
        hose: String,
        time: f64,
        node: usize,
    },
    /// The static solver left an unstable equilibrium (`negative_eigenvalues` of the
    /// tangent) for the stable branch.
    Buckled {
        hose: String,
        time: f64,
        node: usize,
        negative_eigenvalues: usize,
    },
    /// Instabilities met beyond those kept in full.
    More { count: u64 },
    /// `steps` implicit steps did not converge and were taken by the explicit solver,
    /// the first at `first_time` \[s\].
    ExplicitFallback { steps: u64, first_time: f64 },
}

impl fmt::Display for InstabilityNote {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InstabilityNote::SnappedThrough { hose, time, node } => write!(
                f,
                "hose '{hose}' snapped through at t = {time:.3} s (node {node} moved most): its equilibrium \
                 branch ended (a limit point) and the static solver followed the snap to the \
                 next stable equilibrium"
            ),
            InstabilityNote::Buckled {
                hose,
                time,
                node,
                negative_eigenvalues,
            } => write!(
                f,
                "hose '{hose}' buckled at t = {time:.3} s (node {node}, {negative_eigenvalues} negative eigenvalue(s) of the tangent): \
                 the static solver left the unstable equilibrium for the stable branch"
            ),
            InstabilityNote::More { count } => write!(f, "… and {count} more instabilities"),
            InstabilityNote::ExplicitFallback { steps, first_time } => write!(
                f,
                "{steps} implicit step(s) did not converge and were taken by the explicit solver \
                 (in stable steps; first at t = {first_time:.3} s) — the motion is still a dynamic solution"
            ),
        }
    }
}
