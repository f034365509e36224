//! Pliant's validation suite (SPEC §7): each case runs the explicit beam model on
//! a problem with an exact or independently computed answer and reports one row per
//! compared quantity. `pliant validate` prints them; the tests assert them; the table in
//! docs/validation.md is generated from them.

pub mod cases;
/// The exact elastica lives with the independent reference solver.
pub use pliant_reference::elastica;
pub mod harness;
pub mod markdown;
pub mod reference_bridge;
pub mod result;

pub use result::{CaseFn, Check};

/// Every case, by name, in report order.
pub fn all_cases() -> Vec<(&'static str, CaseFn)> {
    cases::ALL.to_vec()
}

/// Runs the named case (or all when `only` is None).
pub fn run(only: Option<&str>) -> Result<Vec<Check>, String> {
    let cases = all_cases();
    if let Some(name) = only {
        if !cases.iter().any(|(n, _)| *n == name) {
            let names: Vec<&str> = cases.iter().map(|(n, _)| *n).collect();
            return Err(format!(
                "unknown validation case '{name}'; cases are: {}",
                names.join(", ")
            ));
        }
    }
    Ok(cases
        .into_iter()
        .filter(|(n, _)| only.is_none_or(|o| o == *n))
        .flat_map(|(_, f)| f())
        .collect())
}
