//! Snapping a hose into a clip (SPEC L7; dissertation sections 4.3.6 and 5.3.6): the
//! clip's geometry, its force law along the opening, and the state machine of engaging,
//! seating and pulling out.

mod error;
mod force;
mod hold;
mod kind;
mod spec;
mod state;

pub use error::ClipError;
pub use kind::ClipKind;
pub use spec::{ClipSpec, RawClipSpec};
pub use state::{ClipObservation, ClipState, ClipTolerance};
