//! Stiffened sections (SPEC M6, dissertation §4.3.1 "Leitungsversteifung"): a span of a
//! hose's nodes declared rigid — a metal tube joining two flexible hoses — becomes one
//! rigid body. Its mass is the sum of the nodes' masses, its centre of mass their mean,
//! its inertia tensor the nodes' own (isotropic) inertias plus the parallel-axis terms,
//! J = Σ [I_I 𝟙 + m_I (|o_I|² 𝟙 − o_I o_Iᵀ)], and its body frame the principal axes from
//! the eigen-decomposition of J. The span's nodes follow it as dependent points; the
//! forces and moments on them are summed onto the body, F = Σ f_I,
//! M = Σ (m_I + o_I × f_I), and the body moves by Newton–Euler:
//! m V̇ = F, J_b Ω̇_b + Ω_b × J_b Ω_b = M_b (body axes). The flexible neighbours stay
//! attached through the elements at the span's end nodes.

use super::attached::AttachedMass;
use crate::math::{exp_map, log_map};
use glam::{DMat3, DQuat, DVec3};

/// A span of one hose to make rigid: local node indices `first..=last`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StiffenedSpan {
    pub hose: usize,
    pub first: usize,
    pub last: usize,
}

/// A rigid body made of a span of nodes.
#[derive(Clone, Debug)]
pub struct RigidBody {
    /// Global node indices: a stiffened span's, or a junction's end nodes.
    pub nodes: Vec<usize>,
    /// Total mass \[kg\].
    pub mass: f64,
    /// Principal moments of inertia about the centre of mass \[kg·m²\], body axes.
    pub principal_inertia: DVec3,
    /// Centre of mass and body frame (principal axes) at rest.
    pub rest_centre: DVec3,
    pub rest_orientation: DQuat,
    /// Each node's rest offset from the centre, in body axes.
    pub offsets: Vec<DVec3>,
    /// Each node's rest frame relative to the body frame.
    pub frames: Vec<DQuat>,
    /// A junction body's own mass, centre and inertia beyond its nodes' (included in
    /// `mass` and `principal_inertia`), or none.
    pub attached: Option<AttachedMass>,
}

/// Principal axes and moments of a symmetric 3×3 tensor (eigen-decomposition), as a
/// right-handed rotation whose columns are the axes.
fn principal_axes(j: DMat3) -> (DQuat, DVec3) {
    let m = nalgebra::Matrix3::from_fn(|r, c| j.col(c)[r]);
    let eig = nalgebra::SymmetricEigen::new(m);
    let col = |k: usize| {
        DVec3::new(
            eig.eigenvectors[(0, k)],
            eig.eigenvectors[(1, k)],
            eig.eigenvectors[(2, k)],
        )
    };
    let (a, b) = (col(0).normalize(), col(1).normalize());
    let c = a.cross(b); // right-handed
    let q = DQuat::from_mat3(&DMat3::from_cols(a, b, c)).normalize();
    (
        q,
        DVec3::new(eig.eigenvalues[0], eig.eigenvalues[1], eig.eigenvalues[2]),
    )
}

impl RigidBody {
    /// Builds the body of global nodes `nodes` from their rest poses, masses and
    /// (isotropic) rotational inertias.
    pub fn new(
        nodes: Vec<usize>,
        x: &[DVec3],
        q: &[DQuat],
        mass: &[f64],
        inertia: &[f64],
    ) -> RigidBody {
        Self::build(nodes, x, q, mass, inertia, None)
    }

    /// Builds the body of global nodes `nodes` carrying a mass of its own: `own_mass`
    /// \[kg\] with its centre of mass `own_centre` and its inertia tensor about that centre
    /// `own_inertia` (world axes, at rest). The body's mass is the nodes' and its own,
    /// its centre of mass the common one x_G, its inertia J_b + m_b (|d|² 𝟙 − d dᵀ) with
    /// d = c − x_G added to the nodes' (parallel-axis theorem).
    pub fn with_attached(
        nodes: Vec<usize>,
        (x, q): (&[DVec3], &[DQuat]),
        (mass, inertia): (&[f64], &[f64]),
        own_mass: f64,
        own_centre: DVec3,
        own_inertia: DMat3,
    ) -> RigidBody {
        Self::build(
            nodes,
            x,
            q,
            mass,
            inertia,
            Some((own_mass, own_centre, own_inertia)),
        )
    }

