//! A rigid body's own mass beyond its nodes' (SPEC N1, a junction body with its own centre
//! of mass and inertia): mass m_b, centre of mass c and inertia tensor J_b about c,
//! carried rigidly by the body. Its loads are those of a rigid body's mass distribution
//! (Goldstein, Poole & Safko, "Classical Mechanics", 3rd ed., §5.3): the weight and the
//! mass-proportional damping act at c, F = m_b (g − α v_c), v_c = V + Ω × (c − x_G), and
//! the rotational damping is −α J_b Ω as on every node. Its share of the composite
//! body's inertia about the common centre of mass x_G is J_b + m_b (|d|² 𝟙 − d dᵀ),
//! d = c − x_G (parallel-axis theorem), added by [`crate::rod::stiffened::RigidBody`].

use glam::{DMat3, DQuat, DVec3};

/// A body's own mass, centre of mass and inertia, in the rigid body's axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttachedMass {
    /// Mass m_b \[kg\].
    pub mass: f64,
    /// Centre of mass c relative to the composite body's centre of mass, body axes \[m\].
    pub offset: DVec3,
    /// Inertia tensor J_b about c, body axes \[kg·m²\].
    pub inertia: DMat3,
}

impl AttachedMass {
    /// World inertia tensor R J_b Rᵀ for body orientation `q`.
    pub fn world_inertia(&self, q: DQuat) -> DMat3 {
        let r = DMat3::from_quat(q);
        r * self.inertia * r.transpose()
    }

    /// Weight and damping of the mass for a body at `centre`, `orientation` moving with
    /// `velocity`, `angular_velocity`: the force, and its moment about `about`.
    #[allow(clippy::too_many_arguments)]
    pub fn loads(
        &self,
        centre: DVec3,
        orientation: DQuat,
        velocity: DVec3,
        angular_velocity: DVec3,
        about: DVec3,
        gravity: DVec3,
        damping: f64,
    ) -> (DVec3, DVec3) {
        let c = centre + orientation * self.offset;
        let v_c = velocity + angular_velocity.cross(c - centre);
        let force = self.mass * (gravity - damping * v_c);
        let moment = (c - about).cross(force)
            - damping * (self.world_inertia(orientation) * angular_velocity);
        (force, moment)
    }
}

/// Checks an inertia tensor about a centre of mass: finite, symmetric (to 1e-9 of its
/// largest entry), positive definite, and its principal moments satisfying the triangle
/// inequality J₁ ≤ J₂ + J₃ (any real mass distribution does: J₂ + J₃ − J₁ = 2 Σ m x₁²).
/// Returns the principal moments, ascending, or the reason it is not one.
pub fn check_inertia(j: DMat3) -> Result<DVec3, String> {
    let a = j.to_cols_array();
    if a.iter().any(|v| !v.is_finite()) {
        return Err("has a non-finite entry".into());
    }
    let largest = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    for (r, c) in [(0, 1), (0, 2), (1, 2)] {
        let (u, l) = (j.col(c)[r], j.col(r)[c]);
        if (u - l).abs() > 1e-9 * largest {
            return Err(format!(
                "is not symmetric: J[{r}][{c}] = {u} but J[{c}][{r}] = {l}"
            ));
        }
    }
    let m = nalgebra::Matrix3::from_fn(|r, c| 0.5 * (j.col(c)[r] + j.col(r)[c]));
    let mut e = nalgebra::SymmetricEigen::new(m).eigenvalues;
    e.as_mut_slice().sort_by(f64::total_cmp);
    if !(e[0] > 0.0) {
        return Err(format!(
            "is not positive definite: its principal moments are {:.6e}, {:.6e}, {:.6e} kg·m²",
            e[0], e[1], e[2]
        ));
    }
    if e[2] > (e[0] + e[1]) * (1.0 + 1e-12) {
        return Err(format!(
            "violates the triangle inequality: its largest principal moment {:.6e} exceeds the sum of the other two, {:.6e} + {:.6e} kg·m² (no mass distribution has it)",
            e[2], e[0], e[1]
        ));
    }
    Ok(DVec3::new(e[0], e[1], e[2]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inertia_checks() {
        // a solid cube: J = m a²/6 𝟙
        assert!(check_inertia(DMat3::from_diagonal(DVec3::splat(1e-3))).is_ok());
        // a thin disc about its axis and diameters: 2, 1, 1 (equality holds)
        let disc = check_inertia(DMat3::from_diagonal(DVec3::new(2.0, 1.0, 1.0))).unwrap();
        assert_eq!(disc, DVec3::new(1.0, 1.0, 2.0));
        let e = check_inertia(DMat3::from_diagonal(DVec3::new(3.0, 1.0, 1.0))).unwrap_err();
        assert!(e.contains("triangle"), "{e}");
        let e = check_inertia(DMat3::from_diagonal(DVec3::new(1.0, 0.0, 1.0))).unwrap_err();
        assert!(e.contains("positive definite"), "{e}");
        let skew = DMat3::from_cols(
            DVec3::new(1.0, 0.2, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        );
        assert!(check_inertia(skew).unwrap_err().contains("symmetric"));
        // a rotated box keeps its principal moments
        let r = DMat3::from_quat(DQuat::from_rotation_y(0.4) * DQuat::from_rotation_x(1.1));
        let j = r * DMat3::from_diagonal(DVec3::new(1.0, 1.5, 2.0)) * r.transpose();
        let p = check_inertia(j).unwrap();
        assert!((p - DVec3::new(1.0, 1.5, 2.0)).length() < 1e-12);
    }

    /// The weight acts at the centre of mass: its moment about a point is (c − p) × m g.
    #[test]
    fn weight_acts_at_the_centre_of_mass() {
        let a = AttachedMass {
            mass: 2.0,
            offset: DVec3::new(0.1, 0.0, 0.0),
            inertia: DMat3::from_diagonal(DVec3::splat(1e-3)),
        };
        let q = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let g = DVec3::new(0.0, 0.0, -9.81);
        let (f, m) = a.loads(
            DVec3::ZERO,
            q,
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::ZERO,
            g,
            0.0,
        );
        assert_eq!(f, 2.0 * g);
        // the offset turned onto y: moment (0, 0.1, 0) × (0, 0, −19.62) = (−1.962, 0, 0)
        assert!((m - DVec3::new(-1.962, 0.0, 0.0)).length() < 1e-12, "{m:?}");
    }
}
