//! Temporal coherence for rigid contact (issue 15): each node's and each beam's nearby
//! triangles are found once, with a margin, and kept from step to step until the node or
//! beam has moved by the margin — the idea of Verlet neighbour lists (L. Verlet, Phys.
//! Rev. 159, 98, 1967) and of the "enlarged bounding volumes" of collision detection
//! (Ericson, "Real-Time Collision Detection", §6.6 / §9.6).
//!
//! A slot's query is a segment [a, b] (a = b for a node) with a contact reach ρ. On a
//! refresh every triangle whose box meets the segment's box grown by ρ + m is examined,
//! and those whose distance to the segment is at most ρ + m are kept, in the environment's
//! own order (parts in order, each part's BVH depth-first). The distance from a segment to
//! a fixed set is 1-Lipschitz in the largest end-point displacement (each point
//! (1−t)a + tb moves by at most max(|Δa|, |Δb|)), so while both end points stay within m
//! of where they were, no triangle that was dropped can come within ρ: the kept list
//! holds every triangle that can touch, in the same order as a fresh query, and the
//! contact found from it is the same to the last bit. Most slots keep an empty list (the
//! hose is clear of the parts) and cost one distance check per step.
//!
//! Storage is allocated once: a fixed number of candidates per slot; a slot that would
//! need more is marked and queried directly (still exact, only slower).

use super::closest_segment_triangle;
use super::environment::RigidEnvironment;
use glam::DVec3;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::Triangle;

/// Candidates kept per slot.
pub const SLOT_CAPACITY: usize = 48;
/// Margin m as a fraction of the reach ρ: a slot is refreshed after moving ρ/4.
pub const MARGIN: f64 = 0.25;
/// Relative slack on distances for rounding (the kept test errs towards keeping).
const SLACK: f64 = 1e-9;
const OVERFLOW: u32 = u32::MAX;

/// One triangle of one part, and its distance from the slot's segment at the refresh.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Candidate {
    part: u32,
    triangle: u32,
    distance: f64,
}

/// Candidate triangles per slot (one slot per node, then one per beam), allocated once.
#[derive(Clone, Debug, Default)]
pub struct CandidateCache {
    /// Whether the lists are used; off, every query goes to the environment's BVH
    /// (the reference the coherent path is tested against).
    pub enabled: bool,
    /// End points and reach of each slot's last refresh (∞: never refreshed).
    anchor_a: Vec<DVec3>,
    anchor_b: Vec<DVec3>,
    reach: Vec<f64>,
    /// Number of candidates of each slot, or `OVERFLOW`.
    len: Vec<u32>,
    /// `SLOT_CAPACITY` entries per slot.
    items: Vec<Candidate>,
    /// Parts and triangles of the environment the lists were made for.
    environment_key: (usize, usize),
    /// Refreshes made (a counter for benchmarks and tests).
    pub refreshes: u64,
}

fn environment_key(env: &RigidEnvironment) -> (usize, usize) {
    let triangles = env.parts.iter().map(|p| p.mesh.indices().len()).sum();
    (env.parts.len(), triangles)
}

/// Distance from segment [a, b] (a point if a = b) to `tri`.
fn segment_distance(a: DVec3, b: DVec3, tri: &Triangle) -> f64 {
    if a == b {
        (tri.project_local_point(a, false).point - a).length()
    } else {
        closest_segment_triangle(a, b, tri).distance
    }
}

/// False only if segment [a, b] (a point if a = b) certainly lies farther than `reach`
/// from `tri`: both end points on one side of its plane, each at least `reach` (plus
/// rounding slack) from it — a lower bound on the distance, 20 flops instead of the
/// closest points.
pub(crate) fn may_touch(a: DVec3, b: DVec3, tri: &Triangle, reach: f64) -> bool {
    let n = (tri.b - tri.a).cross(tri.c - tri.a);
    let (da, db) = ((a - tri.a).dot(n), (b - tri.a).dot(n));
    let limit = reach * (1.0 + SLACK) * n.length();
    !(da * db > 0.0 && da.abs().min(db.abs()) > limit)
}

