//! What a report's pictures draw besides the hoses, made once per report from the model
//! (presentation, never on the live path): the parts' outlines where the scene placed
//! them, every part's outline at its pose at the instant of each picture — each scene
//! picture's (a door drawn at the angle where the hose bent tightest), the worker's worst
//! posture's and the swept envelopes' (the sweep's worst bend) — and the swept envelopes
//! of a range-of-motion study.

use super::part_outline::{part_outlines, posed_outlines, PartOutline};
use crate::sweep::envelope::{swept_envelopes, SweptEnvelopes};
use crate::workcell::RunSummary;
use pliant_core::Model;

/// The parts and envelopes a report draws.
pub struct Drawing {
    /// Every part where the scene placed it.
    pub parts: Vec<PartOutline>,
    /// Per scene picture (by its hose), every part at its pose at the picture's instant.
    pub posed: Vec<(usize, Vec<PartOutline>)>,
    /// Every part at its pose at the worker's worst posture (none without a worker).
    pub worker_parts: Option<Vec<PartOutline>>,
    /// The hoses' swept envelopes, when the run swept a motion.
    pub envelopes: Option<SweptEnvelopes>,
    /// The instant the envelope picture draws the parts at (the sweep's worst bend) and
    /// every part at its pose then.
    pub envelope_parts: Option<(f64, Vec<PartOutline>)>,
}

impl Drawing {
    /// The drawing of `run` of `model`.
    pub fn of(model: &Model, run: &RunSummary) -> Drawing {
        let env = &model.environment;
        let parts = part_outlines(env);
        let posed = run
            .checks
            .pictures
            .all()
            .iter()
            .map(|p| (p.hose, posed_outlines(env, &parts, &p.part_poses)))
            .collect();
        let envelopes = run
            .checks
            .sweep
            .as_ref()
            .and_then(|s| s.swept.as_ref())
            .map(|swept| swept_envelopes(model, swept));
        let worker_parts = run
            .worker
            .as_ref()
            .map(|w| posed_outlines(env, &parts, &w.worst_part_poses));
        let envelope_parts = run
            .checks
            .sweep
            .as_ref()
            .and_then(|s| s.worst_bend_poses.as_ref())
            .filter(|_| envelopes.is_some())
            .map(|w| (w.time, posed_outlines(env, &parts, &w.poses)));
        Drawing {
            parts,
            posed,
            worker_parts,
            envelopes,
            envelope_parts,
        }
    }

    /// The parts at the instant of hose `hose`'s scene picture (at rest if it has none).
    pub fn parts_for_picture(&self, hose: usize) -> &[PartOutline] {
        self.posed
            .iter()
            .find(|(h, _)| *h == hose)
            .map_or(&self.parts, |(_, p)| p)
    }
}
