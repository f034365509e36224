//! The press fit of a hose end on a stub (SPEC L6; dissertation eq. 4.105–4.107): a
//! thick-walled cylinder (the hose) on a rigid shaft (the stub), after Lamé.
//!
//! Contact pressure, with Q = r_i / r_a of the hose and radial interference δ = r_s − r_i:
//!
//! ```text
//! p = E · (δ / r_s) · (1 − Q²) / ((1 + Q²) + ν (1 − Q²))
//! ```
//!
//! (SPEC L6 form of eq. 4.106, whose μ is 1/ν here). Axial force to push the hose further
//! on or pull it off at insertion depth l (eq. 4.107):
//!
//! ```text
//! f = p · γ · 2π r_s · l,   γ = static coefficient at rest, sliding coefficient in motion
//! ```
//!
//! Which modulus: the hose wall is stretched circumferentially by the stub, so
//! [`PressFit::new`] uses the tension modulus E_t of the material (SPEC M3). This is a
//! choice — the dissertation names only "E"; [`PressFit::with_modulus`] takes any E.
//! When δ ≤ 0 (the bore is at least as wide as the stub) there is no press fit: p = 0 and
//! f = 0.

use super::bead::{Bead, Sense};
use super::error::StubError;
use super::fit_relaxation::FitTerms;
use super::spec::{Friction, StubSpec};
use pliant_core::{Material, Section};
use std::f64::consts::PI;

/// Most beads or barbs on one stub.
pub const MAX_PROFILE: usize = 8;

/// Placeholder of an unused profile slot (never read).
const EMPTY_BEAD: Bead = Bead {
    at: 0.0,
    height: 0.0,
    width: 0.0,
    entry_angle: 0.0,
    back_angle: 0.0,
};

/// Lamé contact pressure p \[Pa\] of a hose (bore radius `r_inner`, outer radius `r_outer`,
/// modulus `modulus`, Poisson's ratio `poisson`) on a rigid stub of radius `r_stub`
/// (SPEC L6). 0 when r_stub ≤ r_inner.
///
/// Errors: modulus not finite and positive; ν outside (−1, 0.5]; radii not finite, or
/// not 0 < r_inner < r_outer, or r_stub ≤ 0.
pub fn contact_pressure(
    modulus: f64,
    poisson: f64,
    r_inner: f64,
    r_outer: f64,
    r_stub: f64,
) -> Result<f64, StubError> {
    let refuse = |field, reason| StubError::PressFit { field, reason };
    if !(modulus.is_finite() && modulus > 0.0) {
        return Err(refuse("modulus", "must be finite and positive"));
    }
    if !(poisson > -1.0 && poisson <= 0.5) {
        return Err(refuse("poisson", "must lie in (-1, 0.5]"));
    }
    if !(r_inner.is_finite() && r_outer.is_finite() && r_inner > 0.0 && r_outer > r_inner) {
        return Err(refuse(
            "hose section",
            "needs finite radii with 0 < r_inner < r_outer (a hose with a bore)",
        ));
    }
    if !(r_stub.is_finite() && r_stub > 0.0) {
        return Err(refuse("stub radius", "must be finite and positive"));
    }
    let delta = r_stub - r_inner;
    if delta <= 0.0 {
        return Ok(0.0);
    }
    let q2 = (r_inner / r_outer).powi(2);
    Ok(modulus * (delta / r_stub) * (1.0 - q2) / ((1.0 + q2) + poisson * (1.0 - q2)))
}

/// One hose on one stub: the contact pressure, ready for the axial force at any depth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PressFit {
    stub: StubSpec,
    interference: f64,
    pressure: f64,
    /// The stub's profile (SPEC V4): beads or barbs along the axis in
    /// order of depth, each with the Lamé pressure of the hose wall on its crest \[Pa\];
    /// the first `profile_len` slots are used (a fixed array keeps the fit `Copy`).
    profile: [(Bead, f64); MAX_PROFILE],
    profile_len: usize,
    /// Hose radii and material, for the crest pressure.
    hose: (f64, f64, f64, f64),
    /// How the hose's modulus relaxes (empty: elastic), for the holding force over time
    /// ([`super::FitRelaxation`]).
    relaxation: FitTerms,
}

impl PressFit {
    /// The press fit of a hose with this section and material on `stub`, with E = E_t
    /// (see the module's note on the modulus).
    pub fn new(stub: &StubSpec, section: &Section, material: &Material) -> Result<Self, StubError> {
        let fit = Self::with_modulus(stub, section, material.e_tension, material.poisson)?;
        Ok(PressFit {
            relaxation: FitTerms::new(&material.relaxation),
            ..fit
        })
    }

