//! Bounding planes of a triangle: a lower bound on the distance from a point or segment
//! for ≈ 40 flops, made once per triangle when the environment is built and used by the
//! candidate lists ([`super::coherence`]) to reject triangles before an exact test.

use glam::DVec3;
use parry3d_f64::shape::Triangle;

/// Planes that bound a triangle from outside: its own (unit normal, offset) and, in it,
/// the outward unit normals and offsets of its three edges. A point at height h above the
/// plane and g_k beyond edge k lies at least √(h² + max(0, max_k g_k)²) from the
/// triangle (the distance splits into the plane's normal and in-plane parts, and the
/// in-plane part is at least the distance to any of the edges' half-planes); for a
/// segment, h and g_k are linear along it, so their smaller end values bound it
/// (h only if both ends lie on one side). Made once per triangle with the environment; a
/// degenerate triangle gets zero planes and bounds nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Planes {
    normal: DVec3,
    offset: f64,
    edge_normal: [DVec3; 3],
    edge_offset: [f64; 3],
}

impl Planes {
    pub(crate) fn new(tri: &Triangle) -> Planes {
        let n = (tri.b - tri.a).cross(tri.c - tri.a);
        let len = n.length();
        if !len.is_normal() {
            return Planes::default();
        }
        let normal = n / len;
        let mut planes = Planes {
            normal,
            offset: normal.dot(tri.a),
            ..Planes::default()
        };
        for (k, (v0, v1)) in [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)]
            .into_iter()
            .enumerate()
        {
            // counter-clockwise about the normal: the outside lies to the edge's right
            let m = (v1 - v0).cross(normal);
            let len = m.length();
            if len.is_normal() {
                planes.edge_normal[k] = m / len;
                planes.edge_offset[k] = planes.edge_normal[k].dot(v0);
            }
        }
        planes
    }

    /// A lower bound on the squared distance from segment [a, b] (a point if a = b) to
    /// the triangle, up to rounding (relative 1e-15; users allow a slack).
    #[inline(always)]
    pub(crate) fn lower_bound_squared(&self, a: DVec3, b: DVec3) -> f64 {
        let (ha, hb) = (
            self.normal.dot(a) - self.offset,
            self.normal.dot(b) - self.offset,
        );
        // plain comparisons (no NaN handling: the planes are finite)
        let h = if ha * hb > 0.0 {
            let (ha, hb) = (ha.abs(), hb.abs());
            if ha < hb {
                ha
            } else {
                hb
            }
        } else {
            0.0
        };
        let mut g = 0.0f64;
        for k in 0..3 {
            let m = self.edge_normal[k];
            let o = self.edge_offset[k];
            let (ga, gb) = (m.dot(a) - o, m.dot(b) - o);
            let gk = if ga < gb { ga } else { gb };
            if gk > g {
                g = gk;
            }
        }
        h * h + g * g
    }
}
