//! Conversions between the beam model's glam types and the reference solver's nalgebra
//! types, and the reference rod for a model hose.

use glam::{DQuat, DVec3};
use nalgebra::{Rotation3, UnitQuaternion, Vector3};
use pliant_core::Model;
use pliant_reference::{Pose, Rod, ShootingSolver, Stiffness};

pub fn to_na(v: DVec3) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

pub fn to_glam(v: &Vector3<f64>) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

pub fn rotation(q: DQuat) -> Rotation3<f64> {
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q.w, q.x, q.y, q.z))
        .to_rotation_matrix()
}

/// The reference's stiffness of the validation hose, library hose 1 (bimodular EA, EI,
/// GJ of its material and section).
pub fn hose1_stiffness() -> Result<Stiffness, String> {
    let (mat, sec) = crate::harness::hose1();
    Stiffness::bimodular(
        mat.e_tension * sec.area(),
        mat.e_compression * sec.area(),
        mat.bending_modulus() * sec.second_moment(),
        mat.shear_modulus() * sec.polar_moment(),
    )
    .map_err(|e| e.to_string())
}

/// A reference solver for hose `h` of `model`: same rest polyline, same EA_t, EA_c, EI₁,
/// EI₂, GJ (read from the model's first element — the validation hoses are uniform; the
/// model's section axes y, z are the reference's d2, d3 through the common base frame),
/// base clamped at the rest pose of node 0.
pub fn solver_for(model: &Model, h: usize) -> Result<ShootingSolver, String> {
    let info = &model.hoses[h];
    let e = &model.elements[info.first_element];
    let stiffness = Stiffness::bimodular(
        e.axial_stiffness_tension,
        e.axial_stiffness_compression,
        e.bending_stiffness[0],
        e.torsion_stiffness,
    )
    .and_then(|s| s.with_bending(e.bending_stiffness[0], e.bending_stiffness[1]))
    .map_err(|e| e.to_string())?;
    let nodes: Vec<Vector3<f64>> = info.nodes().map(|i| to_na(model.rest_x[i])).collect();
    let base_frame = rotation(model.rest_q[info.first_node]);
    let rod = Rod::with_base_frame(nodes, base_frame, stiffness).map_err(|e| e.to_string())?;
    let base = rod.rest_base_pose();
    ShootingSolver::new(rod, base).map_err(|e| e.to_string())
}

/// The reference end pose matching a model node pose: the model's node frame and the
/// reference's end frame differ by a constant offset fixed at rest.
pub fn end_pose(model: &Model, node: usize, rest_end: &Pose, x: DVec3, q: DQuat) -> Pose {
    let turn = q * model.rest_q[node].conjugate();
    Pose::new(to_na(x), rotation(turn) * rest_end.frame)
}
