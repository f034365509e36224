//! Whether a static equilibrium is stable, and leaving it when it is not (SPEC
//! S1).
//!
//! An equilibrium is stable when the tangent K = ∂²Π/∂u² of the potential energy is
//! positive definite on the free nodes. The static solver factorises K anyway; by
//! Sylvester's law of inertia its block LDLᵀ factors D'ᵢ carry as many negative
//! eigenvalues as K ([`crate::newton::block_tree::Inertia`]). A negative one means
//! a buckling or bifurcation point has been passed: the hose stands in an equilibrium no
//! real hose keeps (a column compressed straight past its Euler load, a post-buckled
//! shape of a higher mode). The solver then steps off along a direction of negative
//! curvature d (dᵀKd < 0, from the factors: Lᵀ d = e) by the smallest amplitude that
//! lowers the energy, and lets Newton (on a positive-definite modification of K, so
//! every step descends) find the stable equilibrium nearby — the branch a real hose,
//! disturbed by anything at all, would take.

use crate::newton::block_tree::Inertia;
use crate::newton::system::{apply_increment, NewtonSystem};
use crate::{Model, State};
use glam::{DQuat, DVec3};
use nalgebra::Vector6;

/// An unstable equilibrium met, and left, by the static solver — or a limit point
/// passed ([`super::snap`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityEvent {
    /// Input time of the solve \[s\].
    pub time: f64,
    /// The load path's equilibrium branch ended here (a limit point): the hose snapped
    /// through to a distant stable equilibrium, followed dynamically. `mode` is then the
    /// snap's displacement, `amplitude` its largest translation, `energy_drop` the
    /// potential energy released, and `negative_eigenvalues` 0.
    pub limit_point: bool,
    /// Negative eigenvalues of the tangent at the unstable equilibrium (1: a simple
    /// buckling or bifurcation; more: several modes passed at once).
    pub negative_eigenvalues: usize,
    /// The node where the unstable mode moves most (global index).
    pub node: usize,
    /// Potential energy released by stepping off, before the new equilibrium \[J\]
    /// (the whole release is larger).
    pub energy_drop: f64,
    /// The amplitude of the step off \[m\].
    pub amplitude: f64,
    /// The unstable mode: each node's translation, the largest of length 1.
    pub mode: Vec<DVec3>,
}

/// Scratch of the escape, allocated once per solver.
#[derive(Clone, Debug)]
pub struct Escape {
    direction: Vec<Vector6<f64>>,
    saved_x: Vec<DVec3>,
    saved_q: Vec<DQuat>,
}

/// Largest amplitude tried, in mean element lengths.
const MAX_AMPLITUDE_PER_LENGTH: f64 = 8.0;
/// First amplitude tried, in mean element lengths (doubled until the energy drops).
const FIRST_AMPLITUDE_PER_LENGTH: f64 = 1e-3;

impl Escape {
    pub fn new(nodes: usize) -> Self {
        Self {
            direction: vec![Vector6::zeros(); nodes],
            saved_x: vec![DVec3::ZERO; nodes],
            saved_q: vec![DQuat::IDENTITY; nodes],
        }
    }

    /// Steps `state` off the unstable equilibrium whose (modified) factorisation `sys`
    /// holds, along the negative-curvature direction of `inertia`, in the sense and by the
    /// smallest amplitude (1e-3 element lengths, doubled up to 8 lengths) that lowers the
    /// potential energy. `None` (state unchanged) when no amplitude lowers it — the
    /// negative pivot was round-off, not an instability.
    pub fn step_off(
        &mut self,
        model: &Model,
        state: &mut State,
        sys: &mut NewtonSystem,
        inertia: &Inertia,
    ) -> Option<StabilityEvent> {
        let (block, _, eigenvector) = inertia.first?;
        let d = &mut self.direction;
        sys.negative_curvature_direction(block, &eigenvector, d);
        let length = sys.mean_length;
        // scale: the largest translation (or rotation × element length) becomes 1 m
        let mut size: f64 = 0.0;
        let mut node = 0;
        for (i, v) in d.iter().enumerate() {
            if sys.prescribed[i] {
                continue;
            }
            let t = v
                .fixed_rows::<3>(0)
                .norm()
                .max(v.fixed_rows::<3>(3).norm() * length);
            if t > size {
                size = t;
                node = i;
            }
        }
        if !(size > 0.0 && size.is_finite()) {
            return None;
        }
        // descend: −dΠ/da = (f, m)·d ≥ 0 (the loads are −∇Π)
        let mut slope = 0.0;
        for (i, v) in d.iter().enumerate() {
            if !sys.prescribed[i] {
                slope += sys.force[i].dot(DVec3::new(v[0], v[1], v[2]))
                    + sys.moment[i].dot(DVec3::new(v[3], v[4], v[5]));
            }
        }
        let sign = if slope >= 0.0 { 1.0 } else { -1.0 };
        for v in d.iter_mut() {
            *v *= sign / size;
        }
        let moment_work = dead_moment_work(state, d);
        let energy0 = sys.potential_energy(model, state);
        self.saved_x.copy_from_slice(&state.x);
        self.saved_q.copy_from_slice(&state.q);
        let mut amplitude = FIRST_AMPLITUDE_PER_LENGTH * length;
        while amplitude <= MAX_AMPLITUDE_PER_LENGTH * length {
            apply_increment(state, d, &sys.prescribed, amplitude);
            let energy = sys.potential_energy(model, state) - amplitude * moment_work;
            let drop = energy0 - energy;
            if drop > 1e-12 * energy0.abs() && drop.is_finite() {
                let mode = d
                    .iter()
                    .map(|v| DVec3::new(v[0], v[1], v[2]))
                    .collect::<Vec<_>>();
                let largest = mode.iter().map(|m| m.length()).fold(0.0, f64::max);
                let mode = if largest > 0.0 {
                    mode.into_iter().map(|m| m / largest).collect()
                } else {
                    mode
                };
                return Some(StabilityEvent {
                    time: state.time,
                    limit_point: false,
                    negative_eigenvalues: inertia.negative,
                    node,
                    energy_drop: drop,
                    amplitude,
                    mode,
                });
            }
            state.x.copy_from_slice(&self.saved_x);
            state.q.copy_from_slice(&self.saved_q);
            amplitude *= 2.0;
        }
        None
    }
}

/// The work of the dead moments along a unit step d, Σ M·δθ (they have no potential;
/// exact for a fixed axis, first order otherwise).
pub(crate) fn dead_moment_work(state: &State, d: &[Vector6<f64>]) -> f64 {
    let mut work = 0.0;
    for (_, case) in state.loads.iter() {
        if let crate::loads::LoadCase::DeadLoad(l) = case {
            let r = d[l.node];
            work += l.at(state.time).1.dot(DVec3::new(r[3], r[4], r[5]));
        }
    }
    work
}
