//! Pushing a hose end onto a connector stub (SPEC L6; dissertation sections 4.3.5 and
//! 5.3.5): the stub's geometry, the Lamé press fit and its friction force law, and the
//! state machine of approach, insertion, fixing and pulling off. A connector plugged
//! into its counterpart follows the same machine with a measured mating force
//! ([`Mating`]).

mod bead;
mod error;
mod fit_relaxation;
mod law;
mod mating;
mod press_fit;
mod spec;
mod state;

pub use bead::{wedge_factor, Bead, Sense};
pub use error::StubError;
pub use fit_relaxation::{FitRelaxation, FitTerms};
pub use law::{AxialLaw, StubLaw};
pub use mating::{Mating, MAX_MATING_POINTS};
pub use press_fit::{contact_pressure, PressFit, MAX_PROFILE};
pub use spec::{Friction, RawStubSpec, StubSpec};
pub use state::{StubObservation, StubState, StubTolerance};
