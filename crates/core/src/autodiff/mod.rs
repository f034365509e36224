//! Forward-mode automatic differentiation for the consistent tangent stiffness:
//! the element's load function is written once, generic over a [`Scalar`]; evaluated with
//! `f64` it is the explicit solver's load function, evaluated with [`Dual`] numbers it
//! also yields the exact derivatives of the loads with respect to the nodes' position and
//! rotation increments — the element tangent the Newton solvers need (Griewank & Walther,
//! "Evaluating Derivatives", 2008, ch. 3).
//!
//! A small dual type of our own rather than the `num-dual` crate: the element code needs
//! `Copy` scalars with a fixed, stack-allocated derivative part (12 entries), and the
//! handful of operations below is all it uses.

mod dual;
mod lane_dual;
mod scalar;
mod vector;

pub use dual::Dual;
pub use lane_dual::LaneDual;
pub use scalar::Scalar;
pub use vector::{Quat, V3};
