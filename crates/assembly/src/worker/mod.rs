//! The worker in the workcell (SPEC E1–E2): a manikin from `pliant-worker`
//! that follows the hands, is checked against the parts and hoses and is scored for posture as
//! the study runs; its findings enter the verdict ([`WorkerFinding`]), `summary.json`,
//! `worker.csv` and the report.

pub mod body_pose;
pub mod collisions;
pub mod finding;
pub mod posture_note;
pub mod settings;
pub mod step_note;
pub mod track;

pub use body_pose::BodyPose;
pub use collisions::{Obstacle, Penetration};
pub use finding::WorkerFinding;
pub use posture_note::PostureNote;
pub use settings::{Stance, WorkerSettings, AUTO_REACH_FRACTION};
pub use step_note::{StepCause, StepNote};
pub use track::{
    BodyCollision, ClassInstants, ReachRecord, ScoreAt, WorkerNow, WorkerSample, WorkerSummary,
    WorkerTrack, MAX_STEP_NOTES, REACH_TOLERANCE,
};
