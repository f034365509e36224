//! The checked quantities along each hose now, per beam, for the viewer's colour modes:
//! curvature against the minimum bend radius, twist relative to the
//! routed hose (as the running checks judge them, `strain.rs`) and the axial force from
//! the element's axial strain (as the tension-at-rest check judges it). f32: they are for
//! drawing.

use super::strain::{axial_force, bend_and_twist};
use super::tracker::InstallationChecks;
use pliant_core::{Model, State};
use serde::Serialize;

/// One hose's per-beam fields (beam k joins nodes k and k + 1).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct BeamFields {
    /// κ · minimum bend radius = minimum / current bend radius (≥ 1 breaks the minimum;
    /// 0 straight). Empty when the hose has no minimum (checks off).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub bend_radius_ratio: Vec<f32>,
    /// Twist rate relative to the routed, unloaded hose [rad/m] (signed).
    pub twist: Vec<f32>,
    /// Axial force \[N\]: the element's axial strain × E_t·A stretched, × E_c·A shortened
    /// (negative).
    pub axial_force: Vec<f32>,
}

impl InstallationChecks {
    /// Hose `hose`'s fields in `state` (empty if there is no such hose). Allocates the
    /// three arrays only (called per snapshot, never per step).
    pub fn beam_fields(&self, model: &Model, state: &State, hose: usize) -> BeamFields {
        let Some(info) = model.hoses.get(hose) else {
            return BeamFields::default();
        };
        let limits = self.settings().hoses.get(hose);
        let n = info.element_count;
        let mut out = BeamFields {
            bend_radius_ratio: Vec::with_capacity(if limits.is_some() { n } else { 0 }),
            twist: Vec::with_capacity(n),
            axial_force: Vec::with_capacity(n),
        };
        let finite = |x: f64| if x.is_finite() { x as f32 } else { 0.0 };
        for (k, e) in (info.first_element..info.first_element + n).enumerate() {
            let el = &model.elements[e];
            let (kappa, tau) =
                bend_and_twist(state.q[el.node_a], state.q[el.node_b], el.rest_length);
            if let Some(l) = limits {
                out.bend_radius_ratio
                    .push(finite(kappa * l.bend_radius_at(k)));
            }
            out.twist.push(finite(tau - self.rest_twist(e)));
            out.axial_force.push(finite(axial_force(model, state, e)));
        }
        out
    }
}
