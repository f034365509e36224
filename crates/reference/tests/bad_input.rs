//! Invalid input is rejected with a descriptive error, never a panic.

use nalgebra::{Matrix3, Rotation3, Vector3};
use pliant_reference::{
    EndCondition, Pose, ReferenceError, Rod, ShootingSolver, SolverOptions, Stiffness, Unknowns,
};

fn stiffness() -> Stiffness {
    Stiffness::new(100.0, 1.0, 1.0).unwrap()
}

fn straight() -> Vec<Vector3<f64>> {
    vec![Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0)]
}

fn expect_message<T: std::fmt::Debug>(result: Result<T, ReferenceError>, needle: &str) {
    let error = result.expect_err("invalid input must be rejected");
    let message = error.to_string();
    assert!(
        message.contains(needle),
        "message {message:?} lacks {needle:?}"
    );
}

#[test]
fn too_few_rest_nodes() {
    expect_message(Rod::new(vec![], stiffness()), "at least 2 rest nodes");
    expect_message(
        Rod::new(vec![Vector3::zeros()], stiffness()),
        "at least 2 rest nodes",
    );
}

#[test]
fn zero_length_segment() {
    let nodes = vec![Vector3::zeros(), Vector3::x(), Vector3::x()];
    expect_message(
        Rod::new(nodes, stiffness()),
        "segment 1 (nodes 1 and 2) has zero length",
    );
}

#[test]
fn reversed_segments() {
    let nodes = vec![Vector3::zeros(), Vector3::x(), Vector3::zeros()];
    expect_message(Rod::new(nodes, stiffness()), "opposite directions");
}

#[test]
fn non_finite_rest_node() {
    let nodes = vec![Vector3::zeros(), Vector3::new(f64::NAN, 0.0, 0.0)];
    expect_message(Rod::new(nodes, stiffness()), "rest node 1 has non-finite");
}

#[test]
fn base_frame_not_along_first_segment() {
    let frame = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.1);
    expect_message(
        Rod::with_base_frame(straight(), frame, stiffness()),
        "not along the first segment",
    );
}

#[test]
fn non_positive_or_nan_stiffness() {
    expect_message(
        Stiffness::new(0.0, 1.0, 1.0),
        "EA_t must be finite and positive",
    );
    expect_message(
        Stiffness::bimodular(1.0, -1.0, 1.0, 1.0),
        "EA_c must be finite and positive",
    );
    expect_message(
        Stiffness::new(1.0, f64::NAN, 1.0),
        "EI must be finite and positive",
    );
    expect_message(
        Stiffness::new(1.0, 1.0, f64::INFINITY),
        "GJ must be finite and positive",
    );
    expect_message(
        Stiffness::circular_tube(1e6, 0.3, 0.03, 0.04),
        "0 <= d_i < d_a",
    );
    expect_message(
        Stiffness::circular_tube(1e6, 0.5, 0.04, 0.03),
        "Poisson ratio",
    );
}

#[test]
fn non_finite_loads_and_poses() {
    let rod = Rod::new(straight(), stiffness()).unwrap();
    expect_message(
        rod.clone()
            .with_distributed_load(Vector3::new(0.0, f64::NAN, 0.0)),
        "distributed load",
    );
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let nan_load = EndCondition::loaded(Vector3::new(f64::NAN, 0.0, 0.0), Vector3::zeros());
    expect_message(solver.solve(&nan_load, &Unknowns::zero()), "end load");
    expect_message(solver.solve_path(&[nan_load]), "end load");
    let bad_pose = rod
        .rest_end_pose()
        .translated(&Vector3::new(0.0, 0.0, f64::INFINITY));
    expect_message(
        solver.solve_path(&[EndCondition::clamped(bad_pose)]),
        "end pose",
    );
    let skewed = Pose::new(
        Vector3::zeros(),
        Rotation3::from_matrix_unchecked(Matrix3::identity() * 2.0),
    );
    expect_message(
        ShootingSolver::new(rod.clone(), skewed),
        "base frame is not a rotation",
    );
    let guess = Unknowns {
        force: Vector3::new(f64::NAN, 0.0, 0.0),
        moment: Vector3::zeros(),
    };
    let free = EndCondition::loaded(Vector3::zeros(), Vector3::zeros());
    expect_message(solver.solve(&free, &guess), "initial guess");
}

#[test]
fn bad_options_and_sample_points() {
    let rod = Rod::new(straight(), stiffness()).unwrap();
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let options = SolverOptions {
        tolerance: -1.0,
        ..SolverOptions::default()
    };
    expect_message(solver.clone().with_options(options), "tolerance");
    let free = EndCondition::loaded(Vector3::zeros(), Vector3::zeros());
    let solution = solver.solve(&free, &Unknowns::zero()).unwrap();
    expect_message(solution.sample(&[0.5, 1.5]), "invalid arc length 1.5");
    expect_message(solution.sample(&[f64::NAN]), "invalid arc length NaN");
}

#[test]
fn unreachable_target_reports_failure() {
    // A perfectly straight rod pushed straight back past its own base stays
    // straight by symmetry and would need a stretch ν ≤ 0: no solution on the path.
    let rod = Rod::new(straight(), stiffness()).unwrap();
    let options = SolverOptions {
        max_step_halvings: 4,
        ..SolverOptions::default()
    };
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose())
        .unwrap()
        .with_options(options)
        .unwrap();
    let end = EndCondition::clamped(
        rod.rest_end_pose()
            .translated(&Vector3::new(-1.5, 0.0, 0.0)),
    );
    let error = solver.solve_path(&[end]).expect_err("must fail");
    assert!(
        matches!(error, ReferenceError::ContinuationFailed { target: 0, .. }),
        "{error}"
    );
}
