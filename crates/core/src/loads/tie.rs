//! A cable tie between two hoses: the tied node of one hose and the
//! tied node of the other are held at the distance they had when the tie closed — a stiff
//! spring and damper along the line between them, the same on both nodes with opposite
//! signs (a rod with a ball joint at each end):
//!
//! ```text
//! r = x_b − x_a,   n = r/|r|,   e = |r| − L
//! f_a = (k e + c (v_b − v_a)·n) n,   f_b = −f_a
//! ```
//!
//! It carries pull and push along n — a pulled hose drags the tied one, and the two tied
//! points keep their distance to e = |f|/k — but nothing across n: the bundle may swivel
//! about the other hose at the tie, as a tie around two round hoses lets it; the hoses' own
//! bending and their contact resist that.
//!
//! Stiffness as a fixing's support ([`super::support`]): k = [`SUPPORT_FACTOR`] · μ / Δt²
//! with μ = m_a m_b / (m_a + m_b) the pair's reduced mass — the stiffest spring the explicit
//! solver carries stably (ω Δt = √0.5); c = 2 ζ √(k μ), ζ = [`SUPPORT_DAMPING`].

use super::{SUPPORT_DAMPING, SUPPORT_FACTOR};
use crate::{Model, State};
use glam::DVec3;

/// Two nodes (normally of two hoses) held at a distance.
#[derive(Clone, Debug, PartialEq)]
pub struct Tie {
    pub nodes: [usize; 2],
    /// Rest distance L between the two nodes \[m\] (> 0).
    pub length: f64,
}

/// The tie's load and its tangent along n.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TieLoad {
    /// Force on the first node \[N\]; the second gets −force.
    pub force: DVec3,
    /// Unit vector from the first node to the second.
    pub normal: DVec3,
    /// −∂f_a/∂x_a along n: k + c · rate_factor \[N/m\].
    pub stiffness: f64,
    /// Spring energy ½ k e² \[J\].
    pub energy: f64,
}

impl Tie {
    /// Spring and damper constants (k, c) for two nodes of masses `m_a`, `m_b` in a model
    /// stepping by `dt` (module doc).
    pub fn constants(m_a: f64, m_b: f64, dt: f64) -> (f64, f64) {
        let mu = m_a * m_b / (m_a + m_b);
        let k = SUPPORT_FACTOR * mu / (dt * dt);
        (k, 2.0 * SUPPORT_DAMPING * (k * mu).sqrt())
    }

    /// The load in `state` (the model's masses and explicit step); `rate_factor` as in
    /// [`Self::load`].
    pub fn load_in(&self, model: &Model, state: &State, rate_factor: f64) -> TieLoad {
        let [a, b] = self.nodes;
        self.load(
            [state.x[a], state.x[b]],
            [state.v[a], state.v[b]],
            [model.mass[a], model.mass[b]],
            model.time_step,
            rate_factor,
        )
    }

    /// The load at positions `x` and velocities `v` (of the two nodes), masses `m`,
    /// explicit step `dt`; `rate_factor` = ∂v/∂δx (0 in statics).
    pub fn load(
        &self,
        x: [DVec3; 2],
        v: [DVec3; 2],
        m: [f64; 2],
        dt: f64,
        rate_factor: f64,
    ) -> TieLoad {
        let (k, c) = Self::constants(m[0], m[1], dt);
        let r = x[1] - x[0];
        let normal = r.normalize_or_zero();
        let stretch = r.length() - self.length;
        let rate = (v[1] - v[0]).dot(normal);
        TieLoad {
            force: normal * (k * stretch + c * rate),
            normal,
            stiffness: k + c * rate_factor,
            energy: 0.5 * k * stretch * stretch,
        }
    }
}
