//! Errors of the connector-stub load case (SPEC L6).

/// A stub, press fit or observation that cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StubError {
    /// A stub parameter out of range.
    #[error("stub {field}: {reason}")]
    Spec {
        /// The parameter, e.g. "diameter".
        field: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
    /// A hose section or material that cannot form a press fit.
    #[error("press fit {field}: {reason}")]
    PressFit {
        /// The parameter, e.g. "poisson".
        field: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
    /// An observation or tolerance the state machine cannot use.
    #[error("stub state {field}: {reason}")]
    Observation {
        /// The input, e.g. "end_direction".
        field: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
}
