//! Kinematic contact of hose nodes and beam interiors with the rigid environment
//! (SPEC L4; dissertation eq. 4.94–4.95, with Coulomb friction from its outlook 7.2).
//!
//! Each step, after the velocities are updated and before positions are:
//! 1. Detection on the start-of-step positions: every free node against the parts (a ball
//!    of the node's radius) and every beam's interior against nearby triangles: the
//!    nearest pair strictly inside the segment between it and any mesh edge (each edge
//!    measured once, by the triangle that owns it, [`super::owned_edges`]), or a point
//!    where it pierces a face — so contact holds along the whole beam, not only at
//!    nodes. Meshes are two-sided: the normal points from the closest surface point to
//!    the hose point, whatever the triangles' orientation; if that direction flips
//!    against the one remembered from the last step in contact, the point has crossed the
//!    surface and the remembered side is kept (SPEC L4, ch. 5.3.3).
//!    The triangles examined come from lists kept from step to step ([`super::coherence`]),
//!    which find exactly the contacts fresh BVH queries would.
//! 2. Velocities: the contact point loses the approaching normal velocity that would take
//!    it past the surface in this step — all of it when touching or penetrating, and
//!    beyond gap/Δt when found within the detection skin still short of the surface (a
//!    speculative contact, as for moving parts, [`super::moving`]; E. Catto, "Continuous
//!    collision", GDC 2013): the point closes the gap and is held only there, never
//!    hovering at the gap it was found at, where each release when the gap grew past the
//!    skin dropped it onto the part again, a self-sustained cycle. Coulomb friction
//!    removes the tangential velocity if it is below μ_s times the normal velocity change
//!    (sticking), else reduces it by μ_k times that change (sliding). A beam-interior point
//!    at parameter t is changed by spreading the change over its two nodes with weights
//!    (1−t, t)/((1−t)² + t²), which moves the contact point by exactly the wanted amount.
//!    The impulses, divided by Δt, are the reported contact forces.
//! 3. After the position update, remaining penetration is pushed out along the normal by
//!    at most 10 % of the radius per step — position only, so deep penetration is resolved
//!    over a few steps without any explosive force.
//!
//! Parts that move ([`super::moving`]) are found in their own frames and appended to the
//! contacts; steps 2 and 3 use the velocity relative to the part's.
//!
//! Tunnelling: at hand speeds (≤ 2 m/s) and the explicit step (≈ 0.1 ms) a point moves
//! ≈ 0.2 mm per step, far less than a hose radius, so a thin sheet is always detected
//! before it could be crossed.

use super::coherence::{scan_fresh, Nearest, Searcher, SLACK};
use super::environment::{cube, ClosestPoint};
use super::segment_triangle::closest_segment_triangle_edges_within;
use crate::contact::CandidateCache;
use crate::rod::element::BeamElement;
use crate::{Model, State};
use glam::DVec3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::shape::Triangle;

/// Detection distance beyond touching, as a fraction of the radius.
pub(crate) const SKIN: f64 = 0.01;
/// Largest penetration push-out per step, as a fraction of the radius.
const MAX_PUSH: f64 = 0.1;
/// Beam-interior contacts are those strictly between the nodes.
pub(super) const INTERIOR: f64 = 0.02;

/// One active contact in a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactPoint {
    /// The two nodes of the beam (equal for a node contact).
    pub node_a: usize,
    pub node_b: usize,
    /// Parameter of the contact point between them.
    pub t: f64,
    /// Unit normal from the part towards the hose.
    pub normal: DVec3,
    /// Penetration depth \[m\] at detection (negative: still a small gap).
    pub depth: f64,
    /// Index of the part touched.
    pub part: usize,
    /// The part's velocity at the contact point \[m/s\] (zero for a part standing still).
    pub part_velocity: DVec3,
}

