//! The rigid environment: one parry triangle mesh (with its bounding-volume hierarchy)
//! per part, built once with the model, in the part's reference placement.
//!
//! Parts that stand still are searched in world coordinates, through the candidate lists
//! of [`super::coherence`]; a part that moves ([`crate::kinematics`]) is never rebuilt:
//! a query point is mapped into its reference placement by the inverse of its pose
//! (distances are the same in both), and what is found is mapped back
//! ([`super::moving`]). The still parts' searches skip the moving ones, so a world
//! without moving parts is searched exactly as before.

use super::coherence::{scan_fresh, Nearest};
use super::owned_edges::owned_edges;
use super::planes::Planes;
use super::point_triangle::closest_point_on_triangle;
use crate::spec::RigidPartSpec;
use glam::DVec3;
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::shape::{TriMesh, Triangle};

/// One rigid part.
#[derive(Clone, Debug)]
pub struct RigidPart {
    pub name: String,
    pub mesh: TriMesh,
    pub friction_static: f64,
    pub friction_sliding: f64,
    /// The bounding planes of each triangle of `mesh` (in its order), made once.
    pub(crate) planes: Vec<Planes>,
    /// The edges each triangle of `mesh` owns ([`owned_edges`]), made once.
    pub(crate) owned_edges: Vec<u8>,
    /// Whether the part moves (it has a motion, may be moved by inputs, or has a parent
    /// that moves).
    pub moves: bool,
    /// The largest distance of a vertex from the reference origin \[m\]: a point of the
    /// part moves at most |Ṫ| + |ω| · this ([`crate::kinematics::Placement::velocity_at`]).
    pub(crate) extent: f64,
}

/// All rigid parts of a model.
#[derive(Clone, Debug, Default)]
pub struct RigidEnvironment {
    pub parts: Vec<RigidPart>,
    /// The indices of the parts that move, in order.
    pub(crate) moving: Vec<usize>,
}

impl RigidEnvironment {
    /// Builds the meshes; a broken mesh is reported with the part's name.
    pub fn build(specs: &[RigidPartSpec]) -> Result<Self, String> {
        let mut parts = Vec::with_capacity(specs.len());
        for s in specs {
            if s.triangles.is_empty() {
                return Err(format!("rigid part '{}': mesh has no triangles", s.name));
            }
            if let Some(v) = s.vertices.iter().find(|v| !v.is_finite()) {
                return Err(format!(
                    "rigid part '{}': vertex is not finite: {v:?}",
                    s.name
                ));
            }
            let n = s.vertices.len() as u32;
            if let Some(t) = s.triangles.iter().find(|t| t.iter().any(|&i| i >= n)) {
                return Err(format!(
                    "rigid part '{}': triangle {t:?} indexes past {n} vertices",
                    s.name
                ));
            }
            if !(s.friction_static >= 0.0
                && s.friction_sliding >= 0.0
                && s.friction_sliding <= s.friction_static)
            {
                return Err(format!(
                    "rigid part '{}': friction must satisfy 0 ≤ sliding ({}) ≤ static ({})",
                    s.name, s.friction_sliding, s.friction_static
                ));
            }
            let mesh = TriMesh::new(s.vertices.clone(), s.triangles.clone())
                .map_err(|e| format!("rigid part '{}': {e:?}", s.name))?;
            let planes = (0..mesh.indices().len() as u32)
                .map(|i| Planes::new(&mesh.triangle(i)))
                .collect();
            let extent = s.vertices.iter().map(|v| v.length()).fold(0.0, f64::max);
            parts.push(RigidPart {
                name: s.name.clone(),
                planes,
                owned_edges: owned_edges(&mesh),
                mesh,
                friction_static: s.friction_static,
                friction_sliding: s.friction_sliding,
                moves: false,
                extent,
            });
        }
        // a part moves if it or an ancestor has a motion or may be moved (cycles: the
        // kinematics refuse them)
        for k in 0..parts.len() {
            let mut at = Some(k);
            for _ in 0..=specs.len() {
                let Some(a) = at else { break };
                let Some(spec) = specs.get(a) else { break };
                if spec.motion.is_some() || spec.movable {
                    parts[k].moves = true;
                    break;
                }
                at = spec.parent;
            }
        }
        let moving = (0..parts.len()).filter(|&k| parts[k].moves).collect();
        Ok(RigidEnvironment { parts, moving })
    }

