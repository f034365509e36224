//! A block-tridiagonal linear system with 6 × 6 blocks — the shape of a chain of beam
//! nodes' tangent (each node couples only to its neighbours) — solved in O(N) by block
//! Gaussian elimination (the block Thomas algorithm; Golub & Van Loan, "Matrix
//! Computations", §4.5.1), each diagonal block factorised by LU with partial pivoting.
//! All storage is allocated once; a solve allocates nothing.

use nalgebra::{Matrix6, Vector6};

/// Rows/columns of node i are the block i; `upper[i]` is block (i, i+1), `lower[i]` is
/// block (i+1, i).
#[derive(Clone, Debug)]
pub struct BlockTridiagonal {
    pub diag: Vec<Matrix6<f64>>,
    pub upper: Vec<Matrix6<f64>>,
    pub lower: Vec<Matrix6<f64>>,
    /// Scratch: D'⁻¹ U per block row (elimination multipliers).
    gain: Vec<Matrix6<f64>>,
    /// LU factors of the eliminated diagonal blocks D'.
    factors: Vec<Option<BlockLu>>,
}

type BlockLu = nalgebra::LU<f64, nalgebra::Const<6>, nalgebra::Const<6>>;

/// What the elimination of a symmetric tangent says about its definiteness (Sylvester's
/// law of inertia on the block LDLᵀ factorisation K = L D Lᵀ, D = diag(D'ᵢ): K has as
/// many negative eigenvalues as the pivot blocks D'ᵢ together).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Inertia {
    /// Negative eigenvalues of the (symmetric parts of the) pivot blocks.
    pub negative: usize,
    /// The first block with a negative eigenvalue: its index, the eigenvalue and the
    /// eigenvector — the seed of a direction of negative curvature
    /// ([`BlockTridiagonal::negative_curvature_direction`]).
    pub first: Option<(usize, f64, Vector6<f64>)>,
}

impl Inertia {
    /// Whether the factorised matrix is positive definite.
    pub fn positive_definite(&self) -> bool {
        self.negative == 0
    }
}

/// The elimination met a singular pivot block (a node with no stiffness and no mass in
/// some direction — e.g. a free-floating hose in a static solve).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("singular tangent at node {0}")]
pub struct SingularBlock(pub usize);

impl BlockTridiagonal {
    pub fn new(n: usize) -> Self {
        Self {
            diag: vec![Matrix6::zeros(); n],
            upper: vec![Matrix6::zeros(); n.saturating_sub(1)],
            lower: vec![Matrix6::zeros(); n.saturating_sub(1)],
            gain: vec![Matrix6::zeros(); n],
            factors: vec![None; n],
        }
    }

    pub fn len(&self) -> usize {
        self.diag.len()
    }

    pub fn is_empty(&self) -> bool {
        self.diag.is_empty()
    }

    pub fn clear(&mut self) {
        for m in self
            .diag
            .iter_mut()
            .chain(self.upper.iter_mut())
            .chain(self.lower.iter_mut())
        {
            m.fill(0.0);
        }
    }

    /// Replaces node `i`'s equations by δu_i = 0 (a prescribed node): identity on the
    /// diagonal, its row and column couplings removed.
    pub fn eliminate(&mut self, i: usize) {
        self.diag[i] = Matrix6::identity();
        if i > 0 {
            self.upper[i - 1].fill(0.0);
            self.lower[i - 1].fill(0.0);
        }
        if i + 1 < self.diag.len() {
            self.upper[i].fill(0.0);
            self.lower[i].fill(0.0);
        }
    }

    /// Solves A x = rhs in place (rhs becomes x). Destroys the matrix's diagonal blocks.
    pub fn solve(&mut self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        self.factor()?;
        self.solve_factored(rhs)
    }

    /// Block elimination: D'_i = D_i − L_{i−1} D'_{i−1}⁻¹ U_{i−1}, each D'_i factorised by LU
    /// and the multipliers D'_i⁻¹ U_i kept, so that [`Self::solve_factored`] can then solve
    /// for any number of right-hand sides. Overwrites the diagonal blocks.
    pub fn factor(&mut self) -> Result<(), SingularBlock> {
        let n = self.diag.len();
        for i in 0..n {
            if i > 0 {
                let l = self.lower[i - 1];
                self.diag[i] -= l * self.gain[i - 1];
            }
            let lu = self.diag[i].lu();
            if i + 1 < n {
                self.gain[i] = lu.solve(&self.upper[i]).ok_or(SingularBlock(i))?;
            }
            self.factors[i] = Some(lu);
        }
        Ok(())
    }