/// parry's box test (inclusive), as the BVH applies it to its leaves.
fn boxes_meet(a: &Aabb, b: &Aabb) -> bool {
    a.mins.cmple(b.maxs).all() && a.maxs.cmpge(b.mins).all()
}

impl CandidateCache {
    /// A cache of `slots` slots, enabled; empty (and unused) without an environment.
    pub fn new(slots: usize, env: &RigidEnvironment) -> Self {
        let slots = if env.is_empty() { 0 } else { slots };
        CandidateCache {
            enabled: true,
            anchor_a: vec![DVec3::INFINITY; slots],
            anchor_b: vec![DVec3::INFINITY; slots],
            reach: vec![0.0; slots],
            len: vec![0; slots],
            items: vec![Candidate::default(); slots * SLOT_CAPACITY],
            environment_key: environment_key(env),
            refreshes: 0,
        }
    }

    /// Forgets every list (the next query of each slot refreshes it).
    pub fn clear(&mut self) {
        self.anchor_a.fill(DVec3::INFINITY);
        self.anchor_b.fill(DVec3::INFINITY);
    }

    fn refresh(&mut self, env: &RigidEnvironment, slot: usize, a: DVec3, b: DVec3, reach: f64) {
        let keep = (reach * (1.0 + MARGIN)) * (1.0 + SLACK);
        let grow = DVec3::splat(keep);
        let query = Aabb::new(a.min(b) - grow, a.max(b) + grow);
        let base = slot * SLOT_CAPACITY;
        let mut n = 0usize;
        env.for_each_triangle_index_near(&query, |part, triangle, tri| {
            if n > SLOT_CAPACITY || !may_touch(a, b, tri, keep) {
                return;
            }
            let distance = segment_distance(a, b, tri);
            if distance > keep {
                return;
            }
            if n < SLOT_CAPACITY {
                self.items[base + n] = Candidate {
                    part: part as u32,
                    triangle,
                    distance,
                };
            }
            n += 1;
        });
        self.len[slot] = if n > SLOT_CAPACITY {
            OVERFLOW
        } else {
            n as u32
        };
        self.anchor_a[slot] = a;
        self.anchor_b[slot] = b;
        self.reach[slot] = reach;
        self.refreshes += 1;
    }

    /// Calls `f(part, triangle)` for every triangle whose box meets `query` and which may
    /// lie within `reach` of segment [a, b] (a = b for a node); every triangle within
    /// `reach` is among them, in the order of [`RigidEnvironment::for_each_triangle_near`]
    /// (see the module doc). `query` must contain the segment's box grown by `reach`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn for_each_near(
        &mut self,
        env: &RigidEnvironment,
        slot: usize,
        a: DVec3,
        b: DVec3,
        reach: f64,
        query: &Aabb,
        mut f: impl FnMut(usize, &Triangle),
    ) {
        if !self.enabled || slot >= self.len.len() {
            return env.for_each_triangle_near(query, f);
        }
        if self.environment_key != environment_key(env) {
            self.environment_key = environment_key(env);
            self.clear();
        }
        let m = MARGIN * reach;
        let mut moved = (a - self.anchor_a[slot])
            .length_squared()
            .max((b - self.anchor_b[slot]).length_squared());
        if !(moved < m * m) || self.reach[slot] != reach {
            self.refresh(env, slot, a, b, reach);
            moved = 0.0;
        }
        // a candidate that was d away can be no nearer than d − moved now
        let near = (reach + moved.sqrt()) * (1.0 + SLACK);
        let n = self.len[slot];
        if n == OVERFLOW {
            return env.for_each_triangle_near(query, f);
        }
        let base = slot * SLOT_CAPACITY;
        for r in &self.items[base..base + n as usize] {
            if r.distance > near {
                continue;
            }
            let tri = env.parts[r.part as usize].mesh.triangle(r.triangle);
            if boxes_meet(&tri.local_aabb(), query) {
                f(r.part as usize, &tri);
            }
        }
    }
}
