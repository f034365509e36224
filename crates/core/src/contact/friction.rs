//! Coulomb friction of node contacts with rigid parts in the Newton solvers (static and
//! implicit): an elastoplastic tangential penalty spring with a return mapping
//! (Wriggers, "Computational Contact Mechanics", 2nd ed. 2006, §5.2.2; Simo & Laursen,
//! Computers & Structures 42, 1992).
//!
//! Each node keeps an anchor: where it stuck at the end of the last accepted step (or, out
//! of contact, simply where it was). In contact, with the tangential gap
//! g_t = (I − n nᵀ)(x − a) and the normal force f_n = k (r − d):
//! * stick if k_t |g_t| ≤ μ f_n: f_t = −k_t g_t, tangent k_t (I − n nᵀ);
//! * slip otherwise: f_t = −μ_k f_n g_t/|g_t| (the return onto the sliding cone), tangent
//!   μ_k f_n/|g_t| (I − n nᵀ − t tᵀ) (its symmetric part; the term μ k t nᵀ from the
//!   normal force's variation is left out — the solvers stay symmetric and converge
//!   linearly while slipping). Along the slip itself that tangent has no stiffness; the
//!   static solver, which has no inertia to fill it, adds the secant μ_k f_n/|g_t| t tᵀ
//!   there ([`FrictionResponse::secant`]; `NewtonSystem::regularise_slip`).
//!
//! μ in the stick test is the static coefficient for a node that stuck in the last step
//! and the sliding one for a node that slipped — so a node breaks away at μ_s f_n and
//! slides at μ_k f_n from that very step, as in the explicit solver. k_t is the normal
//! penalty stiffness: the elastic creep while sticking is f_t/k_t, of the order of the
//! normal penetration. Friction acts at the node, like the explicit solver's: it resists
//! sliding, not rolling. When a step is accepted, [`FrictionMemory::commit`] moves the anchors of
//! slipping nodes along (so that the spring holds exactly μ_k f_n) and keeps those of
//! sticking nodes.

use glam::DVec3;
use nalgebra::Matrix3;

/// Friction history of every node, carried in the state from one accepted step to the
/// next (allocated once; `clone_from` reuses the buffers, so that the Newton solvers'
/// saving and restoring it in every step allocates nothing).
#[derive(Debug, Default)]
pub struct FrictionMemory {
    /// Where each node's tangential spring is anchored \[m\].
    pub anchor: Vec<DVec3>,
    /// Whether the node slipped in the last accepted step (then μ = μ_k, else μ_s).
    pub sliding: Vec<bool>,
}

/// One node's friction at a trial configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionResponse {
    /// Tangential force on the node \[N\].
    pub force: DVec3,
    /// −∂f_t/∂x \[N/m\] (symmetric).
    pub tangent: Matrix3<f64>,
    /// The force is on the Coulomb limit (slip).
    pub slipping: bool,
    /// Dissipation potential of the trial slip (½ k_t g² while sticking up to
    /// g_c = μ f_n / k_t, then growing by μ_k f_n per metre) \[J\]: its gradient is −f_t at
    /// fixed f_n, so that the static line search sees friction as it sees a spring.
    pub energy: f64,
    /// μ f_n / |g_t| while slipping, the secant stiffness of the friction force along the
    /// slip (0 while sticking) \[N/m\].
    pub secant: f64,
}

impl Clone for FrictionMemory {
    fn clone(&self) -> Self {
        Self {
            anchor: self.anchor.clone(),
            sliding: self.sliding.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.anchor.clone_from(&source.anchor);
        self.sliding.clone_from(&source.sliding);
    }
}

impl FrictionMemory {
    pub fn new(x: &[DVec3]) -> Self {
        Self {
            anchor: x.to_vec(),
            sliding: vec![false; x.len()],
        }
    }

    /// Whether the memory has a slot per node (states built before friction existed in
    /// the Newton solvers have none, and are given one at their first step).
    pub fn fits(&self, nodes: usize) -> bool {
        self.anchor.len() == nodes
    }

