//! Settling: reaching static equilibrium with the explicit step by dynamic relaxation with
//! kinetic damping (Cundall 1976; Barnes 1999, "Form finding and analysis of tension
//! structures by dynamic relaxation"): the explicit step runs on, and every time the
//! total kinetic energy passes a peak all velocities are set to zero. The state walks
//! down the energy landscape to the nearest equilibrium (optionally with viscous damping
//! only). Used by the validation suite and Python's `Simulation.settle` to reach static
//! states of the same explicit model the user runs (its answer is the model's, not
//! another solver's). Pliant's one word for reaching rest is *settle*; the quasi-static
//! Newton solver (`integrators::statics`) solves for the same equilibrium directly.

use crate::health::{check, Divergence};
use crate::integrators::explicit::step;
use crate::{Model, State};
use glam::DVec3;

/// When to stop relaxing.
#[derive(Clone, Copy, Debug)]
pub struct SettleOptions {
    /// Largest allowed out-of-balance force on a free node \[N\].
    pub force_tolerance: f64,
    /// Largest allowed out-of-balance moment on a free node \[N·m\].
    pub moment_tolerance: f64,
    /// Give up after this many steps.
    pub max_steps: u64,
    /// Zero all velocities at each kinetic-energy peak. Fast for stiff, well-conditioned
    /// problems; for a very soft mode (a column near buckling) turn it off and rely on the
    /// model's viscous damping tuned near that mode's critical value instead.
    pub kinetic_damping: bool,
}

/// How relaxation ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SettleReport {
    pub steps: u64,
    pub residual_force: f64,
    pub residual_moment: f64,
    pub converged: bool,
}

/// Largest out-of-balance force and moment on the free nodes after the last step.
pub fn residual(state: &State) -> (f64, f64) {
    let mut f: f64 = 0.0;
    let mut m: f64 = 0.0;
    for i in 0..state.x.len() {
        if !state.held[i] {
            f = f.max(state.force[i].length());
            m = m.max(state.moment[i].length());
        }
    }
    (f, m)
}

/// Sets every velocity to zero (nodes and stiffened bodies): kinetic damping's reset at a
/// peak of the kinetic energy.
pub(crate) fn stop(state: &mut State) {
    state.v.fill(DVec3::ZERO);
    state.w.fill(DVec3::ZERO);
    for b in state.bodies.iter_mut() {
        b.velocity = DVec3::ZERO;
        b.angular_velocity = DVec3::ZERO;
    }
}

/// Kinetic damping (Cundall 1976): every velocity set to zero each time the total kinetic
/// energy passes a peak. Call [`KineticDamping::after_step`] after each explicit step.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct KineticDamping {
    last_energy: f64,
}

impl KineticDamping {
    /// Stops everything if the kinetic energy fell since the last step (a peak passed).
    pub(crate) fn after_step(&mut self, model: &Model, state: &mut State) {
        let energy = state.kinetic_energy(model);
        if energy < self.last_energy {
            stop(state);
            self.last_energy = 0.0;
        } else {
            self.last_energy = energy;
        }
    }
}

/// Relaxes `state` to static equilibrium under its current load cases.
pub fn settle(
    model: &Model,
    state: &mut State,
    opts: &SettleOptions,
) -> Result<SettleReport, Divergence> {
    let mut damping = KineticDamping::default();
    let mut steps = 0;
    while steps < opts.max_steps {
        step(model, state);
        steps += 1;
        if opts.kinetic_damping {
            damping.after_step(model, state);
        }
        if steps % 64 == 0 {
            check(model, state)?;
            let (f, m) = residual(state);
            if f <= opts.force_tolerance && m <= opts.moment_tolerance {
                return Ok(SettleReport {
                    steps,
                    residual_force: f,
                    residual_moment: m,
                    converged: true,
                });
            }
        }
    }
    let (f, m) = residual(state);
    Ok(SettleReport {
        steps,
        residual_force: f,
        residual_moment: m,
        converged: false,
    })
}
