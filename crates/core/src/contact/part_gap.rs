//! The gap between a hose and a rigid part: the smallest distance from the hose's surface
//! to the part's surface, d(x_i, mesh) − r_i over the hose's nodes (centre line points x_i,
//! outer radius r_i; negative where the hose presses into the part), for the clearance a
//! range-of-motion study reports. A moving part's mesh stays in its reference placement:
//! the nodes are mapped into it by the part's pose (as contact with moving parts does).
//!
//! The search is the mesh's bounding-volume tree queried with a shrinking bound (the best
//! gap so far plus the node's radius, parry's `project_local_point_with_max_dist`): a node
//! farther than the bound from the part's bounding box costs one box test, and the tree
//! prunes every subtree farther than the bound, so no triangle far from the hose is
//! visited. Between nodes the centre line may pass nearer a part by at most the sagitta
//! of a beam, l²κ/8 (l the beam length, κ the curvature).

use super::environment::RigidEnvironment;
use crate::kinematics::Pose;
use glam::DVec3;
use parry3d_f64::query::PointQuery;

/// The gap between the hose whose nodes are at `x` (outer radii `radius`) and part `part`
/// of `env`, whose pose is `pose` (`None`: at its reference placement): (gap \[m\], index
/// into `x` of the nearest node). `(∞, 0)` for no nodes or no such part.
pub fn hose_part_gap(
    env: &RigidEnvironment,
    part: usize,
    pose: Option<&Pose>,
    x: &[DVec3],
    radius: &[f64],
) -> (f64, usize) {
    let Some(p) = env.parts.get(part) else {
        return (f64::INFINITY, 0);
    };
    let bounds = p.mesh.local_aabb();
    let mut best = (f64::INFINITY, 0);
    for (i, (&xi, &ri)) in x.iter().zip(radius).enumerate() {
        let local = pose.map_or(xi, |q| q.inverse_apply(xi));
        let reach = best.0 + ri;
        if bounds.distance_to_local_point(local, true) >= reach {
            continue;
        }
        let Some(hit) = p
            .mesh
            .project_local_point_with_max_dist(local, false, reach)
        else {
            continue;
        };
        let gap = (hit.point - local).length() - ri;
        if gap < best.0 {
            best = (gap, i);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::environment::test_plate;
    use glam::DQuat;

    #[test]
    fn the_gap_is_the_nearest_nodes_distance_less_its_radius_in_the_parts_pose() {
        let env = test_plate(); // z = 0, |x|, |y| ≤ 0.5
        let x = [
            DVec3::new(0.0, 0.0, 0.30),
            DVec3::new(0.2, 0.1, 0.05), // the nearest: 0.05 − 0.01
            DVec3::new(0.9, 0.0, 0.02), // beyond the edge: √(0.4² + 0.02²) − 0.01
        ];
        let r = [0.01; 3];
        let (gap, at) = hose_part_gap(&env, 0, None, &x, &r);
        assert!((gap - 0.04).abs() < 1e-12, "{gap}");
        assert_eq!(at, 1);
        // the plate lifted by 0.03 and turned about z: the same node is 0.02 above it
        let pose = Pose {
            rotation: DQuat::from_rotation_z(0.4),
            translation: DVec3::new(0.0, 0.0, 0.03),
        };
        let (gap, at) = hose_part_gap(&env, 0, Some(&pose), &x, &r);
        assert!((gap - 0.01).abs() < 1e-12, "{gap}");
        assert_eq!(at, 1);
        // a node pressed 4 mm into the plate's plane: a negative gap
        let (gap, _) = hose_part_gap(&env, 0, None, &[DVec3::new(0.0, 0.0, 0.006)], &[0.01]);
        assert!((gap + 0.004).abs() < 1e-12, "{gap}");
        assert_eq!(hose_part_gap(&env, 3, None, &x, &r).0, f64::INFINITY);
    }
}