    /// Friction on node `i` at position `x`, touching a part with unit normal `n` (from the
    /// part to the node), normal force `normal_force` ≥ 0, tangential stiffness `k_t`, and
    /// the part's coefficients (μ_s, μ_k).
    pub fn response(
        &self,
        i: usize,
        x: DVec3,
        n: DVec3,
        normal_force: f64,
        k_t: f64,
        (mu_static, mu_sliding): (f64, f64),
    ) -> FrictionResponse {
        let (mu_stick, mu_slip) = if self.sliding[i] {
            (mu_sliding, mu_sliding)
        } else {
            (mu_static, mu_sliding)
        };
        let slip = x - self.anchor[i];
        let gap = slip - n * n.dot(slip);
        let g = gap.length();
        let tangential = Matrix3::identity() - outer(n, n);
        // the spring holds up to μ f_n (μ_s for a node that stuck); beyond, the node slips
        // and friction drops to μ_k f_n
        let reach = mu_stick * normal_force / k_t;
        if g <= reach {
            FrictionResponse {
                force: -k_t * gap,
                tangent: tangential * k_t,
                slipping: false,
                energy: 0.5 * k_t * g * g,
                secant: 0.0,
            }
        } else {
            let t = gap / g;
            let limit = mu_slip * normal_force;
            FrictionResponse {
                force: -limit * t,
                tangent: (tangential - outer(t, t)) * (limit / g),
                slipping: true,
                energy: 0.5 * k_t * reach * reach + limit * (g - reach),
                secant: limit / g,
            }
        }
    }

    /// Accepts a step for node `i`: `response` is its friction at the accepted position
    /// `x` (None when it is not in contact), `k_t` its tangential stiffness. A slipping
    /// node's anchor is moved to where its spring holds exactly the friction force; a
    /// sticking node keeps its anchor; a node out of contact is anchored where it is.
    pub fn commit(&mut self, i: usize, x: DVec3, response: Option<&FrictionResponse>, k_t: f64) {
        match response {
            Some(r) if r.slipping => {
                self.anchor[i] = x + r.force / k_t;
                self.sliding[i] = true;
            }
            Some(_) => self.sliding[i] = false,
            None => {
                self.anchor[i] = x;
                self.sliding[i] = false;
            }
        }
    }
}

/// a bᵀ.
pub(crate) fn outer(a: DVec3, b: DVec3) -> Matrix3<f64> {
    Matrix3::new(
        a.x * b.x,
        a.x * b.y,
        a.x * b.z,
        a.y * b.x,
        a.y * b.y,
        a.y * b.z,
        a.z * b.x,
        a.z * b.y,
        a.z * b.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn memory() -> FrictionMemory {
        FrictionMemory::new(&[DVec3::ZERO])
    }

    #[test]
    fn sticks_up_to_the_static_limit_and_slides_at_the_sliding_one() {
        let m = memory();
        let n = DVec3::Z;
        // f_n = 10 N, μ_s = 0.5: the spring k_t = 1000 N/m holds 5 N up to 5 mm
        let stick = m.response(
            0,
            DVec3::new(0.004, 0.0, 0.001),
            n,
            10.0,
            1000.0,
            (0.5, 0.4),
        );
        assert!(!stick.slipping);
        assert!((stick.force - DVec3::new(-4.0, 0.0, 0.0)).length() < 1e-12);
        let held = m.response(
            0,
            DVec3::new(0.0, 0.00499, 0.0),
            n,
            10.0,
            1000.0,
            (0.5, 0.4),
        );
        assert!(!held.slipping && (held.force.length() - 4.99).abs() < 1e-9);
        let slip = m.response(
            0,
            DVec3::new(0.0, 0.00501, 0.0),
            n,
            10.0,
            1000.0,
            (0.5, 0.4),
        );
        assert!(slip.slipping);
        assert!((slip.force - DVec3::new(0.0, -4.0, 0.0)).length() < 1e-12);
    }

    #[test]
    fn a_committed_slip_holds_the_sliding_force_and_the_energy_gradient_is_the_force() {
        let mut m = memory();
        let n = DVec3::Z;
        let x = DVec3::new(0.03, 0.01, 0.0);
        let r = m.response(0, x, n, 10.0, 1000.0, (0.5, 0.4));
        m.commit(0, x, Some(&r), 1000.0);
        assert!(m.sliding[0]);
        // from the new anchor, the spring at x is on the (sliding) cone: 4 N
        let again = m.response(0, x, n, 10.0, 1000.0, (0.5, 0.4));
        assert!((again.force.length() - 4.0).abs() < 1e-9);
        // energy gradient = −force, and tangent = finite difference of −force
        let h = 1e-7;
        for x0 in [DVec3::new(0.001, 0.002, 0.0), DVec3::new(0.05, -0.02, 0.0)] {
            let f0 = memory().response(0, x0, n, 10.0, 1000.0, (0.5, 0.4));
            for k in 0..2 {
                let mut e = DVec3::ZERO;
                e[k] = h;
                let fp = memory().response(0, x0 + e, n, 10.0, 1000.0, (0.5, 0.4));
                let grad = (fp.energy - f0.energy) / h;
                assert!((grad + f0.force[k]).abs() < 1e-4, "energy gradient {k}");
                let df = (fp.force - f0.force) / h;
                for row in 0..3 {
                    assert!((-df[row] - f0.tangent[(row, k)]).abs() < 1e-3, "tangent");
                }
            }
        }
    }
}
