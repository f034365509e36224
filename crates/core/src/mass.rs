//! Lumped masses and rotational inertias (SPEC P3).

use crate::{Material, Section};

/// Translational mass and (isotropic) rotational inertia a half element of length
/// `half_length` contributes to its node.
///
/// Mass: ρ A l₀/2 (SPEC P3). Rotational inertia: the larger of the half segment's own
/// inertias about the node — polar ρ·2I·h and transverse ρ(I h + A h³/3) — and 3ρ I h.
/// The floor 3ρ I h is the documented scaling of explicit beam codes (e.g. Belytschko,
/// Liu & Moran, "Nonlinear Finite Elements", §6.5): a node's bending stiffness is at most
/// 12 E I / l, so with I_rot ≥ 3ρ I l its rotational frequency stays below the axial one,
/// 2c/l, and rotations do not shrink the stable time step. Used isotropically (one scalar),
/// so Euler's equations lose their gyroscopic term; only dynamics of spinning
/// cross-sections are affected, statics not at all.
pub fn half_element_mass(section: &Section, material: &Material, half_length: f64) -> (f64, f64) {
    let rho = material.density;
    let area = section.area();
    let i = section.second_moment();
    let h = half_length;
    let mass = rho * area * h;
    let polar = rho * 2.0 * i * h;
    let transverse = rho * (i * h + area * h * h * h / 3.0);
    let floor = 3.0 * rho * i * h;
    (mass, polar.max(transverse).max(floor))
}
