//! Contact with parts that move (SPEC K1, L4): the kinematic contact of [`super::rigid`]
//! against parts carried by a pose over time ([`crate::kinematics`]).
//!
//! - Detection in the part's reference placement: a node (ball) or a beam (segment) is
//!   mapped by the inverse of the part's pose at the start of the step, searched against
//!   the part's own BVH (built once, never rebuilt), and the closest points and the normal
//!   are mapped back. Each node and beam keeps its remembered normal in the part's frame,
//!   so it turns with the part.
//! - Relative velocity: the contact and the friction act on v − v_p, where
//!   v_p = Ṫ + ω × (q − T) is the part's velocity at the surface point q, taken at
//!   mid-step (what carries the point from the step's start to its end pose exactly for
//!   a uniformly accelerated part).
//! - No tunnelling: the search reaches beyond touching by how far the part and the hose
//!   point can move in the step, m = (|Ṫ| + |ω| ρ + |v|) Δt (ρ the part's largest vertex
//!   distance from its reference origin, which bounds |ω × (x − T)| over the part). A
//!   contact found with a gap g > 0 is speculative (E. Catto, "Continuous collision",
//!   GDC 2013; Mirtich's conservative advancement bound): the point may still approach
//!   by g in the step, no more — so it stops on the surface wherever the part moves
//!   within the step, and is not pushed early.
//!
//! These searches are BVH queries (the candidate lists of [`super::coherence`] assume
//! parts that stand still); a node or beam far from the part's swept box costs one box
//! test, and one found clear of a part keeps, in the part's frame, the distance D of the
//! part's nearest triangle box: while its end points move less than D − ρ_now from
//! where they were in that frame (distance to a fixed set is 1-Lipschitz in the end
//! points, as in [`super::clearance`]), nothing lies within its reach ρ_now, and it is
//! not searched — the same result as searching. A hose resting on a moving part barely
//! moves in its frame.

use super::coherence::Nearest;
use super::rigid::{side, BeamSearch, ContactPoint, INTERIOR, SKIN};
use crate::{Model, State};
use glam::DVec3;
use parry3d_f64::bounding_volume::Aabb;

/// The box of part `k` at its placement (its reference box's eight corners mapped).
fn world_box(model: &Model, state: &State, k: usize) -> Aabb {
    let local = model.environment.parts[k].mesh.local_aabb();
    let pose = state.contact.placements[k].pose;
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for c in 0..8 {
        let corner = DVec3::new(
            if c & 1 == 0 {
                local.mins.x
            } else {
                local.maxs.x
            },
            if c & 2 == 0 {
                local.mins.y
            } else {
                local.maxs.y
            },
            if c & 4 == 0 {
                local.mins.z
            } else {
                local.maxs.z
            },
        );
        let w = pose.apply(corner);
        lo = lo.min(w);
        hi = hi.max(w);
    }
    Aabb::new(lo, hi)
}

/// How far any point of part `k` moves in a step of `dt` at most.
fn part_sweep(model: &Model, state: &State, k: usize, dt: f64) -> f64 {
    let twist = state.contact.placements[k].twist;
    (twist.linear.length() + twist.angular.length() * model.environment.parts[k].extent) * dt
}

fn meets(b: &Aabb, lo: DVec3, hi: DVec3, grow: f64) -> bool {
    (lo - grow).cmple(b.maxs).all() && b.mins.cmple(hi + grow).all()
}

/// How far (in reaches) a slot clear of a part looks for the part's nearest box.
const FAR: f64 = 4.0;
/// Relative slack on distances for rounding (errs towards searching).
const SLACK: f64 = 1e-9;

/// Whether search slot `slot` (a node or a beam against one moving part), now at [a, b]
/// in the part's frame, is certainly farther than `reach` from the part.
fn known_clear(
    contact: &super::ContactScratch,
    slot: usize,
    a: DVec3,
    b: DVec3,
    reach: f64,
) -> bool {
    let ([anchor_a, anchor_b], nearest) = contact.moving_clear[slot];
    let moved = (a - anchor_a).length().max((b - anchor_b).length());
    moved < nearest / (1.0 + SLACK) - reach * (1.0 + SLACK)
}

/// Remembers that slot `slot`, at [a, b] in `part`'s frame, found nothing within
/// `reach`: the distance of the part's nearest box, up to [`FAR`] reaches.
fn anchor_clear(
    contact: &mut super::ContactScratch,
    part: &super::RigidPart,
    slot: usize,
    a: DVec3,
    b: DVec3,
    reach: f64,
) {
    let nearest = part.nearest_box(a, b, FAR * reach);
    contact.moving_clear[slot] = ([a, b], nearest);
}

