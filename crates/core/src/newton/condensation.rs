//! Junctions in the Newton solvers (SPEC N1): the hose ends joined at a junction move as
//! one rigid body, so all but one of them — the *master* — are dependent points, condensed
//! out of the system by the master–slave transformation of rigid links (Cook, Malkus,
//! Plesha & Witt, "Concepts and Applications of Finite Element Analysis", 4th ed., §9.5):
//!
//! ```text
//! u_s = T_s u_m,   T_s = [ I  −[o]× ]      o = x_s − x_m, the slave's offset from its master
//!                        [ 0    I   ]      (δx_s = δx_m + δθ_m × o, δθ_s = δθ_m)
//! K_mm += T_sᵀ K_ss T_s,   K_mn += T_sᵀ K_sn,   K_nm += K_ns T_s,   r_m += T_sᵀ r_s
//! ```
//!
//! plus the geometric term of the offset turning with the master: T_sᵀ r_s holds
//! o × f_s, whose derivative along δθ_m is \[f_s\]× \[o\]× δθ_m, so K_θθ,m −= \[f_s\]× \[o\]×.
//! A welded branch point has o = 0: T_s = I, the slave's rows and columns are added to
//! the master's. The assembled matrix keeps its chain layout (every element joins
//! consecutive nodes of one hose); the condensed one is a tree of masters and free nodes
//! ([`BlockTree::from_edges`]), eliminated from its leaves in O(N).

use super::block_tree::{BlockTree, Inertia, NotATree, SingularBlock};
use crate::Model;
use glam::DVec3;
use nalgebra::{Matrix3, Matrix6, Vector6};

/// One slave node: its master and its junction.
#[derive(Clone, Copy, Debug)]
struct Slave {
    node: usize,
    junction: usize,
}

/// Where an element's off-diagonal blocks go in the condensed tree: the child node of
/// the tree edge, and whether the element's first node maps to that child.
#[derive(Clone, Copy, Debug)]
struct EdgeSlot {
    child: usize,
    first_is_child: bool,
}

/// The condensation of a model's junctions and its condensed, factorisable matrix.
#[derive(Clone, Debug)]
pub struct Condensation {
    slaves: Vec<Slave>,
    /// Each junction's master node (the node its slaves are folded onto).
    masters: Vec<usize>,
    /// Each junction's node that takes its folded loads: the master, or the member a
    /// kinematic load case holds (then the whole junction is prescribed).
    targets: Vec<usize>,
    /// Per node: the node its equations are folded onto (itself unless a slave).
    representative: Vec<usize>,
    /// Per slave: the offset o = x_s − x_target and the slave's force before folding.
    offsets: Vec<DVec3>,
    forces: Vec<DVec3>,
    /// Per node: the slave index, or `usize::MAX`.
    slave_index: Vec<usize>,
    /// Per chain edge (i, i + 1) that is an element: its slot in the tree.
    edges: Vec<Option<EdgeSlot>>,
    /// The condensed matrix (slaves keep an identity block and a zero right-hand side).
    pub tree: BlockTree,
}

/// [−o]× as a 3 × 3 matrix acting on δθ: the translation part of T_s.
fn cross_matrix(o: DVec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -o.z, o.y, o.z, 0.0, -o.x, -o.y, o.x, 0.0)
}

/// T = [I, −[o]×; 0, I].
fn transform(o: DVec3) -> Matrix6<f64> {
    let mut t = Matrix6::identity();
    t.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(-cross_matrix(o)));
    t
}

