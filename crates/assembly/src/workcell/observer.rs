//! Sees a study as it steps: a recorder writing CSV files, a collector for Python, a
//! progress bar. Only states that passed the divergence check reach `on_state`.

use super::tally::HandRecord;
use crate::timeline::Action;
use pliant_core::{Model, State};

pub trait Observer {
    /// Whether the observer wants the state at simulated time `time` (e.g. a recorder
    /// sampling at an interval).
    fn wants_state(&self, _time: f64) -> bool {
        false
    }
    /// A checked state the observer asked for.
    fn on_state(&mut self, _model: &Model, _state: &State) {}
    /// A timeline action is about to start.
    fn on_action(&mut self, _index: usize, _action: &Action, _state: &State) {}
    /// Called every step with the simulated time (for progress display); keep it cheap.
    fn on_step(&mut self, _time: f64) {}
    /// The hands' loads and their ergonomic assessment, with every state the observer
    /// asked for.
    fn on_hands(&mut self, _time: f64, _hands: &[HandRecord]) {}
}

/// An observer that watches nothing.
pub struct NoObserver;
impl Observer for NoObserver {}
