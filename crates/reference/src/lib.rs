//! # pliant-reference
//!
//! An independent, high-accuracy reference solution of the *static* boundary-value
//! problem of a flexible rod, used to validate Pliant's co-rotational beam element
//! (SPEC §7). It shares no code with the other Pliant crates.
//!
//! ## Model
//!
//! A static, extensible, unshearable Kirchhoff rod (Antman, *Nonlinear Problems of
//! Elasticity*, 2nd ed., ch. 8; for inextensible planar bending it reduces to
//! Euler's elastica), SI units throughout:
//!
//! ```text
//! r' = ν d1,   R' = R [κ]×,   n' = −q,   m' = −r' × n,
//! ν = 1 + (n·d1)/EA   (EA_t for tension, EA_c for compression),
//! κ = (m_b1/GJ, m_b2/EI, m_b3/EI),  m_b = Rᵀ m,
//! ```
//!
//! with a stress-free polyline rest shape whose rest curvature is concentrated at
//! the interior nodes ([`rod`]). The equations are integrated by fixed-step RK4,
//! restarted at every rest kink ([`ode`]).
//!
//! ## Method
//!
//! Shooting ([`shooting`]): the base `s = 0` is clamped; the six unknowns
//! `n(0), m(0)` are found by damped Newton with an exact Jacobian (variational
//! equations) so that the end condition at `s = L` holds: a clamped pose or dead
//! end loads ([`EndCondition`]). Large deformations are reached by path following
//! with automatic step halving ([`continuation`]).
//!
//! Trees ([`Tree`], [`TreeSolver`]): a trunk clamped at its base and branches welded
//! to the ends of other branches, solved by shooting with the unknown force and
//! moment at the base of every branch, force and moment balance at every branch
//! point and dead loads at every tip ([`tree_shooting`]).
//!
//! ## Conventions
//!
//! * Frames: `R = [d1 d2 d3]` maps body to global coordinates; d1 is the tangent,
//!   torsion is about d1, bending about d2 and d3.
//! * `n(s)`, `m(s)`: force and moment (about `r(s)`) exerted by the part `(s, L]`
//!   on the part `[0, s]`, global.
//! * Reactions: the support at `s = L` applies `+n(L)`, `+m(L)` to the rod
//!   ([`Solution::end_reaction`]); the base support applies `−n(0)`, `−m(0)`, moment
//!   about the base point ([`Solution::base_reaction`]).
//!
//! ## Example
//!
//! ```
//! use nalgebra::Vector3;
//! use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};
//!
//! # fn main() -> Result<(), pliant_reference::ReferenceError> {
//! // Cantilever of length 1 m, EI = 1 N m², tip load P = EI/L² normal to the axis.
//! let stiffness = Stiffness::new(1e9, 1.0, 1.0)?;
//! let rod = Rod::new(vec![Vector3::zeros(), Vector3::x()], stiffness)?;
//! let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose())?;
//! let load = EndCondition::loaded(Vector3::new(0.0, 1.0, 0.0), Vector3::zeros());
//! let solutions = solver.solve_path(&[load])?;
//! let tip = solutions[0].end_state().position;
//! assert!((tip.y - 0.301721).abs() < 2e-6);
//! # Ok(())
//! # }
//! ```

pub mod boundary;
pub mod continuation;
pub mod elastica;
pub mod error;
mod newton;
pub mod ode;
pub mod rod;
pub mod shooting;
mod so3;
pub mod solution;
pub mod tree;
pub mod tree_shooting;

pub use boundary::{EndCondition, Pose};
pub use error::{ReferenceError, Result};
pub use rod::{Rod, Stiffness};
pub use shooting::{ShootingSolver, SolverOptions, Unknowns};
pub use solution::{SectionState, Solution, Wrench};
pub use tree::Tree;
pub use tree_shooting::{TreeSolution, TreeSolver};
