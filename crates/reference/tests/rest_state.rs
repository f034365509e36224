//! The unloaded rest state of a bent, non-planar polyline is reproduced exactly
//! (checks the concentrated kink convention), and a moved base carries the rest
//! shape along rigidly.

use nalgebra::{Rotation3, Vector3};
use pliant_reference::{EndCondition, Pose, Rod, ShootingSolver, Stiffness, Unknowns};

fn bent_rod() -> Rod {
    let nodes = vec![
        Vector3::new(0.1, 0.2, 0.0),
        Vector3::new(0.3, 0.25, 0.05),
        Vector3::new(0.45, 0.4, 0.1),
        Vector3::new(0.5, 0.6, 0.3),
        Vector3::new(0.4, 0.7, 0.45),
    ];
    Rod::new(nodes, Stiffness::new(50.0, 1.0, 0.7).unwrap()).unwrap()
}

#[test]
fn rest_state_reproduces_polyline_and_frames() {
    let rod = bent_rod();
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let free = EndCondition::loaded(Vector3::zeros(), Vector3::zeros());
    let solution = solver.solve(&free, &Unknowns::zero()).unwrap();
    assert_eq!(solution.iterations(), 0);
    let states = solution.node_states().unwrap();
    for (k, state) in states.iter().enumerate() {
        let error = (state.position - rod.rest_nodes()[k]).norm();
        // Round-off of the ~1000 summed RK4 increments only.
        assert!(error < 1e-12, "node {k}: position error {error:e}");
        // Frame after the kink at interior nodes, last segment's frame at the end.
        let segment = k.min(rod.segment_count() - 1);
        let frame = rod.rest_frame(segment).unwrap();
        assert!((state.frame.matrix() - frame.matrix()).norm() < 1e-13);
        let d1: Vector3<f64> = frame.matrix().column(0).into();
        if k < rod.segment_count() {
            let tangent = (rod.rest_nodes()[k + 1] - rod.rest_nodes()[k]).normalize();
            assert!((d1 - tangent).norm() < 1e-14);
        }
    }
}

#[test]
fn moved_base_carries_rest_shape_rigidly() {
    let rod = bent_rod();
    let rotation = Rotation3::new(Vector3::new(0.3, -1.2, 2.0));
    let translation = Vector3::new(1.0, -2.0, 0.5);
    let base = rod.rest_base_pose().transformed(&rotation, &translation);
    let solver = ShootingSolver::new(rod.clone(), base).unwrap();
    let end = EndCondition::clamped(solver.unloaded_end_pose());
    let solution = &solver.solve_path(&[end]).unwrap()[0];
    assert!(solution.base_reaction().force.norm() < 1e-10);
    assert!(solution.base_reaction().moment.norm() < 1e-10);
    let expected = rod.rest_end_pose().transformed(&rotation, &translation);
    let reached: Pose = Pose::new(solution.end_state().position, solution.end_state().frame);
    assert!((reached.position - expected.position).norm() < 1e-12);
    assert!((reached.frame.matrix() - expected.frame.matrix()).norm() < 1e-13);
}

#[test]
fn continuing_from_a_solution_of_another_solver_is_rejected() {
    let rod = bent_rod();
    let a = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let moved = rod
        .rest_base_pose()
        .translated(&Vector3::new(0.0, 0.0, 1.0));
    let b = ShootingSolver::new(rod, moved).unwrap();
    let free = EndCondition::loaded(Vector3::zeros(), Vector3::zeros());
    let solution = a.solve(&free, &Unknowns::zero()).unwrap();
    assert!(b.solve_path_from(&solution, &[free]).is_err());
    assert!(a.solve_path_from(&solution, &[free]).is_ok());
}