/// Contact memory and per-step work space, allocated once with the state.
#[derive(Clone, Debug, Default)]
pub struct ContactScratch {
    /// Active contacts of the last step.
    pub points: Vec<ContactPoint>,
    /// Normal of each node's last contact (zero when not in contact).
    pub node_normal: Vec<DVec3>,
    /// Normal of each beam's last interior contact (zero when not in contact).
    pub element_normal: Vec<DVec3>,
    /// Each beam's (slot e) candidate triangles, kept from step to step
    /// ([`CandidateCache`]; the same contacts as fresh queries). A node searches the list
    /// of one of its beams.
    pub candidates: CandidateCache,
    /// Per beam, this step: no triangle within reach ([`CandidateCache::clear_slack`],
    /// asked once and read by the beam and its nodes).
    beam_clear: Vec<bool>,
    /// This step's beams not held at both ends and not clear, in order: the beams whose
    /// interior is searched (capacity: every beam).
    beams_near: Vec<u32>,
    /// The beams that stay clear while the nodes stay near where they were
    /// ([`super::ClearSkin`]).
    skin: super::ClearSkin,
    /// When the stiffened sections' nodes are clear of the parts ([`super::Clearance`],
    /// read by the penalty contact).
    pub(crate) clearance: super::Clearance,
    /// Every part's pose and twist this step ([`crate::kinematics::PartKinematics::place_all`];
    /// empty when no part moves).
    pub placements: Vec<crate::kinematics::Placement>,
    /// Per node and per beam: the moving part of its last contact and the normal there,
    /// in that part's frame ([`super::moving`]; `usize::MAX`: none).
    pub(crate) moving_node_normal: Vec<(usize, DVec3)>,
    pub(crate) moving_element_normal: Vec<(usize, DVec3)>,
    /// Per moving part this step: its box at its placement and how far it moves at most.
    pub(crate) moving_box: Vec<Aabb>,
    pub(crate) moving_sweep: Vec<f64>,
    /// This step, per node: its speed |v| (when a part moves; read by every search that
    /// reaches as far as the node moves in the step, [`super::moving`]).
    pub(crate) moving_speed: Vec<f64>,
    /// This step, per moving part and node (part-major): the node's position in the
    /// part's frame, mapped once and read by the node's and its beams' searches.
    pub(crate) moving_local: Vec<DVec3>,
    /// This step, per moving part and beam (part-major): what the beam's searches
    /// against the part share ([`super::moving`]).
    pub(crate) moving_beam: Vec<super::moving::BeamStep>,
    /// This step's beams near some moving part, in order ([`super::moving`]; capacity:
    /// every beam).
    pub(crate) moving_near: Vec<u32>,
    /// The last step's `moving_near` (their memories are forgotten when they leave it).
    pub(crate) moving_near_last: Vec<u32>,
    /// This step's beam-interior contacts with the moving parts, appended to `points`
    /// after the nodes' (capacity: every beam).
    pub(crate) moving_interior: Vec<ContactPoint>,
    /// The nodes without a beam (searched by fresh queries of the moving parts).
    pub(crate) moving_beamless: Vec<u32>,
    /// Per moving part: each beam's candidate triangles of that part, in the part's own
    /// frame ([`super::moving`]; no slots beyond the memory budget, then fresh queries).
    pub(crate) moving_candidates: Vec<CandidateCache>,
    /// The beam whose list each node searches (`u32::MAX`: none, a fresh query), in the
    /// still parts' lists and the moving parts' ([`super::moving`]).
    pub(crate) node_beam: Vec<u32>,
    /// Per part riding on a junction body ([`crate::junction_shape`]): the impulse its
    /// contacts gave the hose nodes this step and that impulse's moment about the world
    /// origin, Σ J_n and Σ x_n × J_n (empty without junction shapes).
    pub(crate) shape_impulse: Vec<(DVec3, DVec3)>,
}