/// Detects the contacts of nodes and beam interiors with the moving parts and appends
/// them to `state.contact.points` (see the module doc). Before the velocity correction of
/// [`super::resolve_velocities`], which handles them with the still parts' contacts.
pub(crate) fn detect(model: &Model, state: &mut State, dt: f64) {
    let env = &model.environment;
    for slot in 0..env.moving.len() {
        let k = env.moving[slot];
        state.contact.moving_box[slot] = world_box(model, state, k);
        state.contact.moving_sweep[slot] = part_sweep(model, state, k, dt);
    }
    let contact = &mut state.contact;
    // nodes: the nearest moving part's closest point within reach
    for i in 0..state.x.len() {
        if state.held[i] || model.body_of[i].is_some() {
            contact.moving_node_normal[i] = (usize::MAX, DVec3::ZERO);
            continue;
        }
        let (x, r) = (state.x[i], model.radius[i]);
        let own = state.v[i].length() * dt;
        let mut best: Option<(usize, DVec3, f64, f64)> = None; // part, local point, distance, reach
        let moving = env.moving.len();
        for s in 0..moving {
            let k = env.moving[s];
            let reach = r * (1.0 + SKIN) + contact.moving_sweep[s] + own;
            if !meets(&contact.moving_box[s], x, x, reach) {
                continue;
            }
            let part = &env.parts[k];
            let local = contact.placements[k].pose.inverse_apply(x);
            let slot = i * moving + s;
            if known_clear(contact, slot, local, local, reach) {
                continue;
            }
            let bound = best.map_or(reach, |b| b.2.min(reach));
            match part.closest_point_local(k, local, bound) {
                Some(hit) => {
                    if best.is_none_or(|b| hit.distance < b.2) {
                        best = Some((k, hit.point, hit.distance, reach));
                    }
                }
                None => anchor_clear(contact, part, slot, local, local, reach),
            }
        }
        let memory = &mut contact.moving_node_normal[i];
        let Some((k, q_local, _, _)) = best else {
            *memory = (usize::MAX, DVec3::ZERO);
            continue;
        };
        let place = contact.placements[k];
        let local = place.pose.inverse_apply(x);
        let remembered = if memory.0 == k { memory.1 } else { DVec3::ZERO };
        let (normal_local, depth) = side(local, q_local, r, remembered);
        *memory = (k, normal_local);
        contact.points.push(ContactPoint {
            node_a: i,
            node_b: i,
            t: 0.0,
            normal: place.pose.rotation * normal_local,
            depth,
            part: k,
            part_velocity: place.velocity_at(place.pose.apply(q_local)),
        });
    }
    // beam interiors: the nearest pair strictly inside the segment, as for still parts
    for (e, el) in model.elements.iter().enumerate() {
        let (a, b) = (el.node_a, el.node_b);
        if (state.held[a] && state.held[b])
            || model.body_of[a].is_some()
            || model.body_of[b].is_some()
        {
            contact.moving_element_normal[e] = (usize::MAX, DVec3::ZERO);
            continue;
        }
        let (xa, xb) = (state.x[a], state.x[b]);
        let r = model.radius[a].max(model.radius[b]);
        let own = state.v[a].length().max(state.v[b].length()) * dt;
        let mut best = None;
        let moving = env.moving.len();
        for s in 0..moving {
            let k = env.moving[s];
            let reach = r * (1.0 + SKIN) + contact.moving_sweep[s] + own;
            if !meets(&contact.moving_box[s], xa.min(xb), xa.max(xb), reach) {
                continue;
            }
            let part = &env.parts[k];
            let pose = contact.placements[k].pose;
            let (la, lb) = (pose.inverse_apply(xa), pose.inverse_apply(xb));
            let slot = (state.x.len() + e) * moving + s;
            if known_clear(contact, slot, la, lb, reach) {
                continue;
            }
            let mut search = BeamSearch::new(la, lb, reach);
            let grow = DVec3::splat(reach);
            let query = Aabb::new(la.min(lb) - grow, la.max(lb) + grow);
            for (rank, t) in part.mesh.bvh().intersect_aabb(&query).enumerate() {
                let edges = part.owned_edges[t as usize];
                search.offer(k, &part.mesh.triangle(t), rank as u32, edges);
            }
            match search.best {
                Some(hit) => {
                    let nearer =
                        |(_, h): &(usize, super::rigid::BeamHit)| hit.distance < h.distance;
                    if best.as_ref().is_none_or(nearer) {
                        best = Some((k, hit));
                    }
                }
                None => anchor_clear(contact, part, slot, la, lb, reach),
            }
        }
        let memory = &mut contact.moving_element_normal[e];
        let Some((k, hit)) = best else {
            *memory = (usize::MAX, DVec3::ZERO);
            continue;
        };
        let place = contact.placements[k];
        let remembered = if memory.0 == k { memory.1 } else { DVec3::ZERO };
        let (normal_local, depth) = side(hit.p, hit.q, r, remembered);
        *memory = (k, normal_local);
        if hit.t <= INTERIOR || hit.t >= 1.0 - INTERIOR {
            continue;
        }
        contact.points.push(ContactPoint {
            node_a: a,
            node_b: b,
            t: hit.t,
            normal: place.pose.rotation * normal_local,
            depth,
            part: k,
            part_velocity: place.velocity_at(place.pose.apply(hit.q)),
        });
    }
}

/// Wakes the sleeping nodes within reach of a moving part's box (a part that moves
/// under a hose asleep on it must carry it); whether any woke.
pub(crate) fn wake_near(model: &Model, state: &mut State, dt: f64) -> bool {
    let env = &model.environment;
    for slot in 0..env.moving.len() {
        let k = env.moving[slot];
        state.contact.moving_box[slot] = world_box(model, state, k);
        state.contact.moving_sweep[slot] = part_sweep(model, state, k, dt);
    }
    let mut woke = false;
    for i in 0..state.x.len() {
        if !state.sleep.node_asleep[i] {
            continue;
        }
        let reach = 2.0 * model.radius[i];
        let x = state.x[i];
        let near = (0..env.moving.len()).any(|s| {
            let sweep = state.contact.moving_sweep[s];
            sweep > 0.0 && meets(&state.contact.moving_box[s], x, x, reach + sweep)
        });
        if near {
            state.sleep.node_asleep[i] = false;
            woke = true;
        }
    }
    woke
}
