//! Curvature and twist of one beam from its two node frames (SPEC V3).
//!
//! The node frames' local x axis is the hose tangent (`pliant_core::rod::frames`). The
//! rotation vector φ = log(q_a⁻¹ q_b), in node a's axes, turns node a's frame into node
//! b's over the element's rest length l₀ (a Cosserat rod's discrete Darboux vector,
//! e.g. Bergou et al. 2008, "Discrete elastic rods", eq. 4): its x part over l₀ is the
//! twist rate τ = φₓ / l₀ [rad/m], its y/z part the curvature κ = |(φ_y, φ_z)| / l₀
//! [1/m], whose inverse is the bend radius. For a circular arc (a hose rolled up by an
//! end moment M, κ = M / EI) the frames turn uniformly and κ is exact.

use glam::{DQuat, DVec3};
use pliant_core::math::log_map;
use pliant_core::{Model, State};

/// (curvature κ [1/m], twist rate τ [rad/m]) of a beam of rest length `rest_length`
/// \[m\] whose end frames are `qa` and `qb`.
pub fn bend_and_twist(qa: DQuat, qb: DQuat, rest_length: f64) -> (f64, f64) {
    let mut rel = (qa.conjugate() * qb).normalize();
    if rel.w < 0.0 {
        rel = -rel; // the shorter way round
    }
    let phi: DVec3 = log_map(rel);
    let bend = (phi.y * phi.y + phi.z * phi.z).sqrt();
    (bend / rest_length, phi.x / rest_length)
}

/// The axial strain of element `e` in `state`: the element's own, chord and shallow arch
/// measured from its rest shape ([`pliant_core::rod::element::BeamElement::axial_strain`]) —
/// the chord alone would read a bent element's shorter chord, or a curved one
/// straightened, as strain.
pub fn axial_strain(model: &Model, state: &State, e: usize) -> f64 {
    let el = &model.elements[e];
    let (a, b) = (el.node_a, el.node_b);
    el.axial_strain(&el.deformation([state.x[a], state.x[b]], [state.q[a], state.q[b]]))
}

/// The axial force \[N\] of element `e` in `state`: its [`axial_strain`] times E_t·A
/// stretched, E_c·A shortened (negative).
pub fn axial_force(model: &Model, state: &State, e: usize) -> f64 {
    let el = &model.elements[e];
    let strain = axial_strain(model, state, e);
    let ea = if strain >= 0.0 {
        el.axial_stiffness_tension
    } else {
        el.axial_stiffness_compression
    };
    strain * ea
}
