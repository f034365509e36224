//! Pliant's physics core: co-rotational 3-D Euler–Bernoulli beams (SPEC P1) with
//! quaternion node frames (P2), lumped masses (P3), explicit central-difference dynamics
//! (P4), gravity and Rayleigh damping (P6), and the load cases fix, drive and dead load
//! (L1–L3). Plain data and functions: no files or sockets; the explicit step may share
//! its work with helper threads ([`parallel`]), with the same results on any number.
//!
//! Calling convention (as MuJoCo's): a [`Model`] is built once from a [`WorldSpec`]; a
//! [`State`] holds everything that changes; [`integrators::explicit::step`]`(&model, &mut
//! state)` advances it (the implicit and quasi-static solvers: [`Solver`]).
//!
//! The modules are layered; a module uses only modules of its own layer or below
//! (`tests/layering.rs` checks the data layer and the kernels):
//!
//! 1. plain data — [`spec`], [`settings`], [`model`], [`state`], [`material`],
//!    [`section`], [`junction`], [`curve`], [`math`];
//! 2. kernels — [`rod`] (the co-rotational element, its four-lane kernel and tangent,
//!    masses, frames, stiffened sections, the stable time step), [`autodiff`];
//! 3. loads and contact — [`kinematics`] (parts that move), [`loads`], [`contact`];
//! 4. Newton — [`newton`];
//! 5. solvers — [`integrators`], [`relax`];
//!
//! beside the run support used by several layers: [`health`], [`sleep`], [`parallel`].

pub mod autodiff;
pub mod contact;
pub mod curve;
pub mod health;
pub mod integrators;
pub mod junction;
pub mod junction_shape;
pub mod kinematics;
pub mod loads;
pub mod material;
pub mod math;
pub mod model;
pub mod newton;
pub mod parallel;
pub mod relax;
pub mod rod;
pub mod section;
pub mod settings;
pub mod sleep;
pub mod spec;
pub mod state;

pub use health::Divergence;
pub use integrators::{Solver, StepStats};
pub use junction::{HoseEnd, Junction, JunctionSpec, OwnMass};
pub use material::Material;
pub use model::{HoseInfo, Model, ModelError};
pub use section::{GivenStiffness, Section, SectionProperties};
pub use settings::{SolverKind, SolverSettings};
pub use spec::{DeliveredShape, HoseSpec, RigidPartSpec, SimSettings, WorldSpec};
pub use state::State;
