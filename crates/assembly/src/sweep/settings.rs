//! What a range-of-motion study records (the scene's `[sweep]`), SI units.

use serde::{Deserialize, Serialize};

/// The part whose motion is swept, and the clearances to watch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepSettings {
    /// The part whose motion coordinate the rows are given against (index into the
    /// model's parts).
    pub part: usize,
    /// The parts whose clearance to every hose is recorded (indices; all parts when the
    /// scene names none).
    pub clearance_parts: Vec<usize>,
    /// Smallest clearance allowed between a hose and those parts \[m\], if any: a hose
    /// coming nearer is a violation (it decides as the installation checks do).
    pub min_clearance: Option<f64>,
    /// For a part moved by inputs (no `motion` of its own): how its coordinate is
    /// measured — its turn's angle, its centre's travel, or time (None: time).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub moved_by_inputs: Option<super::CoordinateKind>,
    /// Voxel size of the swept envelopes \[m\] (None: [`super::envelope::voxel_size`]'s
    /// default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub envelope_voxel: Option<f64>,
}
