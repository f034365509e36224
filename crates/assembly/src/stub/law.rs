//! What resists a hose end moving along a stub's axis: the press fit of a hose on a stub
//! ([`PressFit`], Lamé and friction) or a connector's measured mating force ([`Mating`]).
//! The state machine ([`super::StubState`]) and the runtime use either through
//! [`AxialLaw`].

use super::bead::Sense;
use super::mating::Mating;
use super::press_fit::PressFit;
use super::spec::{Friction, StubSpec};
use crate::fastener_state::FastenerKind;

/// An axial force law on a stub's geometry.
pub trait AxialLaw {
    /// The geometry: mouth, axis, length, diameter.
    fn stub(&self) -> &StubSpec;

    /// Force \[N\] to move the end in `sense` at insertion depth `depth` \[m\], with the
    /// friction of the given kind where the law has friction.
    fn axial_force_moving(&self, depth: f64, friction: Friction, sense: Sense) -> f64;

    /// The static force \[N\] that starts the end moving in `sense` at this depth.
    fn holding_force_moving(&self, depth: f64, sense: Sense) -> f64 {
        self.axial_force_moving(depth, Friction::Static, sense)
    }

    /// Whether an end released at this depth is assembled (a press fit: anywhere on the
    /// stub; a connector: latched).
    fn assembled_at(&self, depth: f64) -> bool;

    /// Whether an end found past the mouth without having come through it (a fast move, a
    /// hose drawn on the stub) is taken as inserting (a press fit) or left to approach
    /// (a plug must enter its counterpart through the mouth: a harness is drawn with its
    /// plugs home, and the worker brings each plug out to the mouth first).
    fn enters_through_mouth(&self) -> bool {
        false
    }

    /// A force scale \[N\] for the stop at the stub's length (the penalty that keeps the end
    /// from going further), at least 1 N.
    fn stop_force(&self) -> f64;
}

impl AxialLaw for PressFit {
    fn stub(&self) -> &StubSpec {
        PressFit::stub(self)
    }

    fn axial_force_moving(&self, depth: f64, friction: Friction, sense: Sense) -> f64 {
        PressFit::axial_force_moving(self, depth, friction, sense)
    }

    fn assembled_at(&self, _depth: f64) -> bool {
        true
    }

    /// The holding force at full depth (eq. 4.107).
    fn stop_force(&self) -> f64 {
        self.holding_force(self.stub().length()).max(1.0)
    }
}

impl AxialLaw for Mating {
    fn stub(&self) -> &StubSpec {
        self.counterpart()
    }

    /// The measured curve is the force while moving and to start moving alike: the
    /// friction kind does not enter.
    fn axial_force_moving(&self, depth: f64, _friction: Friction, sense: Sense) -> f64 {
        self.force_moving(depth, sense)
    }

    fn assembled_at(&self, depth: f64) -> bool {
        self.latched(depth)
    }

    fn enters_through_mouth(&self) -> bool {
        true
    }

    /// The mating force at full travel.
    fn stop_force(&self) -> f64 {
        self.mating_force(self.counterpart().length()).max(1.0)
    }
}

/// The law of one stub site: a hose end on a stub, or a connector plugged.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // one per stub site, and Copy: boxing would cost more
pub enum StubLaw {
    PressFit(PressFit),
    Mating(Mating),
}

impl StubLaw {
    /// The press fit, if this is a stub.
    pub fn press_fit(&self) -> Option<&PressFit> {
        match self {
            StubLaw::PressFit(f) => Some(f),
            StubLaw::Mating(_) => None,
        }
    }

    /// The law with a press fit's pressures scaled by `ratio` (its relaxation,
    /// [`super::FitRelaxation`]); a connector's mating force does not relax.
    pub fn relaxed(&self, ratio: f64) -> StubLaw {
        match self {
            StubLaw::PressFit(f) => StubLaw::PressFit(f.relaxed(ratio)),
            StubLaw::Mating(m) => StubLaw::Mating(*m),
        }
    }

    /// The fastener's kind: a stub or a connector.
    pub fn kind(&self) -> FastenerKind {
        match self {
            StubLaw::PressFit(_) => FastenerKind::Stub,
            StubLaw::Mating(_) => FastenerKind::Connector,
        }
    }
}

impl From<PressFit> for StubLaw {
    fn from(fit: PressFit) -> Self {
        StubLaw::PressFit(fit)
    }
}

impl From<Mating> for StubLaw {
    fn from(mating: Mating) -> Self {
        StubLaw::Mating(mating)
    }
}

impl AxialLaw for StubLaw {
    fn stub(&self) -> &StubSpec {
        match self {
            StubLaw::PressFit(f) => AxialLaw::stub(f),
            StubLaw::Mating(m) => AxialLaw::stub(m),
        }
    }

    fn axial_force_moving(&self, depth: f64, friction: Friction, sense: Sense) -> f64 {
        match self {
            StubLaw::PressFit(f) => AxialLaw::axial_force_moving(f, depth, friction, sense),
            StubLaw::Mating(m) => AxialLaw::axial_force_moving(m, depth, friction, sense),
        }
    }

    fn assembled_at(&self, depth: f64) -> bool {
        match self {
            StubLaw::PressFit(f) => f.assembled_at(depth),
            StubLaw::Mating(m) => m.assembled_at(depth),
        }
    }

    fn stop_force(&self) -> f64 {
        match self {
            StubLaw::PressFit(f) => f.stop_force(),
            StubLaw::Mating(m) => m.stop_force(),
        }
    }

    fn enters_through_mouth(&self) -> bool {
        matches!(self, StubLaw::Mating(_))
    }
}
