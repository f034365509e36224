//! A bead on a stub (SPEC V4): a ring of height h standing on the stub at some depth,
//! with a gentle entry flank (angle α_in to the axis, towards the mouth), a crest of
//! width w and a steep back flank (α_back). The dissertation measured ≈ 300 N only when
//! pulling hose 3 off its stub, "because the stub thickens and so resists the hose more
//! when it is pulled off" (section 3.3.3, figures 3.30 / 3.31).
//!
//! Hand calculation (a sleeve driven up a cone with Coulomb friction, as a wedge):
//! the hose wall stretched over the crest presses on it with the Lamé pressure
//! p_b = p(r_b) of [`super::contact_pressure`] at the crest radius r_b = r_s + h; the
//! hose end's lip bears on a flank with the radial force N = p_b · 2π r_b · w. Driving
//! the lip up a flank of angle α against friction γ takes the axial force
//!
//! ```text
//! F = N · (tan α + γ) / (1 − γ tan α)        (self-locking when γ tan α ≥ 1)
//! ```
//!
//! Pushing on, the lip climbs the entry flank (depth d ∈ [a, a + h / tan α_in], a the
//! bead's start); pulling off, it climbs the back flank
//! (d ∈ [a + h / tan α_in + w, a + h / tan α_in + w + h / tan α_back]). Once past the
//! crest the wall on it adds p_b γ 2π r_b w of friction both ways. The cylinder's own
//! press fit (eq. 4.107) acts as before.

use super::error::StubError;
use serde::{Deserialize, Serialize};

/// Which way the hose moves on the stub.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    /// Further on (depth increasing).
    On,
    /// Off (depth decreasing).
    Off,
}

/// A bead, checked. All SI (m, rad).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bead {
    /// Depth of the start of its entry flank from the mouth \[m\].
    pub at: f64,
    /// Radial height above the stub \[m\].
    pub height: f64,
    /// Width of its crest \[m\].
    pub width: f64,
    /// Angle of the entry flank to the axis \[rad\], in (0, π/2).
    pub entry_angle: f64,
    /// Angle of the back flank to the axis \[rad\], in (0, π/2).
    pub back_angle: f64,
}

/// Axial force per unit radial force to drive a lip up a flank of angle `alpha` \[rad\]
/// against friction `gamma`: (tan α + γ) / (1 − γ tan α); ∞ when self-locking.
pub fn wedge_factor(alpha: f64, gamma: f64) -> f64 {
    let t = alpha.tan();
    let d = 1.0 - gamma * t;
    if d <= 0.0 {
        f64::INFINITY
    } else {
        (t + gamma) / d
    }
}

impl Bead {
    /// Checks a bead: finite, at ≥ 0, positive height and width, angles in (0, 90°).
    pub fn new(
        at: f64,
        height: f64,
        width: f64,
        entry_angle: f64,
        back_angle: f64,
    ) -> Result<Bead, StubError> {
        let refuse = |field, reason| StubError::Spec { field, reason };
        if !(at.is_finite() && at >= 0.0) {
            return Err(refuse("bead.at", "must be finite and >= 0"));
        }
        if !(height.is_finite() && height > 0.0) {
            return Err(refuse("bead.height", "must be finite and positive"));
        }
        if !(width.is_finite() && width > 0.0) {
            return Err(refuse("bead.width", "must be finite and positive"));
        }
        let angle = |a: f64| a.is_finite() && a > 0.0 && a < std::f64::consts::FRAC_PI_2;
        if !angle(entry_angle) {
            return Err(refuse("bead.entry_angle", "must lie in (0, 90) degrees"));
        }
        if !angle(back_angle) {
            return Err(refuse("bead.back_angle", "must lie in (0, 90) degrees"));
        }
        Ok(Bead {
            at,
            height,
            width,
            entry_angle,
            back_angle,
        })
    }

    /// Depth where the crest begins (the end of the entry flank) \[m\].
    pub fn crest_start(&self) -> f64 {
        self.at + self.height / self.entry_angle.tan()
    }

    /// Depth where the back flank ends (the whole bead passed) \[m\].
    pub fn end(&self) -> f64 {
        self.crest_start() + self.width + self.height / self.back_angle.tan()
    }

    /// The extra axial force \[N\] the bead opposes to moving the hose in `sense` at
    /// depth `depth` \[m\], with the crest pressure `p_crest` \[Pa\] (Lamé at r_s + h), the
    /// stub radius `r_stub` \[m\] and friction `gamma` (see the module's hand calculation).
    pub fn force(&self, depth: f64, sense: Sense, p_crest: f64, r_stub: f64, gamma: f64) -> f64 {
        let r_b = r_stub + self.height;
        let n = p_crest * 2.0 * std::f64::consts::PI * r_b * self.width;
        let crest_friction = if depth > self.crest_start() {
            n * gamma
        } else {
            0.0
        };
        let back_start = self.crest_start() + self.width;
        let flank = match sense {
            Sense::On if (self.at..=self.crest_start()).contains(&depth) => {
                n * wedge_factor(self.entry_angle, gamma)
            }
            Sense::Off if (back_start..=self.end()).contains(&depth) => {
                n * wedge_factor(self.back_angle, gamma)
            }
            _ => 0.0,
        };
        crest_friction + flank
    }
}
