//! Closest points between a segment (a beam's centre line) and a triangle (one face of a
//! rigid part), the narrow phase of capsule–mesh contact (SPEC L4). Built from parry's
//! point–triangle projection and its segment–segment closest points, inlined (Ericson, "Real-Time
//! Collision Detection", §5.1.9–5.1.10): the minimum over the two end points projected
//! onto the triangle, the segment against the three edges, and — if the segment pierces
//! the triangle — the piercing point at distance zero.

use super::owned_edges::ALL_EDGES;
use glam::DVec3;
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::Triangle;

/// Closest pair between a segment and a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentTriangleClosest {
    /// Parameter along the segment, 0 at `a`, 1 at `b`.
    pub t: f64,
    /// Closest point on the segment.
    pub on_segment: DVec3,
    /// Closest point on the triangle.
    pub on_triangle: DVec3,
    /// Their distance \[m\] (0 when the segment pierces the triangle).
    pub distance: f64,
}

/// Closest points between segment [a, b] and `tri`.
pub fn closest_segment_triangle(a: DVec3, b: DVec3, tri: &Triangle) -> SegmentTriangleClosest {
    let mut best = closest_segment_triangle_away_from_ends(a, b, tri);
    if best.distance == 0.0 {
        return best;
    }
    for (t, p) in [(0.0, a), (1.0, b)] {
        let q = tri.project_local_point(p, false).point;
        let d = (p - q).length();
        if d < best.distance {
            best = SegmentTriangleClosest {
                t,
                on_segment: p,
                on_triangle: q,
                distance: d,
            };
        }
    }
    best
}

/// As [`closest_segment_triangle`], but without the two end points' projections onto the
/// face: the piercing point, or the closest pair between the segment and the triangle's
/// edges. If the true closest point lies strictly inside the segment, it is one of these
/// (a segment's interior can be nearest to a face only when it pierces it or runs
/// parallel to it, and then an end point is as near). Contact of the beam interior needs
/// only this; the end points are the nodes, which have their own contact.
pub fn closest_segment_triangle_away_from_ends(
    a: DVec3,
    b: DVec3,
    tri: &Triangle,
) -> SegmentTriangleClosest {
    let (closest, _) =
        closest_segment_triangle_edges_within(a, b, tri, f64::INFINITY, ALL_EDGES, |_| true);
    closest.unwrap_or(SegmentTriangleClosest {
        t: 0.0,
        on_segment: a,
        on_triangle: a,
        distance: f64::INFINITY,
    })
}

/// As [`closest_segment_triangle_away_from_ends`], but only the pairs whose parameter on
/// the segment passes `accept`, among the piercing point and the triangle's `edges` (bit
/// k: vertex k to k + 1; a beam's interior measures the edges its triangle owns,
/// [`super::owned_edges`]); an edge whose line lies farther than `bound` from the
/// segment's line — then the edge lies farther from the segment — is not measured (≈ 30
/// flops instead of the closest pair), and no edge is if both end points lie on one side
/// of the triangle's plane, farther than `bound` from it. Returns the accepted piercing
/// point or the nearest accepted pair among the edges measured (`None` if none was), to
/// the last bit what the unbounded search finds whenever that lies within `bound`, and a
/// lower bound on the distance between the segment and each of those edges, accepted or
/// not (their minimum; 0 if the segment pierces the triangle). An edge nearly parallel
/// to the segment is always measured.
pub(crate) fn closest_segment_triangle_edges_within(
    a: DVec3,
    b: DVec3,
    tri: &Triangle,
    bound: f64,
    edges: u8,
    accept: impl Fn(f64) -> bool,
) -> (Option<SegmentTriangleClosest>, f64) {
    let mut lower = f64::INFINITY;
    // piercing: the end points lie on opposite sides of the triangle's plane
    let normal = (tri.b - tri.a).cross(tri.c - tri.a);
    let (da, db) = ((a - tri.a).dot(normal), (b - tri.a).dot(normal));
    if da * db < 0.0 {
        let t = da / (da - db);
        let p = a + t * (b - a);
        let proj = tri.project_local_point(p, false);
        if (proj.point - p).length_squared() <= 1e-24 * normal.length() {
            if accept(t) {
                let pierce = SegmentTriangleClosest {
                    t,
                    on_segment: p,
                    on_triangle: proj.point,
                    distance: 0.0,
                };
                return (Some(pierce), 0.0);
            }
            lower = 0.0; // it reaches the face, where no pair is accepted; the edges may be
        }
    } else if da * db > 0.0 && bound.is_finite() {
        // on one side: every point of the segment is at least the nearer end's height
        // from the plane, and so from each edge
        let height = da.abs().min(db.abs());
        let height_squared = height * height;
        let normal_squared = normal.length_squared();
        let limit = bound * (1.0 + TIE_SLACK);
        if height_squared > limit * limit * normal_squared {
            return (None, (height_squared / normal_squared).sqrt());
        }
    }
    let mut best: Option<SegmentTriangleClosest> = None;
    let d1 = b - a;
    let d1_squared = d1.length_squared();
    // one edge at a time, inlined (a loop over an array of edges copied the array on
    // every call, and a closure was not inlined)
    let segment = (a, d1, d1_squared);
    let mut measure = |k: u8, e0: DVec3, e1: DVec3| {
        if edges & (1 << k) != 0 {
            measure_edge(segment, e0, e1, bound, &accept, &mut best, &mut lower);
        } // else another triangle owns it
    };
    measure(0, tri.a, tri.b);
    measure(1, tri.b, tri.c);
    measure(2, tri.c, tri.a);
    (best, lower)
}

