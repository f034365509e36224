//! A block-sparse linear system with 6 × 6 blocks whose graph is a tree (a forest) — the
//! shape of the tangent of beam nodes joined into chains and, at junctions, into trees
//! (each node couples only to the nodes it shares an element with) — solved in O(N) by
//! block Gaussian elimination from the leaves: eliminating a node whose children are
//! already eliminated leaves a coupling to its parent only, so no block fills in (Parter,
//! "The use of linear graphs in Gauss elimination", SIAM Review 3, 1961; for a chain this
//! is the block Thomas algorithm, Golub & Van Loan, "Matrix Computations", §4.5.1). Each
//! pivot block is factorised by LU with partial pivoting. All storage is allocated once; a
//! solve allocates nothing.

use super::block_lu::{self, BlockLu};
use nalgebra::{Matrix6, Vector6};

/// No parent: the node is the root of its tree.
pub const NO_PARENT: usize = usize::MAX;

/// Rows/columns of node i are the block i; `upper[i]` is block (i, parent(i)), `lower[i]`
/// is block (parent(i), i). Nodes are eliminated in `order` (children before their
/// parent). A chain — [`BlockTree::new`] — has parent(i) = i + 1 and the natural order:
/// `upper[i]` is then block (i, i+1) and `lower[i]` block (i+1, i), a block-tridiagonal
/// matrix.
#[derive(Clone, Debug)]
pub struct BlockTree {
    pub diag: Vec<Matrix6<f64>>,
    pub upper: Vec<Matrix6<f64>>,
    pub lower: Vec<Matrix6<f64>>,
    /// Each node's parent ([`NO_PARENT`] for a root).
    parent: Vec<usize>,
    /// Elimination order: every node after all of its children.
    order: Vec<usize>,
    /// Children of each node, `children[child_start[i]..child_start[i + 1]]`.
    child_start: Vec<usize>,
    children: Vec<usize>,
    /// Scratch: D'⁻¹ U per block row (elimination multipliers).
    gain: Vec<Matrix6<f64>>,
    /// LU factors of the eliminated diagonal blocks D'.
    factors: Vec<Option<BlockLu>>,
}

/// What the elimination of a symmetric tangent says about its definiteness (Sylvester's
/// law of inertia on the block LDLᵀ factorisation K = L D Lᵀ, D = diag(D'ᵢ): K has as
/// many negative eigenvalues as the pivot blocks D'ᵢ together).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Inertia {
    /// Negative eigenvalues of the (symmetric parts of the) pivot blocks.
    pub negative: usize,
    /// The first block with a negative eigenvalue: its index, the eigenvalue and the
    /// eigenvector — the seed of a direction of negative curvature
    /// ([`BlockTree::negative_curvature_direction`]).
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

/// The graph given to [`BlockTree::from_edges`] is not a forest.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error("the nodes {0} and {1} are joined along two paths (a closed loop); the Newton solvers need a tree")]
pub struct NotATree(pub usize, pub usize);

impl BlockTree {
    /// A chain of `n` nodes: node i couples to i − 1 and i + 1.
    pub fn new(n: usize) -> Self {
        let parent = (0..n)
            .map(|i| if i + 1 < n { i + 1 } else { NO_PARENT })
            .collect();
        Self::with_parents(parent, (0..n).collect())
    }

