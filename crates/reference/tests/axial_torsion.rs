//! Clamped–clamped rods under pure stretch, pure compression (bimodular axial
//! stiffness) and pure torsion, where the exact solutions are uniform states.

use nalgebra::{Rotation3, Vector3};
use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};

const L: f64 = 0.8;
const EI: f64 = 3.0;
const GJ: f64 = 2.2;

fn clamped_rod(stiffness: Stiffness) -> ShootingSolver {
    // Three unequal collinear segments along +x: exercises the segment restarts.
    let nodes = vec![
        Vector3::zeros(),
        Vector3::new(0.2 * L, 0.0, 0.0),
        Vector3::new(0.7 * L, 0.0, 0.0),
        Vector3::new(L, 0.0, 0.0),
    ];
    let rod = Rod::new(nodes, stiffness).unwrap();
    ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap()
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn stretch_gives_tension_stiffness_force() {
    let ea_t = 1e4 * EI / (L * L);
    let ea_c = 1e3 * EI / (L * L);
    let solver = clamped_rod(Stiffness::bimodular(ea_t, ea_c, EI, GJ).unwrap());
    let dl = 0.1 * L;
    let end = EndCondition::clamped(
        solver
            .rod()
            .rest_end_pose()
            .translated(&Vector3::new(dl, 0.0, 0.0)),
    );
    let solution = &solver.solve_path(&[end]).unwrap()[0];
    let expected = ea_t * dl / L;
    let force = solution.end_reaction().force;
    let error = relative(force.x, expected);
    eprintln!("stretch: relative force error {error:.2e}");
    assert!(error < 1e-9, "end force {force:?}, expected {expected}");
    assert!(force.yzx().xy().norm() < 1e-9 * expected);
    assert!((solution.base_reaction().force.x + expected).abs() < 1e-9 * expected);
    assert!(solution.end_reaction().moment.norm() < 1e-9 * expected * L);
}

#[test]
fn compression_gives_compression_stiffness_force() {
    let ea_t = 1e4 * EI / (L * L);
    // N = 0.01 EA_c = 10 EI/L² stays below the Euler load 4π² EI/L² ≈ 39.5 EI/L².
    let ea_c = 1e3 * EI / (L * L);
    let solver = clamped_rod(Stiffness::bimodular(ea_t, ea_c, EI, GJ).unwrap());
    let dl = -0.01 * L;
    let end = EndCondition::clamped(
        solver
            .rod()
            .rest_end_pose()
            .translated(&Vector3::new(dl, 0.0, 0.0)),
    );
    let solution = &solver.solve_path(&[end]).unwrap()[0];
    let expected = ea_c * dl / L;
    let force = solution.end_reaction().force;
    let error = relative(force.x, expected);
    eprintln!("compression: relative force error {error:.2e}");
    assert!(error < 1e-9, "end force {force:?}, expected {expected}");
}

#[test]
fn twist_gives_torsional_stiffness_torque() {
    let solver = clamped_rod(Stiffness::new(1e4 * EI / (L * L), EI, GJ).unwrap());
    let phi = 0.5;
    let rest = solver.rod().rest_end_pose();
    let mut pose = rest;
    pose.frame = Rotation3::from_axis_angle(&Vector3::x_axis(), phi) * rest.frame;
    let solution = &solver.solve_path(&[EndCondition::clamped(pose)]).unwrap()[0];
    let expected = GJ * phi / L;
    let torque = solution.end_reaction().moment;
    let error = relative(torque.x, expected);
    eprintln!("torsion: relative torque error {error:.2e}");
    assert!(error < 1e-9, "end torque {torque:?}, expected {expected}");
    assert!((solution.base_reaction().moment.x + expected).abs() < 1e-9 * expected);
    // Uniform twist: the mid-span frame is rotated by φ/2 about the axis.
    let mid = solution.sample(&[0.5 * L]).unwrap()[0];
    let expected_mid = Rotation3::from_axis_angle(&Vector3::x_axis(), 0.5 * phi);
    assert!((mid.frame.matrix() - expected_mid.matrix()).norm() < 1e-10);
}