    /// [`Self::factor`] of a symmetric matrix that also counts its negative eigenvalues
    /// and factorises a positive-definite neighbour K + E instead (modified LDLᵀ; Gill,
    /// Murray & Wright, "Practical Optimization", 1981, §4.4.2; Cheng & Higham 1998): a
    /// pivot block whose symmetric part is not positive definite has each eigenvalue
    /// λ < δ raised to max(|λ|, δ), δ = 1e-8 of the block's largest |λ|. E = 0 where K is
    /// positive definite, so Newton keeps its quadratic convergence there; elsewhere the
    /// step solved with K + E is a descent direction of the energy.
    pub fn factor_modified(&mut self) -> Result<Inertia, SingularBlock> {
        let n = self.diag.len();
        let mut inertia = Inertia::default();
        for i in 0..n {
            if i > 0 {
                let l = self.lower[i - 1];
                self.diag[i] -= l * self.gain[i - 1];
            }
            let symmetric = (self.diag[i] + self.diag[i].transpose()) * 0.5;
            if symmetric.cholesky().is_none() {
                let eig = symmetric.symmetric_eigen();
                let largest = eig.eigenvalues.amax();
                let floor = 1e-8 * largest;
                for k in 0..6 {
                    let lambda = eig.eigenvalues[k];
                    if lambda >= floor {
                        continue;
                    }
                    let v = eig.eigenvectors.column(k).into_owned();
                    if lambda < -1e-12 * largest {
                        inertia.negative += 1;
                        let more_negative =
                            inertia.first.is_some_and(|(j, l, _)| j == i && lambda < l);
                        if inertia.first.is_none() || more_negative {
                            inertia.first = Some((i, lambda, v));
                        }
                    }
                    let raised = lambda.abs().max(floor);
                    self.diag[i] += v * v.transpose() * (raised - lambda);
                }
            }
            let lu = self.diag[i].lu();
            if i + 1 < n {
                self.gain[i] = lu.solve(&self.upper[i]).ok_or(SingularBlock(i))?;
            }
            self.factors[i] = Some(lu);
        }
        Ok(inertia)
    }

    /// A direction d of negative curvature of a symmetric K from its [`Inertia`]:
    /// Lᵀ d = e, e = the first negative pivot block's eigenvector, so that
    /// dᵀ K d = eᵀ D e = λ < 0 (the gains of the blocks before it are those of K's own
    /// factorisation). Call after [`Self::factor_modified`]; `d` has one entry per node.
    pub fn negative_curvature_direction(
        &self,
        block: usize,
        eigenvector: &Vector6<f64>,
        d: &mut [Vector6<f64>],
    ) {
        d.fill(Vector6::zeros());
        d[block] = *eigenvector;
        for j in (0..block).rev() {
            let next = d[j + 1];
            d[j] = -(self.gain[j] * next);
        }
    }

    /// Solves with the factors of the last [`Self::factor`] (rhs becomes x).
    pub fn solve_factored(&self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        let n = self.diag.len();
        for i in 0..n {
            if i > 0 {
                // r'_i = r_i − L_{i−1} y_{i−1}
                let prev = rhs[i - 1];
                rhs[i] -= self.lower[i - 1] * prev;
            }
            let lu = self.factors[i].as_ref().ok_or(SingularBlock(i))?;
            rhs[i] = lu.solve(&rhs[i]).ok_or(SingularBlock(i))?;
            if !rhs[i].iter().all(|v| v.is_finite()) {
                return Err(SingularBlock(i));
            }
        }
        for i in (0..n.saturating_sub(1)).rev() {
            let next = rhs[i + 1];
            rhs[i] -= self.gain[i] * next;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// Against a dense LU solve of the same (non-symmetric) system.
    #[test]
    fn matches_dense_solve() {
        let n = 7;
        let mut a = BlockTridiagonal::new(n);
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        for i in 0..n {
            a.diag[i] = Matrix6::from_fn(|_, _| rnd()) + Matrix6::identity() * 8.0;
            if i + 1 < n {
                a.upper[i] = Matrix6::from_fn(|_, _| rnd());
                a.lower[i] = Matrix6::from_fn(|_, _| rnd());
            }
        }
        let mut dense = DMatrix::<f64>::zeros(6 * n, 6 * n);
        for i in 0..n {
            dense.view_mut((6 * i, 6 * i), (6, 6)).copy_from(&a.diag[i]);
            if i + 1 < n {
                dense
                    .view_mut((6 * i, 6 * i + 6), (6, 6))
                    .copy_from(&a.upper[i]);
                dense
                    .view_mut((6 * i + 6, 6 * i), (6, 6))
                    .copy_from(&a.lower[i]);
            }
        }
        let b: Vec<Vector6<f64>> = (0..n).map(|_| Vector6::from_fn(|_, _| rnd())).collect();
        let mut flat = nalgebra::DVector::<f64>::zeros(6 * n);
        for i in 0..n {
            flat.rows_mut(6 * i, 6).copy_from(&b[i]);
        }
        let expected = dense.lu().solve(&flat).unwrap();
        let mut x = b.clone();
        a.solve(&mut x).unwrap();
        for i in 0..n {
            for k in 0..6 {
                assert!((x[i][k] - expected[6 * i + k]).abs() < 1e-12);
            }
        }
    }
}