    /// The tree (forest) of `n` nodes with the undirected `edges`; nodes in `skip` take
    /// no part (they keep a diagonal block and are their own roots). Each tree is rooted
    /// at its highest-numbered node and eliminated from its leaves.
    pub fn from_edges(n: usize, edges: &[(usize, usize)], skip: &[bool]) -> Result<Self, NotATree> {
        let mut start = vec![0usize; n + 1];
        for &(a, b) in edges {
            start[a + 1] += 1;
            start[b + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut adjacent = vec![0usize; start[n]];
        for &(a, b) in edges {
            adjacent[fill[a]] = b;
            fill[a] += 1;
            adjacent[fill[b]] = a;
            fill[b] += 1;
        }
        let mut parent = vec![NO_PARENT; n];
        let mut seen = vec![false; n];
        let mut order = Vec::with_capacity(n);
        // depth-first from each root; a node is finished (ordered) after its children
        let mut stack: Vec<(usize, usize)> = Vec::new();
        // the edge to its parent each node passes over once (a second one is a loop)
        let mut passed_parent = vec![false; n];
        for root in (0..n).rev() {
            if seen[root] {
                continue;
            }
            seen[root] = true;
            if skip[root] {
                order.push(root);
                continue;
            }
            stack.push((root, start[root]));
            while let Some(top) = stack.last_mut() {
                let node = top.0;
                if top.1 == start[node + 1] {
                    order.push(node);
                    stack.pop();
                    continue;
                }
                let other = adjacent[top.1];
                top.1 += 1;
                if other == parent[node] && !passed_parent[node] {
                    passed_parent[node] = true;
                    continue;
                }
                if seen[other] {
                    return Err(NotATree(node, other));
                }
                seen[other] = true;
                parent[other] = node;
                stack.push((other, start[other]));
            }
        }
        Ok(Self::with_parents(parent, order))
    }

    fn with_parents(parent: Vec<usize>, order: Vec<usize>) -> Self {
        let n = parent.len();
        let mut child_start = vec![0usize; n + 1];
        for &p in &parent {
            if p != NO_PARENT {
                child_start[p + 1] += 1;
            }
        }
        for i in 0..n {
            child_start[i + 1] += child_start[i];
        }
        let mut fill = child_start.clone();
        let mut children = vec![0usize; child_start[n]];
        for (c, &p) in parent.iter().enumerate() {
            if p != NO_PARENT {
                children[fill[p]] = c;
                fill[p] += 1;
            }
        }
        Self {
            diag: vec![Matrix6::zeros(); n],
            upper: vec![Matrix6::zeros(); n],
            lower: vec![Matrix6::zeros(); n],
            parent,
            order,
            child_start,
            children,
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

    /// Node `i`'s parent, `None` for a root.
    pub fn parent(&self, i: usize) -> Option<usize> {
        let p = self.parent[i];
        (p != NO_PARENT).then_some(p)
    }

    /// The nodes whose parent is `i`.
    pub fn children(&self, i: usize) -> &[usize] {
        &self.children[self.child_start[i]..self.child_start[i + 1]]
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

    /// Zeroes the diagonal blocks only.
    pub fn clear_diagonal(&mut self) {
        for m in &mut self.diag {
            m.fill(0.0);
        }
    }

    /// Replaces node `i`'s equations by δu_i = 0 (a prescribed node): identity on the
    /// diagonal, its row and column couplings removed.
    pub fn eliminate(&mut self, i: usize) {
        self.diag[i] = Matrix6::identity();
        if self.parent[i] != NO_PARENT {
            self.upper[i].fill(0.0);
            self.lower[i].fill(0.0);
        }
        for k in self.child_start[i]..self.child_start[i + 1] {
            let c = self.children[k];
            self.upper[c].fill(0.0);
            self.lower[c].fill(0.0);
        }
    }

    /// Solves A x = rhs in place (rhs becomes x). Destroys the matrix's diagonal blocks.
    pub fn solve(&mut self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        self.factor()?;
        self.solve_factored(rhs)
    }

    /// Block elimination from the leaves: D'_i = D_i − Σ_children L_c D'_c⁻¹ U_c, each D'_i
    /// factorised by LU and the multipliers D'_i⁻¹ U_i kept, so that
    /// [`Self::solve_factored`] can then solve for any number of right-hand sides.
    /// Overwrites the diagonal blocks.
    pub fn factor(&mut self) -> Result<(), SingularBlock> {
        for k in 0..self.order.len() {
            let i = self.order[k];
            let lu = self.diag[i].lu();
            self.pivot(i, lu)?;
        }
        Ok(())
    }

    /// Stores node `i`'s pivot factors, its multipliers, and eliminates it from its
    /// parent's diagonal block.
    fn pivot(&mut self, i: usize, lu: BlockLu) -> Result<(), SingularBlock> {
        let p = self.parent[i];
        if p != NO_PARENT {
            self.gain[i] = block_lu::solve_matrix(&lu, &self.upper[i]).ok_or(SingularBlock(i))?;
            let l = self.lower[i];
            self.diag[p] -= l * self.gain[i];
        }
        self.factors[i] = Some(lu);
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
        let mut inertia = Inertia::default();
        for k in 0..self.order.len() {
            let i = self.order[k];
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
            self.pivot(i, lu)?;
        }
        Ok(inertia)
    }

    /// A direction d of negative curvature of a symmetric K from its [`Inertia`]:
    /// Lᵀ d = e, e = the first negative pivot block's eigenvector, so that
    /// dᵀ K d = eᵀ D e = λ < 0 (the gains of the blocks eliminated before it are those of
    /// K's own factorisation). Call after [`Self::factor_modified`]; `d` has one entry per
    /// node.
    pub fn negative_curvature_direction(
        &self,
        block: usize,
        eigenvector: &Vector6<f64>,
        d: &mut [Vector6<f64>],
    ) {
        d.fill(Vector6::zeros());
        d[block] = *eigenvector;
        let Some(position) = self.order.iter().position(|&i| i == block) else {
            return;
        };
        for &j in self.order[..position].iter().rev() {
            let p = self.parent[j];
            if p != NO_PARENT {
                let next = d[p];
                d[j] = -(self.gain[j] * next);
            }
        }
    }

    /// Solves with the factors of the last [`Self::factor`] (rhs becomes x).
    pub fn solve_factored(&self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        for &i in &self.order {
            let lu = self.factors[i].as_ref().ok_or(SingularBlock(i))?;
            rhs[i] = block_lu::solve(lu, &rhs[i]).ok_or(SingularBlock(i))?;
            if !rhs[i].iter().all(|v| v.is_finite()) {
                return Err(SingularBlock(i));
            }
            let p = self.parent[i];
            if p != NO_PARENT {
                // r'_p = r_p − L_i y_i
                let y = rhs[i];
                rhs[p] -= self.lower[i] * y;
            }
        }
        for &i in self.order.iter().rev() {
            let p = self.parent[i];
            if p != NO_PARENT {
                let next = rhs[p];
                rhs[i] -= self.gain[i] * next;
            }
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
        let mut a = BlockTree::new(n);
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

    /// A tree of three chains meeting at one node (eliminated from the leaves, in an
    /// order that is not the numbering) against a dense LU solve; a closed loop is
    /// refused.
    #[test]
    fn a_tree_matches_dense_solve_and_a_loop_is_refused() {
        // 0-1-2-[9], 3-4-5-[9], 6-7-8-[9]: three arms of three nodes joined at node 9
        let edges: Vec<(usize, usize)> = vec![
            (0, 1),
            (1, 2),
            (2, 9),
            (3, 4),
            (4, 5),
            (5, 9),
            (6, 7),
            (7, 8),
            (8, 9),
        ];
        let n = 10;
        let mut a = BlockTree::from_edges(n, &edges, &[false; 10]).unwrap();
        let mut seed = 99u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        let mut dense = DMatrix::<f64>::zeros(6 * n, 6 * n);
        for i in 0..n {
            a.diag[i] = Matrix6::from_fn(|_, _| rnd()) + Matrix6::identity() * 8.0;
            dense.view_mut((6 * i, 6 * i), (6, 6)).copy_from(&a.diag[i]);
        }
        for i in 0..n {
            if let Some(p) = a.parent(i) {
                a.upper[i] = Matrix6::from_fn(|_, _| rnd());
                a.lower[i] = Matrix6::from_fn(|_, _| rnd());
                dense
                    .view_mut((6 * i, 6 * p), (6, 6))
                    .copy_from(&a.upper[i]);
                dense
                    .view_mut((6 * p, 6 * i), (6, 6))
                    .copy_from(&a.lower[i]);
            }
        }
        assert_eq!(a.children(9).len(), 3);
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
        let mut looped = edges.clone();
        looped.push((0, 3));
        assert!(BlockTree::from_edges(n, &looped, &[false; 10]).is_err());
        // a doubled edge is a loop too
        let mut doubled = edges;
        doubled.push((1, 0));
        assert!(BlockTree::from_edges(n, &doubled, &[false; 10]).is_err());
    }
}
