//! The manikin's capsules against the parts and the hoses (SPEC E1: "Kollisionen zum
//! Beispiel des Oberkörpers"): for each capsule the part or hose it sinks deepest into
//! and how deep.
//!
//! - A part: the capsule's radius less its axis's distance to the part's surface, from
//!   the physics core's segment–triangle closest points over the triangles whose boxes
//!   meet the capsule's box. A part that moves is searched where it is now: the capsule
//!   is mapped into the part's reference placement by the inverse of its pose at the
//!   instant (a rigid map keeps distances), as the core's own moving contact does.
//! - A hose: the capsule's radius plus the tube's (the larger of a beam's two node
//!   radii) less the distance between the capsule's axis and the beam, from the core's
//!   segment–segment closest points (Ericson §5.1.9). A beam whose closest point lies
//!   within a hand length of a hand target is left out: the hose there runs through the
//!   worker's hand and along the wrist, which is holding it, not a collision.
//!
//! What it does not see: a capsule wholly inside a closed part without touching its
//! surface. The hands are not checked: fingers round a hose touch what lies around it,
//! which is no collision of the body.

use glam::DVec3;
use parry3d_f64::bounding_volume::{Aabb, BoundingVolume};
use pliant_core::contact::closest_segment_triangle;
use pliant_core::contact::hose_hose::closest_segment_segment;
use pliant_core::{Model, State};
use pliant_worker::{Capsule, Segment};
use serde::Serialize;

/// What a body segment ran into: a part or a hose, by index in the model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", content = "index", rename_all = "snake_case")]
pub enum Obstacle {
    Part(usize),
    Hose(usize),
}

impl Obstacle {
    /// The part's or hose's name in `model`.
    pub fn name(self, model: &Model) -> String {
        match self {
            Obstacle::Part(k) => model
                .environment
                .parts
                .get(k)
                .map_or_else(String::new, |p| p.name.clone()),
            Obstacle::Hose(h) => model
                .hoses
                .get(h)
                .map_or_else(String::new, |h| h.name.clone()),
        }
    }

    /// "part" or "hose".
    pub fn kind(self) -> &'static str {
        match self {
            Obstacle::Part(_) => "part",
            Obstacle::Hose(_) => "hose",
        }
    }
}

/// The deepest penetration of one capsule: what it ran into and how deep \[m\] (> 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Penetration {
    pub obstacle: Obstacle,
    pub depth: f64,
}

/// Whether a segment is checked against parts and hoses (the hands are not; module doc).
pub fn checked(segment: Segment) -> bool {
    !matches!(segment, Segment::Hand(_))
}

/// The deepest penetration of `capsule` into a part (where it is at `state`'s time) or
/// a hose (where `state` has it), if any; `held` the hand targets, `hand` the hand's
/// length \[m\] (a hose within it of a target is being held, module doc).
pub fn deepest(
    model: &Model,
    state: &State,
    capsule: &Capsule,
    held: &[Option<DVec3>; 2],
    hand: f64,
) -> Option<Penetration> {
    let mut best: Option<Penetration> = None;
    let mut keep = |obstacle: Obstacle, depth: f64| {
        if depth > 0.0 && best.is_none_or(|b| depth > b.depth) {
            best = Some(Penetration { obstacle, depth });
        }
    };
    let env = &model.environment;
    let aabb = aabb_of(capsule.a, capsule.b, capsule.radius);
    env.for_each_triangle_near(&aabb, |part, tri| {
        let c = closest_segment_triangle(capsule.a, capsule.b, tri);
        keep(Obstacle::Part(part), capsule.radius - c.distance);
    });
    for (k, part) in env.parts.iter().enumerate() {
        if !part.moves {
            continue;
        }
        let pose = model
            .kinematics
            .placement_at(k, state.time, &state.part_moves)
            .pose;
        let (a, b) = (pose.inverse_apply(capsule.a), pose.inverse_apply(capsule.b));
        let local = aabb_of(a, b, capsule.radius);
        if !part.mesh.local_aabb().intersects(&local) {
            continue;
        }
        for i in part.mesh.bvh().intersect_aabb(&local) {
            let c = closest_segment_triangle(a, b, &part.mesh.triangle(i));
            keep(Obstacle::Part(k), capsule.radius - c.distance);
        }
    }
    for (h, hose) in model.hoses.iter().enumerate() {
        for n in hose.first_node..hose.first_node + hose.element_count {
            let (p, q) = (state.x[n], state.x[n + 1]);
            let tube = model.radius[n].max(model.radius[n + 1]);
            if !aabb.intersects(&aabb_of(p, q, tube)) {
                continue;
            }
            let (s, t) = closest_segment_segment(capsule.a, capsule.b, p, q);
            let on_beam = p + (q - p) * t;
            let on_axis = capsule.a + (capsule.b - capsule.a) * s;
            if held.iter().flatten().any(|g| g.distance(on_beam) < hand) {
                continue;
            }
            keep(
                Obstacle::Hose(h),
                capsule.radius + tube - on_axis.distance(on_beam),
            );
        }
    }
    best
}

/// The box around the capsule of axis [a, b] and radius `r`.
fn aabb_of(a: DVec3, b: DVec3, r: f64) -> Aabb {
    Aabb::new(a.min(b) - DVec3::splat(r), a.max(b) + DVec3::splat(r))
}
