//! What a timeline run keeps for Python: node positions at the scene's record interval,
//! and every hand's load at those times — sampled exactly as `pliant run`'s recorder
//! samples (same times, so the same fastener series and report plots).

use glam::DVec3;
use pliant_assembly::report::HandSample;
use pliant_assembly::{HandRecord, Observer};
use pliant_core::{Model, State};

/// Collects a run.
pub struct Collector {
    interval: f64,
    next_time: f64,
    /// Recorded times \[s\].
    pub times: Vec<f64>,
    /// All nodes' positions per recorded time, record after record.
    pub positions: Vec<DVec3>,
    /// Hand samples for the report plots.
    pub hand_samples: Vec<HandSample>,
    /// Full hand records with their time, for the per-hand series.
    pub hand_records: Vec<(f64, HandRecord)>,
}

impl Collector {
    pub fn new(interval: f64) -> Self {
        Collector {
            interval,
            next_time: 0.0,
            times: Vec::new(),
            positions: Vec::new(),
            hand_samples: Vec::new(),
            hand_records: Vec::new(),
        }
    }

    /// Records the final state if it was not recorded (as the recorder does).
    pub fn finish(&mut self, state: &State) {
        if self.times.last() != Some(&state.time) {
            self.record(state);
        }
    }

    fn record(&mut self, state: &State) {
        self.times.push(state.time);
        self.positions.extend_from_slice(&state.x);
    }
}

impl Observer for Collector {
    fn wants_state(&self, time: f64) -> bool {
        time + 1e-12 >= self.next_time
    }

    fn on_state(&mut self, _model: &Model, state: &State) {
        self.record(state);
        self.next_time = if self.interval > 0.0 {
            state.time + self.interval
        } else {
            0.0
        };
    }

    fn on_hands(&mut self, time: f64, hands: &[HandRecord]) {
        for r in hands {
            self.hand_samples.push(HandSample::new(time, r));
            self.hand_records.push((time, *r));
        }
    }
}