impl Condensation {
    /// The condensation of `model`'s junctions; `None` when it has none. Fails when the
    /// hoses and junctions form a closed loop.
    pub fn new(model: &Model) -> Result<Option<Self>, NotATree> {
        if model.junctions.is_empty() {
            return Ok(None);
        }
        let n = model.node_count();
        let mut representative: Vec<usize> = (0..n).collect();
        let mut slave_index = vec![usize::MAX; n];
        let mut slaves = Vec::new();
        let mut masters = Vec::new();
        for (j, junction) in model.junctions.iter().enumerate() {
            let master = junction.nodes[0];
            masters.push(master);
            for &s in &junction.nodes[1..] {
                representative[s] = master;
                slave_index[s] = slaves.len();
                slaves.push(Slave {
                    node: s,
                    junction: j,
                });
            }
        }
        let mut tree_edges = Vec::new();
        let mut element_edge = vec![false; n.saturating_sub(1)];
        for e in &model.elements {
            element_edge[e.node_a] = true;
            tree_edges.push((representative[e.node_a], representative[e.node_b]));
        }
        let skip: Vec<bool> = slave_index.iter().map(|&k| k != usize::MAX).collect();
        let tree = BlockTree::from_edges(n, &tree_edges, &skip)?;
        let edges = (0..n.saturating_sub(1))
            .map(|i| {
                element_edge[i].then(|| {
                    let (a, b) = (representative[i], representative[i + 1]);
                    if tree.parent(a) == Some(b) {
                        EdgeSlot {
                            child: a,
                            first_is_child: true,
                        }
                    } else {
                        EdgeSlot {
                            child: b,
                            first_is_child: false,
                        }
                    }
                })
            })
            .collect();
        Ok(Some(Self {
            offsets: vec![DVec3::ZERO; slaves.len()],
            forces: vec![DVec3::ZERO; slaves.len()],
            targets: masters.clone(),
            masters,
            slaves,
            representative,
            slave_index,
            edges,
            tree,
        }))
    }

    /// What the condensed matrix depends on besides the assembled one: each slave's
    /// offset, then each slave's force (the geometric term of an offset slave).
    pub fn fold_inputs(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.offsets.iter().chain(&self.forces).copied()
    }

    /// Whether node `i` is a slave (its equations live in its master's).
    pub fn is_slave(&self, i: usize) -> bool {
        self.slave_index[i] != usize::MAX
    }

    /// Folds the loads of every slave onto its junction's target node: f_t += f_s,
    /// m_t += m_s + o × f_s (the slave's rows of T_sᵀ r), and leaves the slave's zero.
    /// `held` names, per junction, a member a kinematic load case holds, if any.
    pub fn fold_loads(
        &mut self,
        x: &[DVec3],
        force: &mut [DVec3],
        moment: &mut [DVec3],
        prescribed: &[bool],
    ) {
        for (j, &master) in self.masters.iter().enumerate() {
            self.targets[j] = master;
        }
        for s in &self.slaves {
            if prescribed[s.node] && !prescribed[self.targets[s.junction]] {
                self.targets[s.junction] = s.node;
            }
        }
        for (k, s) in self.slaves.iter().enumerate() {
            let t = self.targets[s.junction];
            let (node, t) = if t == s.node {
                // the held slave takes the loads; the master is folded onto it
                (self.masters[s.junction], t)
            } else {
                (s.node, t)
            };
            let o = x[node] - x[t];
            let f = force[node];
            self.offsets[k] = x[s.node] - x[self.masters[s.junction]];
            self.forces[k] = force[s.node];
            force[t] += f;
            moment[t] += moment[node] + o.cross(f);
            force[node] = DVec3::ZERO;
            moment[node] = DVec3::ZERO;
        }
    }

