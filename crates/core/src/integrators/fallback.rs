//! The implicit solver's fallback: a step whose Newton iterations do not converge even
//! halved is taken from its start by the explicit method ([`explicit::step_by`]) in
//! n = ⌈h / Δt_stable⌉ equal pieces. The kinematic targets set for the step's end (a
//! hand's fix, a loose grip's or a clip's support) are approached linearly over the
//! pieces — positions interpolated, orientations slerped — so the held nodes move as
//! the implicit step would have moved them, not in one jump at the first piece.

use super::explicit;
use crate::loads::LoadCase;
use crate::{Model, State};
use glam::{DQuat, DVec3};

/// A kinematic target of the step: load case index, start pose, end pose.
pub type Target = (usize, (DVec3, DQuat), (DVec3, DQuat));

/// Advances `state` (at the start of the step, its load cases holding the end-of-step
/// targets) by `h` in explicit pieces; returns how many. `targets` is scratch, reused.
pub fn explicit_pieces(
    model: &Model,
    state: &mut State,
    h: f64,
    targets: &mut Vec<Target>,
) -> usize {
    targets.clear();
    for (i, (_, case)) in state.loads.iter().enumerate() {
        match case {
            LoadCase::Fix(f) => targets.push((
                i,
                (state.x[f.node], state.q[f.node]),
                (f.position, f.orientation),
            )),
            // a support a hand moved this step (a clip's stays where it is)
            LoadCase::Support(s) if s.moved => targets.push((
                i,
                (state.x[s.node], s.orientation),
                (s.position, s.orientation),
            )),
            LoadCase::Support(_)
            | LoadCase::Drive(_)
            | LoadCase::DeadLoad(_)
            | LoadCase::Tie(_)
            | LoadCase::Mount(_) => {}
        }
    }
    let pieces = (h / model.time_step).ceil().max(1.0) as usize;
    for k in 1..=pieces {
        let s = k as f64 / pieces as f64;
        set_targets(state, targets, s);
        explicit::step_by(model, state, h / pieces as f64);
    }
    pieces
}

/// Puts every target at fraction `s` of the way from its start to its end pose.
fn set_targets(state: &mut State, targets: &[Target], s: f64) {
    let mut next = targets.iter().peekable();
    for (i, (_, case)) in state.loads.iter_mut().enumerate() {
        let Some(&&(j, (x0, q0), (x1, q1))) = next.peek() else {
            return;
        };
        if i != j {
            continue;
        }
        next.next();
        let (x, q) = if s >= 1.0 {
            (x1, q1)
        } else {
            (x0.lerp(x1, s), q0.slerp(q1, s).normalize())
        };
        match case {
            LoadCase::Fix(f) => {
                f.position = x;
                f.orientation = q;
            }
            LoadCase::Support(sp) => {
                sp.moved |= sp.position != x;
                sp.position = x;
            }
            LoadCase::Drive(_) | LoadCase::DeadLoad(_) | LoadCase::Tie(_) | LoadCase::Mount(_) => {}
        }
    }
}
