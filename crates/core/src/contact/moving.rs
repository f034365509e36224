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
//! The searches keep candidate lists from step to step as for the still parts
//! ([`super::coherence`]), one list per beam and moving part, in the part's own frame:
//! there a hose resting on the part barely moves, so its lists last, and a beam clear of
//! the part costs one displacement test. The lists give the contacts a fresh query of the
//! part's BVH gives, to the last bit. Their reach is this step's search reach rounded up
//! (it grows with the speeds), so that it need not be made anew each step.
//!
//! Each step, before any search, every beam's reach, list reach and clear test against
//! each moving part are taken once ([`BeamStep`]) and read by the beam's interior search
//! and by the node that searches its list: a beam clear of the part settles both without
//! any further set-up, as the still parts' first pass does in [`super::rigid`].

use super::coherence::{CandidateCache, Searcher};
use super::environment::{cube, ClosestPoint};
use super::rigid::{side, BeamSearch, ContactPoint, ContactScratch, INTERIOR, SKIN};
use super::triangle_set::PartFrame;
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

/// Memory the moving parts' candidate lists may take together; the parts beyond it
/// are searched by fresh BVH queries (the same contacts, dearer).
const LIST_BUDGET_BYTES: usize = 512 << 20;

/// One candidate list per moving part with a slot per beam ([`CandidateCache`], in the
/// part's frame), while [`LIST_BUDGET_BYTES`] allows.
pub(super) fn candidate_lists(model: &Model) -> Vec<CandidateCache> {
    let env = &model.environment;
    let slots = model.elements.len();
    let per_part = slots.saturating_mul(CandidateCache::BYTES_PER_SLOT);
    let mut left = LIST_BUDGET_BYTES;
    env.moving
        .iter()
        .map(|&k| {
            let frame = PartFrame {
                part: &env.parts[k],
                index: k,
            };
            if per_part <= left {
                left -= per_part;
                CandidateCache::for_set(slots, &frame)
            } else {
                CandidateCache::for_set(0, &frame)
            }
        })
        .collect()
}

/// The reach a beam's list of a moving part is kept for: at least `need`, this step's
/// reach of the beam's search (which grows with the part's and the beam's speeds), so
/// that its nodes' searches and its own are served by it. A list made for up to `base`/8
/// more is kept; else it is made anew for `base`/16 more (`base`: the reach at rest), so
/// that speeds changing from step to step do not remake it every step.
fn list_reach(current: f64, need: f64, base: f64) -> f64 {
    if need <= current && current <= need + base / 8.0 {
        current
    } else {
        need + base / 16.0
    }
}

/// What a beam's searches against one moving part share in a step, made once per beam
/// and part before any search ([`beam_steps`]) and read by the beam's interior search and
/// the node that searches its list.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct BeamStep {
    /// The beam's reach this step: its capsule's, plus how far the part and the beam's
    /// end points can move in the step.
    need: f64,
    /// The reach its list is kept for ([`list_reach`]).
    list: f64,
    /// No triangle of the part within reach of the beam, nor of its nodes
    /// ([`CandidateCache::clear_slack`]): its searches need not be set up.
    clear: bool,
}

/// Fills `steps` (one per beam) for moving part `s`, whose lists are `lists`, moving by
/// up to `sweep` in the step of `dt`: the beams' end points in the part's frame are
/// `local`, the nodes' speeds `speed`. Appends to `near` the beams within reach of this
/// part and clear of every earlier one (`earlier`: their steps, part-major).
#[allow(clippy::too_many_arguments)]
fn beam_steps(
    model: &Model,
    lists: &CandidateCache,
    local: &[DVec3],
    speed: &[f64],
    sweep: f64,
    dt: f64,
    (earlier, steps): (&[BeamStep], &mut [BeamStep]),
    near: &mut Vec<u32>,
) {
    let elements = steps.len();
    for (e, (el, step)) in model.elements.iter().zip(steps).enumerate() {
        let (a, b) = (el.node_a, el.node_b);
        let base = model.radius[a].max(model.radius[b]) * (1.0 + SKIN);
        let need = base + sweep + speed[a].max(speed[b]) * dt;
        let list = list_reach(lists.slot_reach(e), need, base);
        let clear = lists.clear_slack(e, local[a], local[b], list).is_some();
        *step = BeamStep { need, list, clear };
        if !clear && earlier.iter().skip(e).step_by(elements).all(|t| t.clear) {
            near.push(e as u32);
        }
    }
}

