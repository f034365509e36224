//! Penalty contact for stiffened sections (SPEC L4: "rigid (stiffened) parts use penalty
//! contact, f = k·x"). A stiffened section's nodes are dependent points of a rigid body,
//! so their velocities cannot be corrected one by one; instead each dependent node that
//! penetrates a part gets a spring force k·d along the normal, with a damper c·v_n on the
//! approaching speed, and these forces move the body through Newton–Euler.
//!
//! Stiffness: k = m_i (ω_max/2)², so the contact spring's frequency stays at half the
//! model's highest one and the stable time step is unchanged; damping at half critical,
//! c = √(k m_i). With k that soft a heavy metal section may sink by a fraction of its
//! radius under load; deep penetration is never corrected by more than the spring.

use crate::{Model, State};

/// Adds penalty contact forces on stiffened-section nodes to `state.force` and
/// `state.contact_force`. Call after the body loads, before the bodies are stepped.
/// A node known to be clear of the parts ([`super::Clearance`]) is not searched for.
pub(crate) fn add_penalty_forces(model: &Model, state: &mut State) {
    let omega = model.time_step_report.max_frequency;
    let env = &model.environment;
    let clearance = &mut state.contact.clearance;
    clearance.follow(env);
    for body in &model.bodies {
        for &i in &body.nodes {
            let r = model.radius[i];
            let x = state.x[i];
            // farther than r from every still part: nothing to find there
            let still = if clearance.is_clear(i, x) {
                None
            } else {
                let hit = env.closest_point(x, r);
                if hit.is_none() {
                    clearance.anchor(env, i, x, r);
                }
                hit
            };
            let placements = &state.contact.placements;
            let moving = if env.any_moves() {
                // not the shape of its own junction body, which it sits in
                let shapes = &model.junction_shapes;
                let allowed = |k: usize| !shapes.excludes_node(k, i);
                env.closest_moving_where(x, still.map_or(r, |h| h.2), placements, allowed)
            } else {
                None
            };
            let Some((part, q, d)) = moving.or(still) else {
                continue;
            };
            if d >= r || d <= 1e-12 * r {
                continue;
            }
            let n = (state.x[i] - q) / d;
            let k = model.mass[i] * 0.25 * omega * omega;
            let c = (k * model.mass[i]).sqrt();
            // relative to the part's velocity there
            let v_part = match placements.get(part) {
                Some(p) if env.parts[part].moves => p.velocity_at(q),
                _ => glam::DVec3::ZERO,
            };
            let vn = (state.v[i] - v_part).dot(n);
            let f = n * (k * (r - d) - c * vn.min(0.0));
            state.force[i] += f;
            state.contact_force[i] += f;
        }
    }
}