/// One edge `e0`–`e1` of [`closest_segment_triangle_edges_within`] against the segment
/// (its start, direction and squared length): lowers `lower` to the edge's distance or a
/// bound on it, and keeps its pair in `best` if accepted and nearer.
#[inline(always)]
fn measure_edge(
    (a, d1, d1_squared): (DVec3, DVec3, f64),
    e0: DVec3,
    e1: DVec3,
    bound: f64,
    accept: &impl Fn(f64) -> bool,
    best: &mut Option<SegmentTriangleClosest>,
    lower: &mut f64,
) {
    let d2 = e1 - e0;
    // An edge can replace the best only if it is strictly nearer, so once one is found,
    // the others are measured only within it (plus a slack far above the rounding of
    // either distance): the result and the least bound are the same.
    let within = best.map_or(bound, |b| bound.min(b.distance * (1.0 + TIE_SLACK)));
    if within.is_finite() {
        // the distance between the lines (sin θ > 1e-3 between them keeps its rounding
        // far below the callers' slack)
        let w = d1.cross(d2);
        let w2 = w.length_squared();
        let s = (a - e0).dot(w);
        let far = s * s > within * within * w2;
        if w2 > 1e-6 * d1_squared * d2.length_squared() && far {
            *lower = lower.min((s * s / w2).sqrt());
            return;
        }
    }
    let (t, s) = segment_segment_parameters(a, d1, d1_squared, e0, d2);
    let (p, q) = (a + t * d1, e0 + s * d2);
    let d = (p - q).length();
    *lower = lower.min(d);
    if accept(t) && d < best.as_ref().map_or(f64::INFINITY, |b| b.distance) {
        *best = Some(SegmentTriangleClosest {
            t,
            on_segment: p,
            on_triangle: q,
            distance: d,
        });
    }
}

/// Relative slack of the pruning tests: a found distance below which another edge is
/// still measured, and the margin of the plane test (far above rounding, far below any
/// gap that matters).
const TIE_SLACK: f64 = 1e-9;