/// Forgets the remembered normals of the beams near a moving part last step (`last`)
/// but not in this one (`now`; both in order), and of the nodes that search their lists
/// (`node_beam`): their searches would find nothing, so the beams are not visited.
fn forget_left(
    model: &Model,
    (last, now): (&[u32], &[u32]),
    node_beam: &[u32],
    node_memory: &mut [(usize, DVec3)],
    element_memory: &mut [(usize, DVec3)],
) {
    let mut now = now.iter().peekable();
    for &e in last {
        while now.next_if(|&&f| f < e).is_some() {}
        if now.peek() == Some(&&e) {
            continue; // still near
        }
        element_memory[e as usize] = (usize::MAX, DVec3::ZERO);
        let el = &model.elements[e as usize];
        for i in [el.node_a, el.node_b] {
            if node_beam[i] == e {
                node_memory[i] = (usize::MAX, DVec3::ZERO);
            }
        }
    }
}

/// Detects the contacts of nodes and beam interiors with the moving parts and appends
/// them to `state.contact.points` (see the module doc): the nodes' contacts in the nodes'
/// order, then the beam interiors' in the beams' order. Before the velocity correction of
/// [`super::resolve_velocities`], which handles them with the still parts' contacts.
///
/// Only the beams near some part are visited ([`beam_steps`]), each once: the nodes that
/// search its list, then its interior. The others' searches would find nothing: their
/// remembered normals are forgotten when they leave ([`forget_left`]).
pub(crate) fn detect(model: &Model, state: &mut State, dt: f64) {
    let env = &model.environment;
    for slot in 0..env.moving.len() {
        let k = env.moving[slot];
        state.contact.moving_box[slot] = world_box(model, state, k);
        state.contact.moving_sweep[slot] = part_sweep(model, state, k, dt);
    }
    let contact = &mut state.contact;
    let moving = env.moving.len();
    let frame = |s: usize| PartFrame {
        part: &env.parts[env.moving[s]],
        index: env.moving[s],
    };
    for s in 0..moving {
        contact.moving_candidates[s].follow(&frame(s));
    }
    // each node's speed, and its position in each moving part's frame, once a step
    let n = state.x.len();
    for (speed, v) in contact.moving_speed.iter_mut().zip(&state.v) {
        *speed = v.length();
    }
    for (s, local) in contact.moving_local.chunks_exact_mut(n.max(1)).enumerate() {
        let pose = contact.placements[env.moving[s]].pose;
        for (l, &x) in local.iter_mut().zip(&state.x) {
            *l = pose.inverse_apply(x);
        }
    }
    // each beam's reach, list reach and clear test per part, once a step; the near beams
    let elements = model.elements.len();
    std::mem::swap(&mut contact.moving_near, &mut contact.moving_near_last);
    contact.moving_near.clear();
    for s in 0..moving {
        let (earlier, steps) = contact.moving_beam[..(s + 1) * elements].split_at_mut(s * elements);
        beam_steps(
            model,
            &contact.moving_candidates[s],
            &contact.moving_local[s * n..(s + 1) * n],
            &contact.moving_speed,
            contact.moving_sweep[s],
            dt,
            (earlier, steps),
            &mut contact.moving_near,
        );
    }
    if moving > 1 {
        contact.moving_near.sort_unstable();
    }
    forget_left(
        model,
        (&contact.moving_near_last, &contact.moving_near),
        &contact.node_beam,
        &mut contact.moving_node_normal,
        &mut contact.moving_element_normal,
    );
    let first_node_contact = contact.points.len();
    let mut last_node = None; // the node contacts are in the nodes' order while rising
    let mut in_order = true;
    contact.moving_interior.clear();
    let (x, held) = (&state.x[..], &state.held[..]);
    for v in 0..contact.moving_near.len() {
        let e = contact.moving_near[v];
        let el = &model.elements[e as usize];
        for i in [el.node_a, el.node_b] {
            if contact.node_beam[i] != e {
                continue; // it searches another beam's list
            }
            if let Some(c) = node_contact(model, x, held, contact, Some(e as usize), i, dt) {
                in_order &= last_node < Some(i);
                last_node = Some(i);
                contact.points.push(c);
            }
        }
        if let Some(c) = interior_contact(model, x, held, contact, e as usize) {
            contact.moving_interior.push(c);
        }
    }
    // the nodes without a beam: a fresh query each
    for v in 0..contact.moving_beamless.len() {
        let i = contact.moving_beamless[v] as usize;
        if let Some(c) = node_contact(model, x, held, contact, None, i, dt) {
            in_order &= last_node < Some(i);
            last_node = Some(i);
            contact.points.push(c);
        }
    }
    if !in_order {
        contact.points[first_node_contact..].sort_unstable_by_key(|c| c.node_a);
    }
    contact.points.extend_from_slice(&contact.moving_interior);
}

