//! Pliant's assembly layer: turns scripts (and, later, hands) into load cases on the
//! physics core, with the force laws of connector stubs (SPEC L6) and clips (SPEC L7) and
//! the ergonomic limits hand loads are judged against (SPEC I3–I4). It knows no input
//! device and no scene file format.

pub mod clip;
pub mod ergonomics;
pub mod fasteners;
pub mod hand;
pub mod runner;
pub mod stub;
pub mod timeline;

pub use fasteners::{ClipSite, FastenerReport, FastenerSample, StubSite};
pub use hand::{Hand, HandLoad};
pub use runner::{
    ContactEpisode, HandPeak, HandRecord, NoObserver, NodePeak, Observer, RunError, RunSummary,
    Runner, SettleOutcome,
};
pub use timeline::{Action, MovePath, NodeRef, Rotation, Timeline};
