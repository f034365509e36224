//! Divergence detection: a run that produces non-finite numbers or runaway speeds is
//! stopped with a message naming the step, the node and the likely cause, instead of
//! silently writing NaN.

use crate::{Model, State};

/// A diverged simulation.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("simulation diverged at step {step} (t = {time:.6} s), hose '{hose}' node {node}: {what}. Likely cause: {cause}")]
pub struct Divergence {
    pub step: u64,
    pub time: f64,
    pub hose: String,
    pub node: usize,
    pub what: String,
    pub cause: String,
}

/// Largest support force \[N\] (and moment \[N·m\]) taken as physical: far beyond anything a
/// hose, a hand or a clip can carry, so a larger one is a numerical blow-up — also while
/// every held node stays where its hand puts it.
pub const MAX_FORCE: f64 = 1e9;

/// Checks the state for non-finite values and for node speeds beyond the material's wave
/// speed c = √(E/ρ) — no hose point moves that fast in an assembly study, so such a speed
/// is a numerical blow-up. O(N); call it every few steps.
pub fn check(model: &Model, state: &State) -> Result<(), Divergence> {
    check_against(model, state, wave_speed_limit(model))
}

/// [`check`] for non-finite values only: for the static solver, whose velocities are
/// displacements over an input step (a correct large-deflection solve may move a soft
/// hose faster than its wave speed "per step"; that is no blow-up).
pub fn check_finite(model: &Model, state: &State) -> Result<(), Divergence> {
    check_against(model, state, f64::INFINITY)
}

/// The check that makes sense for a solver: [`check`] where velocities are motion
/// (explicit, implicit), [`check_finite`] for the static solver.
pub fn check_for(kind: crate::SolverKind, model: &Model, state: &State) -> Result<(), Divergence> {
    match kind {
        crate::SolverKind::Static => check_finite(model, state),
        _ => check(model, state),
    }
}

fn check_against(model: &Model, state: &State, speed_limit: f64) -> Result<(), Divergence> {
    for i in 0..state.x.len() {
        let x = state.x[i];
        let v = state.v[i];
        let bad = if !x.is_finite() || !state.q[i].is_finite() {
            Some("position/orientation is not finite".to_string())
        } else if !v.is_finite() || !state.w[i].is_finite() {
            Some("velocity is not finite".to_string())
        } else if !(state.reaction_force[i].length() <= MAX_FORCE
            && state.reaction_moment[i].length() <= MAX_FORCE)
        {
            Some(format!(
                "a support force or moment is beyond {MAX_FORCE:e} N (N·m) or not finite"
            ))
        } else if v.length() > speed_limit {
            Some(format!(
                "speed {:.3e} m/s exceeds the wave speed {:.3e} m/s",
                v.length(),
                speed_limit
            ))
        } else {
            None
        };
        if let Some(what) = bad {
            let (hose, node) = locate(model, i);
            let cause = likely_cause(model, state);
            return Err(Divergence {
                step: state.step,
                time: state.time,
                hose,
                node,
                what,
                cause,
            });
        }
    }
    Ok(())
}

fn wave_speed_limit(model: &Model) -> f64 {
    model
        .elements
        .iter()
        .map(|e| {
            (e.axial_stiffness_tension.max(e.axial_stiffness_compression) / e.mass_per_length)
                .sqrt()
        })
        .fold(0.0, f64::max)
}

fn locate(model: &Model, global: usize) -> (String, usize) {
    for h in &model.hoses {
        if h.nodes().contains(&global) {
            return (h.name.clone(), global - h.first_node);
        }
    }
    ("?".into(), global)
}

fn likely_cause(model: &Model, state: &State) -> String {
    let r = &model.time_step_report;
    if model.time_step > r.critical {
        format!(
            "the time step {:.3e} s is above the stable limit {:.3e} s; leave time_step unset",
            model.time_step, r.critical
        )
    } else if state.loads.any_drive_moving(state.time)
        // the check runs every few steps: a drive that ended since the last one counts
        || state.loads.any_drive_moving(state.time - 16.0 * model.time_step)
    {
        "a drive moves or turns a node too fast for the hose to follow; give the move a longer duration".into()
    } else {
        "numerical instability: lower time_step_safety, or check for extreme material values".into()
    }
}