impl ContactScratch {
    pub fn new(model: &Model) -> Self {
        let (nodes, elements) = (model.node_count(), model.elements.len());
        ContactScratch {
            points: Vec::with_capacity(nodes + elements),
            node_normal: vec![DVec3::ZERO; nodes],
            element_normal: vec![DVec3::ZERO; elements],
            candidates: CandidateCache::new(elements, &model.environment),
            node_beam: node_beams(model),
            beam_clear: vec![false; elements],
            beams_near: Vec::with_capacity(elements),
            skin: super::ClearSkin::new(nodes, elements),
            clearance: super::Clearance::new(nodes, &model.environment),
            placements: if model.environment.any_moves() {
                vec![Default::default(); model.environment.parts.len()]
            } else {
                Vec::new()
            },
            moving_node_normal: vec![(usize::MAX, DVec3::ZERO); moving_slots(model, nodes)],
            moving_element_normal: vec![(usize::MAX, DVec3::ZERO); moving_slots(model, elements)],
            moving_box: vec![Aabb::new_invalid(); model.environment.moving.len()],
            moving_sweep: vec![0.0; model.environment.moving.len()],
            moving_speed: vec![0.0; moving_slots(model, nodes)],
            moving_local: vec![
                DVec3::ZERO;
                moving_slots(model, nodes) * model.environment.moving.len()
            ],
            moving_beam: vec![
                Default::default();
                moving_slots(model, elements) * model.environment.moving.len()
            ],
            moving_near: Vec::with_capacity(moving_slots(model, elements)),
            moving_near_last: Vec::with_capacity(moving_slots(model, elements)),
            moving_interior: Vec::with_capacity(moving_slots(model, elements)),
            moving_beamless: if model.environment.any_moves() {
                beamless_nodes(model)
            } else {
                Vec::new()
            },
            moving_candidates: super::moving::candidate_lists(model),
            shape_impulse: if model.junction_shapes.any() {
                vec![(DVec3::ZERO, DVec3::ZERO); model.environment.parts.len()]
            } else {
                Vec::new()
            },
        }
    }
}

/// `n` when some part moves, else none.
fn moving_slots(model: &Model, n: usize) -> usize {
    if model.environment.any_moves() {
        n
    } else {
        0
    }
}

/// For each node, the first beam that starts at it, else the first that ends at it.
fn node_beams(model: &Model) -> Vec<u32> {
    let mut beam = vec![u32::MAX; model.node_count()];
    for (e, el) in model.elements.iter().enumerate() {
        if beam[el.node_a] == u32::MAX {
            beam[el.node_a] = e as u32;
        }
    }
    for (e, el) in model.elements.iter().enumerate() {
        if beam[el.node_b] == u32::MAX {
            beam[el.node_b] = e as u32;
        }
    }
    beam
}

/// The nodes no beam starts or ends at, in order.
fn beamless_nodes(model: &Model) -> Vec<u32> {
    let mut has_beam = vec![false; model.node_count()];
    for el in &model.elements {
        (has_beam[el.node_a], has_beam[el.node_b]) = (true, true);
    }
    (0..model.node_count() as u32)
        .filter(|&i| !has_beam[i as usize])
        .collect()
}

/// Reach of the capsule of beam `e`: its larger end radius plus the skin.
fn beam_reach(model: &Model, e: usize) -> f64 {
    reach_of(model, &model.elements[e])
}

/// [`beam_reach`] of beam `el`.
fn reach_of(model: &Model, el: &BeamElement) -> f64 {
    model.radius[el.node_a].max(model.radius[el.node_b]) * (1.0 + SKIN)
}

/// Normal and depth from a hose point `p` of radius `r` and the closest surface point `q`,
/// keeping the remembered side when the point has crossed the surface.
pub(super) fn side(p: DVec3, q: DVec3, r: f64, remembered: DVec3) -> (DVec3, f64) {
    let d = (p - q).length();
    let fresh = if d > 1e-12 * r {
        (p - q) / d
    } else {
        remembered
    };
    if remembered != DVec3::ZERO && fresh.dot(remembered) < 0.0 {
        (remembered, r + d) // crossed: still on the remembered side, depth through
    } else if fresh == DVec3::ZERO {
        (DVec3::Z, r - d) // touching exactly with no history: any normal; depth decides
    } else {
        (fresh, r - d)
    }
}

