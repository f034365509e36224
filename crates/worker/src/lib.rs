//! Pliant's worker model (SPEC E1–E2): a manikin sized from cited
//! anthropometric data, its hands brought to the session's hand targets by inverse
//! kinematics within joint limits, its body as capsules for collision checks, and its
//! posture scored by RULA and REBA.
//!
//! Depends on no other Pliant crate: the assembly layer feeds it hand targets and forces
//! and checks its capsules against the parts.
//!
//! - [`anthropometry`]: the data table (`data/anthropometry.toml`, sources in its
//!   header), [`Population`], [`Body`];
//! - [`placement`]: where the worker stands and faces;
//! - [`posture`]: joint angles and positions;
//! - [`seat`]: a seated worker's seat and legs;
//! - [`posture_class`]: upright, bent trunk, arms above shoulder or sitting (trunk
//!   supported or bent), for the force limits;
//! - [`ik`]: the inverse kinematics ([`Manikin::solve`]);
//! - [`mod@capsules`]: the body of capsules of a posture;
//! - [`step`]: where the feet step when a target is out of reach or a VR user walks;
//! - [`rula`], [`reba`]: the two posture scores, their tables in their own files;
//! - [`scores`]: both scores of a manikin posture with the hands' forces.

pub mod anthropometry;
pub mod capsules;
pub mod error;
pub mod ik;
pub mod placement;
pub mod posture;
pub mod posture_class;
pub mod quantile;
pub mod reba;
pub mod rula;
pub mod scores;
pub mod seat;
pub mod step;

pub use anthropometry::{body, popliteal_height, stature, Body, JointLimits, Population, Sex};
pub use capsules::{capsules, Capsule, Segment, CAPSULE_COUNT, SEGMENTS};
pub use error::WorkerError;
pub use ik::{assign_hands, HeadTarget, Manikin};
pub use placement::Placement;
pub use posture::{ArmPose, Joints, Posture, Side, Sitting, TrunkAngles};
pub use posture_class::PostureClass;
pub use reba::{Coupling, RebaInput, RebaScore};
pub use rula::{RulaInput, RulaScore};
pub use scores::{score_posture, PostureScores, ScoreOptions};
pub use seat::{Seat, SeatBox, SeatedLegs};
pub use step::{
    describe_step, max_step, reach_step, reach_turn, walk_step, STEP_FRACTION, TURN_BEARING,
};
