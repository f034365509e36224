//! Planar elastica benchmarks: cantilever under a dead tip load, a cantilever
//! rolled up by an end moment, and the small-load limit under a distributed load.
//! Near-inextensible rod (EA = 1e9 EI/L²), so the exact solutions are those of
//! the inextensible elastica.

use std::f64::consts::PI;

use nalgebra::Vector3;
use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};

const L: f64 = 1.0;
const EI: f64 = 2.0;

fn straight_cantilever(segments: usize) -> ShootingSolver {
    let stiffness = Stiffness::new(1e9 * EI / (L * L), EI, 0.7 * EI).unwrap();
    let nodes = (0..=segments)
        .map(|i| Vector3::new(L * i as f64 / segments as f64, 0.0, 0.0))
        .collect();
    let rod = Rod::new(nodes, stiffness).unwrap();
    ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap()
}

/// Mattiasson (1981) / Bisshopp–Drucker: tip deflection w/L and axial shortening
/// −u/L of a cantilever under a dead tip load normal to the axis, λ = PL²/EI.
#[test]
fn cantilever_tip_load_matches_elastica() {
    let solver = straight_cantilever(1);
    let cases = [
        (1.0, 0.301721, 0.056433),
        (2.0, 0.493457, 0.160642),
        (5.0, 0.713792, 0.387628),
        (10.0, 0.810609, 0.554996),
    ];
    let targets: Vec<EndCondition> = cases
        .iter()
        .map(|&(lambda, _, _)| {
            EndCondition::loaded(
                Vector3::new(0.0, lambda * EI / (L * L), 0.0),
                Vector3::zeros(),
            )
        })
        .collect();
    let start = std::time::Instant::now();
    let solutions = solver.solve_path(&targets).unwrap();
    eprintln!("cantilever path (4 targets): {:?}", start.elapsed());
    for (solution, &(lambda, w, u)) in solutions.iter().zip(&cases) {
        let tip = solution.end_state().position;
        let dw = tip.y / L - w;
        let du = (L - tip.x) / L - u;
        eprintln!("λ = {lambda}: error w/L {dw:.2e}, −u/L {du:.2e}");
        assert!(dw.abs() < 2e-6, "λ = {lambda}: w/L off by {dw:e}");
        assert!(du.abs() < 2e-6, "λ = {lambda}: −u/L off by {du:e}");
        assert!(tip.z.abs() < 1e-12);
    }
}

/// End moment M = πEI/L bends the rod into a half circle of radius L/π; M = 2πEI/L
/// closes it into a full circle.
#[test]
fn end_moment_rolls_rod_into_circle() {
    let solver = straight_cantilever(4);
    let half = EndCondition::loaded(Vector3::zeros(), Vector3::new(0.0, 0.0, PI * EI / L));
    let full = EndCondition::loaded(Vector3::zeros(), Vector3::new(0.0, 0.0, 2.0 * PI * EI / L));
    let start = std::time::Instant::now();
    let solutions = solver.solve_path(&[half, full]).unwrap();
    eprintln!("roll-up path: {:?}", start.elapsed());

    let tip = solutions[0].end_state().position;
    let error = (tip - Vector3::new(0.0, 2.0 * L / PI, 0.0)).norm() / L;
    eprintln!("half circle tip error {error:.2e} L");
    assert!(error < 1e-8, "half circle tip error {error:e}");

    let closed = solutions[1].end_state();
    let gap = closed.position.norm() / L;
    eprintln!("full circle gap {gap:.2e} L");
    assert!(gap < 1e-6, "full circle gap {gap:e}");
    // The tangent has turned by 2π: the end frame equals the base frame.
    let turn = (closed.frame.matrix() - nalgebra::Matrix3::identity()).norm();
    assert!(turn < 1e-8, "end frame off by {turn:e} rad");
    // Pure bending: the mid-point lies diametrically opposite the base.
    let mid = solutions[1].sample(&[0.5 * L]).unwrap()[0].position;
    assert!((mid - Vector3::new(0.0, L / PI, 0.0)).norm() < 1e-8 * L);
}

/// A small distributed load q (q L³/EI = 1e-3) reproduces the linear cantilever
/// tip deflection qL⁴/(8EI) to the size of the geometric nonlinearity.
#[test]
fn small_distributed_load_matches_linear_beam_theory() {
    let q = 1e-3 * EI / L.powi(3);
    let stiffness = Stiffness::new(1e9 * EI / (L * L), EI, 0.7 * EI).unwrap();
    let rod = Rod::new(vec![Vector3::zeros(), Vector3::new(L, 0.0, 0.0)], stiffness)
        .unwrap()
        .with_distributed_load(Vector3::new(0.0, 0.0, -q))
        .unwrap();
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let free = EndCondition::loaded(Vector3::zeros(), Vector3::zeros());
    let solution = &solver.solve_path(&[free]).unwrap()[0];
    let w = solution.end_state().position.z;
    let linear = -q * L.powi(4) / (8.0 * EI);
    let relative = (w - linear).abs() / linear.abs();
    eprintln!("distributed load: relative deviation from linear theory {relative:.2e}");
    assert!(relative < 1e-5, "tip deflection {w} vs linear {linear}");
    // Base reaction carries the whole weight: −n(0) + n(L) + qL = 0 with n(L) = 0.
    let reaction = solution.base_reaction();
    assert!((reaction.force - Vector3::new(0.0, 0.0, q * L)).norm() < 1e-12 * q * L);
    assert!((reaction.moment.y - (-q * L * L / 2.0)).abs() < 1e-6 * q * L * L);
}
