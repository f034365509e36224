//! Pliant's assembly layer: the [`Workcell`] that owns an assembly study and steps it,
//! the shells' common vocabulary of inputs, hands, connector stubs (SPEC L6) and clips
//! (SPEC L7), the ergonomic limits hand loads are judged against (SPEC I3–I4), the
//! verdict, input logs and their replay, and the timeline runner. It knows no input
//! device and no scene file format.

pub mod checks;
pub mod clip;
pub mod ergonomics;
pub mod fastener_state;
pub mod fasteners;
pub mod grip;
pub mod hand;
pub mod move_speed;
pub mod part_frame;
pub mod report;
pub mod runner;
pub mod series_cap;
pub mod stub;
pub mod sweep;
pub mod timeline;
pub mod workcell;
pub mod worker;

pub use fastener_state::{FastenerKind, FastenerState};
pub use fasteners::{ClipSite, FastenerReport, FastenerSample, StubSite};
pub use grip::Grip;
pub use hand::{Hand, HandLoad};
pub use runner::{run_timeline, RunError, Runner};
pub use timeline::{Action, MovePath, NodeRef, Rotation, SettleFinish, Timeline};
pub use workcell::{
    Applied, ContactEpisode, Findings, HandPeak, HandRecord, InitialLoad, Input, InstabilityNote,
    NoObserver, NodePeak, Observer, Reason, Refusal, RunSummary, SettleOutcome, SolverDoubt, Stage,
    Verdict, Workcell, WorkcellError, WorkcellOptions, WorkcellSetup,
};
