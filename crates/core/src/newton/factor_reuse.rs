//! Reuse of a modified factorisation whose input has not changed.
//!
//! The static solver factorises the tangent at each equilibrium it finds, to read its
//! inertia (the stability check). The next input step starts from that very
//! configuration, and its first Newton iteration assembles the same tangent again — the
//! loads that changed (a hand's target, a dead load's value) enter the right-hand side,
//! not the matrix. When the eliminated matrix, and what the junctions' condensation folds
//! in, are the same bit for bit as those the factors in hand were computed from, the
//! factors are those of the new matrix: they are used again, and the results are
//! unchanged to the last bit.

use super::block_tree::{BlockTree, Inertia};
use super::condensation::Condensation;
use glam::DVec3;
use nalgebra::Matrix6;

/// The input of the last modified factorisation, and the inertia it found.
#[derive(Clone, Debug, Default)]
pub struct FactorReuse {
    /// Diagonal, upper and lower blocks of the eliminated matrix, one after the other.
    blocks: Vec<Matrix6<f64>>,
    /// The junction slaves' offsets and forces the condensation folded in.
    junction: Vec<DVec3>,
    /// `None`: the factors in hand are not a modified factorisation of `blocks`.
    inertia: Option<Inertia>,
    /// Factorisations skipped because the input was the same.
    pub reused: u64,
}

impl FactorReuse {
    /// Buffers for a matrix of `nodes` block rows and the condensation `junctions`.
    pub fn new(nodes: usize, junctions: Option<&Condensation>) -> Self {
        let slaves = junctions.map_or(0, |j| j.fold_inputs().count());
        Self {
            blocks: vec![Matrix6::zeros(); 3 * nodes],
            junction: vec![DVec3::ZERO; slaves],
            inertia: None,
            reused: 0,
        }
    }

    /// The inertia of the factors in hand if they were computed from exactly `matrix`
    /// and `junctions`' fold inputs (counted in [`Self::reused`]).
    pub fn reusable(
        &mut self,
        matrix: &BlockTree,
        junctions: Option<&Condensation>,
    ) -> Option<Inertia> {
        let inertia = self.inertia?;
        let n = matrix.len();
        if self.blocks.len() != 3 * n {
            return None;
        }
        let (diag, rest) = self.blocks.split_at(n);
        let (upper, lower) = rest.split_at(n);
        let same = same_bits(diag, &matrix.diag)
            && same_bits(upper, &matrix.upper)
            && same_bits(lower, &matrix.lower)
            && junctions.is_none_or(|j| {
                j.fold_inputs()
                    .zip(&self.junction)
                    .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits))
            });
        if same {
            self.reused += 1;
            Some(inertia)
        } else {
            None
        }
    }

    /// Keeps a copy of `matrix` and `junctions`' fold inputs, about to be factorised;
    /// [`Self::factorised`] completes the record.
    pub fn record(&mut self, matrix: &BlockTree, junctions: Option<&Condensation>) {
        let n = matrix.len();
        self.inertia = None;
        self.blocks.resize(3 * n, Matrix6::zeros());
        let (diag, rest) = self.blocks.split_at_mut(n);
        let (upper, lower) = rest.split_at_mut(n);
        diag.copy_from_slice(&matrix.diag);
        upper.copy_from_slice(&matrix.upper);
        lower.copy_from_slice(&matrix.lower);
        if let Some(j) = junctions {
            for (slot, v) in self.junction.iter_mut().zip(j.fold_inputs()) {
                *slot = v;
            }
        }
    }

    /// The recorded matrix was factorised, with this inertia.
    pub fn factorised(&mut self, inertia: Inertia) {
        self.inertia = Some(inertia);
    }

    /// The factors in hand no longer belong to the record (another factorisation, or a
    /// failed one).
    pub fn forget(&mut self) {
        self.inertia = None;
    }
}

/// Whether two block lists are equal bit for bit (a −0 is not a +0; NaN payloads
/// compare by their bits, which no factorisation would produce twice alike in practice,
/// but equal bits are equal input all the same).
fn same_bits(a: &[Matrix6<f64>], b: &[Matrix6<f64>]) -> bool {
    a.len() == b.len() && bits(a) == bits(b)
}

/// The blocks' entries as their bit patterns (a `Matrix6<f64>` is 36 contiguous `f64`s).
fn bits(blocks: &[Matrix6<f64>]) -> &[u64] {
    let entries = blocks.len() * 36;
    debug_assert_eq!(std::mem::size_of::<Matrix6<f64>>(), 36 * 8);
    // SAFETY: `Matrix6<f64>` stores its 36 entries contiguously (nalgebra's `ArrayStorage`
    // is `[[f64; 6]; 6]`, `repr(C)`), a slice of them has no padding, and `u64` has the
    // size and alignment of `f64`: the memory is `entries` valid, aligned `u64`s.
    unsafe { std::slice::from_raw_parts(blocks.as_ptr().cast::<u64>(), entries) }
}