/// The contact of node `i` (positions `x`, `held` its flag) with the nearest moving part
/// within reach, if any; searched in the list of its beam `e` (a fresh query without
/// one). Updates the node's remembered normal.
fn node_contact(
    model: &Model,
    x: &[DVec3],
    held: &[bool],
    contact: &mut ContactScratch,
    e: Option<usize>,
    i: usize,
    dt: f64,
) -> Option<ContactPoint> {
    let env = &model.environment;
    if held[i] || model.body_of[i].is_some() {
        contact.moving_node_normal[i] = (usize::MAX, DVec3::ZERO);
        return None;
    }
    let moving = env.moving.len();
    let n = x.len();
    let mut best: Option<(usize, DVec3, f64)> = None; // slot, local point, distance
    for s in 0..moving {
        let step = e.map(|e| contact.moving_beam[s * model.elements.len() + e]);
        if step.is_some_and(|b| b.clear) {
            continue; // no triangle within reach of its beam
        }
        let k = env.moving[s];
        if model.junction_shapes.excludes_node(k, i) {
            continue; // inside its own junction body's shape (crate::junction_shape)
        }
        let r = model.radius[i];
        let sweep = contact.moving_sweep[s];
        let reach = r * (1.0 + SKIN) + sweep + contact.moving_speed[i] * dt;
        if !meets(&contact.moving_box[s], x[i], x[i], reach) {
            continue;
        }
        let local = contact.moving_local[s * n + i];
        let bound = best.map_or(reach, |b| b.2.min(reach));
        let frame = PartFrame {
            part: &env.parts[k],
            index: k,
        };
        let hit = match (e, step) {
            (Some(e), Some(step)) => {
                // the node searches its beam's list: a point of the segment is no
                // nearer to any triangle than the segment (as for still parts)
                let el = &model.elements[e];
                let searcher = if el.node_a == i {
                    Searcher::StartNode
                } else {
                    Searcher::EndNode
                };
                let (la, lb) = (
                    contact.moving_local[s * n + el.node_a],
                    contact.moving_local[s * n + el.node_b],
                );
                let lists = &mut contact.moving_candidates[s];
                if lists.settled(e, searcher, la, lb, bound) {
                    None // its search would find none
                } else {
                    let mut search = ClosestPoint::new(local, bound);
                    let query = cube(local, bound);
                    let probe = [local, local];
                    lists.scan(
                        &frame,
                        e,
                        la,
                        lb,
                        step.list,
                        searcher,
                        probe,
                        &query,
                        &mut search,
                    );
                    search.best
                }
            }
            _ => env.parts[k].closest_point_local(k, local, bound),
        };
        if let Some(hit) = hit {
            if best.is_none_or(|b| hit.distance < b.2) {
                best = Some((s, hit.point, hit.distance));
            }
        }
    }
    let memory = &mut contact.moving_node_normal[i];
    let Some((s, q_local, _)) = best else {
        *memory = (usize::MAX, DVec3::ZERO);
        return None;
    };
    let k = env.moving[s];
    let place = contact.placements[k];
    let local = contact.moving_local[s * n + i];
    let remembered = if memory.0 == k { memory.1 } else { DVec3::ZERO };
    let (normal_local, depth) = side(local, q_local, model.radius[i], remembered);
    *memory = (k, normal_local);
    Some(ContactPoint {
        node_a: i,
        node_b: i,
        t: 0.0,
        normal: place.pose.rotation * normal_local,
        depth,
        part: k,
        part_velocity: place.velocity_at(place.pose.apply(q_local)),
    })
}