/// Parameters (t on segment p0 + t·d1, s on segment e0 + s·d2) of the closest points of
/// two segments (Ericson, "Real-Time Collision Detection", §5.1.9), with |d1|² given:
/// the arithmetic of parry's `closest_points_segment_segment_with_locations_nD`, step
/// for step, so that the results agree to the last bit (tested), without its locations
/// and with the first segment's terms computed once per triangle. (Hose–hose contact's
/// [`super::hose_hose::closest_segment_segment`] is the same method with another rule for
/// parallel segments, the middle of their overlap; this one keeps parry's, so rigid
/// contacts stay what they were.)
#[inline(always)]
fn segment_segment_parameters(p0: DVec3, d1: DVec3, a: f64, e0: DVec3, d2: DVec3) -> (f64, f64) {
    const EPS: f64 = f64::EPSILON; // parry's DEFAULT_EPSILON
    let r = p0 - e0;
    let e = d2.length_squared();
    let f = d2.dot(r);
    if a <= EPS && e <= EPS {
        return (0.0, 0.0);
    }
    if a <= EPS {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(r);
    if e <= EPS {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let (ae, bb) = (a * e, b * b);
    let denom = ae - bb;
    // parry's `ulps_eq!(ae, bb)` where ae − bb > ε: both are non-negative, ae the larger
    let nearly_parallel = || ae.to_bits() - bb.to_bits() <= 4;
    let mut t = if denom > EPS && !nearly_parallel() {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut s = (b * t + f) / e;
    if s < 0.0 {
        s = 0.0;
        t = (-c / a).clamp(0.0, 1.0);
    } else if s > 1.0 {
        s = 1.0;
        t = ((b - c) / a).clamp(0.0, 1.0);
    }
    // + 0.0: a clamped −0 becomes 0, as parry's end-point location does
    (t + 0.0, s + 0.0)
}

#[cfg(test)]
mod tests {
    use super::super::test_random::uniform;
    use super::*;

    /// parry's closest points of segments [a, b] and [e0, e1], as parameters (t, s).
    fn parry_parameters(a: DVec3, b: DVec3, e0: DVec3, e1: DVec3) -> (f64, f64) {
        use parry3d_f64::query::closest_points::closest_points_segment_segment_with_locations_nD;
        use parry3d_f64::shape::SegmentPointLocation;
        let parameter = |loc| match loc {
            SegmentPointLocation::OnVertex(i) => i as f64,
            SegmentPointLocation::OnEdge(w) => w[1],
        };
        let (l1, l2) = closest_points_segment_segment_with_locations_nD((&a, &b), (&e0, &e1));
        (parameter(l1), parameter(l2))
    }

    /// The inlined segment–segment parameters agree with parry's to the last bit, for
    /// random segments, parallel and nearly parallel ones, and degenerate ones.
    #[test]
    fn segment_parameters_are_parrys_to_the_last_bit() {
        let mut next = uniform(0x9e37_79b9_7f4a_7c15);
        for k in 0..60_000 {
            let mut point = || DVec3::new(next(), next(), next());
            let (a, b, e0) = (point(), point(), point());
            let e1 = match k % 6 {
                0 => e0 + (b - a) * 0.7,                    // parallel
                1 => e0 + (b - a) * 0.7 + point() * 1e-9,   // nearly parallel
                2 => e0 + point() * 1e-9,                   // a degenerate edge
                3 => e0 + (b - a) * -1.3 + point() * 1e-14, // antiparallel
                _ => point(),
            };
            let (a, b) = if k % 11 == 0 { (a, a) } else { (a, b) };
            let (t_parry, s_parry) = parry_parameters(a, b, e0, e1);
            let d1 = b - a;
            let (t, s) = segment_segment_parameters(a, d1, d1.length_squared(), e0, e1 - e0);
            assert_eq!(
                (t.to_bits(), s.to_bits()),
                (t_parry.to_bits(), s_parry.to_bits()),
                "case {k}: {a} {b} {e0} {e1}"
            );
        }
    }

    /// The accepted piercing point, else the first nearest accepted pair of the edges in
    /// `edges`, each measured by parry's own segment–segment closest points (no bound, no
    /// pruning); and the least distance to those edges, accepted or not (0 if pierced).
    fn every_edge(
        a: DVec3,
        b: DVec3,
        tri: &Triangle,
        edges: u8,
        accept: impl Fn(f64) -> bool,
    ) -> (Option<SegmentTriangleClosest>, f64) {
        let any = closest_segment_triangle_away_from_ends(a, b, tri);
        let pierced = any.distance == 0.0;
        if pierced && accept(any.t) {
            return (Some(any), 0.0);
        }
        let mut best: Option<SegmentTriangleClosest> = None;
        let mut least = if pierced { 0.0 } else { f64::INFINITY };
        let sides = [(tri.a, tri.b), (tri.b, tri.c), (tri.c, tri.a)];
        for (k, (e0, e1)) in sides.into_iter().enumerate() {
            if edges & (1 << k) == 0 {
                continue;
            }
            let (t, s) = parry_parameters(a, b, e0, e1);
            let (p, q) = (a + t * (b - a), e0 + s * (e1 - e0));
            let distance = (p - q).length();
            least = least.min(distance);
            if accept(t) && best.is_none_or(|b| distance < b.distance) {
                best = Some(SegmentTriangleClosest {
                    t,
                    on_segment: p,
                    on_triangle: q,
                    distance,
                });
            }
        }
        (best, least)
    }

    fn unit_tri() -> Triangle {
        Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y)
    }

    #[test]
    fn segment_above_interior_is_closest_at_its_lower_end() {
        let c = closest_segment_triangle(
            DVec3::new(0.2, 0.2, 0.1),
            DVec3::new(0.2, 0.2, 0.5),
            &unit_tri(),
        );
        assert!((c.distance - 0.1).abs() < 1e-15 && c.t == 0.0);
    }

    #[test]
    fn segment_beside_an_edge_is_closest_to_that_edge() {
        // vertical segment outside the hypotenuse: closest to its midpoint, at z = 0
        let c = closest_segment_triangle(
            DVec3::new(1.0, 1.0, 0.3),
            DVec3::new(1.0, 1.0, -0.3),
            &unit_tri(),
        );
        assert!((c.t - 0.5).abs() < 1e-12, "{c:?}");
        assert!((c.on_triangle - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-12);
        assert!((c.distance - 0.5f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn piercing_segment_has_zero_distance() {
        let c = closest_segment_triangle(
            DVec3::new(0.25, 0.25, -1.0),
            DVec3::new(0.25, 0.25, 3.0),
            &unit_tri(),
        );
        assert!(c.distance < 1e-15 && (c.t - 0.25).abs() < 1e-12);
    }

    /// The unbounded search finds, to the last bit, what measuring each of the given
    /// edges finds, keeping the accepted pairs; the bounded one finds the same whenever
    /// that lies within the bound, and its lower bound never exceeds the distance to any
    /// of those edges (random segments near random triangles, random edge sets, bounds
    /// around their distance; every fourth segment passes over a vertex, where two edges
    /// tie).
    #[test]
    fn the_bounded_edge_search_agrees_with_the_unbounded_one() {
        let mut next = uniform(0x2545_f491_4f6c_dd1d);
        let (mut within, mut beyond) = (0, 0);
        for k in 0..20_000 {
            let mut point = || DVec3::new(next(), next(), 0.2 * next());
            let tri = Triangle::new(point(), point(), point());
            let a = DVec3::new(next(), next(), 0.1 + 0.3 * next());
            let (mut a, mut b) = (a, a + 0.5 * DVec3::new(next(), next(), 0.2 * next()));
            if k % 4 == 0 {
                // across the line above vertex c, in the direction of its bisector
                let out = ((tri.c - tri.a).normalize() + (tri.c - tri.b).normalize()).normalize();
                let above = tri.c + DVec3::new(0.0, 0.0, 0.05 + 0.1 * (next() + 0.5));
                (a, b) = (
                    above - 0.3 * out.cross(DVec3::Z),
                    above + 0.3 * out.cross(DVec3::Z),
                );
            }
            let full = closest_segment_triangle_away_from_ends(a, b, &tri);
            assert_eq!(Some(full), every_edge(a, b, &tri, ALL_EDGES, |_| true).0);
            // some edges, some parameters (all, or strictly inside as a beam's interior)
            let edges = 1 + (k % 7) as u8;
            let margin = if k % 3 == 0 { -1.0 } else { 0.02 };
            let accept = |t: f64| t > margin && t < 1.0 - margin;
            let (reference, least) = every_edge(a, b, &tri, edges, accept);
            let unbounded =
                closest_segment_triangle_edges_within(a, b, &tri, f64::INFINITY, edges, accept);
            assert_eq!(unbounded.0, reference, "unbounded, edges {edges:03b}");
            let distance = reference.map_or(least, |r| r.distance);
            let bound = distance * (0.5 + 1.5 * (next() + 0.5));
            let (found, lower) =
                closest_segment_triangle_edges_within(a, b, &tri, bound, edges, accept);
            assert!(lower <= least * (1.0 + 1e-12), "{lower} > {least}");
            match reference {
                Some(r) if r.distance <= bound => {
                    within += 1;
                    assert_eq!(found, reference, "bound {bound}, edges {edges:03b}");
                }
                _ => {
                    beyond += 1;
                    assert!(found.is_none_or(|c| c.distance > bound), "{found:?}");
                }
            }
        }
        assert!(
            within > 5_000 && beyond > 5_000,
            "{within} within, {beyond} beyond"
        );
    }

    /// Brute force over sampled segment points agrees (the minimum over samples can only
    /// be larger than the true minimum, and close to it).
    #[test]
    fn agrees_with_sampling() {
        let tri = Triangle::new(
            DVec3::new(0.1, -0.2, 0.0),
            DVec3::new(1.0, 0.3, 0.2),
            DVec3::new(-0.1, 0.9, -0.1),
        );
        let (a, b) = (DVec3::new(-0.5, 0.2, 0.4), DVec3::new(1.2, 0.6, -0.05));
        let c = closest_segment_triangle(a, b, &tri);
        let sampled = (0..=10_000)
            .map(|i| {
                let p = a + (b - a) * (i as f64 / 10_000.0);
                (tri.project_local_point(p, false).point - p).length()
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            c.distance <= sampled + 1e-12 && sampled - c.distance < 1e-4,
            "{} vs {}",
            c.distance,
            sampled
        );
    }
}