    /// As [`PressFit::new`] with an explicit modulus E \[Pa\] and Poisson's ratio ν.
    pub fn with_modulus(
        stub: &StubSpec,
        section: &Section,
        modulus: f64,
        poisson: f64,
    ) -> Result<Self, StubError> {
        let (r_i, r_a, r_s) = (0.5 * section.d_inner, 0.5 * section.d_outer, stub.radius());
        let pressure = contact_pressure(modulus, poisson, r_i, r_a, r_s)?;
        Ok(PressFit {
            stub: *stub,
            interference: r_s - r_i,
            pressure,
            profile: [(EMPTY_BEAD, 0.0); MAX_PROFILE],
            profile_len: 0,
            hose: (modulus, poisson, r_i, r_a),
            relaxation: FitTerms::new(&[]),
        })
    }

    /// The same fit with one more bead or barb on the stub, deeper than the ones before
    /// (SPEC V4; see [`Bead`]); its crest pressure is the Lamé pressure at the crest
    /// radius r_s + h. Errors: more than [`MAX_PROFILE`] beads, or a bead starting before
    /// the previous one ends (`bead.at`).
    pub fn with_bead(mut self, bead: Bead) -> Result<Self, StubError> {
        let refuse = |reason| StubError::Spec {
            field: "bead.at",
            reason,
        };
        if self.profile_len == MAX_PROFILE {
            return Err(StubError::Spec {
                field: "profile",
                reason: "at most 8 beads or barbs",
            });
        }
        if self.beads().last().is_some_and(|prev| bead.at < prev.end()) {
            return Err(refuse(
                "must not start before the previous bead's back flank ends",
            ));
        }
        let (e, nu, r_i, r_a) = self.hose;
        let p = contact_pressure(e, nu, r_i, r_a, self.stub.radius() + bead.height)?;
        self.profile[self.profile_len] = (bead, p);
        self.profile_len += 1;
        Ok(self)
    }

    /// How the hose's modulus relaxes (no terms: elastic).
    pub fn relaxation(&self) -> &FitTerms {
        &self.relaxation
    }

    /// The fit with every contact pressure (cylinder and crests) scaled by `ratio`: the
    /// relaxed fit ([`super::FitRelaxation::ratio`]).
    pub fn relaxed(&self, ratio: f64) -> PressFit {
        let mut fit = *self;
        fit.pressure *= ratio;
        for (_, p) in &mut fit.profile[..fit.profile_len] {
            *p *= ratio;
        }
        fit
    }

    /// The first bead, if the stub has one.
    pub fn bead(&self) -> Option<&Bead> {
        self.beads().next()
    }

    /// The profile's beads and barbs, from the mouth inwards.
    pub fn beads(&self) -> impl Iterator<Item = &Bead> {
        self.profile[..self.profile_len].iter().map(|(b, _)| b)
    }

    /// Axial force \[N\] to move the hose in `sense` at insertion depth `depth`: the
    /// cylinder's [`Self::axial_force`] plus each bead's ([`Bead::force`]; the forces add:
    /// crests passed rub, the flank under the lip is climbed).
    pub fn axial_force_moving(&self, depth: f64, friction: Friction, sense: Sense) -> f64 {
        let base = self.axial_force(depth, friction);
        let l = self.stub.clamp_depth(depth);
        let gamma = self.stub.friction(friction);
        let r_s = self.stub.radius();
        base + self.profile[..self.profile_len]
            .iter()
            .map(|(b, p)| b.force(l, sense, *p, r_s, gamma))
            .sum::<f64>()
    }

    /// The stub.
    pub fn stub(&self) -> &StubSpec {
        &self.stub
    }

    /// Radial interference δ = r_s − r_i \[m\]; ≤ 0 means no press fit.
    pub fn interference(&self) -> f64 {
        self.interference
    }

    /// Contact pressure p \[Pa\] (0 when δ ≤ 0).
    pub fn pressure(&self) -> f64 {
        self.pressure
    }

    /// Axial force f = p · γ · 2π r_s · l \[N\] needed to move the hose at insertion depth
    /// `depth` (clamped to [0, length]; NaN counts as 0), with γ of the given kind
    /// (eq. 4.107). With `Friction::Static` it is the holding force.
    pub fn axial_force(&self, depth: f64, friction: Friction) -> f64 {
        let l = self.stub.clamp_depth(depth);
        self.pressure * self.stub.friction(friction) * 2.0 * PI * self.stub.radius() * l
    }

    /// The holding force at this depth: the static axial force \[N\].
    pub fn holding_force(&self, depth: f64) -> f64 {
        self.axial_force(depth, Friction::Static)
    }

    /// The static force \[N\] that starts the hose moving in `sense` at this depth.
    pub fn holding_force_moving(&self, depth: f64, sense: Sense) -> f64 {
        self.axial_force_moving(depth, Friction::Static, sense)
    }
}