    /// Makes part `k` a moving one (a junction body's shape, [`crate::junction_shape`]).
    pub(crate) fn add_moving(&mut self, k: usize) {
        if let Err(at) = self.moving.binary_search(&k) {
            self.moving.insert(at, k);
        }
    }

    /// Whether any part moves.
    pub fn any_moves(&self) -> bool {
        !self.moving.is_empty()
    }

    /// Whether any part stands still (the still parts' searches have anything to find).
    pub fn any_still(&self) -> bool {
        self.parts.iter().any(|p| !p.moves)
    }

    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }

    /// Closest point to `p` on any still part within `max_distance`: (part, point, distance),
    /// found among the triangles whose bounding boxes meet the cube of half-size
    /// `max_distance` around `p` (anything outside that cube is farther away).
    pub fn closest_point(&self, p: DVec3, max_distance: f64) -> Option<(usize, DVec3, f64)> {
        let mut search = ClosestPoint::new(p, max_distance);
        scan_fresh(self, &cube(p, max_distance), &mut search);
        search.best.map(|b| (b.part, b.point, b.distance))
    }

    /// [`Self::closest_point`] among every part, the moving ones at `placements` (one per
    /// part; ignored without moving parts): the nearest, a still part on a tie.
    pub fn closest_point_placed(
        &self,
        p: DVec3,
        max_distance: f64,
        placements: &[crate::kinematics::Placement],
    ) -> Option<(usize, DVec3, f64)> {
        let still = self.closest_point(p, max_distance);
        let reach = still.map_or(max_distance, |b| b.2);
        match self.closest_moving(p, reach, placements) {
            Some(m) if still.is_none_or(|b| m.2 < b.2) => Some(m),
            _ => still,
        }
    }

    /// Closest point to `p` within `max_distance` on a moving part at `placements` (one
    /// per part): (part, point, distance), the point in world coordinates. The search runs
    /// in the part's reference placement (module doc).
    pub fn closest_moving(
        &self,
        p: DVec3,
        max_distance: f64,
        placements: &[crate::kinematics::Placement],
    ) -> Option<(usize, DVec3, f64)> {
        self.closest_moving_where(p, max_distance, placements, |_| true)
    }

    /// [`Self::closest_moving`] among the moving parts `k` with `allowed(k)`.
    pub(crate) fn closest_moving_where(
        &self,
        p: DVec3,
        max_distance: f64,
        placements: &[crate::kinematics::Placement],
        allowed: impl Fn(usize) -> bool,
    ) -> Option<(usize, DVec3, f64)> {
        let mut best: Option<(usize, DVec3, f64)> = None;
        for &k in self.moving.iter().filter(|&&k| allowed(k)) {
            let Some(place) = placements.get(k) else {
                continue;
            };
            let reach = best.map_or(max_distance, |b| b.2);
            let local = place.pose.inverse_apply(p);
            let found = self.parts[k].closest_point_local(k, local, reach);
            if let Some(hit) = found {
                if best.is_none_or(|b| hit.distance < b.2) {
                    best = Some((k, place.pose.apply(hit.point), hit.distance));
                }
            }
        }
        best
    }

    /// Calls `f(part, triangle)` for every still part's triangle whose box meets `aabb`, parts in
    /// order, each part's triangles in its BVH's depth-first order.
    pub fn for_each_triangle_near(&self, aabb: &Aabb, mut f: impl FnMut(usize, &Triangle)) {
        self.for_each_index_near(aabb, |k, i| f(k, &self.parts[k].mesh.triangle(i)));
    }

    /// As [`Self::for_each_triangle_near`], with only the part and the triangle's index
    /// in its part's mesh (for callers that need the triangle itself for few of them).
    pub(crate) fn for_each_index_near(&self, aabb: &Aabb, mut f: impl FnMut(usize, u32)) {
        for (k, part) in self.parts.iter().enumerate() {
            if part.moves || !part.mesh.local_aabb().intersects(aabb) {
                continue;
            }
            for i in part.mesh.bvh().intersect_aabb(aabb) {
                f(k, i);
            }
        }
    }
}

impl RigidEnvironment {
    /// Triangle `triangle` of part `part` and the edges it owns ([`owned_edges`]).
    #[inline(always)]
    pub(crate) fn triangle_and_edges(&self, part: usize, triangle: u32) -> (Triangle, u8) {
        let part = &self.parts[part];
        (
            part.mesh.triangle(triangle),
            part.owned_edges[triangle as usize],
        )
    }

