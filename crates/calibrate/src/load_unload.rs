//! The curve of a test past yield: loaded once (the controlled quantity rising to its
//! largest value) and unloaded once (falling) — its check, and Masing's rule, which
//! gives the unloading branch of a law with linear kinematic hardening from its loading
//! curve:
//!
//! y(x) = y_mono(x_max) − 2 y_mono((x_max − x)/2)
//!
//! (Masing 1926; Lubliner, *Plasticity Theory*, 1990, §8.2): every fibre unloads
//! elastically and yields in reverse after a stress change of 2σ_y along its own loading
//! curve stretched by two. It holds for a section (moment against curvature, torque
//! against twist rate: each fibre's strain is proportional to them) and for a statically
//! determinate beam (its deflection is linear in the curvatures, each section's moment
//! proportional to the load).

use crate::error::CalibError;
use crate::mechanics::TestKind;

/// Fewest points of the unloading branch.
pub const MIN_UNLOADING_POINTS: usize = 3;

/// Fewest points of a whole load–unload curve.
pub const MIN_POINTS: usize = 8;

/// The index of the curve's largest `x` (where unloading starts) after checking that `x`
/// rises to it and falls after it, with at least [`MIN_UNLOADING_POINTS`] falling;
/// `quantity` names x in messages (e.g. "curvature", with `unit`).
pub fn peak(
    kind: TestKind,
    file: &str,
    x: &[f64],
    lines: &[usize],
    (quantity, unit): (&str, &str),
) -> Result<usize, CalibError> {
    let n = x.len();
    if n < MIN_POINTS {
        return Err(CalibError::file(
            file,
            format!(
                "too few points: {n} data rows, a {} fit needs at least {MIN_POINTS} (loading past yield and unloading)",
                kind.name()
            ),
        ));
    }
    let peak = (0..n).fold(0, |best, i| if x[i] > x[best] { i } else { best });
    for i in 1..=peak {
        if x[i] < x[i - 1] {
            return Err(CalibError::line(
                file,
                lines[i],
                format!(
                    "not monotonic: the {quantity} falls from {:.6} to {:.6} {unit} before its largest value (line {}); the test loads once, then unloads",
                    x[i - 1], x[i], lines[peak]
                ),
            ));
        }
    }
    for i in peak + 1..n {
        if x[i] > x[i - 1] {
            return Err(CalibError::line(
                file,
                lines[i],
                format!(
                    "not monotonic: the {quantity} rises from {:.6} to {:.6} {unit} while unloading; a {} test unloads once (cyclic tests trace loops)",
                    x[i - 1],
                    x[i],
                    kind.name()
                ),
            ));
        }
    }
    if n - 1 - peak < MIN_UNLOADING_POINTS {
        return Err(CalibError::line(
            file,
            lines[peak],
            format!(
                "unloading missing: the curve ends at (or {} points after) its largest {quantity} {:.6} {unit}; record at least {MIN_UNLOADING_POINTS} points of the unloading branch (the springback check needs it)",
                n - 1 - peak,
                x[peak]
            ),
        ));
    }
    Ok(peak)
}

/// y at `x` on loading (`unloading` false: `mono(x)`) or on unloading from `x_max` by
/// Masing's rule (module doc).
pub fn masing(mono: impl Fn(f64) -> f64, x_max: f64, x: f64, unloading: bool) -> f64 {
    if unloading {
        mono(x_max) - 2.0 * mono(0.5 * (x_max - x))
    } else {
        mono(x)
    }
}
