//! `summary.json`: what a run did, its peak support loads and its final state.

use crate::workcell::{RunSummary, SettleOutcome};
use pliant_core::health::{Divergence, DivergenceKind};
use pliant_core::rod::timestep::TimeStepReport;
use pliant_core::{Model, State};
use serde::Serialize;

#[derive(Serialize)]
pub struct PeakRow {
    pub hose: String,
    pub hose_index: usize,
    pub node: usize,
    pub max_force_n: f64,
    pub max_force_time_s: f64,
    pub max_moment_nm: f64,
    pub max_moment_time_s: f64,
    pub final_force_n: [f64; 3],
    pub final_moment_nm: [f64; 3],
}

/// One hose's final state. A hose whose state is not finite (a diverged run stopped
/// after the blow-up) has neither positions nor orientations, only `omitted` saying why:
/// no output holds a non-finite number.
#[derive(Serialize)]
pub struct FinalHose {
    pub name: String,
    /// Node positions \[m\].
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub positions_m: Vec<[f64; 3]>,
    /// Node orientations as unit quaternions (w, x, y, z).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub orientations: Vec<[f64; 4]>,
    /// Why positions and orientations are left out.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub omitted: Option<String>,
}

/// Why a run stopped early (`summary.json` `diverged`): the typed reason — `kind` and
/// its numbers, and for a divergence where and when — beside the human message.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stopped {
    #[serde(flatten)]
    pub reason: StopReason,
    /// The same in words (what `pliant run` prints).
    pub message: String,
}

/// The typed part of [`Stopped`].
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum StopReason {
    /// The simulation diverged at `step` (`time_s`), at node `node` of hose `hose`.
    Diverged {
        #[serde(flatten)]
        kind: DivergenceKind,
        step: u64,
        time_s: f64,
        hose: String,
        node: usize,
    },
    /// The run stopped for a reason other than a divergence.
    Other(OtherStop),
}

/// A run stopped without a divergence.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum OtherStop {
    /// The workcell could not be built.
    Setup,
    /// Timeline action `action` (`name`) was refused.
    ActionRefused { action: usize, name: &'static str },
    /// A replayed log's input `input` was refused or late.
    ReplayRefused { input: usize },
}

impl Stopped {
    /// A divergence, typed, with its message.
    pub fn diverged(d: &Divergence) -> Stopped {
        Stopped {
            reason: StopReason::Diverged {
                kind: d.kind.clone(),
                step: d.step,
                time_s: d.time,
                hose: d.hose.clone(),
                node: d.node,
            },
            message: d.to_string(),
        }
    }

    /// Another reason, with its message.
    pub fn other(reason: OtherStop, message: String) -> Stopped {
        Stopped {
            reason: StopReason::Other(reason),
            message,
        }
    }

    /// The typed divergence, if it was one.
    pub fn divergence_kind(&self) -> Option<&DivergenceKind> {
        match &self.reason {
            StopReason::Diverged { kind, .. } => Some(kind),
            StopReason::Other(_) => None,
        }
    }
}

#[derive(Serialize)]
pub struct Summary {
    pub pliant_version: &'static str,
    pub scene: String,
    pub source: String,
    pub completed: bool,
    /// Why the run stopped early (`null`: it did not).
    pub diverged: Option<Stopped>,
    pub steps: u64,
    pub simulated_time_s: f64,
    /// The step the solver advanced by \[s\] (the explicit stable step, or the implicit /
    /// static step).
    pub time_step_s: f64,
    /// How the explicit stable step was chosen (reported for every solver).
    pub time_step: TimeStepReport,
    /// explicit, implicit or static.
    pub solver: &'static str,
    pub wall_time_s: f64,
    pub realtime_factor: f64,
    pub elements: usize,
    pub actions_completed: usize,
    pub settles: Vec<SettleOutcome>,
    /// Newton solvers: most iterations in one step; steps that missed the tolerance
    /// (first and worst); unstable equilibria met and left, with their mode shapes.
    pub newton: crate::workcell::SolverRecord,
    /// Why the numbers are uncertain (unconverged or unstable steps); empty if they are not.
    pub warnings: Vec<String>,
    pub peaks: Vec<PeakRow>,
    pub final_state: Vec<FinalHose>,
    /// The worker (SPEC E1–E2), when the scene has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worker: Option<WorkerReport>,
    /// The hoses' swept envelopes over a range of motion (`[sweep]`): files, volumes,
    /// clearance to the parts that stand still.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub envelopes: Option<crate::sweep::envelope::SweptEnvelopes>,
}

/// `summary.json`'s `worker`: the worker's account and what they could not do.
#[derive(Serialize)]
pub struct WorkerReport {
    #[serde(flatten)]
    pub summary: crate::worker::WorkerSummary,
    /// Out of reach and body collisions, typed ([`crate::worker::WorkerFinding`]).
    pub findings: Vec<crate::worker::WorkerFinding>,
}

pub fn peak_rows(model: &Model, run: &RunSummary) -> Vec<PeakRow> {
    run.peaks
        .iter()
        .map(|p| PeakRow {
            hose: model.hoses[p.hose].name.clone(),
            hose_index: p.hose,
            node: p.node,
            max_force_n: p.max_force,
            max_force_time_s: p.max_force_time,
            max_moment_nm: p.max_moment,
            max_moment_time_s: p.max_moment_time,
            final_force_n: p.last_force.to_array(),
            final_moment_nm: p.last_moment.to_array(),
        })
        .collect()
}

pub fn final_state(model: &Model, state: &State) -> Vec<FinalHose> {
    model
        .hoses
        .iter()
        .map(|h| {
            let finite = h
                .nodes()
                .all(|i| state.x[i].is_finite() && state.q[i].is_finite());
            if !finite {
                return FinalHose {
                    name: h.name.clone(),
                    positions_m: Vec::new(),
                    orientations: Vec::new(),
                    omitted: Some(
                        "the hose's state is not finite (the run diverged): see `diverged`".into(),
                    ),
                };
            }
            FinalHose {
                name: h.name.clone(),
                positions_m: h.nodes().map(|i| state.x[i].to_array()).collect(),
                orientations: h
                    .nodes()
                    .map(|i| [state.q[i].w, state.q[i].x, state.q[i].y, state.q[i].z])
                    .collect(),
                omitted: None,
            }
        })
        .collect()
}
