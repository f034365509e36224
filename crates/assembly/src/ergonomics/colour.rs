//! Colour feedback (SPEC I4, dissertation section 5.3.7, eq. 5.13): the grabbed hose is
//! coloured by how close its hand load is to the limit — blue for no load, green at half
//! the limit, red at or above the limit, blending linearly in between.

use serde::{Deserialize, Serialize};

/// A colour with channels in [0, 1].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rgb {
    pub r: f64,
    pub g: f64,
    pub b: f64,
}

/// c = min(ratio, 1) with ratio = |f| / f_max (eq. 5.13); also clamped below at 0.
/// A NaN ratio gives 1 (red): a load that cannot be judged is shown as over the limit.
pub fn colour_value(ratio: f64) -> f64 {
    if ratio.is_nan() {
        1.0
    } else {
        ratio.clamp(0.0, 1.0)
    }
}

/// Blue (c = 0) → green (c = 0.5) → red (c ≥ 1), linear in each half. `c` is passed
/// through [`colour_value`] first, so any input gives a valid colour.
pub fn colour_rgb(c: f64) -> Rgb {
    let c = colour_value(c);
    if c <= 0.5 {
        let t = 2.0 * c;
        Rgb {
            r: 0.0,
            g: t,
            b: 1.0 - t,
        }
    } else {
        let t = 2.0 * c - 1.0;
        Rgb {
            r: t,
            g: 1.0 - t,
            b: 0.0,
        }
    }
}
