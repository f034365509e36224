//! Divergence detection: a run that produces non-finite numbers or runaway speeds is
//! stopped with a message naming the step, the node and the likely cause, instead of
//! silently writing NaN.

use crate::{Model, State};

/// A diverged simulation: where and when, what happened as a typed reason with its
/// numbers (`kind`), and the same in words (`what`, `cause`) for the message.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("simulation diverged at step {step} (t = {time:.6} s), hose '{hose}' node {node}: {what}. Likely cause: {cause}")]
pub struct Divergence {
    pub step: u64,
    pub time: f64,
    pub hose: String,
    pub node: usize,
    pub kind: DivergenceKind,
    pub what: String,
    pub cause: String,
}

/// What diverged, with its numbers; serialised as an object whose `kind` names the
/// variant (`summary.json` `diverged`). A number that is not finite is left out.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DivergenceKind {
    /// A node's position or orientation is not finite.
    NonFiniteState,
    /// A node's velocity or angular velocity is not finite.
    NonFiniteVelocity,
    /// A support force \[N\] or moment \[N·m\] beyond `limit` (or not finite: left out).
    SupportLoad {
        #[serde(skip_serializing_if = "Option::is_none")]
        force_n: Option<f64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        moment_nm: Option<f64>,
        limit: f64,
    },
    /// A node faster than the material's wave speed.
    Speed { speed_m_s: f64, wave_speed_m_s: f64 },
    /// The implicit solver's Newton iterations did not converge even with the step
    /// halved `halvings` times; `residual_n` is the last residual force \[N\].
    NotConverged {
        solver: &'static str,
        halvings: u32,
        #[serde(skip_serializing_if = "Option::is_none")]
        residual_n: Option<f64>,
    },
    /// The static solve produced non-finite values at Newton iteration `iteration`.
    NonFiniteIteration {
        solver: &'static str,
        iteration: usize,
    },
    /// A Newton system had a singular block at `node` (global node index).
    Singular { solver: &'static str, node: usize },
    /// The hose–hose contact pairs found in one search exceed the model's budget.
    ContactPairs { pairs: usize, limit: usize },
}

/// `x` if it is finite, else `None` (left out of the output: no output holds a non-finite
/// number).
pub fn finite_or_none(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
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
    if let Some(o) = state.hose_contact.overflow {
        let node = model.elements.get(o.element).map_or(0, |e| e.node_a);
        let (hose, node) = locate(model, node);
        return Err(Divergence {
            step: state.step,
            time: state.time,
            hose,
            node,
            kind: DivergenceKind::ContactPairs {
                pairs: o.pairs,
                limit: o.limit,
            },
            what: format!(
                "more than {} hose–hose contact pairs (the memory budget's)",
                o.limit
            ),
            cause: "hoses piled on one another: lay them apart, switch hose contact off \
                    (hose_contact = \"off\") or raise --max-memory"
                .into(),
        });
    }
    for i in 0..state.x.len() {
        let x = state.x[i];
        let v = state.v[i];
        let (force, moment) = (
            state.reaction_force[i].length(),
            state.reaction_moment[i].length(),
        );
        let bad = if !x.is_finite() || !state.q[i].is_finite() {
            Some((
                DivergenceKind::NonFiniteState,
                "position/orientation is not finite".to_string(),
            ))
        } else if !v.is_finite() || !state.w[i].is_finite() {
            Some((
                DivergenceKind::NonFiniteVelocity,
                "velocity is not finite".to_string(),
            ))
        } else if !(force <= MAX_FORCE && moment <= MAX_FORCE) {
            Some((
                DivergenceKind::SupportLoad {
                    force_n: finite_or_none(force),
                    moment_nm: finite_or_none(moment),
                    limit: MAX_FORCE,
                },
                format!("a support force or moment is beyond {MAX_FORCE:e} N (N·m) or not finite"),
            ))
        } else if v.length() > speed_limit {
            Some((
                DivergenceKind::Speed {
                    speed_m_s: v.length(),
                    wave_speed_m_s: speed_limit,
                },
                format!(
                    "speed {:.3e} m/s exceeds the wave speed {:.3e} m/s",
                    v.length(),
                    speed_limit
                ),
            ))
        } else {
            None
        };
        if let Some((kind, what)) = bad {
            let (hose, node) = locate(model, i);
            let cause = likely_cause(model, state);
            return Err(Divergence {
                step: state.step,
                time: state.time,
                hose,
                node,
                kind,
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
