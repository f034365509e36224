//! Recovery points of a live study (a divergence never costs the
//! session). The workcell keeps the last few healthy [`Checkpoint`]s, one every
//! \[`RECOVERY_EVERY`\] steps, each taken right after a health check passed; on a
//! divergence [`super::Input::Rollback`] goes back to the newest one, instead of
//! resetting the whole study.
//!
//! Checkpoints are taken at fixed steps (`state.step`), whoever watches, so a replay of
//! the log takes the same ones and a logged rollback lands on the same state bit for
//! bit. A checkpoint used by a rollback is given up, and no new one is taken until the
//! study has passed the step where it diverged: if it diverges again on the way, the
//! following rollback goes further back (four rollbacks at most for one cause, 0.25 s to
//! 1 s back), never round in a circle.

use super::Checkpoint;
use std::collections::VecDeque;

/// Simulated time between two recovery points \[s\] (rounded to whole health-check
/// periods): with four points kept, a rollback goes back 0.25–1 s.
pub const RECOVERY_INTERVAL: f64 = 0.25;

/// Recovery points kept (the oldest is dropped first).
pub const RECOVERY_POINTS: usize = 4;

/// The newest healthy checkpoints, oldest first.
#[derive(Clone)]
pub struct Recovery {
    points: VecDeque<Checkpoint>,
    /// Steps between two points: a multiple of `check_every`.
    every: u64,
    /// No new points up to this step (the step of the last divergence rolled back).
    hold_until: u64,
}

impl Recovery {
    /// Points every [`RECOVERY_INTERVAL`] at time step `dt`, on steps that are health
    /// checked (multiples of `check_every`).
    pub fn new(dt: f64, check_every: u64) -> Self {
        let checks = (RECOVERY_INTERVAL / (dt * check_every as f64)).round();
        let checks = if checks.is_finite() {
            checks.clamp(1.0, 1e6) as u64
        } else {
            1
        };
        Recovery {
            points: VecDeque::with_capacity(RECOVERY_POINTS),
            every: checks * check_every,
            hold_until: 0,
        }
    }

    /// Whether a recovery point is due after step number `step`.
    pub fn due(&self, step: u64) -> bool {
        step % self.every == 0 && step > self.hold_until
    }

    /// Keeps `checkpoint` as the newest point, dropping the oldest beyond
    /// [`RECOVERY_POINTS`] (a copy of the state every few hundred steps, not in every
    /// step).
    pub fn keep(&mut self, checkpoint: Checkpoint) {
        if self.points.len() == RECOVERY_POINTS {
            self.points.pop_front();
        }
        self.points.push_back(checkpoint);
    }

    /// Gives up the newest point, for a rollback from a divergence at step
    /// `diverged_at`; no new point is taken until the study is past that step.
    pub fn take_newest(&mut self, diverged_at: u64) -> Option<Checkpoint> {
        self.hold_until = self.hold_until.max(diverged_at);
        self.points.pop_back()
    }

    /// Forgets every point (a reset starts a new study).
    pub fn clear(&mut self) {
        self.points.clear();
        self.hold_until = 0;
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}