    fn build(
        nodes: Vec<usize>,
        x: &[DVec3],
        q: &[DQuat],
        mass: &[f64],
        inertia: &[f64],
        own: Option<(f64, DVec3, DMat3)>,
    ) -> RigidBody {
        let mut total: f64 = nodes.iter().map(|&i| mass[i]).sum();
        let mut centre = nodes.iter().map(|&i| mass[i] * x[i]).sum::<DVec3>();
        if let Some((m, c, _)) = own {
            total += m;
            centre += m * c;
        }
        let centre = centre / total;
        let mut j = DMat3::ZERO;
        for &i in &nodes {
            let o = x[i] - centre;
            j += DMat3::IDENTITY * (inertia[i] + mass[i] * o.length_squared())
                - mass[i] * outer(o, o);
        }
        if let Some((m, c, jc)) = own {
            let d = c - centre;
            j += jc + DMat3::IDENTITY * (m * d.length_squared()) - m * outer(d, d);
        }
        let (orientation, principal) = principal_axes(j);
        let inv = orientation.conjugate();
        let r_inv = DMat3::from_quat(inv);
        RigidBody {
            mass: total,
            principal_inertia: principal,
            rest_centre: centre,
            rest_orientation: orientation,
            offsets: nodes.iter().map(|&i| inv * (x[i] - centre)).collect(),
            frames: nodes.iter().map(|&i| (inv * q[i]).normalize()).collect(),
            nodes,
            attached: own.map(|(mass, c, jc)| AttachedMass {
                mass,
                offset: inv * (c - centre),
                inertia: r_inv * jc * r_inv.transpose(),
            }),
        }
    }

    /// The body's centre and orientation when its `k`-th node is at (x_k, q_k):
    /// R = q_k f_kᵀ, centre = x_k − R o_k.
    pub fn pose_from_node(&self, k: usize, x: DVec3, q: DQuat) -> (DVec3, DQuat) {
        let orientation = (q * self.frames[k].conjugate()).normalize();
        (x - orientation * self.offsets[k], orientation)
    }

    /// Inertia tensor in world axes for body orientation `q`: R diag(J) Rᵀ.
    pub fn world_inertia(&self, q: DQuat) -> DMat3 {
        let r = DMat3::from_quat(q);
        r * DMat3::from_diagonal(self.principal_inertia) * r.transpose()
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
}

/// Pose and velocity of one rigid body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyState {
    pub centre: DVec3,
    pub orientation: DQuat,
    pub velocity: DVec3,
    /// Angular velocity, world axes \[rad/s\].
    pub angular_velocity: DVec3,
}

