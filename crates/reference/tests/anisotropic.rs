//! A non-round section (EI₂ ≠ EI₃): each bending plane follows its own stiffness. Small
//! tip loads along d2 and d3 give the linear cantilever deflection PL³/3EI with the
//! stiffness about the other axis; a large load along d2 gives the planar elastica with
//! EI₃ and stays in its plane although the other axis is ten times stiffer.

use nalgebra::Vector3;
use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};

const L: f64 = 1.0;
/// Bending stiffness about d2 (resists deflection along d3) and about d3 (along d2).
const EI2: f64 = 0.2;
const EI3: f64 = 2.0;

fn ribbon() -> ShootingSolver {
    let stiffness = Stiffness::new(1e9 * EI3 / (L * L), EI2, 0.1)
        .and_then(|s| s.with_bending(EI2, EI3))
        .unwrap();
    let nodes = vec![Vector3::zeros(), Vector3::new(L, 0.0, 0.0)];
    let rod = Rod::new(nodes, stiffness).unwrap();
    let base = rod.rest_base_pose();
    ShootingSolver::new(rod, base).unwrap()
}

/// The rest base frame's d2 and d3 axes in world coordinates.
fn axes(solver: &ShootingSolver) -> (Vector3<f64>, Vector3<f64>) {
    let frame = solver.base().frame;
    (frame * Vector3::y(), frame * Vector3::z())
}

#[test]
fn small_loads_bend_each_axis_with_its_own_stiffness() {
    let solver = ribbon();
    let (d2, d3) = axes(&solver);
    for (direction, ei) in [(d2, EI3), (d3, EI2)] {
        let p = 1e-5 * ei / (L * L);
        let solution = &solver
            .solve_path(&[EndCondition::loaded(direction * p, Vector3::zeros())])
            .unwrap()[0];
        let tip = solution.end_state().position.dot(&direction);
        let exact = p * L.powi(3) / (3.0 * ei);
        assert!(
            (tip / exact - 1.0).abs() < 1e-4,
            "deflection {tip:e} vs PL³/3EI = {exact:e}"
        );
    }
}

#[test]
fn large_load_in_one_plane_follows_that_planes_elastica() {
    let solver = ribbon();
    let (d2, d3) = axes(&solver);
    // λ = PL²/EI₃ = 2: w/L = 0.493457, −u/L = 0.160642 (Mattiasson 1981)
    let p = 2.0 * EI3 / (L * L);
    let solution = &solver
        .solve_path(&[EndCondition::loaded(d2 * p, Vector3::zeros())])
        .unwrap()[0];
    let tip = solution.end_state().position;
    assert!(
        (tip.dot(&d2) / L - 0.493457).abs() < 2e-6,
        "w/L {}",
        tip.dot(&d2)
    );
    assert!(
        (1.0 - tip.x / L - 0.160642).abs() < 2e-6,
        "−u/L {}",
        1.0 - tip.x
    );
    assert!(
        tip.dot(&d3).abs() < 1e-10,
        "out of plane by {}",
        tip.dot(&d3)
    );
}
