//! Rod trees: a trunk clamped at its base and branches welded to the ends of other
//! branches (a T, a Y, a harness with break-outs).
//!
//! Every branch is a [`Rod`] with its own polyline rest shape, stiffness and
//! distributed load. A branch starts at the end point of its parent; the joint is a
//! weld: the branch's base frame stays turned against the parent's end frame by the
//! constant rest rotation `W_b = R_parent,endᵀ R_b,base` (both rest frames), so the
//! unloaded tree reproduces the rest shape.

use nalgebra::Rotation3;

use crate::error::{ReferenceError, Result};
use crate::rod::Rod;

/// Largest gap between a branch's first rest node and its parent's last, relative to
/// the longest branch, for the two to count as joined.
const JOINT_TOLERANCE: f64 = 1e-9;

/// A tree of rods: one trunk (no parent) and branches attached to the ends of their
/// parents. Branches are numbered by their position in the list given to
/// [`Tree::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct Tree {
    rods: Vec<Rod>,
    parents: Vec<Option<usize>>,
    children: Vec<Vec<usize>>,
    /// Branches with every parent before its children (the trunk first).
    order: Vec<usize>,
    /// Rest rotation of each branch's base frame against its parent's end frame
    /// (identity for the trunk).
    welds: Vec<Rotation3<f64>>,
}

impl Tree {
    /// A tree from `(rod, parent)` pairs: exactly one branch (the trunk) has no
    /// parent; every other branch starts at the last rest node of its parent.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidTree`] for an empty list or more than one trunk,
    /// [`ReferenceError::UnknownParent`] for a parent index out of range,
    /// [`ReferenceError::TreeCycle`] when parents form a cycle (a branch that is its
    /// own ancestor, or no trunk at all), [`ReferenceError::DanglingBranch`] for a
    /// branch that does not start at its parent's end.
    pub fn new(branches: Vec<(Rod, Option<usize>)>) -> Result<Self> {
        let count = branches.len();
        if count == 0 {
            return Err(ReferenceError::InvalidTree(
                "a tree needs at least one branch".to_string(),
            ));
        }
        let (rods, parents): (Vec<Rod>, Vec<Option<usize>>) = branches.into_iter().unzip();
        for (branch, parent) in parents.iter().enumerate() {
            if let Some(parent) = *parent {
                if parent >= count {
                    return Err(ReferenceError::UnknownParent {
                        branch,
                        parent,
                        count,
                    });
                }
            }
        }
        for branch in 0..count {
            // a chain of parents longer than the tree has branches loops
            let mut current = branch;
            let mut steps = 0;
            while let Some(parent) = parents[current] {
                current = parent;
                steps += 1;
                if steps > count {
                    return Err(ReferenceError::TreeCycle { branch });
                }
            }
        }
        let roots: Vec<usize> = (0..count).filter(|&b| parents[b].is_none()).collect();
        let [root] = roots[..] else {
            return Err(ReferenceError::InvalidTree(format!(
                "exactly one branch (the trunk) must have no parent; branches {roots:?} have none"
            )));
        };
        let longest = rods.iter().map(Rod::length).fold(0.0, f64::max);
        let mut welds = vec![Rotation3::identity(); count];
        let mut children = vec![Vec::new(); count];
        for (branch, parent) in parents.iter().enumerate() {
            let Some(parent) = *parent else { continue };
            let parent_end = rods[parent].rest_end_pose();
            let base = rods[branch].rest_base_pose();
            let gap = (base.position - parent_end.position).norm();
            if gap > JOINT_TOLERANCE * longest {
                return Err(ReferenceError::DanglingBranch {
                    branch,
                    parent,
                    gap,
                });
            }
            welds[branch] = parent_end.frame.inverse() * base.frame;
            children[parent].push(branch);
        }
        let mut order = vec![root];
        let mut next = 0;
        while next < order.len() {
            order.extend_from_slice(&children[order[next]]);
            next += 1;
        }
        Ok(Self {
            rods,
            parents,
            children,
            order,
            welds,
        })
    }

    /// Number of branches.
    pub fn branch_count(&self) -> usize {
        self.rods.len()
    }

    /// The rod of branch `branch`.
    pub fn rod(&self, branch: usize) -> Option<&Rod> {
        self.rods.get(branch)
    }

    /// The trunk's index (the branch without a parent).
    pub fn trunk(&self) -> usize {
        self.order[0]
    }

    /// The parent of `branch` (`None` for the trunk or an index out of range).
    pub fn parent(&self, branch: usize) -> Option<usize> {
        self.parents.get(branch).copied().flatten()
    }

    /// The branches attached to the end of `branch` (empty for a tip).
    pub fn children(&self, branch: usize) -> &[usize] {
        self.children.get(branch).map_or(&[], Vec::as_slice)
    }

    /// Branches ordered with every parent before its children, the trunk first.
    pub fn order(&self) -> &[usize] {
        &self.order
    }

    /// The rod of a branch index known to be valid (from [`Tree::order`]).
    pub(crate) fn branch_rod(&self, branch: usize) -> &Rod {
        &self.rods[branch]
    }

    /// Rest rotation `W_b` of the base frame of `branch` against its parent's end
    /// frame (identity for the trunk).
    pub(crate) fn weld(&self, branch: usize) -> &Rotation3<f64> {
        &self.welds[branch]
    }

    /// Longest rest arc length from the trunk's base to a tip \[m\].
    pub fn reach(&self) -> f64 {
        let mut to_end = vec![0.0; self.branch_count()];
        let mut longest: f64 = 0.0;
        for &b in &self.order {
            let start = self.parent(b).map_or(0.0, |p| to_end[p]);
            to_end[b] = start + self.rods[b].length();
            longest = longest.max(to_end[b]);
        }
        longest
    }
}
