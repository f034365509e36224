//! The quasi-static solve restricted to what is out of equilibrium (SPEC P5). Nodes held
//! in all six degrees of freedom — fixings pressed in, seated clips, fixed connector
//! ends, mounts, hands — transmit nothing between their neighbours in a static
//! equilibrium, so the network falls apart at them into independent problems
//! ([`super::component`]: joined along elements, through rigid bodies, along ties and
//! across hose–hose contact reach). A component whose free nodes are in balance and
//! whose held nodes stay where they are is already at its equilibrium: Newton would not
//! move it. So the static solver assembles the whole model once, takes as seeds the free
//! nodes out of balance (the tolerance of the whole problem, above their round-off floor)
//! and the held nodes whose targets moved, and solves the component of those seeds alone
//! on a model of its own ([`super::cut::Cut`]), with the whole problem's residual
//! limits; the rest is not touched. The result is then checked on the whole model: one
//! more assembly, every free node against the tolerance. Only if that holds is the
//! solve done — the equilibrium of every component, the solved ones' stability checked
//! by their own solve ([`super::stability`]); otherwise (a solved hose pressed into
//! another component's reach during the solve) the whole model is solved on from there.
//! Models a cut cannot carry exactly (yielding or relaxing elements, parts riding on
//! junction bodies) are solved whole.

use super::component::ComponentSearch;
use super::cut::Cut;
use super::stability::StabilityEvent;
use super::statics::{StaticError, StaticOptions, StaticReport, StaticSolver};
use crate::newton::block_tree::SingularBlock;
use crate::newton::convergence::Tolerance;
use crate::newton::system::residual_norms;
use crate::{Model, State};
use glam::DVec3;

/// The component solved last and its own static solver, kept while the component and
/// its load cases stay the same ([`Cut::refresh`]).
#[derive(Clone, Debug)]
pub struct Split {
    cut: Cut,
    solver: StaticSolver,
}

/// How a solve restricted to the components out of balance ended.
pub(super) enum Outcome {
    /// Solved, and the whole model checked in balance: the report of the whole.
    Solved(StaticReport),
    /// The whole model is to be solved, from the state as it is now: after the solve of
    /// a component (its report: the iterations spent, the first increment) or as it was.
    Whole(Option<StaticReport>),
}

/// Solves only the components of `model` out of balance in `state` (module doc), with
/// the prescribed poses `solver.system` was set up with ([`crate::newton::NewtonSystem::set_prescribed`]).
/// `seeds` and `search` are scratch.
pub(super) fn solve_out_of_balance(
    solver: &mut StaticSolver,
    model: &Model,
    state: &mut State,
    (seeds, search): (&mut Vec<usize>, &mut ComponentSearch),
) -> Result<Outcome, StaticError> {
    let whole = Outcome::Whole(None);
    if !Cut::carries(model) {
        return Ok(whole);
    }
    let n = model.node_count();
    let sys = &mut solver.system;
    sys.assemble(model, state, 0.0);
    let tolerance = solver.options.tolerance;
    let (limit_f, limit_m) = tolerance.limits(sys.scale);
    seeds.clear();
    for i in 0..n {
        let out = if sys.prescribed[i] {
            sys.moves(state, i)
        } else {
            let (floor_f, floor_m) = sys.noise_floor(state, i);
            let (f, m) = (sys.force[i].length(), sys.moment[i].length());
            // not finite: out of balance, the solve reports it
            !(f <= floor_f.max(limit_f) && m <= floor_m.max(limit_m))
        };
        if out {
            seeds.push(i);
        }
    }
    if seeds.is_empty() {
        return Ok(whole); // in balance: the whole path confirms it and checks stability
    }
    let nodes = search.run(model, state, seeds);
    if nodes.len() == n {
        return Ok(whole);
    }
    let kept = match &mut solver.split {
        Some(split) => split.cut.refresh(state, nodes),
        None => false,
    };
    if !kept {
        let Some(cut) = Cut::new(model, state, nodes.to_vec()) else {
            return Ok(whole);
        };
        let Ok(own) = StaticSolver::new(&cut.model) else {
            return Ok(whole);
        };
        solver.split = Some(Box::new(Split { cut, solver: own }));
    }
    let split = solver.split.as_mut().expect("made above");
    // the whole problem's limits (the component's own load scale is smaller)
    split.solver.options = StaticOptions {
        tolerance: Tolerance {
            relative: tolerance.relative,
            force: limit_f,
            moment: limit_m,
        },
        split: false,
        ..solver.options
    };
    let (cut, own) = (&mut split.cut, &mut split.solver);
    let part = own.solve(&cut.model, &mut cut.state).map_err(|e| match e {
        StaticError::Singular(SingularBlock(k)) => {
            StaticError::Singular(SingularBlock(cut.nodes.get(k).copied().unwrap_or(k)))
        }
        other => other,
    })?;
    if !part.converged {
        // the whole solve from the start, as without the split
        return Ok(whole);
    }
    cut.write_back(state);
    let sys = &mut solver.system;
    // the component's held nodes are on their targets: the whole system's are now
    sys.move_prescribed(state);
    sys.assemble(model, state, 0.0);
    let (rf, rm) = residual_norms(&sys.force, &sys.moment, &sys.prescribed);
    let (above_f, above_m) = sys.residuals_above_noise(state);
    carry_events(&own.events, &cut.nodes, n, &mut solver.events);
    if !tolerance.met(sys.scale, above_f, above_m) {
        return Ok(Outcome::Whole(Some(part)));
    }
    let (force_limit, moment_limit) = tolerance.limits(sys.scale);
    super::statics::finish(model, state, &solver.system, true);
    Ok(Outcome::Solved(StaticReport {
        residual_force: rf,
        residual_moment: rm,
        force_limit,
        moment_limit,
        converged: true,
        solved_nodes: cut.nodes.len(),
        ..part
    }))
}

/// The unstable equilibria a component's solve stepped off, in the whole model's
/// numbering (`nodes`: the component's nodes among the whole model's `n`), appended to
/// `out`.
fn carry_events(
    events: &[StabilityEvent],
    nodes: &[usize],
    n: usize,
    out: &mut Vec<StabilityEvent>,
) {
    for event in events {
        let mut mode = vec![DVec3::ZERO; n];
        for (k, &i) in nodes.iter().enumerate() {
            mode[i] = event.mode[k];
        }
        out.push(StabilityEvent {
            node: nodes[event.node],
            mode,
            ..event.clone()
        });
    }
}