/// Weights spreading a contact-point change over the free nodes of a contact.
fn weights(state: &State, c: &ContactPoint) -> Option<(f64, f64)> {
    let (wa, wb) = if c.node_a == c.node_b {
        (1.0, 0.0)
    } else {
        (1.0 - c.t, c.t)
    };
    let wa = if state.held[c.node_a] { 0.0 } else { wa };
    let wb = if c.node_a == c.node_b || state.held[c.node_b] {
        0.0
    } else {
        wb
    };
    let denom = wa * wa + wb * wb;
    (denom > 1e-12).then(|| (wa / denom, wb / denom))
}

fn contact_velocity(state: &State, c: &ContactPoint) -> DVec3 {
    (1.0 - c.t) * state.v[c.node_a] + c.t * state.v[c.node_b]
}

/// A beam-interior contact: part, parameter, points on the beam and the triangle.
#[derive(Clone, Copy)]
pub(super) struct BeamHit {
    part: usize,
    pub t: f64,
    pub p: DVec3,
    pub q: DVec3,
    pub distance: f64,
    rank: u32,
}

/// The search for a beam's interior contact: the nearest pair strictly inside the
/// segment (away from its nodes, which have their own contacts) and any mesh edge, or a
/// piercing point, within reach.
pub(super) struct BeamSearch {
    a: DVec3,
    b: DVec3,
    reach: f64,
    pub best: Option<BeamHit>,
}

impl BeamSearch {
    /// A search along [a, b] within `reach`.
    pub fn new(a: DVec3, b: DVec3, reach: f64) -> Self {
        BeamSearch {
            a,
            b,
            reach,
            best: None,
        }
    }
}

impl Nearest for BeamSearch {
    /// Returns a lower bound on the distance from the segment to the triangle's own
    /// `edges` (0 if it pierces the face), the distance of any hit of it that does not
    /// pierce it. A hit is the nearest pair strictly inside the segment between it and
    /// any edge (each measured by the one triangle that owns it), or a piercing point.
    fn offer(&mut self, part: usize, tri: &Triangle, rank: u32, edges: u8) -> f64 {
        let bound = self.bound() * (1.0 + SLACK);
        let interior = |t: f64| t > INTERIOR && t < 1.0 - INTERIOR;
        let (closest, lower) =
            closest_segment_triangle_edges_within(self.a, self.b, tri, bound, edges, interior);
        let Some(c) = closest else {
            return lower; // no accepted pair within the bound
        };
        let better =
            |b: &BeamHit| c.distance < b.distance || (c.distance == b.distance && rank < b.rank);
        if c.distance < self.reach && self.best.as_ref().is_none_or(better) {
            self.best = Some(BeamHit {
                part,
                t: c.t,
                p: c.on_segment,
                q: c.on_triangle,
                distance: c.distance,
                rank,
            });
        }
        lower
    }
    fn bound(&self) -> f64 {
        self.best.map_or(self.reach, |b| b.distance)
    }
    fn reset(&mut self) {
        self.best = None;
    }
    fn found(&self) -> bool {
        self.best.is_some()
    }
}

