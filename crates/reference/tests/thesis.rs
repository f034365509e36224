//! The dissertation's validation hose (SPEC §7): L = 0.5 m in 20 segments of 25 mm
//! along +x, 1 mm imperfection in +z at the middle node (0.5 mm at its
//! neighbours), tube d_a = 40 mm, d_i = 30 mm, E = 12.36 MPa, ν = 0.49. The end is
//! moved by (−120, +120, +120) mm with its frame held at the rest frame.

use nalgebra::Vector3;
use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};

fn thesis_rod() -> Rod {
    let nodes = (0..=20)
        .map(|i| {
            let z = match i {
                10 => 1e-3,
                9 | 11 => 0.5e-3,
                _ => 0.0,
            };
            Vector3::new(0.025 * i as f64, 0.0, z)
        })
        .collect();
    let stiffness = Stiffness::circular_tube(12.36e6, 0.49, 0.040, 0.030).unwrap();
    Rod::new(nodes, stiffness).unwrap()
}

#[test]
fn thesis_case_moved_end_is_in_equilibrium() {
    let rod = thesis_rod();
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let rest_end = rod.rest_end_pose();
    let displacement = Vector3::new(-0.120, 0.120, 0.120);
    let steps = 24;
    let targets: Vec<EndCondition> = (1..=steps)
        .map(|i| {
            let t = i as f64 / steps as f64;
            EndCondition::clamped(rest_end.translated(&(displacement * t)))
        })
        .collect();
    let start = std::time::Instant::now();
    let solutions = solver.solve_path(&targets).unwrap();
    eprintln!("thesis path ({steps} targets): {:?}", start.elapsed());

    for (i, solution) in solutions.iter().enumerate() {
        let base = solution.base_reaction();
        let end = solution.end_reaction();
        let scale = end.force.norm();
        // Force balance (no distributed load): base and end reactions cancel.
        let force_balance = (base.force + end.force).norm() / scale;
        // Moment balance about the base point.
        let arm = solution.end_state().position - solution.base_state().position;
        let moment_scale = end.moment.norm() + arm.norm() * scale;
        let moment_balance =
            (base.moment + end.moment + arm.cross(&end.force)).norm() / moment_scale;
        assert!(
            force_balance < 1e-8,
            "step {i}: force balance {force_balance:e}"
        );
        assert!(
            moment_balance < 1e-8,
            "step {i}: moment balance {moment_balance:e}"
        );
        // The end sits where it was sent, with its rest frame.
        let pose = match solution.end_condition() {
            EndCondition::Clamped(pose) => *pose,
            EndCondition::Loaded { .. } => unreachable!("clamped targets"),
        };
        assert!((solution.end_state().position - pose.position).norm() < 1e-10);
        assert!((solution.end_state().frame.matrix() - pose.frame.matrix()).norm() < 1e-10);
    }
    let last = solutions.last().unwrap();
    let nodes = last.node_states().unwrap();
    let force = last.end_reaction().force;
    eprintln!(
        "final end force {force:?} N, moment {:?} N m",
        last.end_reaction().moment
    );
    eprintln!("final mid-node position {:?} m", nodes[10].position);
    // The imperfection makes the hose bow out towards +z.
    assert!(nodes[10].position.z > 0.06);
}
