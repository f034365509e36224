//! The manikin's capsules against the rigid parts (SPEC E1: "Kollisionen zum Beispiel
//! des Oberkörpers"): for each capsule the part it sinks deepest into and how deep — the
//! capsule's radius less its axis's distance to the part's surface, from the physics
//! core's segment–triangle closest points over the triangles whose boxes meet the
//! capsule's box.
//!
//! What it does not see: a capsule wholly inside a closed part without touching its
//! surface, parts that move (their triangles are searched in their reference placement
//! by the core, not here), and the hoses. The hands are not checked: fingers round a
//! hose touch what lies around it, which is no collision of the body.

use glam::DVec3;
use parry3d_f64::bounding_volume::Aabb;
use pliant_core::contact::{closest_segment_triangle, RigidEnvironment};
use pliant_worker::{Capsule, Segment};

/// The deepest penetration of one capsule: part index and depth \[m\] (> 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Penetration {
    pub part: usize,
    pub depth: f64,
}

/// Whether a segment is checked against the parts (the hands are not; module doc).
pub fn checked(segment: Segment) -> bool {
    !matches!(segment, Segment::Hand(_))
}

/// The deepest penetration of `capsule` into a part that stands still, if any.
pub fn deepest(env: &RigidEnvironment, capsule: &Capsule) -> Option<Penetration> {
    let mut best: Option<Penetration> = None;
    let aabb = aabb_of(capsule.a, capsule.b, capsule.radius);
    env.for_each_triangle_near(&aabb, |part, tri| {
        if env.parts[part].moves {
            return;
        }
        let c = closest_segment_triangle(capsule.a, capsule.b, tri);
        let depth = capsule.radius - c.distance;
        if depth > 0.0 && best.is_none_or(|b| depth > b.depth) {
            best = Some(Penetration { part, depth });
        }
    });
    best
}

/// The box around the capsule of axis [a, b] and radius `r`.
fn aabb_of(a: DVec3, b: DVec3, r: f64) -> Aabb {
    Aabb::new(a.min(b) - DVec3::splat(r), a.max(b) + DVec3::splat(r))
}
