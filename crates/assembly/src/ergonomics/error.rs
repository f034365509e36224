//! Errors of the ergonomics layer (SPEC I3–I5).

/// What can go wrong when reading limits, profiles or hand loads.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ErgonomicsError {
    /// A name (posture, population, duty, …) that is not one of the allowed values.
    #[error("unknown {what} `{given}`; allowed: {allowed}")]
    UnknownName {
        /// What was being named, e.g. "pull posture".
        what: &'static str,
        /// The text as given.
        given: String,
        /// The allowed names, comma-separated.
        allowed: String,
    },
    /// A limits file that does not parse or fails a plausibility check.
    #[error("ergonomic limits file: {0}")]
    File(String),
    /// A profile string that does not parse.
    #[error("ergonomic profile `{given}`: {reason}")]
    Profile {
        /// The profile text as given.
        given: String,
        /// Why it was refused.
        reason: String,
    },
    /// A hand force, torque or reference direction that cannot be classified.
    #[error("{what}: {reason}")]
    BadInput {
        /// Which input, e.g. "reference direction".
        what: &'static str,
        /// Why it was refused.
        reason: &'static str,
    },
}
