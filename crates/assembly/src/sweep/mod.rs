//! Range of motion (SPEC K2): a study that moves a part through its range reports every
//! installation check as a function of the part's motion coordinate — the door's angle,
//! the seat's travel, the engine's phase in its cycle — together with the fixing forces
//! and the clearance between each hose and each part, and names the worst position in the
//! motion's own unit ("bend radius 31 mm < 45 mm at door angle 68°").
//!
//! The motion itself is the part's (`kinematics::PartMotion`): a static solver sees it as a
//! sequence of poses (quasi-static sweep), a dynamic one at the speed its keyframes give.
//! The sweep is sampled at the installation checks' instants, from the state alone, so
//! every shell and every replay records the same rows.
//!
//! Each hose's swept envelope over the motion — the volume its tube took at some checked
//! instant — is a voxel set and its closed surface ([`envelope`]), with its clearance to
//! every part that stands still, written as STL and GLB ([`glb`]).

pub mod centreline_samples;
mod coordinate;
pub mod envelope;
mod extremes;
pub mod glb;
mod settings;
mod summary;
mod tracker;
pub mod voxel_surface;
pub mod voxels;

pub use coordinate::{Coordinate, CoordinateKind};
pub use extremes::{ClosestApproach, MotionExtremes, RadiusAt};
pub use settings::SweepSettings;
pub use summary::{
    ClearanceViolation, SweepSummary, Worst, AXIAL_FORCE, BEND_LIMIT, BEND_RADIUS, BEND_RATIO,
    TWIST,
};
pub use tracker::{row_len, MotionSweep};
