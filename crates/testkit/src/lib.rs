//! What the workspace's tests share, in one place: the dissertation's library hoses typed
//! out as core materials and sections ([`hoses`]), small models built from them
//! ([`models`]), mini-scenes in the scene format ([`scenes`]) and a builder of scene text from
//! typed pieces ([`scene_text`]), tables of bad inputs a
//! reader must refuse ([`bad_inputs`]), deterministic pseudo-random numbers ([`random`])
//! and the repository's real data files ([`files`]).
//! A dev-dependency of the crates' integration tests, never of a library.

pub mod bad_inputs;
pub mod files;
pub mod hoses;
pub mod models;
pub mod random;
pub mod scene_text;
pub mod scenes;

pub use hoses::{hose1, hose1_material, hose1_section, hose3};
pub use models::{hose3_along_x, straight_hose1};
pub use random::Lcg;
