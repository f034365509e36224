//! Restarted GMRES (Saad & Schultz 1986, "GMRES: a generalized minimal residual
//! algorithm for solving nonsymmetric linear systems", SIAM J. Sci. Stat. Comput. 7;
//! Saad, "Iterative Methods for Sparse Linear Systems", 2003, alg. 6.9 with Givens
//! rotations) on vectors of node blocks, for the Newton solvers' hose–hose contact
//! coupling ([`super::system::NewtonSystem::solve_linear`]).
//!
//! The contact tangent of a pair of beams on different stretches of the node chain
//! couples nodes far outside the block band. With the band T factorised, the Newton
//! system (T + C) δu = r is solved as (I + T⁻¹C) δu = T⁻¹r. The plain fixed-point
//! iteration δu ← T⁻¹(r − C δu) on the same splitting converges with the ratio of the
//! contact stiffness to the contact stiffness plus the hoses' own stiffness at the
//! contact — 1 − 4·10⁻⁴ for two soft hoses pressed together, i.e. not at all in practice.
//! T⁻¹C has rank at most twice the number of contact pairs, so GMRES on I + T⁻¹C finds
//! the solution in at most that many iterations plus one (exact arithmetic), whatever the
//! stiffness ratio.
//!
//! All storage is allocated when the solver is built (restart length × nodes blocks);
//! a solve allocates nothing.

use nalgebra::Vector6;

/// Krylov vectors kept before a restart.
pub const RESTART: usize = 24;
/// Restart cycles at most (iterations ≤ `RESTART` × this).
const MAX_CYCLES: usize = 8;

/// Buffers of a restarted GMRES on `n` node blocks.
#[derive(Clone, Debug, Default)]
pub struct Gmres {
    n: usize,
    /// The Krylov basis, `RESTART + 1` vectors of `n` blocks, one after the other.
    basis: Vec<Vector6<f64>>,
    /// Scratch vector of `n` blocks.
    w: Vec<Vector6<f64>>,
    /// Hessenberg matrix, column-major ((RESTART + 1) × RESTART), after the rotations.
    h: Vec<f64>,
    cs: Vec<f64>,
    sn: Vec<f64>,
    g: Vec<f64>,
    y: Vec<f64>,
}

/// How a GMRES solve ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GmresReport {
    /// Operator applications.
    pub iterations: usize,
    /// Final residual ‖b − A x‖ over ‖b‖ (as the Givens recursion tracks it).
    pub relative_residual: f64,
    pub converged: bool,
}

fn dot(a: &[Vector6<f64>], b: &[Vector6<f64>]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x.dot(y)).sum()
}

fn norm(a: &[Vector6<f64>]) -> f64 {
    dot(a, a).sqrt()
}

impl Gmres {
    /// Buffers for systems of `n` node blocks.
    pub fn new(n: usize) -> Self {
        let m = RESTART;
        Self {
            n,
            basis: vec![Vector6::zeros(); (m + 1) * n],
            w: vec![Vector6::zeros(); n],
            h: vec![0.0; (m + 1) * m],
            cs: vec![0.0; m],
            sn: vec![0.0; m],
            g: vec![0.0; m + 1],
            y: vec![0.0; m],
        }
    }

    /// Node blocks the buffers are for.
    pub fn len(&self) -> usize {
        self.n
    }

