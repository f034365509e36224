//! What a fastener is and which state it ended in, as typed values the reports and the
//! verdict decide on and name (SPEC L6, L7).

use crate::clip::ClipState;
use crate::stub::StubState;
use serde::Serialize;
use std::fmt;

/// The kind of a fastener: a press-fit stub, a connector's counterpart or a clip.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FastenerKind {
    #[default]
    Stub,
    Connector,
    Clip,
}

impl FastenerKind {
    /// The name the reports and `fasteners.csv` use: "stub", "connector" or "clip".
    pub fn name(self) -> &'static str {
        match self {
            FastenerKind::Stub => "stub",
            FastenerKind::Connector => "connector",
            FastenerKind::Clip => "clip",
        }
    }
}

impl fmt::Display for FastenerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The state a fastener is in: a stub's ([`StubState`]), a connector's once released on
/// its counterpart (latched or half mated) or a clip's ([`ClipState`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FastenerState {
    /// Stub or connector: not engaged.
    #[default]
    Approach,
    /// In front of the mouth, aligned with the axis.
    Aligned,
    /// On the stub and moving with the hand.
    Inserting,
    /// Released on the stub.
    Fixed,
    /// Just pulled off the stub.
    PulledOff,
    /// A connector released on its counterpart with its latch engaged.
    Latched,
    /// A connector released on its counterpart short of its latch.
    HalfMated,
    /// Clip: not engaged.
    Free,
    /// Clip: the snap force acts.
    Snapping,
    /// Clip: seated.
    Seated,
}

impl FastenerState {
    /// The name the reports use (e.g. "fixed", "seated", "approach").
    pub fn name(self) -> &'static str {
        match self {
            FastenerState::Approach => "approach",
            FastenerState::Aligned => "aligned",
            FastenerState::Inserting => "inserting",
            FastenerState::Fixed => "fixed",
            FastenerState::PulledOff => "pulled_off",
            FastenerState::Latched => "latched",
            FastenerState::HalfMated => "half_mated",
            FastenerState::Free => "free",
            FastenerState::Snapping => "snapping",
            FastenerState::Seated => "seated",
        }
    }
}

impl fmt::Display for FastenerState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl From<StubState> for FastenerState {
    fn from(s: StubState) -> Self {
        match s {
            StubState::Approach => FastenerState::Approach,
            StubState::Aligned => FastenerState::Aligned,
            StubState::Inserting { .. } => FastenerState::Inserting,
            StubState::Fixed { .. } => FastenerState::Fixed,
            StubState::PulledOff => FastenerState::PulledOff,
        }
    }
}

impl From<ClipState> for FastenerState {
    fn from(s: ClipState) -> Self {
        match s {
            ClipState::Free => FastenerState::Free,
            ClipState::Snapping => FastenerState::Snapping,
            ClipState::Seated => FastenerState::Seated,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names are the serialised forms (what `report.json` has always carried).
    #[test]
    fn names_are_the_serialised_forms() {
        let states = [
            FastenerState::Approach,
            FastenerState::Aligned,
            FastenerState::Inserting,
            FastenerState::Fixed,
            FastenerState::PulledOff,
            FastenerState::Latched,
            FastenerState::HalfMated,
            FastenerState::Free,
            FastenerState::Snapping,
            FastenerState::Seated,
        ];
        for s in states {
            assert_eq!(serde_json::to_value(s).unwrap(), s.name());
        }
        for k in [
            FastenerKind::Stub,
            FastenerKind::Connector,
            FastenerKind::Clip,
        ] {
            assert_eq!(serde_json::to_value(k).unwrap(), k.name());
        }
        let on_stub = FastenerState::from(StubState::Fixed { depth: 0.01 });
        assert_eq!(on_stub.name(), "fixed");
    }
}
