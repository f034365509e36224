//! Contact with the rigid environment (SPEC L4, dissertation §4.3.4 eq. 4.94–4.95):
//! kinematic contact for flexible hoses — each beam is a capsule, a node or beam point
//! that touches or penetrates a part loses its approaching normal velocity (the impulse is
//! reported as contact force), Coulomb friction acts on the tangential velocity, and any
//! penetration is pushed out over a few steps (position only, never an explosive force).
//!
//! The Newton solvers (static, implicit) use penalty springs on the node balls instead,
//! with Coulomb friction by an elastoplastic tangential spring ([`friction`]).
//!
//! Hose–hose and self contact (SPEC L5, [`hose_hose`]): penalty forces between beam
//! capsules, found by an O(N) uniform-grid broad phase ([`broad_phase`]) or, for boxes
//! spread along one axis, by sort and sweep ([`sweep`]) in the grid's order.

pub mod broad_phase;
mod clear_skin;
mod clearance;
pub mod coherence;
mod environment;
pub mod friction;
pub mod hose_hose;
mod moving;
mod network_gaps;
mod owned_edges;
mod pair_count;
pub mod part_gap;
mod penalty;
mod planes;
mod point_triangle;
pub mod rest_overlap;
mod rigid;
mod segment_triangle;
pub mod sweep;
#[cfg(test)]
mod test_random;
mod triangle_set;

pub use broad_phase::BroadPhase;
pub use clear_skin::ClearSkin;
pub use clearance::Clearance;
pub use coherence::CandidateCache;
pub use environment::{RigidEnvironment, RigidPart};
pub use hose_hose::{
    add_hose_contact_forces, hose_contact_forces, hose_contact_forces_with, ContactPair,
    HoseContactModel, HoseContactScratch, PairOverflow, SAFETY_FOR_HOSE_CONTACT,
};
pub use pair_count::{rest_pair_count, BYTES_PER_CONTACT_PAIR};
pub use rest_overlap::HoseContactRule;
pub use rigid::{ContactPoint, ContactScratch};
pub use segment_triangle::{
    closest_segment_triangle, closest_segment_triangle_away_from_ends, SegmentTriangleClosest,
};

pub(crate) use moving::wake_near as wake_near_moving_parts;
pub(crate) use penalty::add_penalty_forces;
pub(crate) use rigid::{project_positions, resolve_velocities, SKIN};
