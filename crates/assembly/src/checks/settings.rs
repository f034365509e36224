//! Which installation checks a study runs and their limits (SPEC V3), as the scene's
//! `[checks]` gives them (documented defaults in `docs/scene-format.md`), SI units.

use serde::{Deserialize, Serialize};

/// Default twist limit: 10 °/m relative to the routed hose. An assumption: DIN 20066
/// asks for hose lines free of twist; makers of hydraulic hose warn that a few degrees
/// shorten life markedly; 10 °/m is about what one sees of a lay line turning over a
/// metre, i.e. the smallest twist a fitter would notice and correct.
pub const DEFAULT_TWIST_LIMIT_RAD_PER_M: f64 = 10.0 * std::f64::consts::PI / 180.0;
/// Default axial strain at rest: 0.5 %. An assumption: "no tension at rest" (DIN
/// 20066) with room for the sag of a hose under its own weight (a 1 m coolant hose
/// hanging straight down stretches by about 0.15 %).
pub const DEFAULT_REST_STRAIN_LIMIT: f64 = 0.005;
/// Default straight length behind a stub: 1.5 × the outer diameter (the hose-line
/// installation rule of DIN 20066 as hose makers quote it; an assumption where a
/// datasheet says otherwise).
pub const DEFAULT_STRAIGHT_LENGTH_FACTOR: f64 = 1.5;
/// Default radius that counts as straight: 10 × the minimum bend radius.
pub const DEFAULT_STRAIGHT_RADIUS_FACTOR: f64 = 10.0;

/// The limits of one hose \[m\].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HoseCheckLimits {
    /// Minimum bend radius of the centre line \[m\] (material data).
    pub min_bend_radius: f64,
    /// Outer diameter \[m\] (the straight length is a multiple of it).
    pub d_outer: f64,
    /// Minimum bend radius of each element \[m\] where stretches of the hose differ (a
    /// harness segment under a protection); empty: `min_bend_radius` throughout.
    #[serde(default)]
    pub bend_radii: Vec<f64>,
}

impl HoseCheckLimits {
    /// The minimum bend radius of the hose's element `k` (counted from its first).
    pub fn bend_radius_at(&self, k: usize) -> f64 {
        self.bend_radii
            .get(k)
            .copied()
            .unwrap_or(self.min_bend_radius)
    }
}

/// The checks a study runs and their limits.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckSettings {
    pub bend_radius: bool,
    pub twist: bool,
    pub tension_at_rest: bool,
    pub straight_behind_stub: bool,
    /// Whether violations make the verdict NOT FEASIBLE (else they are warnings).
    pub decide: bool,
    /// Twist rate limit relative to the routed hose [rad/m].
    pub twist_limit: f64,
    /// Largest axial strain allowed at the end of the study.
    pub rest_strain_limit: f64,
    /// Straight length behind a stub, in outer diameters.
    pub straight_length_factor: f64,
    /// Bend radius that counts as straight, in minimum bend radii.
    pub straight_radius_factor: f64,
    /// Interval between checked instants \[s\] (the scene's record interval; 0 = every
    /// step).
    pub interval: f64,
    /// Per hose, by index.
    pub hoses: Vec<HoseCheckLimits>,
    /// A range-of-motion study: the checks recorded against a part's motion coordinate
    /// ([`crate::sweep`]), if the scene asks for one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep: Option<crate::sweep::SweepSettings>,
}

impl CheckSettings {
    /// Every check on, default limits, the given hoses.
    pub fn with_hoses(hoses: Vec<HoseCheckLimits>) -> Self {
        CheckSettings {
            bend_radius: true,
            twist: true,
            tension_at_rest: true,
            straight_behind_stub: true,
            decide: true,
            twist_limit: DEFAULT_TWIST_LIMIT_RAD_PER_M,
            rest_strain_limit: DEFAULT_REST_STRAIN_LIMIT,
            straight_length_factor: DEFAULT_STRAIGHT_LENGTH_FACTOR,
            straight_radius_factor: DEFAULT_STRAIGHT_RADIUS_FACTOR,
            interval: 0.01,
            hoses,
            sweep: None,
        }
    }

    /// No check at all (a workcell built without scene data).
    pub fn none() -> Self {
        CheckSettings {
            bend_radius: false,
            twist: false,
            tension_at_rest: false,
            straight_behind_stub: false,
            ..Self::with_hoses(Vec::new())
        }
    }

    /// Whether any check runs while the study goes.
    pub fn any_running(&self) -> bool {
        ((self.bend_radius || self.twist) && !self.hoses.is_empty()) || self.sweep.is_some()
    }
}
