//! The rigid parts as the report's scene pictures draw them (SPEC V7): in each view of
//! [`View`], a part's silhouette is the convex hull of its vertices projected onto the
//! picture plane (Andrew's monotone chain, Inf. Proc. Letters 9, 1979), drawn far to near
//! (painter's order by the depth of its farthest vertex, so that a floor under
//! everything is drawn first). Presentation data: the report writer makes it once per
//! report from the model; the live path (a server's snapshots, the per-step summary)
//! never does — a hull of a million vertices is a sort, far too slow for every snapshot.

use glam::DVec3;
use pliant_core::contact::{RigidEnvironment, RigidPart};
use pliant_core::kinematics::Pose;
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

/// The outlines of every part of `environment`, where the scene placed it.
pub fn part_outlines(environment: &RigidEnvironment) -> Vec<PartOutline> {
    COMPUTED.with(|c| c.set(c.get() + 1));
    environment
        .parts
        .iter()
        .map(|part| outline_at(part, &Pose::IDENTITY))
        .collect()
}

/// The outlines of every part of `environment` at its pose in `poses` (one per part):
/// those of `at_rest` for a part at the identity, the others made anew.
pub fn posed_outlines(
    environment: &RigidEnvironment,
    at_rest: &[PartOutline],
    poses: &[Pose],
) -> Vec<PartOutline> {
    environment
        .parts
        .iter()
        .zip(at_rest)
        .enumerate()
        .map(|(k, (part, rest))| match poses.get(k) {
            Some(pose) if *pose != Pose::IDENTITY => outline_at(part, pose),
            _ => rest.clone(),
        })
        .collect()
}

/// The outline of `part` moved by `pose`.
fn outline_at(part: &RigidPart, pose: &Pose) -> PartOutline {
    let vertices: Vec<DVec3> = part
        .mesh
        .vertices()
        .iter()
        .map(|v| pose.apply(DVec3::new(v.x, v.y, v.z)))
        .collect();
    let mut out = PartOutline {
        name: part.name.clone(),
        ..Default::default()
    };
    for (k, view) in View::all().iter().enumerate() {
        out.hulls[k] = convex_hull(vertices.iter().map(|&v| view.project(v)).collect());
        out.depth[k] = vertices
            .iter()
            .map(|v| v.dot(view.towards))
            .fold(f64::INFINITY, f64::min);
    }
    out
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

#[cfg(test)]
mod posed_tests {
    use super::*;
    use glam::DQuat;
    use pliant_core::spec::RigidPartSpec;

    /// A flat door 1 × 0.5 m in the plane y = 0 (x from 0 to 1), hinged about z.
    fn door() -> RigidEnvironment {
        let vertices = vec![
            glam::DVec3::new(0.0, 0.0, 0.0),
            glam::DVec3::new(1.0, 0.0, 0.0),
            glam::DVec3::new(1.0, 0.0, 0.5),
            glam::DVec3::new(0.0, 0.0, 0.5),
        ];
        RigidEnvironment::build(&[RigidPartSpec {
            name: "door".into(),
            vertices,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            friction_static: 0.5,
            friction_sliding: 0.4,
            motion: None,
            parent: None,
            movable: true,
        }])
        .unwrap()
    }

    #[test]
    fn a_turned_part_is_drawn_where_it_was() {
        let env = door();
        let rest = part_outlines(&env);
        // seen from above, the door closed is the segment x ∈ [0, 1] on y = 0
        let above = |o: &PartOutline| {
            o.hulls[0].iter().fold([f64::NEG_INFINITY; 2], |m, p| {
                [m[0].max(p[0]), m[1].max(p[1])]
            })
        };
        assert!((above(&rest[0])[0] - 1.0).abs() < 1e-12 && above(&rest[0])[1].abs() < 1e-12);
        // opened 90° about z: along y
        let open = Pose {
            rotation: DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2),
            translation: glam::DVec3::ZERO,
        };
        let posed = posed_outlines(&env, &rest, &[open]);
        let m = above(&posed[0]);
        assert!(m[0].abs() < 1e-12 && (m[1] - 1.0).abs() < 1e-12, "{m:?}");
        // at the identity, the outline at rest
        assert_eq!(posed_outlines(&env, &rest, &[Pose::IDENTITY]), rest);
    }
}
