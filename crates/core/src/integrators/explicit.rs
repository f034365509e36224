//! Explicit dynamics (SPEC P4, dissertation §4.2.4 eq. 4.51–4.58): central differences
//! (Newmark β = 0, γ = ½, in leapfrog form) for the node positions, and Euler's equations
//! for the node rotations with the isotropic lumped inertia of [`crate::rod::mass`]
//! (I ω̇ = M, the gyroscopic term vanishing for isotropic I), the orientation advanced by
//! the exponential map q ← exp(ω Δt) q (appendix A.2) — never by adding small angles.
//!
//! Nodes held by a kinematic load case (fix, drive) take their prescribed pose; the load
//! the support must apply is the one that makes the node's own momentum balance hold:
//! R = m (v_new − v_old)/Δt − f  (and likewise for moments). Contact with rigid parts
//! ([`crate::contact`]) corrects velocities before and positions after the position
//! update. No allocation in a step.

use crate::contact::{
    add_hose_contact_forces, add_penalty_forces, project_positions, resolve_velocities,
    wake_near_moving_parts,
};
use crate::integrators::advance::{advance, Advance, Nodes};
use crate::loads::LoadCase;
use crate::math::log_map;
use crate::parallel::{Pool, SharedMut};
use crate::rod::forces::{chunk_nodes, step_loads, whole_hose_chunks};
use crate::rod::inelastic::HistoryView;
use crate::rod::node_view::NodeView;
use crate::rod::stiffened::step_body;
use crate::{Model, State};
use glam::DVec3;

/// Advances `state` by one time step of `model.time_step`.
pub fn step(model: &Model, state: &mut State) {
    step_by(model, state, model.time_step);
}

/// Advances `state` by `dt` ≤ `model.time_step` (the stable step): the implicit
/// solver's fallback takes a step it could not converge in explicit pieces.
pub fn step_by(model: &Model, state: &mut State, dt: f64) {
    let t_next = state.time + dt;
    if model.environment.any_moves() {
        // the parts' poses at the step's start, their twists at mid-step
        // (crate::contact::moving)
        let placements = &mut state.contact.placements;
        model.kinematics.place_all(
            state.time,
            state.time + 0.5 * dt,
            &state.part_moves,
            placements,
        );
        if model.junction_shapes.any() {
            model.place_junction_shapes(state);
        }
        if state.sleep.enabled {
            // hoses asleep on a moving part wake if it would no longer carry them at rest
            crate::sleep::carried::before_step(model, state, dt);
        }
    }
    {
        let config = NodeView {
            x: &state.x,
            q: &state.q,
            v: &state.v,
            w: &state.w,
            inelastic_history: HistoryView {
                values: &state.inelastic_history,
                age: state.inelastic_age(state.time),
            },
        };
        let asleep = &state.sleep.node_asleep;
        let sleeping = state.sleep.enabled && state.sleep.hose_asleep.contains(&true);
        step_loads(
            model,
            &config,
            model.damping_stiffness,
            &mut state.force,
            &mut state.moment,
            |a| sleeping && asleep[a],
        );
    }
    add_hose_contact_forces(model, state);
    state.held.fill(false);
    state.reaction_force.fill(DVec3::ZERO);
    state.reaction_moment.fill(DVec3::ZERO);
    state.contact_force.fill(DVec3::ZERO);
    for (_, case) in state.loads.iter() {
        if let LoadCase::DeadLoad(d) = case {
            let (force, moment) = d.at(state.time);
            state.force[d.node] += force;
            state.moment[d.node] += moment;
        }
    }
    // a support moved (by a hand) wakes its hose below, as a moving fix does
    let mut moved_any = false;
    if state.sleep.enabled && model.environment.any_moves() {
        moved_any |= wake_near_moving_parts(model, state, dt);
    }
    for (_, case) in state.loads.iter_mut() {
        if let LoadCase::Support(s) = case {
            if s.moved && state.sleep.enabled {
                state.sleep.node_asleep[s.node] = false;
                moved_any = true;
            }
            s.moved = false;
        }
    }
    // Fixings' supports: springs in their fixed directions (reaction = their load), the
    // slip anchors accepted with this step's forces
    crate::loads::support_reactions(model, state, true);
    // Only supports and ties write reactions here; without them the arrays are the zeros
    // just filled in, and adding them would change nothing, so
    // both passes are skipped.
    let supported = state
        .loads
        .iter()
        .any(|(_, c)| matches!(c, LoadCase::Support(_) | LoadCase::Tie(_)));
    if supported {
        for (f, r) in state.force.iter_mut().zip(&state.reaction_force) {
            *f += *r;
        }
        for (m, r) in state.moment.iter_mut().zip(&state.reaction_moment) {
            *m += *r;
        }
    }
    // Kinematic load cases, in order (a later one on the same node wins).
    for (_, case) in state.loads.iter() {
        let Some((x_new, q_new)) =
            case.prescribed_pose(t_next, &model.kinematics, &state.part_moves)
        else {
            continue;
        };
        let i = case.node();
        // a support on the part that carries the node's hose asleep moves with it
        let (x_now, q_now) = state
            .sleep
            .carried
            .target(i)
            .unwrap_or((state.x[i], state.q[i]));
        if state.sleep.enabled && !same_pose((x_new, q_new), (x_now, q_now)) {
            // a moving support wakes its hose below
            state.sleep.node_asleep[i] = false;
            moved_any = true;
        }
        let v_new = (x_new - state.x[i]) / dt;
        let w_new = log_map(q_new * state.q[i].conjugate()) / dt;
        state.reaction_force[i] = model.mass[i] * (v_new - state.v[i]) / dt - state.force[i];
        state.reaction_moment[i] = model.inertia[i] * (w_new - state.w[i]) / dt - state.moment[i];
        state.x[i] = x_new;
        state.q[i] = q_new;
        state.v[i] = v_new;
        state.w[i] = w_new;
        state.held[i] = true;
    }
    // Stiffened sections move as rigid bodies; their nodes are then dependent points,
    // pushed off parts by penalty springs (the kinematic contact below skips them).
    if !model.bodies.is_empty() && !model.environment.is_empty() {
        add_penalty_forces(model, state);
    }
    for (b, body) in model.bodies.iter().enumerate() {
        if state.sleep.enabled && state.sleep.node_asleep[body.nodes[0]] {
            state.bodies[b].velocity = DVec3::ZERO;
            state.bodies[b].angular_velocity = DVec3::ZERO;
            continue; // a sleeping section stays put (its nodes are held below)
        }
        let held = body.nodes.iter().copied().find(|&i| state.held[i]);
        step_body(
            body,
            (model.gravity, model.damping_mass),
            &mut state.bodies[b],
            held,
            &mut state.x,
            &mut state.q,
            &mut state.v,
            &mut state.w,
            &state.force,
            &state.moment,
            (&mut state.reaction_force, &mut state.reaction_moment),
            dt,
        );
        for &i in &body.nodes {
            state.held[i] = true;
        }
    }
    if state.sleep.enabled {
        // sleeping nodes go with the part that carries them, or stay where they are,
        // like held ones (no reaction reported)
        crate::sleep::carried::carry(state, dt);
        for i in 0..state.x.len() {
            if state.sleep.node_asleep[i] && !state.held[i] {
                state.held[i] = true;
                state.v[i] = DVec3::ZERO;
                state.w[i] = DVec3::ZERO;
                state.force[i] = DVec3::ZERO;
                state.moment[i] = DVec3::ZERO;
            }
        }
    }
    let contact = !model.environment.is_empty();
    if contact {
        advance_nodes(model, state, dt, Advance::Velocities);
        resolve_velocities(model, state, dt);
        if model.junction_shapes.any() {
            model.react_on_junction_shapes(state, dt);
        }
        advance_nodes(model, state, dt, Advance::Positions);
        project_positions(model, state, dt);
    } else {
        advance_nodes(model, state, dt, Advance::Both);
    }
    state.time = t_next;
    state.step += 1;
    // the step is accepted: inelastic elements keep their history
    state.commit_inelastic(model, &model.elements, state.time);
    if state.sleep.enabled {
        update_sleep(model, state, moved_any);
    }
}

