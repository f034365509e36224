//! A scene's workcell in one call (SPEC W1): the model with its stiffened spans, the
//! stubs and clips bound to its nodes, the initial load cases (the timeline's leading
//! fixes and dead loads) and the ergonomic profile. Every inconsistency — a stub bound
//! to no hose end, a span out of range — is an error here, so nothing is half-loaded.

use crate::scene::LoadedScene;
use pliant_assembly::{
    Action, InitialLoad, Runner, Workcell, WorkcellError, WorkcellOptions, WorkcellSetup,
};
use pliant_core::Model;
use std::sync::Arc;

impl LoadedScene {
    /// The model of this scene, stiffened sections and junctions included.
    pub fn build_model(&self) -> Result<Model, String> {
        self.build_model_typed()
            .map_err(|e| format!("{}: cannot build the model: {e}", self.source))
    }

    /// [`Self::build_model`] with the core's typed error.
    pub fn build_model_typed(&self) -> Result<Model, pliant_core::ModelError> {
        Model::build(&self.world)
            .and_then(|m| m.with_delivered_shapes(&self.delivered_shapes(), &self.world.settings))
            .and_then(|m| m.with_stiffened_spans(&self.stiffened_spans()))
            .and_then(|m| m.with_junctions(&self.junctions))
    }

    /// The scene's initial load cases: the leading instantaneous actions of its timeline
    /// — fixes and dead loads — up to the first action that takes time or involves a
    /// hand. A live or Python session starts from them; the rest of the timeline is the
    /// script of `pliant run`.
    pub fn initial_actions(&self) -> Vec<Action> {
        self.timeline
            .actions
            .iter()
            .take_while(|a| {
                matches!(
                    a,
                    Action::Fix { .. } | Action::Mount { .. } | Action::Load { .. }
                )
            })
            .cloned()
            .collect()
    }

    /// [`Self::initial_actions`] typed as the workcell's initial load cases.
    pub fn initial_loads(&self) -> Vec<InitialLoad> {
        self.initial_actions()
            .iter()
            .filter_map(InitialLoad::from_action)
            .collect()
    }

    /// Everything a workcell of this scene needs.
    pub fn workcell_setup(&self) -> Result<WorkcellSetup, WorkcellError> {
        let model = self
            .build_model_typed()
            .map_err(|error| WorkcellError::Model {
                scene: self.source.clone(),
                error,
            })?;
        self.workcell_setup_of(Arc::new(model))
    }

    /// [`Self::workcell_setup`] on `model`, already built from this scene
    /// ([`Self::build_model_typed`]): the stubs and clips bound to its nodes, the initial
    /// load cases, the ergonomic profile, the checks and the worker.
    pub fn workcell_setup_of(&self, model: Arc<Model>) -> Result<WorkcellSetup, WorkcellError> {
        let (stubs, clips) =
            self.fastener_sites(&model)
                .map_err(|reason| WorkcellError::Fasteners {
                    scene: self.source.clone(),
                    reason,
                })?;
        Ok(WorkcellSetup {
            model,
            stubs,
            clips,
            initial: self.initial_loads(),
            profile: self.ergonomics,
            checks: self.check_settings(),
            worker: self.worker,
        })
    }

    /// The scene's installation checks (`[checks]`) with each hose's limits.
    pub fn check_settings(&self) -> pliant_assembly::checks::CheckSettings {
        self.checks.clone()
    }

    /// A workcell of this scene at rest at t = 0.
    pub fn workcell(&self, options: WorkcellOptions) -> Result<Workcell, WorkcellError> {
        Workcell::new(self.workcell_setup()?, options)
    }

    /// Refuses a run of this scene's timeline at `time_step` \[s\] planned beyond
    /// `max_steps` steps (its duration over the step), or whose estimated memory — the
    /// scene's ([`crate::budget::Estimate`]) plus the series it records in memory for the
    /// report over the planned run ([`crate::budget::Recorded`]) — exceeds the
    /// memory limit it was loaded under; naming the scene and the estimate. Else the
    /// planned steps. Every command that runs a scene's timeline checks it before the run
    /// starts.
    pub fn check_planned_steps(&self, time_step: f64, max_steps: u64) -> Result<u64, String> {
        self.check_planned_run(time_step, max_steps, false)
    }

    /// [`Self::check_planned_steps`] for a caller that also keeps every node's position
    /// at each recorded time in memory (`keeps_positions`: the Python `RunResult`).
    pub fn check_planned_run(
        &self,
        time_step: f64,
        max_steps: u64,
        keeps_positions: bool,
    ) -> Result<u64, String> {
        let planned = Runner::planned_duration(&self.timeline);
        let steps = crate::budget::check_steps(planned, time_step, max_steps)
            .map_err(|e| format!("{}: {e}", self.source))?;
        let kept = self.recorded(time_step, keeps_positions);
        crate::budget::check_recorded(&self.estimate, &self.limits, &kept)
            .map_err(|e| format!("{}: {e}", self.source))?;
        Ok(steps)
    }

    /// Refuses a live session of this scene (which has no planned end) whose series kept
    /// in memory for as long as it runs — the range-of-motion rows and the worker's
    /// samples, each capped ([`pliant_assembly::series_cap`]) — would exceed, on top of
    /// the scene's estimate, the memory limit it was loaded under.
    pub fn check_live_session(&self) -> Result<(), String> {
        let forever = crate::budget::Recorded {
            records: u64::MAX,
            hands: 0,
            fasteners: 0,
            nodes: 0,
            ..self.recorded(f64::INFINITY, false)
        };
        crate::budget::check_recorded(&self.estimate, &self.limits, &forever)
            .map_err(|e| format!("{}: {e}", self.source))
    }

    /// What a run of the timeline at `time_step` \[s\] keeps in memory per recorded time,
    /// and how many times it records (`keeps_positions`: also every node's position).
    pub fn recorded(&self, time_step: f64, keeps_positions: bool) -> crate::budget::Recorded {
        let planned = Runner::planned_duration(&self.timeline);
        let steps = (planned / time_step).ceil();
        let steps = if steps.is_finite() && steps >= 0.0 {
            steps as u64
        } else {
            u64::MAX
        };
        let nodes = if keeps_positions {
            self.world.hoses.iter().map(|h| h.nodes.len() as u64).sum()
        } else {
            0
        };
        crate::budget::Recorded {
            records: crate::budget::planned_records(planned, self.record_interval, steps),
            hands: self.hands_used(),
            fasteners: (self.stubs.len() + self.connectors.len() + self.clips.len()) as u64,
            nodes,
            sweep_values: self.checks.sweep.as_ref().map_or(0, |s| {
                let hoses = self.world.hoses.len();
                let parts = if s.clearance_parts.is_empty() {
                    self.world.rigid_parts.len()
                } else {
                    s.clearance_parts.len()
                };
                pliant_assembly::sweep::row_len(hoses, hoses * parts) as u64
            }),
            worker: self.worker.is_some(),
        }
    }

    /// How many hands the timeline uses (distinct hand numbers it grabs with).
    pub fn hands_used(&self) -> u64 {
        let mut hands: Vec<usize> = self
            .timeline
            .actions
            .iter()
            .filter_map(|a| match a {
                Action::Grab { hand, .. } | Action::GrabNode { hand, .. } => Some(*hand),
                _ => None,
            })
            .collect();
        hands.sort_unstable();
        hands.dedup();
        hands.len() as u64
    }
}