/// One explicit step of a body (SPEC M6), then its nodes placed as dependent points.
/// If a kinematic load case holds one of its nodes (`held_node`), the body follows that
/// node and the node's support reaction becomes the whole body's momentum balance.
/// `gravity` and `damping` (mass-proportional, 1/s) load the body's own mass, if it
/// has one ([`AttachedMass::loads`]); its nodes' are in `force` and `moment`.
#[allow(clippy::too_many_arguments)]
pub fn step_body(
    body: &RigidBody,
    (gravity, damping): (DVec3, f64),
    s: &mut BodyState,
    held_node: Option<usize>,
    x: &mut [DVec3],
    q: &mut [DQuat],
    v: &mut [DVec3],
    w: &mut [DVec3],
    force: &[DVec3],
    moment: &[DVec3],
    reaction: (&mut [DVec3], &mut [DVec3]),
    dt: f64,
) {
    // total load about the centre of mass
    let mut f = DVec3::ZERO;
    let mut m = DVec3::ZERO;
    for &i in &body.nodes {
        f += force[i];
        m += moment[i] + (x[i] - s.centre).cross(force[i]);
    }
    if let Some(own) = &body.attached {
        let (fo, mo) = own.loads(
            s.centre,
            s.orientation,
            s.velocity,
            s.angular_velocity,
            s.centre,
            gravity,
            damping,
        );
        f += fo;
        m += mo;
    }
    match held_node {
        Some(h) => {
            let k = body.nodes.iter().position(|&i| i == h).unwrap_or(0);
            let orientation = (q[h] * body.frames[k].conjugate()).normalize();
            let centre = x[h] - orientation * body.offsets[k];
            let velocity = (centre - s.centre) / dt;
            let omega = log_map(orientation * s.orientation.conjugate()) / dt;
            let jw = body.world_inertia(s.orientation);
            let r_force = body.mass * (velocity - s.velocity) / dt - f;
            let r_moment_c = jw * (omega - s.angular_velocity) / dt
                + s.angular_velocity.cross(jw * s.angular_velocity)
                - m;
            reaction.0[h] = r_force;
            reaction.1[h] = r_moment_c - (x[h] - centre).cross(r_force);
            *s = BodyState {
                centre,
                orientation,
                velocity,
                angular_velocity: omega,
            };
        }
        None => {
            s.velocity += dt / body.mass * f;
            // Euler's equations in body axes
            let inv = s.orientation.conjugate();
            let wb = inv * s.angular_velocity;
            let mb = inv * m;
            let jb = body.principal_inertia;
            let dwb = (mb - wb.cross(jb * wb)) / jb;
            s.angular_velocity = s.orientation * (wb + dt * dwb);
            s.centre += dt * s.velocity;
            s.orientation = (exp_map(dt * s.angular_velocity) * s.orientation).normalize();
        }
    }
    for (k, &i) in body.nodes.iter().enumerate() {
        let o = s.orientation * body.offsets[k];
        x[i] = s.centre + o;
        v[i] = s.velocity + s.angular_velocity.cross(o);
        q[i] = (s.orientation * body.frames[k]).normalize();
        w[i] = s.angular_velocity;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Four equal masses on a line along x: J about y and z is Σ m x² (+ node terms),
    /// about x only the node terms; the principal axes are the global ones.
    #[test]
    fn inertia_of_a_straight_span() {
        let x: Vec<DVec3> = (0..4)
            .map(|i| DVec3::new(0.1 * i as f64, 0.0, 0.0))
            .collect();
        let q = vec![DQuat::IDENTITY; 4];
        let body = RigidBody::new((0..4).collect(), &x, &q, &[1.0; 4], &[1e-4; 4]);
        assert!((body.mass - 4.0).abs() < 1e-15);
        assert!((body.rest_centre - DVec3::new(0.15, 0.0, 0.0)).length() < 1e-15);
        let along: f64 = x.iter().map(|p| (p.x - 0.15).powi(2)).sum::<f64>() + 4e-4;
        let mut moments = body.principal_inertia.to_array();
        moments.sort_by(f64::total_cmp);
        assert!((moments[0] - 4e-4).abs() < 1e-12);
        assert!((moments[1] - along).abs() < 1e-12 && (moments[2] - along).abs() < 1e-12);
        // the axis of the smallest moment is the span's direction
        let kmin = (0..3)
            .min_by(|&a, &b| body.principal_inertia[a].total_cmp(&body.principal_inertia[b]))
            .unwrap();
        let mut e = DVec3::ZERO;
        e[kmin] = 1.0;
        assert!((body.rest_orientation * e).cross(DVec3::X).length() < 1e-9);
    }

    /// A free body spinning about its principal axis keeps its angular momentum, and its
    /// nodes stay at their offsets.
    #[test]
    fn free_body_moves_rigidly_and_conserves_momentum() {
        let x: Vec<DVec3> = vec![
            DVec3::ZERO,
            DVec3::new(0.1, 0.02, 0.0),
            DVec3::new(0.2, 0.0, 0.03),
        ];
        let q = vec![DQuat::IDENTITY; 3];
        let body = RigidBody::new((0..3).collect(), &x, &q, &[1.0, 2.0, 1.5], &[1e-3; 3]);
        let mut s = BodyState {
            centre: body.rest_centre,
            orientation: body.rest_orientation,
            velocity: DVec3::new(0.1, 0.0, 0.0),
            angular_velocity: DVec3::new(0.0, 0.0, 2.0),
        };
        let (mut xs, mut qs, mut vs, mut ws) = (
            x.clone(),
            q.clone(),
            vec![DVec3::ZERO; 3],
            vec![DVec3::ZERO; 3],
        );
        let zero = vec![DVec3::ZERO; 3];
        let (mut rf, mut rm) = (zero.clone(), zero.clone());
        let l0 = body.world_inertia(s.orientation) * s.angular_velocity;
        for _ in 0..10_000 {
            step_body(
                &body,
                (DVec3::ZERO, 0.0),
                &mut s,
                None,
                &mut xs,
                &mut qs,
                &mut vs,
                &mut ws,
                &zero,
                &zero,
                (&mut rf, &mut rm),
                1e-4,
            );
        }
        let l1 = body.world_inertia(s.orientation) * s.angular_velocity;
        assert!((l1 - l0).length() < 1e-3 * l0.length(), "{l0:?} → {l1:?}");
        assert!(((xs[1] - xs[0]).length() - (x[1] - x[0]).length()).abs() < 1e-12);
        assert!((s.centre - (body.rest_centre + DVec3::new(0.1, 0.0, 0.0))).length() < 1e-9);
    }
}