    /// A lower bound on the distance from segment [a, b] to every part, capped at `max`:
    /// the distance to the nearest triangle's box, found best first down each part's BVH.
    pub(crate) fn nearest_box(&self, a: DVec3, b: DVec3, max: f64) -> f64 {
        let mut nearest = max;
        for part in &self.parts {
            if !part.moves {
                nearest = part.nearest_box(a, b, nearest);
            }
        }
        nearest
    }
}

impl RigidPart {
    /// The closest point to `local` (in the part's reference placement) within `reach`,
    /// offered the triangles whose boxes meet the cube of half-size `reach` around it in
    /// the BVH's order; `k` is the part's index, recorded in the hit.
    pub(crate) fn closest_point_local(
        &self,
        k: usize,
        local: DVec3,
        reach: f64,
    ) -> Option<PointHit> {
        let mut search = ClosestPoint::new(local, reach);
        let query = cube(local, reach);
        for (rank, i) in self.mesh.bvh().intersect_aabb(&query).enumerate() {
            search.offer(k, &self.mesh.triangle(i), rank as u32, 0);
        }
        search.best
    }

    /// A lower bound on the distance from segment [a, b] (in the part's reference
    /// placement) to the part, capped at `max`: the nearest triangle box, best first down
    /// the BVH.
    pub(crate) fn nearest_box(&self, a: DVec3, b: DVec3, max: f64) -> f64 {
        let segment = Aabb::new(a.min(b), a.max(b));
        if box_distance(&segment, &self.mesh.local_aabb()) >= max {
            return max;
        }
        let best = self.mesh.bvh().find_best(
            max,
            |node, _| box_distance(&segment, &node.aabb()),
            |i, _| Some(box_distance(&segment, &self.mesh.triangle(i).local_aabb())),
        );
        best.map_or(max, |(_, d)| d.min(max))
    }
}

/// The distance between two boxes: no point of one is nearer to a point of the other.
fn box_distance(p: &Aabb, q: &Aabb) -> f64 {
    let gap = (p.mins - q.maxs).max(q.mins - p.maxs).max(DVec3::ZERO);
    gap.length()
}

/// A 1 m × 1 m plate in the plane z = 0 about the origin (two triangles), for tests.
#[cfg(test)]
pub(crate) fn test_plate() -> RigidEnvironment {
    RigidEnvironment::build(&[crate::spec::RigidPartSpec {
        name: "plate".into(),
        vertices: vec![
            DVec3::new(-0.5, -0.5, 0.0),
            DVec3::new(0.5, -0.5, 0.0),
            DVec3::new(0.5, 0.5, 0.0),
            DVec3::new(-0.5, 0.5, 0.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        friction_static: 0.5,
        friction_sliding: 0.5,
        ..Default::default()
    }])
    .unwrap()
}

/// The cube of half-size `h` around `p`.
pub(crate) fn cube(p: DVec3, h: f64) -> Aabb {
    Aabb::new(p - DVec3::splat(h), p + DVec3::splat(h))
}

/// The closest point found: part, point, distance, rank.
#[derive(Clone, Copy)]
pub(crate) struct PointHit {
    pub part: usize,
    pub point: DVec3,
    pub distance: f64,
    rank: u32,
}

/// The search for the closest point of any triangle to `x` within `reach` (equal
/// distances: the first in the environment's order) — a node's contact.
pub(crate) struct ClosestPoint {
    x: DVec3,
    reach: f64,
    pub best: Option<PointHit>,
}

impl ClosestPoint {
    pub fn new(x: DVec3, reach: f64) -> Self {
        ClosestPoint {
            x,
            reach,
            best: None,
        }
    }
}

impl Nearest for ClosestPoint {
    /// Returns the point's distance to the triangle (all of it: `edges` concerns searches
    /// whose hits lie on edges).
    fn offer(&mut self, part: usize, tri: &Triangle, rank: u32, _edges: u8) -> f64 {
        let point = closest_point_on_triangle(self.x, tri);
        let distance = (point - self.x).length();
        let better =
            |b: &PointHit| distance < b.distance || (distance == b.distance && rank < b.rank);
        if distance <= self.reach && self.best.as_ref().is_none_or(better) {
            self.best = Some(PointHit {
                part,
                point,
                distance,
                rank,
            });
        }
        distance
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
