//! Which pairs of beams hose–hose contact considers ([`HoseContactRule`]), and the pairs
//! whose capsules overlap in the shape the model is drawn in.
//!
//! A route from CAD — a harness's segments from KBL, bundles laid in one channel — draws
//! neighbouring bundles as centre lines only, often closer than their diameters: in the
//! vehicle they lie side by side, pressed flat or taped together. Pushing such pairs
//! apart with contact springs sized for hose walls would fight the design (residuals of
//! megANewtons on the imported main harness). Under [`HoseContactRule::ApartAtRest`]
//! those pairs never touch; every other pair does.

use super::hose_hose::{closest_segment_segment, HoseContactModel, HoseContactScratch};
use crate::Model;
use glam::DVec3;
use serde::{Deserialize, Serialize};
use std::str::FromStr;

/// Which pairs of beams may press on each other (scene `[simulation] hose_contact`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HoseContactRule {
    /// Every pair the tightest-U rule allows ([`super::hose_hose`]); pairs overlapping at
    /// rest are pushed apart.
    #[default]
    All,
    /// As `All`, but pairs of beams that overlap in the drawn shape never touch.
    ApartAtRest,
    /// No hose–hose or self contact.
    Off,
}

impl HoseContactRule {
    pub fn is_default(&self) -> bool {
        *self == Self::All
    }
}

impl FromStr for HoseContactRule {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "all" => Ok(Self::All),
            "apart_at_rest" => Ok(Self::ApartAtRest),
            "off" => Ok(Self::Off),
            _ => Err(format!(
                "unknown hose contact rule '{s}' (expected all, apart_at_rest or off)"
            )),
        }
    }
}

/// The pairs (i < j) of beams, not otherwise excluded by `constants`, whose capsules
/// overlap at the model's rest positions — the narrow phase of [`super::hose_hose`] on
/// the broad phase's candidates — sorted.
pub fn overlapping_at_rest(model: &Model, constants: &HoseContactModel) -> Vec<(u32, u32)> {
    let x: &[DVec3] = &model.rest_x;
    let mut scratch = HoseContactScratch::new(model);
    scratch.rebuild_with(model, constants, x);
    let mut pairs: Vec<(u32, u32)> = scratch
        .candidates
        .iter()
        .filter(|&&(i, j)| {
            let (ei, ej) = (&model.elements[i as usize], &model.elements[j as usize]);
            let (a, b, c, d) = (ei.node_a, ei.node_b, ej.node_a, ej.node_b);
            let (s, t) = closest_segment_segment(x[a], x[b], x[c], x[d]);
            let r1 = model.radius[a] + s * (model.radius[b] - model.radius[a]);
            let r2 = model.radius[c] + t * (model.radius[d] - model.radius[c]);
            x[a].lerp(x[b], s).distance(x[c].lerp(x[d], t)) < r1 + r2
        })
        .map(|&(i, j)| (i.min(j), i.max(j)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}