    /// The condensed matrix from the assembled one (chain layout, prescribed nodes already
    /// eliminated there).
    fn fold_matrix(&mut self, assembled: &BlockTree) {
        // each tree edge carries exactly one element (a second would close a loop), so
        // its off-diagonal blocks are written, not summed; the edges no element maps to
        // (roots, slaves) keep the zeros they were built with
        self.tree.clear_diagonal();
        let n = assembled.len();
        for i in 0..n {
            let k = self.slave_index[i];
            if k == usize::MAX {
                self.tree.diag[i] += assembled.diag[i];
                continue;
            }
            let r = self.representative[i];
            let o = self.offsets[k];
            if o == DVec3::ZERO {
                self.tree.diag[r] += assembled.diag[i];
            } else {
                let t = transform(o);
                let mut folded = t.transpose() * assembled.diag[i] * t;
                // the offset turns with the master: −[f]×[o]× on δθ
                let geometric = cross_matrix(self.forces[k]) * cross_matrix(o);
                let mut rr = folded.fixed_view_mut::<3, 3>(3, 3);
                rr -= geometric;
                self.tree.diag[r] += folded;
            }
            self.tree.diag[i] = Matrix6::identity();
        }
        for (i, slot) in self.edges.iter().enumerate() {
            let Some(slot) = slot else { continue };
            let (ti, tj) = (self.transform_of(i), self.transform_of(i + 1));
            // block (i, i+1) and block (i+1, i), carried to the representatives
            let mut forward = assembled.upper[i];
            let mut backward = assembled.lower[i];
            if ti.is_some() || tj.is_some() {
                let (ti, tj) = (
                    ti.unwrap_or_else(Matrix6::identity),
                    tj.unwrap_or_else(Matrix6::identity),
                );
                forward = ti.transpose() * forward * tj;
                backward = tj.transpose() * backward * ti;
            }
            let c = slot.child;
            if slot.first_is_child {
                self.tree.upper[c] = forward;
                self.tree.lower[c] = backward;
            } else {
                self.tree.upper[c] = backward;
                self.tree.lower[c] = forward;
            }
        }
    }

    /// T of node `i` when it is a slave with a non-zero offset.
    fn transform_of(&self, i: usize) -> Option<Matrix6<f64>> {
        let k = self.slave_index[i];
        (k != usize::MAX && self.offsets[k] != DVec3::ZERO).then(|| transform(self.offsets[k]))
    }

    /// rhs_m += T_sᵀ rhs_s, rhs_s = 0 for every slave (idempotent).
    pub fn fold_rhs(&self, rhs: &mut [Vector6<f64>]) {
        for (k, s) in self.slaves.iter().enumerate() {
            let m = self.representative[s.node];
            let r = rhs[s.node];
            let o = self.offsets[k];
            let f = DVec3::new(r[0], r[1], r[2]);
            let extra = o.cross(f);
            rhs[m] += Vector6::new(
                r[0],
                r[1],
                r[2],
                r[3] + extra.x,
                r[4] + extra.y,
                r[5] + extra.z,
            );
            rhs[s.node] = Vector6::zeros();
        }
    }

    /// u_s = T_s u_m for every slave.
    pub fn expand(&self, u: &mut [Vector6<f64>]) {
        for (k, s) in self.slaves.iter().enumerate() {
            let m = u[self.representative[s.node]];
            let theta = DVec3::new(m[3], m[4], m[5]);
            let dx = DVec3::new(m[0], m[1], m[2]) + theta.cross(self.offsets[k]);
            u[s.node] = Vector6::new(dx.x, dx.y, dx.z, m[3], m[4], m[5]);
        }
    }

    /// Condenses `assembled` and factorises the result ([`BlockTree::factor`]).
    pub fn factor(&mut self, assembled: &BlockTree) -> Result<(), SingularBlock> {
        self.fold_matrix(assembled);
        self.tree.factor()
    }

    /// Condenses `assembled` and factorises a positive-definite neighbour of the result
    /// ([`BlockTree::factor_modified`]).
    pub fn factor_modified(&mut self, assembled: &BlockTree) -> Result<Inertia, SingularBlock> {
        self.fold_matrix(assembled);
        self.tree.factor_modified()
    }

    /// Solves the condensed system for `rhs` (one entry per node, slaves included) with the
    /// last factors, and expands the slaves' increments.
    pub fn solve_factored(&self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        self.fold_rhs(rhs);
        self.tree.solve_factored(rhs)?;
        self.expand(rhs);
        Ok(())
    }
}

/// A factorised Newton matrix: the assembled one itself, or its junctions' condensation.
#[derive(Clone, Copy)]
pub enum Factored<'a> {
    Chain(&'a BlockTree),
    Condensed(&'a Condensation),
}

impl Factored<'_> {
    pub fn solve_factored(&self, rhs: &mut [Vector6<f64>]) -> Result<(), SingularBlock> {
        match self {
            Factored::Chain(m) => m.solve_factored(rhs),
            Factored::Condensed(c) => c.solve_factored(rhs),
        }
    }
}
