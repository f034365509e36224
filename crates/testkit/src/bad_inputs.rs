//! Tables of bad inputs: each case breaks one thing in a valid text by replacements, and
//! the reader must refuse it without panicking, with an error that names the file, the
//! field (exactly, where the mistake is about one field) and a piece of the reason.

use std::fmt::Display;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// One bad input: replacements applied to a valid text, the field the error must name
/// (exactly, where it is about one field) and the pieces of the reason it must say.
pub struct BadInput {
    pub what: &'static str,
    pub edits: &'static [(&'static str, &'static str)],
    pub field: Option<&'static str>,
    pub message: &'static [&'static str],
}

/// What a reader must say when it refuses a case: the case's name for the test's
/// failures, the field the error must name (exactly) and the pieces of its reason.
pub struct Refusal<'a> {
    pub what: &'a str,
    pub field: Option<&'a str>,
    pub message: &'a [&'a str],
}

impl BadInput {
    /// What the reader must say when it refuses this case.
    pub fn refusal(&self) -> Refusal<'static> {
        Refusal {
            what: self.what,
            field: self.field,
            message: self.message,
        }
    }

    /// `base` with this case's edits applied, each to its first occurrence; fails the
    /// test if an edit changes nothing (the case would test the valid text).
    pub fn applied_to(&self, base: &str) -> String {
        let mut text = base.to_string();
        for (from, to) in self.edits {
            assert!(
                text.contains(from),
                "case '{}': base text does not contain {from:?}",
                self.what
            );
            text = text.replacen(from, to, 1);
        }
        text
    }
}

/// Reads each case of `cases` applied to `base` with `read` ([`check_refusals`]).
pub fn check_bad_inputs<T, E: Display>(
    base: &str,
    cases: &[BadInput],
    file: &str,
    read: impl Fn(&str) -> Result<T, E>,
    field_of: impl Fn(&E) -> Option<&str>,
) {
    let cases = cases.iter().map(|c| (c.applied_to(base), c.refusal()));
    check_refusals(cases, file, read, field_of);
}

/// Reads the text of each case with `read` (which names the file `file`), and fails the
/// test with every case whose reader panicked, accepted the text, or refused it without
/// naming the file, the case's field (as `field_of` finds it in the error, and in the
/// message) or a piece of its reason.
pub fn check_refusals<'a, T, E: Display>(
    cases: impl IntoIterator<Item = (String, Refusal<'a>)>,
    file: &str,
    read: impl Fn(&str) -> Result<T, E>,
    field_of: impl Fn(&E) -> Option<&str>,
) {
    let mut failures = Vec::new();
    for (text, case) in cases {
        let err = match catch_unwind(AssertUnwindSafe(|| read(&text))) {
            Err(_) => {
                failures.push(format!("{}: PANICKED", case.what));
                continue;
            }
            Ok(Ok(_)) => {
                failures.push(format!("{}: loaded without error", case.what));
                continue;
            }
            Ok(Err(e)) => e,
        };
        let shown = err.to_string();
        if !shown.starts_with(file) {
            failures.push(format!(
                "{}: error does not name the file: {shown}",
                case.what
            ));
        }
        if let Some(field) = case.field {
            if field_of(&err) != Some(field) {
                failures.push(format!(
                    "{}: field {:?}, expected {field:?}: {shown}",
                    case.what,
                    field_of(&err)
                ));
            }
            if !shown.contains(field) {
                failures.push(format!(
                    "{}: message does not name {field}: {shown}",
                    case.what
                ));
            }
        }
        for piece in case.message {
            if !shown.contains(piece) {
                failures.push(format!("{}: message lacks {piece:?}: {shown}", case.what));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