    /// Whether the buffers are for no nodes at all ([`Gmres::default`]).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Solves A x = b to ‖b − A x‖ ≤ `tolerance` ‖b‖, starting from the `x` given.
    /// `apply(v, out)` writes A v into `out` (all `n` blocks).
    pub fn solve(
        &mut self,
        b: &[Vector6<f64>],
        x: &mut [Vector6<f64>],
        tolerance: f64,
        mut apply: impl FnMut(&[Vector6<f64>], &mut [Vector6<f64>]),
    ) -> GmresReport {
        let (n, m) = (self.n, RESTART);
        assert!(b.len() == n && x.len() == n, "GMRES built for {n} blocks");
        let b_norm = norm(b);
        let mut report = GmresReport {
            iterations: 0,
            relative_residual: 0.0,
            converged: true,
        };
        if b_norm == 0.0 {
            x.fill(Vector6::zeros());
            return report;
        }
        let target = tolerance * b_norm;
        for _ in 0..MAX_CYCLES {
            // r = b − A x into the first basis vector
            apply(x, &mut self.w);
            report.iterations += 1;
            let (v0, _) = self.basis.split_at_mut(n);
            for ((v, bi), wi) in v0.iter_mut().zip(b).zip(&self.w) {
                *v = bi - wi;
            }
            let beta = norm(v0);
            report.relative_residual = beta / b_norm;
            if !beta.is_finite() {
                report.converged = false;
                return report;
            }
            if beta <= target {
                report.converged = true;
                return report;
            }
            v0.iter_mut().for_each(|v| *v /= beta);
            self.g.fill(0.0);
            self.g[0] = beta;
            let mut k = 0;
            for j in 0..m {
                let (done, rest) = self.basis.split_at_mut((j + 1) * n);
                apply(&done[j * n..], &mut self.w);
                report.iterations += 1;
                // modified Gram–Schmidt
                for i in 0..=j {
                    let vi = &done[i * n..(i + 1) * n];
                    let hij = dot(&self.w, vi);
                    self.h[j * (m + 1) + i] = hij;
                    for (w, v) in self.w.iter_mut().zip(vi) {
                        *w -= hij * v;
                    }
                }
                let h_next = norm(&self.w);
                self.h[j * (m + 1) + j + 1] = h_next;
                // the earlier rotations on the new column, then its own
                let col = &mut self.h[j * (m + 1)..(j + 1) * (m + 1)];
                for i in 0..j {
                    let (a, c) = (col[i], col[i + 1]);
                    col[i] = self.cs[i] * a + self.sn[i] * c;
                    col[i + 1] = -self.sn[i] * a + self.cs[i] * c;
                }
                let r = col[j].hypot(col[j + 1]);
                let (c, s) = if r > 0.0 {
                    (col[j] / r, col[j + 1] / r)
                } else {
                    (1.0, 0.0)
                };
                self.cs[j] = c;
                self.sn[j] = s;
                col[j] = r;
                col[j + 1] = 0.0;
                self.g[j + 1] = -s * self.g[j];
                self.g[j] *= c;
                k = j + 1;
                report.relative_residual = self.g[j + 1].abs() / b_norm;
                // breakdown (the Krylov space is invariant: the solution is in it) or done
                if h_next <= 1e-14 * beta || self.g[j + 1].abs() <= target {
                    break;
                }
                let next = &mut rest[..n];
                for (v, w) in next.iter_mut().zip(&self.w) {
                    *v = w / h_next;
                }
            }
            // y = R⁻¹ g, x += V y
            for i in (0..k).rev() {
                let mut s = self.g[i];
                for l in i + 1..k {
                    s -= self.h[l * (m + 1) + i] * self.y[l];
                }
                let d = self.h[i * (m + 1) + i];
                self.y[i] = if d != 0.0 { s / d } else { 0.0 };
            }
            for i in 0..k {
                let yi = self.y[i];
                for (xj, v) in x.iter_mut().zip(&self.basis[i * n..(i + 1) * n]) {
                    *xj += yi * v;
                }
            }
            if report.relative_residual <= tolerance {
                report.converged = true;
                return report;
            }
        }
        report.converged = report.relative_residual <= tolerance;
        report
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    fn rng(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    }

    fn as_blocks(v: &DVector<f64>) -> Vec<Vector6<f64>> {
        (0..v.len() / 6)
            .map(|i| Vector6::from_column_slice(&v.as_slice()[6 * i..6 * i + 6]))
            .collect()
    }

    fn flat(v: &[Vector6<f64>]) -> DVector<f64> {
        DVector::from_iterator(6 * v.len(), v.iter().flat_map(|b| b.iter().copied()))
    }

    /// I + a low-rank, nearly singular, non-symmetric perturbation — the shape of the
    /// contact-coupled Newton system — against a dense LU solve: converged within two
    /// cycles of rank + 2 operator applications (one in exact arithmetic; the near-
    /// cancelling direction costs a restart in round-off), to 1e-10.
    #[test]
    fn identity_plus_low_rank_is_solved_in_rank_steps() {
        let n = 30;
        let mut seed = 7;
        for rank in [1, 3, 8] {
            let mut a = DMatrix::<f64>::identity(6 * n, 6 * n);
            for r in 0..rank {
                let u = DVector::from_fn(6 * n, |_, _| rng(&mut seed));
                let v = DVector::from_fn(6 * n, |_, _| rng(&mut seed));
                // eigenvalues of I + T⁻¹C lie in (0, 2]: one direction almost cancelling the
                // identity (two nodes moving together, stiff contact on soft hoses), the
                // others doubling it (the contact spring stretched)
                let scale = if r == 0 { -0.9996 } else { 1.0 } / u.dot(&v);
                a += scale * &u * v.transpose();
            }
            let b = DVector::from_fn(6 * n, |_, _| rng(&mut seed));
            let exact = a.clone().lu().solve(&b).unwrap();
            let mut gmres = Gmres::new(n);
            let mut x = vec![Vector6::zeros(); n];
            let report = gmres.solve(&as_blocks(&b), &mut x, 1e-13, |v, out| {
                let y = &a * flat(v);
                out.copy_from_slice(&as_blocks(&y));
            });
            assert!(report.converged, "rank {rank}: {report:?}");
            assert!(report.converged, "rank {rank}: {report:?}");
            // rank + 2 applications in exact arithmetic; one restart allowed for round-off
            assert!(
                report.iterations <= 2 * (rank + 2),
                "rank {rank}: {report:?}"
            );
            let err = (flat(&x) - &exact).norm() / exact.norm();
            assert!(err < 1e-10, "rank {rank}: relative error {err:e}");
        }
    }

    /// A general non-symmetric system needs restarts; they converge too.
    #[test]
    fn restarts_converge_on_a_general_system() {
        let n = 10;
        let mut seed = 11;
        let a = DMatrix::<f64>::from_fn(6 * n, 6 * n, |i, j| {
            rng(&mut seed) * 0.6 + if i == j { 2.0 } else { 0.0 }
        });
        let b = DVector::from_fn(6 * n, |_, _| rng(&mut seed));
        let exact = a.clone().lu().solve(&b).unwrap();
        let mut gmres = Gmres::new(n);
        let mut x = vec![Vector6::zeros(); n];
        let report = gmres.solve(&as_blocks(&b), &mut x, 1e-12, |v, out| {
            out.copy_from_slice(&as_blocks(&(&a * flat(v))));
        });
        assert!(report.converged, "{report:?}");
        assert!(report.iterations > RESTART, "needed a restart: {report:?}");
        let err = (flat(&x) - &exact).norm() / exact.norm();
        assert!(err < 1e-9, "relative error {err:e}");
    }

    #[test]
    fn zero_right_hand_side_gives_zero() {
        let mut gmres = Gmres::new(2);
        let mut x = vec![Vector6::repeat(1.0); 2];
        let r = gmres.solve(&[Vector6::zeros(); 2], &mut x, 1e-12, |v, out| {
            out.copy_from_slice(v)
        });
        assert!(r.converged && x.iter().all(|v| v.norm() == 0.0));
    }
}