/// The leapfrog update of the nodes not held ([`advance`]), shared between
/// `model.threads` threads hose group by hose group (each node's update is its own).
fn advance_nodes(model: &Model, state: &mut State, dt: f64, what: Advance) {
    let chunks = &model.hose_chunks;
    if model.threads > 1 && chunks.len() > 1 && whole_hose_chunks(model) {
        let (x, q) = (SharedMut::new(&mut state.x), SharedMut::new(&mut state.q));
        let (v, w) = (SharedMut::new(&mut state.v), SharedMut::new(&mut state.w));
        let (held, force, moment) = (&state.held, &state.force, &state.moment);
        Pool::global().run(model.threads, chunks.len(), &|k| {
            let r = chunk_nodes(model, chunks[k].clone());
            // SAFETY: the chunks' node ranges are disjoint and within the arrays.
            let mut nodes = unsafe {
                Nodes {
                    mass: &model.mass[r.clone()],
                    inertia: &model.inertia[r.clone()],
                    held: &held[r.clone()],
                    force: &force[r.clone()],
                    moment: &moment[r.clone()],
                    x: x.slice(r.clone()),
                    q: q.slice(r.clone()),
                    v: v.slice(r.clone()),
                    w: w.slice(r.clone()),
                }
            };
            advance(&mut nodes, dt, what);
        });
        return;
    }
    let mut nodes = Nodes {
        mass: &model.mass,
        inertia: &model.inertia,
        held: &state.held,
        force: &state.force,
        moment: &state.moment,
        x: &mut state.x,
        q: &mut state.q,
        v: &mut state.v,
        w: &mut state.w,
    };
    advance(&mut nodes, dt, what);
}

/// Whether a support's pose is the one a sleeping node has (to rounding, when the node is
/// carried by a part: the support's and the carried pose are composed differently).
fn same_pose(a: (DVec3, glam::DQuat), b: (DVec3, glam::DQuat)) -> bool {
    const ROUNDING: f64 = 1e-12;
    a == b
        || ((a.0 - b.0).length() <= ROUNDING && log_map(a.1 * b.1.conjugate()).length() <= ROUNDING)
}

/// Sleep bookkeeping after a step: a node whose support moved this step was marked awake
/// above (its hose wakes); then calm hoses fall asleep ([`crate::sleep`]).
fn update_sleep(model: &Model, state: &mut State, moved_any: bool) {
    if moved_any {
        for h in 0..model.hoses.len() {
            let info = &model.hoses[h];
            if state.sleep.hose_asleep[h] && info.nodes().any(|i| !state.sleep.node_asleep[i]) {
                state.sleep.wake(model, h);
            }
        }
    }
    crate::sleep::update(model, state, |_| false);
}
