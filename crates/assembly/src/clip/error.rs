//! Errors of the clip load case (SPEC L7).

/// A clip or observation that cannot be used.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ClipError {
    /// A clip parameter out of range.
    #[error("clip {field}: {reason}")]
    Spec {
        /// The parameter, e.g. "opening_width".
        field: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
    /// An observation or tolerance the state machine cannot use.
    #[error("clip state {field}: {reason}")]
    Observation {
        /// The input, e.g. "radius".
        field: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
}
