//! Converged solutions: reactions and sampling of the fields along the rod.

use nalgebra::{Rotation3, Vector3};

use crate::boundary::EndCondition;
use crate::error::{ReferenceError, Result};
use crate::ode::{integrate, Augmented};
use crate::shooting::{ShootingSolver, Unknowns};
use crate::so3;

/// A force and a moment; the point the moment is taken about is stated where a
/// `Wrench` is returned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wrench {
    /// Force \[N\], global.
    pub force: Vector3<f64>,
    /// Moment \[N m\], global.
    pub moment: Vector3<f64>,
}

/// The fields at one reference arc length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionState {
    /// Reference arc length `s` \[m\].
    pub arc_length: f64,
    /// Centre line `r(s)` \[m\].
    pub position: Vector3<f64>,
    /// Material frame `R(s) = [d1 d2 d3]`. At an interior rest node this is the
    /// frame *after* the concentrated rest kink (that of the following segment).
    pub frame: Rotation3<f64>,
    /// Internal force `n(s)` \[N\]: exerted by the part `(s, L]` on `[0, s]`.
    pub force: Vector3<f64>,
    /// Internal moment `m(s)` \[N m\] (about `r(s)`), same convention.
    pub moment: Vector3<f64>,
}

/// A converged static equilibrium.
///
/// Reaction conventions: the support at `s = L` applies `+n(L)`, `+m(L)` (about
/// `r(L)`) to the rod; the base support applies `−n(0)`, `−m(0)` (about the base
/// point `r(0)`). Global equilibrium then reads
/// `−n(0) + n(L) + ∫q ds = 0` and
/// `−m(0) + m(L) + (r(L) − r(0)) × n(L) + ∫(r − r(0)) × q ds = 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    solver: ShootingSolver,
    end_condition: EndCondition,
    unknowns: Unknowns,
    end_state: SectionState,
    iterations: usize,
    residual: f64,
    load_scale: f64,
}

impl Solution {
    pub(crate) fn new(
        solver: ShootingSolver,
        end_condition: EndCondition,
        unknowns: Unknowns,
        end_state: SectionState,
        iterations: usize,
        residual: f64,
        load_scale: f64,
    ) -> Self {
        Self {
            solver,
            end_condition,
            unknowns,
            end_state,
            iterations,
            residual,
            load_scale,
        }
    }

    /// The solver that produced this solution.
    pub(crate) fn solver(&self) -> &ShootingSolver {
        &self.solver
    }

    /// The converged shooting unknowns `n(0)`, `m(0)`.
    pub fn unknowns(&self) -> Unknowns {
        self.unknowns
    }

    /// The end condition this solution satisfies.
    pub fn end_condition(&self) -> &EndCondition {
        &self.end_condition
    }

    /// Newton iterations used by the final solve.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// Final scaled residual (max norm).
    pub fn residual(&self) -> f64 {
        self.residual
    }

    /// Fields at the base, `s = 0`.
    pub fn base_state(&self) -> SectionState {
        let base = self.solver.base();
        SectionState {
            arc_length: 0.0,
            position: base.position,
            frame: base.frame,
            force: self.unknowns.force,
            moment: self.unknowns.moment,
        }
    }

    /// Fields at the end, `s = L`.
    pub fn end_state(&self) -> &SectionState {
        &self.end_state
    }

    /// Force and moment the base support applies to the rod: `−n(0)`, `−m(0)`,
    /// moment about the base point `r(0)`.
    pub fn base_reaction(&self) -> Wrench {
        Wrench {
            force: -self.unknowns.force,
            moment: -self.unknowns.moment,
        }
    }

    /// Force and moment the end support (or end load) applies to the rod:
    /// `+n(L)`, `+m(L)`, moment about the end point `r(L)`.
    pub fn end_reaction(&self) -> Wrench {
        Wrench {
            force: self.end_state.force,
            moment: self.end_state.moment,
        }
    }

    /// Fields at the given reference arc lengths (any order, each in `[0, L]`), on
    /// the same RK4 grid as the solve.
    ///
    /// # Errors
    ///
    /// [`ReferenceError::InvalidArcLength`] for arc lengths outside `[0, L]` or not
    /// finite.
    pub fn sample(&self, arc_lengths: &[f64]) -> Result<Vec<SectionState>> {
        let rod = self.solver.rod();
        let length = rod.length();
        if let Some(&bad) = arc_lengths
            .iter()
            .find(|s| !(s.is_finite() && **s >= 0.0 && **s <= length))
        {
            return Err(ReferenceError::InvalidArcLength {
                arc_length: bad,
                length,
            });
        }
        let mut order: Vec<usize> = (0..arc_lengths.len()).collect();
        order.sort_by(|&a, &b| arc_lengths[a].total_cmp(&arc_lengths[b]));
        let sorted: Vec<f64> = order.iter().map(|&i| arc_lengths[i]).collect();
        let mut out = vec![None; arc_lengths.len()];
        let start = Augmented::<0> {
            state: self.solver.base_state(&self.unknowns),
            variations: [],
        };
        integrate(
            rod,
            self.load_scale,
            self.solver.options().steps_per_length,
            start,
            &sorted,
            |i, a| {
                out[order[i]] = Some(SectionState {
                    arc_length: sorted[i],
                    position: a.state.r,
                    frame: so3::nearest_rotation(&a.state.frame),
                    force: a.state.n,
                    moment: a.state.m,
                });
            },
        )?;
        out.into_iter()
            .zip(arc_lengths)
            .map(|(state, &s)| {
                state.ok_or_else(|| ReferenceError::Integration {
                    arc_length: s,
                    reason: "sample point not reached".to_string(),
                })
            })
            .collect()
    }

    /// Fields at the rest nodes `s_0 … s_K` (see [`crate::Rod::node_arc_lengths`]).
    ///
    /// # Errors
    ///
    /// never in practice (the node arc lengths are valid); see
    /// [`Solution::sample`].
    pub fn node_states(&self) -> Result<Vec<SectionState>> {
        let arc = self.solver.rod().node_arc_lengths().to_vec();
        self.sample(&arc)
    }
}