/// The contact of beam `e`'s interior with the nearest moving part within reach, if any
/// (the nearest pair strictly inside the segment, as for still parts); updates the
/// beam's remembered normal.
fn interior_contact(
    model: &Model,
    x: &[DVec3],
    held: &[bool],
    contact: &mut ContactScratch,
    e: usize,
) -> Option<ContactPoint> {
    let env = &model.environment;
    let el = &model.elements[e];
    let (a, b) = (el.node_a, el.node_b);
    if (held[a] && held[b]) || model.body_of[a].is_some() || model.body_of[b].is_some() {
        contact.moving_element_normal[e] = (usize::MAX, DVec3::ZERO);
        return None; // no interior contact to find
    }
    let (moving, n) = (env.moving.len(), x.len());
    let (xa, xb) = (x[a], x[b]);
    let mut best = None;
    for s in 0..moving {
        let step = contact.moving_beam[s * model.elements.len() + e];
        let k = env.moving[s];
        if step.clear || model.junction_shapes.excludes_beam(k, a, b) {
            continue; // clear, or inside its own junction body's shape
        }
        let reach = step.need;
        if !meets(&contact.moving_box[s], xa.min(xb), xa.max(xb), reach) {
            continue;
        }
        let (la, lb) = (
            contact.moving_local[s * n + a],
            contact.moving_local[s * n + b],
        );
        let lists = &mut contact.moving_candidates[s];
        if lists.settled(e, Searcher::Interior, la, lb, reach) {
            continue;
        }
        let mut search = BeamSearch::new(la, lb, reach);
        let grow = DVec3::splat(reach);
        let query = Aabb::new(la.min(lb) - grow, la.max(lb) + grow);
        // an accepted hit lies at t in (INTERIOR, 1 − INTERIOR): the candidates'
        // bounds are taken from that part of the beam
        let d = lb - la;
        let probe = [la + INTERIOR * d, la + (1.0 - INTERIOR) * d];
        let frame = PartFrame {
            part: &env.parts[k],
            index: k,
        };
        let interior = Searcher::Interior;
        lists.scan(
            &frame,
            e,
            la,
            lb,
            step.list,
            interior,
            probe,
            &query,
            &mut search,
        );
        if let Some(hit) = search.best {
            let nearer = |(_, h): &(usize, super::rigid::BeamHit)| hit.distance < h.distance;
            if best.as_ref().is_none_or(nearer) {
                best = Some((k, hit));
            }
        }
    }
    let memory = &mut contact.moving_element_normal[e];
    let Some((k, hit)) = best else {
        *memory = (usize::MAX, DVec3::ZERO);
        return None;
    };
    let place = contact.placements[k];
    let r = model.radius[a].max(model.radius[b]);
    let remembered = if memory.0 == k { memory.1 } else { DVec3::ZERO };
    let (normal_local, depth) = side(hit.p, hit.q, r, remembered);
    *memory = (k, normal_local);
    if hit.t <= INTERIOR || hit.t >= 1.0 - INTERIOR {
        return None;
    }
    Some(ContactPoint {
        node_a: a,
        node_b: b,
        t: hit.t,
        normal: place.pose.rotation * normal_local,
        depth,
        part: k,
        part_velocity: place.velocity_at(place.pose.apply(hit.q)),
    })
}

