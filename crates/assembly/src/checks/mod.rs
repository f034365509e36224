//! Installation checks (SPEC V3; cf. DIN 20066 for hose lines): minimum bend radius
//! everywhere and at all times, twist relative to the routed hose, no axial tension at
//! rest after assembly, a straight length behind each stub. Each violation names the
//! hose, the arc length, the time, the value and the limit.

mod fields;
mod kind;
mod pictures;
mod settings;
mod strain;
mod tracker;

pub use fields::BeamFields;
pub use kind::{CheckKind, Violation};
pub use pictures::{ScenePicture, ScenePictures, MAX_SCENE_PICTURES};
pub use settings::{
    CheckSettings, HoseCheckLimits, DEFAULT_REST_STRAIN_LIMIT, DEFAULT_STRAIGHT_LENGTH_FACTOR,
    DEFAULT_STRAIGHT_RADIUS_FACTOR, DEFAULT_TWIST_LIMIT_RAD_PER_M,
};
pub use strain::{axial_force, axial_strain, bend_and_twist};
pub use tracker::{HoseProfile, InstallationChecks};

use serde::Serialize;

/// What the checks found in a study (part of the run summary).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ChecksSummary {
    /// The checks that ran (names) and whether violations decide feasibility.
    pub enabled: Vec<&'static str>,
    pub decide: bool,
    /// Every violation: the running checks' worst per hose, then (at the end of a study)
    /// the assembled state's.
    pub violations: Vec<Violation>,
    /// Per hose: curvature and twist along it at its worst instants.
    pub profiles: Vec<HoseProfile>,
    /// The scene at the worst bends of the few hoses bent furthest below their limit
    /// (the report's pictures; presentation, not written to `report.json`).
    #[serde(skip)]
    pub pictures: ScenePictures,
    /// The range-of-motion study's rows and worst positions, if it sweeps a motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sweep: Option<crate::sweep::SweepSummary>,
}

impl ChecksSummary {
    /// The summary of `checks`, with the end-of-study violations `end` appended.
    pub fn of(checks: &InstallationChecks, end: Vec<Violation>) -> Self {
        let s = checks.settings();
        let on = [
            s.bend_radius,
            s.twist,
            s.tension_at_rest,
            s.straight_behind_stub,
        ];
        ChecksSummary {
            enabled: CheckKind::ALL
                .iter()
                .zip(on)
                .filter(|(_, on)| *on)
                .map(|(k, _)| k.name())
                .collect(),
            decide: s.decide,
            violations: checks.running_violations().cloned().chain(end).collect(),
            profiles: checks.profiles().to_vec(),
            pictures: checks.pictures().clone(),
            sweep: checks.sweep().map(|s| s.summary().clone()),
        }
    }
}
