//! A scene's workcell in one call (SPEC W1): the model with its stiffened spans, the
//! stubs and clips bound to its nodes, the initial load cases (the timeline's leading
//! fixes and dead loads) and the ergonomic profile. Every inconsistency — a stub bound
//! to no hose end, a span out of range — is an error here, so nothing is half-loaded.

use crate::scene::LoadedScene;
use pliant_assembly::{
    run_timeline, Action, NoObserver, RunSummary, Workcell, WorkcellOptions, WorkcellSetup,
};
use pliant_core::{Model, SolverKind};
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
            .take_while(|a| matches!(a, Action::Fix { .. } | Action::Load { .. }))
            .cloned()
            .collect()
    }

    /// Everything a workcell of this scene needs.
    pub fn workcell_setup(&self) -> Result<WorkcellSetup, String> {
        let model = self.build_model()?;
        let (stubs, clips) = self
            .fastener_sites(&model)
            .map_err(|e| format!("{}: {e}", self.source))?;
        Ok(WorkcellSetup {
            model: Arc::new(model),
            stubs,
            clips,
            initial: self.initial_actions(),
            profile: self.ergonomics,
            checks: self.check_settings(),
        })
    }

    /// The scene's installation checks (`[checks]`) with each hose's limits.
    pub fn check_settings(&self) -> pliant_assembly::checks::CheckSettings {
        self.checks.clone()
    }

    /// A workcell of this scene at rest at t = 0.
    pub fn workcell(&self, options: WorkcellOptions) -> Result<Workcell, String> {
        Workcell::new(self.workcell_setup()?, options)
    }

    /// The scene's whole timeline run with `solver` (the scene's own if `None`), as
    /// `pliant run` runs it but writing nothing: the workcell at the end and the summary.
    pub fn run_with(&self, solver: Option<SolverKind>) -> Result<(Workcell, RunSummary), String> {
        let mut cell = self.workcell(WorkcellOptions {
            solver,
            initial_loads: false,
            ..Default::default()
        })?;
        let run = run_timeline(&mut cell, &self.timeline, &mut NoObserver).map_err(|e| e.reason)?;
        Ok((cell, run))
    }
}
