//! A junction body's shape in the Newton solvers (SPEC N1; [`crate::junction_shape`]):
//! hose nodes touch the shape, posed from the body's master node, and the contact's
//! reaction acts on the body.
//!
//! The body is rigid with its junction's master node m ([`super::condensation`]), so
//! its shape's pose follows from the master's (x_m, q_m) as the explicit solver's does
//! from the body's state ([`crate::Model::junction_shape_placement`]). A hose node i
//! whose ball penetrates the shape takes the penalty force and friction of any moving
//! part at that pose ([`super::system`]): f = k (r − d) n + f_t, with its tangent
//! S = −∂f/∂r = k n nᵀ + K_t along the node's displacement relative to the body point
//! it lies on, δr = δx_i − δx_m − δθ_m × a, a = x_i − x_m. The equal and opposite force
//! goes to the body at x_i (Newton's third law: the pair carries no net force or moment),
//! that is on the master as a force −f and a moment −a × f.
//!
//! **Consistent tangent.** In the body's frame the contact force is a field of the
//! node's local position, f = R φ(Rᵀ(x_i − T)), so a rigid turn δθ_m of the body with the
//! node's relative position kept turns the force: δf = δθ_m × f − S δr. With
//! B = [I, −\[a\]×] (δr = δx_i − B δu_m) and K = −∂(loads)/∂u:
//!
//! ```text
//! K_ii = S                                     (the hose node's block, as for any part)
//! K_im = −S B + [0, [f]×]                      (hose node × master)
//! K_mi = −Bᵀ S − [0; [f]×]                     (master × hose node)
//! K_mm = Bᵀ S B + [0, −[f]×; [f]×, −[a]×[f]×]  (the master's block)
//! ```
//!
//! the geometric terms \[f\]× from the force turning with the body and the arm a changing
//! with both nodes. It is exact where S is (a node on a face of the shape; S leaves out
//! the normal's turn around an edge or corner, of relative size depth/distance, and the
//! friction tangent is its symmetric part, [`crate::contact::friction`]). K_ii and K_mm
//! lie in the matrix's block band; K_im and K_mi couple nodes far apart and are applied
//! in the linear solve's contact-coupled system with the hose–hose pairs'
//! ([`super::system::NewtonSystem::solve_linear`]).

use crate::kinematics::Placement;
use crate::rod::stiffened::BodyState;
use crate::Model;
use glam::{DMat3, DVec3};
use nalgebra::{Matrix3, Matrix6, Vector6};

/// The coupling of one hose node touching a junction body's shape with the body's master
/// node (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeCoupling {
    /// The hose node i.
    pub hose: usize,
    /// The body's master node m.
    pub master: usize,
    /// a = x_i − x_m \[m\].
    pub arm: DVec3,
    /// S = −∂f/∂r \[N/m\] (normal penalty and friction).
    pub stiffness: DMat3,
    /// The contact force f on the hose node \[N\].
    pub force: DVec3,
}

impl ShapeCoupling {
    /// Multiplies the coupling by `factor` (the HHT-α weight of the implicit solver's
    /// Jacobian).
    pub fn scale(&mut self, factor: f64) {
        self.stiffness *= factor;
        self.force *= factor;
    }
}

/// The junction whose body part `part` is the shape of, if any.
pub fn shape_junction(model: &Model, part: usize) -> Option<usize> {
    model
        .junction_shapes
        .junction_of_part
        .get(part)
        .copied()
        .flatten()
}

