//! One compared quantity of a validation case.

use serde::Serialize;

/// A validation case: runs and returns its checks.
pub type CaseFn = fn() -> Vec<Check>;

/// One row of the validation report. `error` and `tolerance` are relative unless the
/// quantity's name ends in `_abs` (absolute, in the quantity's unit) or says otherwise.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    pub case: String,
    pub quantity: String,
    pub computed: f64,
    pub reference: f64,
    pub error: f64,
    pub tolerance: f64,
    pub pass: bool,
}

impl Check {
    /// Relative error |computed − reference| / |reference|.
    pub fn relative(
        case: &str,
        quantity: &str,
        computed: f64,
        reference: f64,
        tolerance: f64,
    ) -> Check {
        let error = (computed - reference).abs() / reference.abs().max(f64::MIN_POSITIVE);
        Check::with_error(case, quantity, computed, reference, error, tolerance)
    }

    /// Error relative to a given scale (e.g. the hose length or the peak force).
    pub fn scaled(
        case: &str,
        quantity: &str,
        computed: f64,
        reference: f64,
        scale: f64,
        tolerance: f64,
    ) -> Check {
        let error = (computed - reference).abs() / scale;
        Check::with_error(case, quantity, computed, reference, error, tolerance)
    }

    /// A check with an error already computed.
    pub fn with_error(
        case: &str,
        quantity: &str,
        computed: f64,
        reference: f64,
        error: f64,
        tolerance: f64,
    ) -> Check {
        Check {
            case: case.into(),
            quantity: quantity.into(),
            computed,
            reference,
            error,
            tolerance,
            pass: error.is_finite() && error <= tolerance,
        }
    }

    /// A check that failed to produce a number at all (e.g. the run diverged).
    pub fn failed(case: &str, quantity: &str, why: &str) -> Check {
        eprintln!("{case}/{quantity}: {why}");
        Check::with_error(case, quantity, f64::NAN, f64::NAN, f64::INFINITY, 0.0)
    }
}