/// Step 1 for the still parts: their contacts with the nodes and the beam interiors,
/// appended to `state.contact.points` (see the module doc).
fn detect_still(model: &Model, state: &mut State) {
    let env = &model.environment;
    let contact = &mut state.contact;
    contact.candidates.follow(env);
    // Most beams are clear: they are settled here (their interior is not in contact, and
    // a beam not held at both ends forgets its normal), and the beam loop below visits
    // only the others.
    contact.beams_near.clear();
    // the beams clear at the last full pass are still clear while the skin holds
    let skin = contact.skin.holds(&contact.candidates, &state.x);
    if !skin {
        contact.skin.begin(&contact.candidates, &state.x);
    }
    let beams = model.elements.iter().zip(&mut contact.beam_clear);
    for (e, ((el, clear), normal)) in beams.zip(&mut contact.element_normal).enumerate() {
        let (a, b) = (el.node_a, el.node_b);
        if !(skin && contact.skin.is_member(e)) {
            let slack =
                contact
                    .candidates
                    .clear_slack(e, state.x[a], state.x[b], reach_of(model, el));
            *clear = slack.is_some();
            if let (false, Some(slack)) = (skin, slack) {
                contact.skin.add(e, slack);
            }
        }
        if state.held[a] && state.held[b] {
            continue; // a beam held at both ends has no interior contact to find
        }
        let settled = |cache: &CandidateCache| {
            let reach = reach_of(model, el);
            cache.settled(e, Searcher::Interior, state.x[a], state.x[b], reach)
        };
        if *clear || settled(&contact.candidates) {
            *normal = DVec3::ZERO; // no triangle within reach, or its search would find none
        } else {
            contact.beams_near.push(e as u32);
        }
    }
    if !skin {
        contact.skin.end();
    }
    // each node with its beam, held flag, radius and remembered normal, side by side
    let nodes = contact.node_beam.iter().zip(&state.held).zip(&model.radius);
    let nodes = nodes.zip(contact.node_normal.iter_mut()).enumerate();
    for (i, (((&e, &held), &r), remembered)) in nodes {
        let e = e as usize;
        if contact.beam_clear.get(e) == Some(&true) || held {
            *remembered = DVec3::ZERO;
            continue; // no triangle within reach of its beam, or held (no contact)
        }
        let reach = r * (1.0 + SKIN);
        let beam = model.elements.get(e).map(|el| {
            let searcher = if el.node_a == i {
                Searcher::StartNode
            } else {
                Searcher::EndNode
            };
            (el, searcher, state.x[el.node_a], state.x[el.node_b])
        });
        if let Some((_, searcher, xa, xb)) = beam {
            if contact.candidates.settled(e, searcher, xa, xb, reach) {
                *remembered = DVec3::ZERO;
                continue; // its search would find nothing
            }
        }
        let x = state.x[i];
        let mut search = ClosestPoint::new(x, reach);
        let query = cube(x, reach);
        match beam {
            None => scan_fresh(env, &query, &mut search),
            Some((el, searcher, xa, xb)) => contact.candidates.scan(
                env,
                e,
                xa,
                xb,
                reach_of(model, el),
                searcher,
                [x, x],
                &query,
                &mut search,
            ),
        }
        let found = search.best.map(|b| (b.part, b.point));
        match found {
            Some((part, q)) => {
                let (normal, depth) = side(x, q, r, *remembered);
                *remembered = normal;
                contact.points.push(ContactPoint {
                    node_a: i,
                    node_b: i,
                    t: 0.0,
                    normal,
                    depth,
                    part,
                    part_velocity: DVec3::ZERO,
                });
            }
            None => *remembered = DVec3::ZERO,
        }
    }
    for k in 0..contact.beams_near.len() {
        let e = contact.beams_near[k] as usize;
        let (a, b) = (model.elements[e].node_a, model.elements[e].node_b);
        let reach = beam_reach(model, e);
        let (xa, xb) = (state.x[a], state.x[b]);
        let r = model.radius[a].max(model.radius[b]);
        let aabb = Aabb::new(
            xa.min(xb) - DVec3::splat(reach),
            xa.max(xb) + DVec3::splat(reach),
        );
        let mut search = BeamSearch {
            a: xa,
            b: xb,
            reach,
            best: None,
        };
        // an accepted hit lies at t in (INTERIOR, 1 − INTERIOR): the candidates' bounds
        // are taken from that part of the beam
        let d = xb - xa;
        let probe = [xa + INTERIOR * d, xa + (1.0 - INTERIOR) * d];
        contact.candidates.scan(
            env,
            e,
            xa,
            xb,
            reach,
            Searcher::Interior,
            probe,
            &aabb,
            &mut search,
        );
        let best = search.best;
        match best {
            Some(BeamHit { part, t, p, q, .. }) => {
                let (normal, depth) = side(p, q, r, contact.element_normal[e]);
                contact.element_normal[e] = normal;
                contact.points.push(ContactPoint {
                    node_a: a,
                    node_b: b,
                    t,
                    normal,
                    depth,
                    part,
                    part_velocity: DVec3::ZERO,
                });
            }
            None => contact.element_normal[e] = DVec3::ZERO,
        }
    }
}

