//! Pliant's physics core: co-rotational 3-D Euler–Bernoulli beams (SPEC P1) with
//! quaternion node frames (P2), lumped masses (P3), explicit central-difference dynamics
//! (P4), gravity and Rayleigh damping (P6), and the load cases fix, drive and dead load
//! (L1–L3). Plain data and functions: no files or sockets; the explicit step may share
//! its work with helper threads ([`parallel`]), with the same results on any number.
//!
//! Calling convention (as MuJoCo's): a [`Model`] is built once from a [`WorldSpec`]; a
//! [`State`] holds everything that changes; [`integrators::explicit::step`]`(&model, &mut
//! state)` advances it (the implicit and quasi-static solvers: [`Solver`]).

pub mod autodiff;
pub mod body_loads;
pub mod contact;
pub mod curve;
pub mod element;
pub mod element_block;
pub mod forces;
pub mod frames;
pub mod health;
pub mod integrators;
pub mod junction;
pub mod lane_arith;
pub mod lanes;
pub mod loads;
pub mod mass;
pub mod material;
pub mod math;
pub mod model;
pub mod newton;
pub mod parallel;
pub mod section;
pub mod settle;
pub mod sleep;
pub mod spec;
pub mod state;
pub mod stiffened;
pub mod tangent;
pub mod tangent_kernel;
#[cfg(test)]
mod test_elements;
pub mod timestep;

pub use health::Divergence;
pub use integrators::{Solver, SolverKind, SolverSettings, StepStats};
pub use junction::{HoseEnd, Junction, JunctionSpec};
pub use material::Material;
pub use model::{HoseInfo, Model, ModelError};
pub use section::{GivenStiffness, Section, SectionProperties};
pub use spec::{HoseSpec, RigidPartSpec, SimSettings, WorldSpec};
pub use state::State;
