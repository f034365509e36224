//! The triangles a candidate list ([`super::coherence`]) is kept for: the parts that
//! stand still, in world coordinates ([`RigidEnvironment`]), or one part in its own
//! reference placement ([`PartFrame`]) — a moving part's searches run there, on points
//! mapped by the inverse of its pose ([`super::moving`]). Distances are the same in both
//! frames, so the lists' bounds hold in either.

use super::environment::{RigidEnvironment, RigidPart};
use super::planes::Planes;
use glam::DVec3;
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::shape::Triangle;

/// A set of triangles searched by box, each known by its part's index and its index in
/// that part's mesh.
pub(crate) trait TriangleSet {
    /// Calls `f(part, triangle)` for every triangle whose box meets `aabb`, parts in
    /// order, each part's triangles in its BVH's depth-first order.
    fn for_each_index_near(&self, aabb: &Aabb, f: impl FnMut(usize, u32));
    /// Triangle `triangle` of part `part` and the edges it owns.
    fn triangle_and_edges(&self, part: usize, triangle: u32) -> (Triangle, u8);
    /// The bounding planes of that triangle.
    fn planes(&self, part: usize, triangle: u32) -> &Planes;
    /// A lower bound on the distance from segment [a, b] to the set, capped at `max`.
    fn nearest_box(&self, a: DVec3, b: DVec3, max: f64) -> f64;
    /// Parts and triangles: lists made for another set are forgotten.
    fn key(&self) -> (usize, usize);
}

impl TriangleSet for RigidEnvironment {
    fn for_each_index_near(&self, aabb: &Aabb, f: impl FnMut(usize, u32)) {
        RigidEnvironment::for_each_index_near(self, aabb, f)
    }
    fn triangle_and_edges(&self, part: usize, triangle: u32) -> (Triangle, u8) {
        RigidEnvironment::triangle_and_edges(self, part, triangle)
    }
    fn planes(&self, part: usize, triangle: u32) -> &Planes {
        &self.parts[part].planes[triangle as usize]
    }
    fn nearest_box(&self, a: DVec3, b: DVec3, max: f64) -> f64 {
        RigidEnvironment::nearest_box(self, a, b, max)
    }
    fn key(&self) -> (usize, usize) {
        let triangles = self.parts.iter().map(|p| p.mesh.indices().len()).sum();
        (self.parts.len(), triangles)
    }
}

/// Part `index` of an environment, alone, in its reference placement.
#[derive(Clone, Copy)]
pub(crate) struct PartFrame<'a> {
    pub part: &'a RigidPart,
    pub index: usize,
}

impl TriangleSet for PartFrame<'_> {
    fn for_each_index_near(&self, aabb: &Aabb, mut f: impl FnMut(usize, u32)) {
        if !self.part.mesh.local_aabb().intersects(aabb) {
            return;
        }
        for i in self.part.mesh.bvh().intersect_aabb(aabb) {
            f(self.index, i);
        }
    }
    fn triangle_and_edges(&self, _part: usize, triangle: u32) -> (Triangle, u8) {
        (
            self.part.mesh.triangle(triangle),
            self.part.owned_edges[triangle as usize],
        )
    }
    fn planes(&self, _part: usize, triangle: u32) -> &Planes {
        &self.part.planes[triangle as usize]
    }
    fn nearest_box(&self, a: DVec3, b: DVec3, max: f64) -> f64 {
        self.part.nearest_box(a, b, max)
    }
    fn key(&self) -> (usize, usize) {
        (self.index, self.part.mesh.indices().len())
    }
}
