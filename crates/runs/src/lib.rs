//! Running scenes: the layer above the scene file format (`pliant-scene`) that the
//! programs share — a scene's whole timeline run ([`run_with`]), session folders that
//! record a workcell's inputs and replay them bit for bit ([`session`]), and the STEP
//! converter the scene loader calls to fill its cache ([`cad_converter`]), handed to the
//! loader by [`load_options`].
//!
//! The scene crate reads and checks files and never starts a process, runs a timeline or
//! writes a file (it only makes the cache folder a converter writes into); everything
//! here does one of those.

pub mod cad_converter;
pub mod load;
pub mod run;
pub mod session;
pub mod time_limit;

pub use cad_converter::{converting, load_options, PythonStepConverter, PYTHON_STEP_CONVERTER};
pub use run::{run_with, run_within};
pub use session::Session;
