//! Newton-based solvers beyond the dissertation (issue 5, SPEC P5): quasi-static
//! equilibrium ([`statics`]) and implicit HHT-α dynamics ([`implicit`]), sharing the
//! assembly of loads and consistent tangent ([`system`]) and the O(N) block-tridiagonal
//! linear solve ([`block_tridiagonal`]).

pub mod block_tridiagonal;
pub mod implicit;
pub mod statics;
pub mod system;

pub use implicit::{
    ImplicitError, ImplicitHistory, ImplicitOptions, ImplicitReport, ImplicitSolver,
};
pub use statics::{StaticError, StaticOptions, StaticReport, StaticSolver};
pub use system::{NewtonSystem, NotAChain, RIGID_FACTOR};
