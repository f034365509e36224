//! The modified Newton method (Ortega & Rheinboldt 1970, §7.1; Deuflhard 2004, "Newton
//! Methods for Nonlinear Problems", §2.1.4 "simplified Newton"): the Jacobian factorised
//! at one iterate solves for the increments of the next ones,
//!   J(u₀) δuₖ = r(uₖ),  uₖ₊₁ = uₖ + δuₖ,
//! so that those iterations need the residual alone — the loads without the elements'
//! tangents ([`NewtonSystem::assemble_loads`]) — and no factorisation. It converges
//! linearly, at a rate that grows with the distance from u₀; the caller refactorises when
//! the residual stops contracting fast enough. The solution is that of the residual
//! r(u) = 0, whatever matrix produced the increments: only the path of the iterates
//! changes.
//!
//! [`FrozenJacobian`] keeps the factors of the system's last factorisation, and the
//! couplings the linear solve applies beside them (hose–hose pairs, a junction shape's
//! contacts, ties), while loads-only assemblies run: it exchanges them with spare
//! buffers for the assembly and back (nothing is copied).

use super::block_tree::{BlockTree, SingularBlock};
use super::shape_contact::ShapeCoupling;
use super::ties::TieCouplings;
use super::NewtonSystem;
use crate::contact::ContactPair;
use nalgebra::Vector6;

/// The factors of a Newton system's last factorisation, kept for modified Newton steps.
#[derive(Clone, Debug)]
pub struct FrozenJacobian {
    /// Spare buffers while the factors are in the system; the factors while a loads-only
    /// assembly writes into the spare ones ([`Self::exchange`]).
    matrix: BlockTree,
    pairs: Vec<ContactPair>,
    shape_couplings: Vec<ShapeCoupling>,
    ties: TieCouplings,
    /// Whether the system holds factors that [`Self::solve`] may use.
    frozen: bool,
    /// Solves with kept factors so far.
    pub reused: usize,
}

impl FrozenJacobian {
    /// Spare buffers shaped like `system`'s.
    pub fn new(system: &NewtonSystem) -> Self {
        Self {
            matrix: system.matrix.clone(),
            pairs: Vec::new(),
            shape_couplings: Vec::new(),
            ties: TieCouplings::default(),
            frozen: false,
            reused: 0,
        }
    }

    /// The system's matrix was just factorised (with its couplings scaled as the solve
    /// applies them): keep those factors.
    pub fn freeze(&mut self) {
        self.frozen = true;
    }

    /// The factors are gone or no longer wanted (an assembly with the tangent overwrites
    /// them).
    pub fn thaw(&mut self) {
        self.frozen = false;
    }

    pub fn is_frozen(&self) -> bool {
        self.frozen
    }

    /// Exchanges the system's matrix and couplings with the spare ones. Called in pairs
    /// around a loads-only assembly: the assembly clears and writes the spare buffers, and
    /// the factors come back unchanged. (With junctions the factors are in the
    /// condensation's own tree, which an assembly does not touch.)
    pub fn exchange(&mut self, system: &mut NewtonSystem) {
        std::mem::swap(&mut self.matrix, &mut system.matrix);
        std::mem::swap(&mut self.pairs, &mut system.pairs);
        std::mem::swap(&mut self.shape_couplings, &mut system.shape_couplings);
        std::mem::swap(&mut self.ties, &mut system.ties);
    }

    /// Solves J δu = rhs with the kept factors (rhs becomes δu; prescribed nodes'
    /// increments are zero).
    pub fn solve(&mut self, system: &mut NewtonSystem) -> Result<(), SingularBlock> {
        debug_assert!(self.frozen, "no factors kept");
        for (r, &p) in system.rhs.iter_mut().zip(&system.prescribed) {
            if p {
                *r = Vector6::zeros();
            }
        }
        self.reused += 1;
        system.solve_with_factors()
    }
}
