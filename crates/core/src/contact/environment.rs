//! The rigid environment: one parry triangle mesh (with its bounding-volume hierarchy)
//! per part, built once with the model.

use crate::spec::RigidPartSpec;
use glam::DVec3;
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh, Triangle};

/// One rigid part.
#[derive(Clone, Debug)]
pub struct RigidPart {
    pub name: String,
    pub mesh: TriMesh,
    pub friction_static: f64,
    pub friction_sliding: f64,
}

/// All rigid parts of a model.
#[derive(Clone, Debug, Default)]
pub struct RigidEnvironment {
    pub parts: Vec<RigidPart>,
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
            parts.push(RigidPart {
                name: s.name.clone(),
                mesh,
                friction_static: s.friction_static,
                friction_sliding: s.friction_sliding,
            });
        }
        Ok(RigidEnvironment { parts })
    }

    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }

    /// Closest point to `p` on any part within `max_distance`: (part, point, distance),
    /// found among the triangles whose bounding boxes meet the cube of half-size
    /// `max_distance` around `p` (anything outside that cube is farther away).
    pub fn closest_point(&self, p: DVec3, max_distance: f64) -> Option<(usize, DVec3, f64)> {
        let mut best = None;
        self.for_each_triangle_near(&cube(p, max_distance), |k, tri| {
            closer(&mut best, p, max_distance, k, tri)
        });
        best
    }

    /// Calls `f(part, triangle)` for every triangle whose box meets `aabb`, parts in
    /// order, each part's triangles in its BVH's depth-first order.
    pub fn for_each_triangle_near(&self, aabb: &Aabb, mut f: impl FnMut(usize, &Triangle)) {
        self.for_each_triangle_index_near(aabb, |k, _, tri| f(k, tri));
    }

    /// As [`Self::for_each_triangle_near`], with each triangle's index in its part's mesh.
    pub fn for_each_triangle_index_near(
        &self,
        aabb: &Aabb,
        mut f: impl FnMut(usize, u32, &Triangle),
    ) {
        for (k, part) in self.parts.iter().enumerate() {
            if !part.mesh.local_aabb().intersects(aabb) {
                continue;
            }
            for i in part.mesh.bvh().intersect_aabb(aabb) {
                f(k, i, &part.mesh.triangle(i));
            }
        }
    }
}

/// The cube of half-size `h` around `p`.
pub(crate) fn cube(p: DVec3, h: f64) -> Aabb {
    Aabb::new(p - DVec3::splat(h), p + DVec3::splat(h))
}

/// Keeps in `best` the first-found closest (part, point, distance) to `p` within
/// `max_distance`, offered triangle `tri` of part `k`.
pub(crate) fn closer(
    best: &mut Option<(usize, DVec3, f64)>,
    p: DVec3,
    max_distance: f64,
    k: usize,
    tri: &Triangle,
) {
    let q = tri.project_local_point(p, false).point;
    let d = (q - p).length();
    if d <= max_distance && best.is_none_or(|b| d < b.2) {
        *best = Some((k, q, d));
    }
}