/// Wakes the sleeping nodes within reach of a moving part's box (a part that moves
/// under a hose asleep on it must carry it) — but for the part that carries them
/// ([`crate::sleep::carried`]); whether any woke.
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
        let carrier = state.sleep.carried.part_of_node[i];
        let near = (0..env.moving.len()).any(|s| {
            let sweep = state.contact.moving_sweep[s];
            if env.moving[s] == carrier {
                return false;
            }
            sweep > 0.0 && meets(&state.contact.moving_box[s], x, x, reach + sweep)
        });
        if near {
            state.sleep.node_asleep[i] = false;
            woke = true;
        }
    }
    woke
}

#[cfg(test)]
mod tests {
    use crate::integrators::explicit;
    use crate::kinematics::{Oscillation, PartMotion, Periodic};
    use crate::{HoseSpec, Material, Model, RigidPartSpec, Section, SimSettings, State, WorldSpec};
    use glam::DVec3;

    /// A rippled floor patch of 2·n² triangles over x in `[x0, x1]` and y in ±0.3 m,
    /// rocking ±3 mm up and down at `heave` Hz and ±2° in roll at 1.5 Hz.
    fn floor_patch(name: &str, n: usize, (x0, x1): (f64, f64), heave: f64) -> RigidPartSpec {
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let x = x0 + (x1 - x0) * i as f64 / n as f64;
                let y = 0.6 * j as f64 / n as f64 - 0.3;
                vertices.push(DVec3::new(
                    x,
                    y,
                    0.002 * (40.0 * x).sin() * (30.0 * y).cos(),
                ));
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n as u32 {
            for j in 0..n as u32 {
                let a = i * (n as u32 + 1) + j;
                let (b, c, d) = (a + 1, a + n as u32 + 1, a + n as u32 + 2);
                triangles.extend([[a, c, d], [a, d, b]]);
            }
        }
        let swing = |amplitude: f64, frequency: f64| Oscillation {
            amplitude,
            frequency,
            phase: 0.0,
        };
        RigidPartSpec {
            name: name.into(),
            vertices,
            triangles,
            friction_static: 0.6,
            friction_sliding: 0.5,
            motion: Some(PartMotion::Periodic(Periodic {
                centre: DVec3::ZERO,
                translation: [
                    Oscillation::default(),
                    Oscillation::default(),
                    swing(0.003, heave),
                ],
                rotation: [
                    swing(2f64.to_radians(), 1.5),
                    Oscillation::default(),
                    Oscillation::default(),
                ],
            })),
            parent: None,
            movable: false,
        }
    }

    /// A bent hose of 24 elements dropped onto `parts`.
    fn hose_over(parts: Vec<RigidPartSpec>) -> Model {
        let nodes = (0..=24)
            .map(|i| {
                let s = i as f64 / 24.0;
                DVec3::new(0.4 * s - 0.2, 0.05 * (6.0 * s).sin(), 0.012 + 0.01 * s)
            })
            .collect();
        let hose = HoseSpec {
            name: "h".into(),
            material: Material::isotropic(12e6, 0.49, 940.0),
            nodes,
            sections: vec![Section::new(0.010, 0.016)],
            normal_hint: None,
        };
        Model::build(&WorldSpec {
            hoses: vec![hose],
            rigid_parts: parts,
            settings: SimSettings::default(),
        })
        .unwrap()
    }