/// Steps 1 and 2: detect contacts and correct velocities (see the module doc).
pub(crate) fn resolve_velocities(model: &Model, state: &mut State, dt: f64) {
    let env = &model.environment;
    state.contact.points.clear();
    if env.any_still() {
        detect_still(model, state);
    } // else no still part: no contact to find, the normals stay zero
    if env.any_moves() {
        super::moving::detect(model, state, dt);
    }
    for k in 0..state.contact.points.len() {
        let c = state.contact.points[k];
        let Some((wa, wb)) = weights(state, &c) else {
            continue;
        };
        let part = &env.parts[c.part];
        // a junction body's shape moves with its body's velocity now and shares the
        // impulse with it ([`crate::junction_shape`])
        let shape = model.junction_shape_contact(state, &c);
        let part_velocity = shape.map_or(c.part_velocity, |s| s.velocity);
        // relative to the part's velocity; a contact found with a gap lets the point
        // approach by the gap in this step (step 2 of the module doc)
        let v_c = contact_velocity(state, &c) - part_velocity;
        let vn = v_c.dot(c.normal);
        let allowed = (-c.depth).max(0.0) / dt;
        if vn >= -allowed {
            continue;
        }
        let vt = v_c - vn * c.normal;
        let speed_t = vt.length();
        // the hose point's shares of the normal and the tangential change: all of them
        // against a part, 1/(1 + m_h k_b) against a junction body's shape (the hose
        // point's effective mass m_h = Σ m_n w_n)
        let (share_n, share_t) = shape.map_or((1.0, 1.0), |s| {
            let hose_mass = model.mass[c.node_a] * wa + model.mass[c.node_b] * wb;
            s.hose_shares(model, state, hose_mass, c.normal, vt)
        });
        let dvn = share_n * (-vn - allowed);
        let dvt = if share_t * speed_t <= part.friction_static * dvn {
            -vt * share_t
        } else {
            -vt * (part.friction_sliding * dvn / speed_t)
        };
        let dv = dvn * c.normal + dvt;
        let (mut impulse, mut moment) = (DVec3::ZERO, DVec3::ZERO);
        for (node, w) in [(c.node_a, wa), (c.node_b, wb)] {
            if w != 0.0 {
                state.v[node] += w * dv;
                state.contact_force[node] += model.mass[node] * w * dv / dt;
                impulse += model.mass[node] * w * dv;
                moment += state.x[node].cross(model.mass[node] * w * dv);
            }
        }
        if let Some(s) = shape {
            model.push_junction_shape(state, s, impulse, moment);
        }
    }
}

/// Step 3: push remaining penetration out, at most `MAX_PUSH`·r per step.
pub(crate) fn project_positions(model: &Model, state: &mut State, dt: f64) {
    for k in 0..state.contact.points.len() {
        let c = state.contact.points[k];
        let Some((wa, wb)) = weights(state, &c) else {
            continue;
        };
        let r = model.radius[c.node_a].max(model.radius[c.node_b]);
        let moved_out = (contact_velocity(state, &c) - c.part_velocity)
            .dot(c.normal)
            .max(0.0)
            * dt;
        let push = (c.depth - moved_out).clamp(0.0, MAX_PUSH * r);
        if push > 0.0 {
            state.x[c.node_a] += wa * push * c.normal;
            if c.node_b != c.node_a {
                state.x[c.node_b] += wb * push * c.normal;
            }
        }
    }
}