/// Poses every junction shape in `placements` (one per part) from its body's master
/// node at (x, q) moving with (v, w).
pub fn place_shapes(
    model: &Model,
    (x, q): (&[DVec3], &[glam::DQuat]),
    (v, w): (&[DVec3], &[DVec3]),
    placements: &mut [Placement],
) {
    for (k, j) in model.junction_shapes.junction_of_part.iter().enumerate() {
        let (Some(j), Some(slot)) = (*j, placements.get_mut(k)) else {
            continue;
        };
        let junction = &model.junctions[j];
        let m = junction.nodes[0];
        let (centre, orientation) = model.bodies[junction.body].pose_from_node(0, x[m], q[m]);
        let body = BodyState {
            centre,
            orientation,
            velocity: v[m] + w[m].cross(centre - x[m]),
            angular_velocity: w[m],
        };
        *slot = model.junction_shape_placement(j, &body);
    }
}

/// [v]× as a 3 × 3 matrix: [v]× u = v × u.
fn cross(v: DVec3) -> DMat3 {
    DMat3::from_cols(
        DVec3::new(0.0, v.z, -v.y),
        DVec3::new(-v.z, 0.0, v.x),
        DVec3::new(v.y, -v.x, 0.0),
    )
}

fn nalgebra3(m: DMat3) -> Matrix3<f64> {
    Matrix3::from_column_slice(&m.to_cols_array())
}

/// Adds the reaction of the contact force `force` the shape of `junction`'s body gives
/// hose node `hose` (tangent `stiffness`, S) to the master's `loads` (force, moment) and
/// K_mm to its diagonal block in `diag`; returns the coupling of the two nodes (module
/// doc).
pub fn add_reaction(
    model: &Model,
    junction: usize,
    (hose, x): (usize, &[DVec3]),
    (force, stiffness): (DVec3, DMat3),
    (loads_force, loads_moment): (&mut [DVec3], &mut [DVec3]),
    diag: &mut [Matrix6<f64>],
) -> ShapeCoupling {
    let m = model.junctions[junction].nodes[0];
    let arm = x[hose] - x[m];
    loads_force[m] -= force;
    loads_moment[m] -= arm.cross(force);
    // Bᵀ S B + the geometric terms, B = [I, −[a]×]
    let (ax, fx) = (cross(arm), cross(force));
    let s_b = -(stiffness * ax);
    let blocks = [
        (0, 0, stiffness),
        (0, 3, s_b - fx),
        (3, 0, ax * stiffness + fx),
        (3, 3, ax * s_b - ax * fx),
    ];
    for (r, c, block) in blocks {
        let mut view = diag[m].fixed_view_mut::<3, 3>(r, c);
        view += nalgebra3(block);
    }
    ShapeCoupling {
        hose,
        master: m,
        arm,
        stiffness,
        force,
    }
}

fn translation(v: &Vector6<f64>) -> DVec3 {
    DVec3::new(v[0], v[1], v[2])
}

fn rotation(v: &Vector6<f64>) -> DVec3 {
    DVec3::new(v[3], v[4], v[5])
}

/// out += −C v for the shape couplings outside the block band, C = K_im and K_mi
/// (module doc), on the free rows.
pub fn add_minus_shape_coupling(
    couplings: &[ShapeCoupling],
    prescribed: &[bool],
    v: &[Vector6<f64>],
    out: &mut [Vector6<f64>],
) {
    for c in couplings {
        let (i, m) = (c.hose, c.master);
        if !prescribed[i] {
            // −K_im v_m = S (δx_m + δθ_m × a) − f × δθ_m
            let (dx, dth) = (translation(&v[m]), rotation(&v[m]));
            let f = c.stiffness * (dx + dth.cross(c.arm)) - c.force.cross(dth);
            let mut row = out[i].fixed_rows_mut::<3>(0);
            row += nalgebra::Vector3::new(f.x, f.y, f.z);
        }
        if !prescribed[m] {
            // −K_mi v_i = (S δx_i, a × S δx_i + f × δx_i)
            let dx = translation(&v[i]);
            let s = c.stiffness * dx;
            let turn = c.arm.cross(s) + c.force.cross(dx);
            out[m] += Vector6::new(s.x, s.y, s.z, turn.x, turn.y, turn.z);
        }
    }
}
