//! Pliant's physics core: co-rotational 3-D Euler–Bernoulli beams (SPEC P1) with
//! quaternion node frames (P2), lumped masses (P3), explicit central-difference dynamics
//! (P4), gravity and Rayleigh damping (P6), and the load cases fix, drive and dead load
//! (L1–L3). Plain data and functions: no files, threads or sockets.

pub mod material;
pub mod section;
pub mod spec;

pub use material::Material;
pub use section::Section;
pub use spec::{HoseSpec, SimSettings, WorldSpec};
