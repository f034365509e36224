//! The rigid parts as the report's scene pictures draw them (SPEC V7): in each view of
//! [`View`], a part's silhouette is the convex hull of its vertices projected onto the
//! picture plane (Andrew's monotone chain, Inf. Proc. Letters 9, 1979), drawn far to near
//! (painter's order by the depth of its farthest vertex, so that a floor under
//! everything is drawn first). Presentation data: the report writer makes it once per
//! report from the model; the live path (a server's snapshots, the per-step summary)
//! never does — a hull of a million vertices is a sort, far too slow for every snapshot.

use glam::DVec3;
use pliant_core::contact::RigidEnvironment;
use std::cell::Cell;

thread_local! {
    /// Calls of [`part_outlines`] on this thread.
    static COMPUTED: Cell<u64> = const { Cell::new(0) };
}

/// How many times [`part_outlines`] has run on the calling thread: lets a test check
/// that a path (a snapshot, a report) computes the outlines as often as it should,
/// undisturbed by tests running on other threads.
pub fn computed_on_this_thread() -> u64 {
    COMPUTED.with(Cell::get)
}

/// A direction the scene is drawn from: picture axes `right`, `up` and `towards` the
/// viewer (right-handed, unit).
#[derive(Clone, Copy, Debug)]
pub struct View {
    pub name: &'static str,
    pub right: DVec3,
    pub up: DVec3,
    pub towards: DVec3,
}

impl View {
    /// From above, from the side (−y), and from the front-right above (an isometric-like
    /// view down 35° from the direction (1, −1, 0)).
    pub fn all() -> [View; 3] {
        let towards = DVec3::new(1.0, -1.0, 1.0).normalize();
        let right = DVec3::Z.cross(towards).normalize();
        [
            View {
                name: "from above (x right, y up)",
                right: DVec3::X,
                up: DVec3::Y,
                towards: DVec3::Z,
            },
            View {
                name: "from the side (x right, z up)",
                right: DVec3::X,
                up: DVec3::Z,
                towards: DVec3::NEG_Y,
            },
            View {
                name: "from the front right, above",
                right,
                up: towards.cross(right),
                towards,
            },
        ]
    }

    /// A point's picture coordinates.
    pub fn project(&self, p: DVec3) -> [f64; 2] {
        [p.dot(self.right), p.dot(self.up)]
    }
}

/// One part seen in every view of [`View::all`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PartOutline {
    pub name: String,
    /// The silhouette per view, counter-clockwise.
    pub hulls: [Vec<[f64; 2]>; 3],
    /// Depth of the part's farthest vertex per view (larger: nearer the viewer).
    pub depth: [f64; 3],
}

/// The outlines of every part of `environment`.
pub fn part_outlines(environment: &RigidEnvironment) -> Vec<PartOutline> {
    COMPUTED.with(|c| c.set(c.get() + 1));
    let views = View::all();
    environment
        .parts
        .iter()
        .map(|part| {
            let vertices = part.mesh.vertices();
            let mut out = PartOutline {
                name: part.name.clone(),
                ..Default::default()
            };
            for (k, view) in views.iter().enumerate() {
                let projected: Vec<[f64; 2]> = vertices
                    .iter()
                    .map(|v| view.project(DVec3::new(v.x, v.y, v.z)))
                    .collect();
                out.hulls[k] = convex_hull(projected);
                out.depth[k] = vertices
                    .iter()
                    .map(|v| DVec3::new(v.x, v.y, v.z).dot(view.towards))
                    .fold(f64::INFINITY, f64::min);
            }
            out
        })
        .collect()
}

/// The convex hull of `points`, counter-clockwise, without collinear points.
pub fn convex_hull(mut points: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    points.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * points.len());
    for pass in [false, true] {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &[f64; 2]>> = if pass {
            Box::new(points.iter().rev())
        } else {
            Box::new(points.iter())
        };
        for &p in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop(); // the last point of each chain starts the other
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hull_of_a_square_with_inner_and_edge_points_is_its_corners() {
        let pts = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [0.5, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.5],
            [0.2, 0.7],
            [1.0, 1.0],
        ];
        assert_eq!(
            convex_hull(pts),
            vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        );
    }

    #[test]
    fn views_are_right_handed_and_unit() {
        for v in View::all() {
            assert!(
                (v.right.cross(v.up) - v.towards).length() < 1e-12,
                "{}",
                v.name
            );
            assert!((v.right.length() - 1.0).abs() < 1e-12);
            assert!((v.up.length() - 1.0).abs() < 1e-12);
        }
    }
}