    /// A rippled floor of 2·n² triangles, 0.6 m square, rocking (±3 mm up and down at
    /// 2 Hz, ±2° roll at 1.5 Hz), and a bent hose of 24 elements dropped onto it.
    fn rocking_floor(n: usize) -> Model {
        hose_over(vec![floor_patch("floor", n, (-0.3, 0.3), 2.0)])
    }

    /// `steps` steps of `model` with the moving parts' candidate lists and with fresh
    /// queries instead: the same positions and contacts to the last bit at every step.
    /// Returns the steps in contact, the lists' refreshes, and how often a beam left the
    /// beams visited with the lists (with fresh queries every beam is visited, none clear).
    fn kept_against_fresh(model: &Model, steps: usize) -> (usize, u64, usize) {
        let (mut kept, mut fresh) = (State::at_rest(model), State::at_rest(model));
        for lists in &mut fresh.contact.moving_candidates {
            lists.enabled = false;
        }
        let (mut touching, mut left) = (0, 0);
        for step in 0..steps {
            explicit::step(model, &mut kept);
            explicit::step(model, &mut fresh);
            assert_eq!(kept.x, fresh.x, "step {step}");
            assert_eq!(kept.contact.points, fresh.contact.points, "step {step}");
            assert_eq!(fresh.contact.moving_near.len(), model.elements.len());
            touching += usize::from(!kept.contact.points.is_empty());
            let near = &kept.contact.moving_near;
            let last = &kept.contact.moving_near_last;
            left += last.iter().filter(|e| !near.contains(e)).count();
        }
        let refreshes = kept
            .contact
            .moving_candidates
            .iter()
            .map(|c| c.refreshes)
            .sum();
        (touching, refreshes, left)
    }

    /// The candidate lists kept in the moving part's frame find, step after step, the
    /// contacts fresh BVH queries find: the same positions to the last bit, while the
    /// hose falls onto the rocking floor, bounces and rides on it.
    #[test]
    fn lists_in_the_part_frame_give_the_fresh_queries_contacts_to_the_bit() {
        let (touching, refreshes, left) = kept_against_fresh(&rocking_floor(60), 4000);
        eprintln!(
            "{touching} of 4000 steps in contact; {refreshes} list refreshes; \
             {left} times a beam left the beams visited"
        );
        assert!(touching > 2000, "{touching} steps in contact");
        // beams clear of the part are not visited, and leave the visited ones (their
        // normals forgotten) as the hose bounces
        assert!(left > 0, "no beam left the beams visited");
        // the lists are kept, not remade every step: fewer refreshes than beams × steps / 10
        assert!(refreshes < 24 * 4000 / 10, "{refreshes} refreshes");
    }

    /// Two floor patches rocking at different rates, overlapping by 4 cm under the middle
    /// of the hose: the beams and nodes there search both parts' lists and take the
    /// nearer contact, as fresh queries of both parts do, to the last bit.
    #[test]
    fn two_moving_parts_under_one_hose_give_the_fresh_queries_contacts_to_the_bit() {
        let model = hose_over(vec![
            floor_patch("left", 30, (-0.3, 0.02), 2.0),
            floor_patch("right", 30, (-0.02, 0.3), 2.5),
        ]);
        let (mut state, mut parts_touched) = (State::at_rest(&model), [false; 2]);
        for _ in 0..3000 {
            explicit::step(&model, &mut state);
            for c in &state.contact.points {
                parts_touched[c.part] = true;
            }
        }
        assert_eq!(parts_touched, [true, true], "the hose lies on both parts");
        let (touching, _, left) = kept_against_fresh(&model, 3000);
        assert!(touching > 1500, "{touching} steps in contact");
        assert!(left > 0, "no beam left the beams visited");
    }
}
