//! The one error type of calibration: it names the file and, where it can, the line
//! and column (1-based) of what is wrong. Calibration never panics on its input.

use std::fmt;

/// What went wrong, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct CalibError {
    /// The file (CSV or calibration TOML) at fault, as given.
    pub file: String,
    /// 1-based line, if the fault has one.
    pub line: Option<usize>,
    /// 1-based column (CSV field), if the fault has one.
    pub column: Option<usize>,
    /// What is wrong and what to do.
    pub message: String,
}

impl CalibError {
    pub fn file(file: &str, message: impl Into<String>) -> Self {
        Self {
            file: file.to_string(),
            line: None,
            column: None,
            message: message.into(),
        }
    }

    pub fn line(file: &str, line: usize, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            ..Self::file(file, message)
        }
    }

    pub fn cell(file: &str, line: usize, column: usize, message: impl Into<String>) -> Self {
        Self {
            line: Some(line),
            column: Some(column),
            ..Self::file(file, message)
        }
    }
}

impl fmt::Display for CalibError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for CalibError {}
