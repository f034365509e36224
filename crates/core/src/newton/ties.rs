//! Cable ties in the Newton solvers ([`crate::loads::Tie`]): a tie's tangent k n nᵀ
//! couples two nodes the block-tridiagonal band does not connect (two hoses). It is a
//! rank-one term per tie,
//!
//! ```text
//! K = T + Σᵢ kᵢ gᵢ gᵢᵀ,   gᵢ = +n at the first node's translation, −n at the second's
//!                              (zero at a prescribed node)
//! ```
//!
//! solved exactly on the factorised band T by the Sherman–Morrison–Woodbury formula:
//!
//! ```text
//! K⁻¹ r = v − Z S⁻¹ Gᵀ v,   v = T⁻¹ r,   Z = T⁻¹ G,   S = C⁻¹ + Gᵀ Z   (m × m, C = diag kᵢ)
//! ```
//!
//! — m more band solves per factorisation and an m × m Cholesky solve per right-hand side,
//! exact however stiff the tie. (The splitting iteration used for hose–hose contact pairs
//! converges at the rate k/(k + k_hose): hopeless for a tie as stiff as the explicit
//! solver's supports on a hose as soft as a rubber cantilever.) Buffers grow with the
//! number of ties and are reused: no allocation once a run's ties are known.

use super::block_tree::SingularBlock;
use super::condensation::Factored;
use glam::DVec3;
use nalgebra::Vector6;

/// The ties of the last assembly and their Woodbury factors.
#[derive(Clone, Debug, Default)]
pub struct TieCouplings {
    /// (first node, second node, n, k) per tie.
    ties: Vec<(usize, usize, DVec3, f64)>,
    /// Z = T⁻¹ G, one column (a full right-hand side) per tie.
    z: Vec<Vec<Vector6<f64>>>,
    /// Cholesky factor of S, row-major m × m (lower triangle).
    s: Vec<f64>,
    /// Scratch of length m.
    y: Vec<f64>,
}

/// gᵀ v for the tie (a, b, n) with prescribed nodes dropped.
fn project(v: &[Vector6<f64>], (a, b, n): (usize, usize, DVec3), prescribed: &[bool]) -> f64 {
    let part = |i: usize| {
        if prescribed[i] {
            0.0
        } else {
            n.x * v[i][0] + n.y * v[i][1] + n.z * v[i][2]
        }
    };
    part(a) - part(b)
}

impl TieCouplings {
    pub fn clear(&mut self) {
        self.ties.clear();
    }

    pub fn is_empty(&self) -> bool {
        self.ties.is_empty()
    }

    /// Adds a tie between nodes `a` and `b` along the unit `normal` with stiffness `k`.
    pub fn push(&mut self, a: usize, b: usize, normal: DVec3, k: f64) {
        self.ties.push((a, b, normal, k));
    }

    /// After T is factorised: Z = T⁻¹ G and the Cholesky factor of S.
    pub fn prepare(
        &mut self,
        matrix: Factored<'_>,
        prescribed: &[bool],
    ) -> Result<(), SingularBlock> {
        let m = self.ties.len();
        let n = prescribed.len();
        if self.z.len() < m {
            self.z.resize_with(m, Vec::new);
        }
        self.s.resize(m * m, 0.0);
        self.y.resize(m, 0.0);
        for (k, &(a, b, normal, _)) in self.ties.iter().enumerate() {
            let z = &mut self.z[k];
            z.resize(n, Vector6::zeros());
            z.fill(Vector6::zeros());
            for (node, sign) in [(a, 1.0), (b, -1.0)] {
                if !prescribed[node] {
                    let g = normal * sign;
                    z[node][0] += g.x;
                    z[node][1] += g.y;
                    z[node][2] += g.z;
                }
            }
            matrix.solve_factored(z)?;
        }
        // S = C⁻¹ + Gᵀ Z, then its Cholesky factor in place
        for i in 0..m {
            let (a, b, normal, k) = self.ties[i];
            for j in 0..m {
                let g_z = project(&self.z[j], (a, b, normal), prescribed);
                self.s[i * m + j] = g_z + if i == j { 1.0 / k } else { 0.0 };
            }
        }
        for j in 0..m {
            let mut d = self.s[j * m + j];
            for k in 0..j {
                d -= self.s[j * m + k] * self.s[j * m + k];
            }
            if d.is_nan() || d <= 0.0 {
                return Err(SingularBlock(self.ties[j].0));
            }
            let d = d.sqrt();
            self.s[j * m + j] = d;
            for i in j + 1..m {
                let mut x = self.s[i * m + j];
                for k in 0..j {
                    x -= self.s[i * m + k] * self.s[j * m + k];
                }
                self.s[i * m + j] = x / d;
            }
        }
        Ok(())
    }

    /// Turns v = T⁻¹ r into K⁻¹ r (see the module doc); [`Self::prepare`] first.
    pub fn correct(&mut self, v: &mut [Vector6<f64>], prescribed: &[bool]) {
        let m = self.ties.len();
        for (i, &(a, b, normal, _)) in self.ties.iter().enumerate() {
            self.y[i] = project(v, (a, b, normal), prescribed);
        }
        // S y' = y by the Cholesky factor L Lᵀ
        for i in 0..m {
            let mut x = self.y[i];
            for k in 0..i {
                x -= self.s[i * m + k] * self.y[k];
            }
            self.y[i] = x / self.s[i * m + i];
        }
        for i in (0..m).rev() {
            let mut x = self.y[i];
            for k in i + 1..m {
                x -= self.s[k * m + i] * self.y[k];
            }
            self.y[i] = x / self.s[i * m + i];
        }
        for (j, z) in self.z.iter().take(m).enumerate() {
            let yj = self.y[j];
            for (vi, zi) in v.iter_mut().zip(z) {
                *vi -= zi * yj;
            }
        }
    }
}
