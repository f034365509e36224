//! Errors of the scene loader. Every error names where it happened (file and, where the
//! parser knows it, line and column), the field path (`hoses[1].section.d_inner`), the
//! offending value where there is one, and the reason.

use std::fmt;

/// Why a scene could not be loaded. Nothing is ever half-loaded: a load either returns a
/// complete scene or one of these.
#[derive(Debug)]
pub enum SceneError {
    /// The file could not be read.
    Io {
        /// The path as given.
        path: String,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The text is not valid TOML / JSON.
    Syntax {
        /// File name or other description of where the text came from.
        origin: String,
        /// 1-based line and column of the problem, where known.
        location: Option<(usize, usize)>,
        /// The parser's message.
        message: String,
    },
    /// The text is valid TOML / JSON but does not have the scene file's shape: a missing
    /// or unknown field, a wrong type, an unknown enumeration value.
    Structure {
        /// File name or other description of where the text came from.
        origin: String,
        /// 1-based line and column of the problem, where known.
        location: Option<(usize, usize)>,
        /// Field path, e.g. `hoses[0].section`; `.` for the top level.
        field: String,
        /// The parser's message.
        message: String,
    },
    /// A value has the right type but is not acceptable (out of range, inconsistent with
    /// another value, refers to something that does not exist).
    Invalid {
        /// File name or other description of where the text came from.
        origin: String,
        /// The field, its value and the reason.
        error: FieldError,
    },
    /// The built-in material library is broken (a build defect, never the user's input).
    Library {
        /// What is wrong with it.
        message: String,
    },
}

impl SceneError {
    /// The field path the error is about, if it is about one field.
    pub fn field(&self) -> Option<&str> {
        match self {
            SceneError::Structure { field, .. } => Some(field),
            SceneError::Invalid { error, .. } => Some(&error.field),
            _ => None,
        }
    }

    /// 1-based line and column, where the parser knows them.
    pub fn location(&self) -> Option<(usize, usize)> {
        match self {
            SceneError::Syntax { location, .. } | SceneError::Structure { location, .. } => {
                *location
            }
            _ => None,
        }
    }
}

/// Writes `origin:line:column` or just `origin`.
fn write_origin(
    f: &mut fmt::Formatter<'_>,
    origin: &str,
    location: Option<(usize, usize)>,
) -> fmt::Result {
    match location {
        Some((line, column)) => write!(f, "{origin}:{line}:{column}"),
        None => write!(f, "{origin}"),
    }
}

impl fmt::Display for SceneError {
    /// The message, with echoed user text clipped ([`crate::clip`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let whole = UnclippedScene(self).to_string();
        f.write_str(&crate::clip::clip_words(&whole))
    }
}

/// [`SceneError`]'s message before clipping.
struct UnclippedScene<'a>(&'a SceneError);

impl fmt::Display for UnclippedScene<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            SceneError::Io { path, source } => {
                write!(f, "{path}: cannot read scene file: {source}")
            }
            SceneError::Syntax {
                origin,
                location,
                message,
            } => {
                write_origin(f, origin, *location)?;
                write!(f, ": syntax error: {message}")
            }
            SceneError::Structure {
                origin,
                location,
                field,
                message,
            } => {
                write_origin(f, origin, *location)?;
                write!(f, ": {field}: {message}")
            }
            SceneError::Invalid { origin, error } => write!(f, "{origin}: {error}"),
            SceneError::Library { message } => {
                write!(f, "built-in material library is invalid: {message}")
            }
        }
    }
}

impl std::error::Error for SceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SceneError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// A value that is not acceptable: which field, what it was, and why not.
/// Displayed as `field = value: reason` (or `field: reason` when there is no single value).
#[derive(Clone, Debug, PartialEq)]
pub struct FieldError {
    /// Field path, e.g. `hoses[1].section.d_inner`.
    pub field: String,
    /// The offending value as written, with its unit (`40 mm`), if there is one.
    pub value: Option<String>,
    /// Why it is not acceptable, e.g. `must be smaller than d_outer (35 mm)`.
    pub reason: String,
}

impl FieldError {
    /// An error about `field` having `value`.
    pub fn new(
        field: impl Into<String>,
        value: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            field: field.into(),
            value: Some(value.into()),
            reason: reason.into(),
        }
    }

    /// An error about `field` as a whole (missing, empty, inconsistent).
    pub fn about(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            value: None,
            reason: reason.into(),
        }
    }

    /// Attaches the origin, turning this into a [`SceneError`].
    pub fn at(self, origin: &str) -> SceneError {
        SceneError::Invalid {
            origin: origin.to_string(),
            error: self,
        }
    }
}

impl fmt::Display for FieldError {
    /// `field = value: reason`, with echoed user text clipped ([`crate::clip`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let whole = match &self.value {
            Some(value) => format!("{} = {}: {}", self.field, value, self.reason),
            None => format!("{}: {}", self.field, self.reason),
        };
        f.write_str(&crate::clip::clip_words(&whole))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_reads_field_value_reason() {
        let e = FieldError::new(
            "hoses[1].section.d_inner",
            "40 mm",
            "must be smaller than d_outer (35 mm)",
        )
        .at("scene.toml");
        assert_eq!(
            e.to_string(),
            "scene.toml: hoses[1].section.d_inner = 40 mm: must be smaller than d_outer (35 mm)"
        );
        assert_eq!(e.field(), Some("hoses[1].section.d_inner"));
    }

    #[test]
    fn structure_has_location() {
        let e = SceneError::Structure {
            origin: "a.toml".into(),
            location: Some((3, 7)),
            field: "hoses[0]".into(),
            message: "unknown field `sectoin`".into(),
        };
        assert_eq!(
            e.to_string(),
            "a.toml:3:7: hoses[0]: unknown field `sectoin`"
        );
        assert_eq!(e.location(), Some((3, 7)));
    }
}
