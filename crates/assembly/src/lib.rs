//! Pliant's assembly layer: turns scripts (and, later, hands) into load cases on the
//! physics core. It knows no input device and no file format.

pub mod runner;
pub mod timeline;

pub use runner::{NoObserver, NodePeak, Observer, RunError, RunSummary, Runner, SettleOutcome};
pub use timeline::{Action, MovePath, NodeRef, Rotation, Timeline};
