//! A junction body's own mass in the Newton solvers (SPEC N1; [`crate::rod::attached`]).
//! The body is rigid with its junction's master node m, its centre of mass at
//! c = x_m + d, d = R d₀ turning with the master. Its loads go onto the master as a
//! force and a moment about x_m:
//!
//! ```text
//! weight and damping   F = m_b (g − α v_c),  M = d × F − α J_c Ω,   v_c = v_m + Ω × d
//! inertia (implicit)   F = −m_b a_c,         M = d × F − J_c Ω̇ − Ω × J_c Ω,
//!                      a_c = a_m + Ω̇ × d + Ω × (Ω × d)
//! ```
//!
//! with J_c = R J_b Rᵀ about c. Their tangent is the rigid body's mass matrix about the
//! master (Shabana, "Dynamics of Multibody Systems", 4th ed., §3.7), scaled by the
//! derivative of the acceleration (or velocity) with respect to the master's increment,
//!
//! ```text
//! M_m = [ m_b 𝟙       −m_b [d]×              ]
//!       [ m_b [d]×    J_c − m_b [d]× [d]×    ]
//! ```
//!
//! plus the geometric term of the weight's arm turning with the master,
//! K_θθ −= \[F\]× \[d\]× (as for an offset slave in [`super::condensation`]).

use crate::rod::attached::AttachedMass;
use crate::rod::stiffened::RigidBody;
use crate::{Model, State};
use glam::{DMat3, DVec3};
use nalgebra::{Matrix3, Matrix6};

/// [v]× as a 3 × 3 matrix: [v]× u = v × u.
fn cross_matrix(v: DVec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

fn matrix3(m: DMat3) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| m.col(c)[r])
}

/// The rigid mass matrix M_m of mass `mass` centred `d` from the master, inertia `j`
/// about its centre (world axes).
fn rigid_mass_matrix(mass: f64, d: DVec3, j: DMat3) -> Matrix6<f64> {
    let dx = cross_matrix(d);
    let mut out = Matrix6::zeros();
    out.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(Matrix3::identity() * mass));
    out.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-mass * dx));
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&(mass * dx));
    out.fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&(matrix3(j) - mass * dx * dx));
    out
}

/// Each junction body with a mass of its own, with its master node.
fn owned(model: &Model) -> impl Iterator<Item = (usize, &RigidBody, &AttachedMass)> {
    model.junctions.iter().filter_map(|j| {
        let body = &model.bodies[j.body];
        body.attached.as_ref().map(|own| (j.nodes[0], body, own))
    })
}

/// Where the body's centre of mass lies from its master `m`, and its world inertia.
fn arm(body: &RigidBody, own: &AttachedMass, state: &State, m: usize) -> (DVec3, DMat3) {
    let (centre, orientation) = body.pose_from_node(0, state.x[m], state.q[m]);
    let d = centre + orientation * own.offset - state.x[m];
    (d, own.world_inertia(orientation))
}

/// Adds every junction body's own weight and mass-proportional damping to its master's
/// `force` and `moment`, and their tangent to its block of `diag` (`rate_factor`: the
/// derivative of the velocity with respect to the increment). Returns the largest weight
/// (for the load scale).
pub fn add_body_loads(
    model: &Model,
    state: &State,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    diag: &mut [Matrix6<f64>],
    rate_factor: f64,
) -> f64 {
    let alpha = model.damping_mass;
    let mut largest: f64 = 0.0;
    for (m, body, own) in owned(model) {
        let (d, j) = arm(body, own, state, m);
        let w = state.w[m];
        let weight = own.mass * model.gravity;
        let f = weight - alpha * own.mass * (state.v[m] + w.cross(d));
        force[m] += f;
        moment[m] += d.cross(f) - alpha * (j * w);
        largest = largest.max(weight.length());
        let mut k = rigid_mass_matrix(own.mass, d, j) * (alpha * rate_factor);
        let mut rr = k.fixed_view_mut::<3, 3>(3, 3);
        rr -= cross_matrix(weight) * cross_matrix(d);
        diag[m] += k;
    }
    largest
}

/// Adds every junction body's own inertia to its master's dynamic residual `rhs`
/// (force rows then moment rows) and its mass matrix times `c_acc` (the derivative of
/// the acceleration with respect to the increment) to `diag`; `acceleration(m)` gives
/// the master's translational and angular acceleration at the iterate.
pub fn add_body_inertia(
    model: &Model,
    state: &State,
    acceleration: impl Fn(usize) -> (DVec3, DVec3),
    rhs: &mut [nalgebra::Vector6<f64>],
    diag: &mut [Matrix6<f64>],
    c_acc: f64,
) {
    for (m, body, own) in owned(model) {
        let (d, j) = arm(body, own, state, m);
        let (a, alp) = acceleration(m);
        let w = state.w[m];
        let a_c = a + alp.cross(d) + w.cross(w.cross(d));
        let f = -own.mass * a_c;
        let t = d.cross(f) - j * alp - w.cross(j * w);
        rhs[m] += nalgebra::Vector6::new(f.x, f.y, f.z, t.x, t.y, t.z);
        diag[m] += rigid_mass_matrix(own.mass, d, j) * c_acc;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// M_m u is the momentum of the rigid mass moving with the master at (v, ω):
    /// p = m (v + ω × d), L_m = d × p + J ω.
    #[test]
    fn mass_matrix_gives_momentum_about_the_master() {
        let (mass, d) = (2.5, DVec3::new(0.1, -0.2, 0.05));
        let j = DMat3::from_cols(
            DVec3::new(0.3, 0.01, 0.0),
            DVec3::new(0.01, 0.2, 0.02),
            DVec3::new(0.0, 0.02, 0.25),
        );
        let (v, w) = (DVec3::new(0.4, 0.1, -0.3), DVec3::new(-1.0, 2.0, 0.5));
        let u = nalgebra::Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z);
        let out = rigid_mass_matrix(mass, d, j) * u;
        let p = mass * (v + w.cross(d));
        let l = d.cross(p) + j * w;
        for k in 0..3 {
            assert!((out[k] - p[k]).abs() < 1e-12);
            assert!((out[3 + k] - l[k]).abs() < 1e-12);
        }
    }
}
