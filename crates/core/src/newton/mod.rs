//! The Newton machinery the implicit and quasi-static integrators share (SPEC
//! P5; the integrators themselves are in [`crate::integrators`]): the assembly of loads
//! and consistent tangent ([`system`]), the O(N) linear solve of a chain or tree of
//! nodes ([`block_tree`], its pivot blocks' solve [`block_lu`]), the condensation of junctions onto their master nodes
//! ([`condensation`]), a junction body's own mass on its master ([`body_terms`]), the
//! contact of hoses with a junction body's shape ([`shape_contact`]), GMRES for the
//! contact coupling outside the band ([`gmres`]) and the convergence test
//! ([`convergence`]).

pub mod block_lu;
pub mod block_tree;
pub mod body_terms;
pub mod condensation;
pub mod convergence;
pub mod factor_reuse;
pub mod gmres;
pub mod shape_contact;
pub mod system;
pub mod ties;

pub use convergence::{LoadScale, Tolerance};
pub use system::{NewtonSystem, TopologyError, RIGID_FACTOR};
