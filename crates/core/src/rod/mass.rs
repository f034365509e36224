//! Lumped masses and rotational inertias (SPEC P3).

use crate::section::SectionProperties;

/// Translational mass and (isotropic) rotational inertia a half element of length
/// `half_length` contributes to its node.
///
/// Mass: μ l₀/2, μ = ρ A (SPEC P3); ρI below is the section's rotary inertia per length. Rotational inertia: the larger of the half segment's own
/// inertias about the node — polar ρ·2I·h and transverse ρ(I h + A h³/3) — and 3ρ I h.
/// The floor 3ρ I h is the documented scaling of explicit beam codes (e.g. Belytschko,
/// Liu & Moran, "Nonlinear Finite Elements", §6.5): a node's bending stiffness is at most
/// 12 E I / l, so with I_rot ≥ 3ρ I l its rotational frequency stays below the axial one,
/// 2c/l, and rotations do not shrink the stable time step. Used isotropically (one scalar),
/// so Euler's equations lose their gyroscopic term; only dynamics of spinning
/// cross-sections are affected, statics not at all.
pub fn half_element_mass(props: &SectionProperties, half_length: f64) -> (f64, f64) {
    let (mu, rho_i) = (props.mass_per_length, props.rotary_inertia_per_length);
    let h = half_length;
    let mass = mu * h;
    let polar = 2.0 * rho_i * h;
    let transverse = rho_i * h + mu * h * h * h / 3.0;
    let floor = 3.0 * rho_i * h;
    (mass, polar.max(transverse).max(floor))
}
