//! The worker model's errors: what was wrong, in which field, and why — never a panic on
//! a user's input.

use thiserror::Error;

/// A bad value for the worker model.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum WorkerError {
    /// A field of a worker description (a scene's `[worker]`, a study parameter) has a
    /// value the model cannot take.
    #[error("{field} = {value}: {reason}")]
    Field {
        field: String,
        value: String,
        reason: String,
    },
    /// The built-in data table (`data/anthropometry.toml`) is broken: a build error.
    #[error("the built-in anthropometry table: {0}")]
    Data(String),
}

impl WorkerError {
    pub fn field(field: &str, value: impl std::fmt::Display, reason: impl Into<String>) -> Self {
        WorkerError::Field {
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}
