//! Clamped–clamped Euler buckling of a rod with a tiny kink imperfection
//! (middle rest node raised by 1e-4 L), end shortened step by step to 2 % of L.

use std::f64::consts::PI;

use nalgebra::Vector3;
use pliant_reference::elastica::clamped_column;
use pliant_reference::{EndCondition, Rod, ShootingSolver, Stiffness};

const EI: f64 = 1.5;

/// Perfect inextensible elastica, clamped–clamped: for end shortening Δ/L the axial load
/// over the Euler load ([`clamped_column`], ends (1 − Δ/L) L apart).
fn elastica_load_ratio(shortening: f64) -> f64 {
    clamped_column(1.0 - shortening).load_ratio
}

#[test]
fn clamped_clamped_buckling_follows_the_elastica() {
    let nodes = vec![
        Vector3::zeros(),
        Vector3::new(0.5, 0.0, 1e-4),
        Vector3::new(1.0, 0.0, 0.0),
    ];
    let stiffness = Stiffness::new(1e9 * EI, EI, 0.8 * EI).unwrap();
    let rod = Rod::new(nodes, stiffness).unwrap();
    let l = rod.length();
    let solver = ShootingSolver::new(rod.clone(), rod.rest_base_pose()).unwrap();
    let rest_end = solver.unloaded_end_pose();
    // Finely near the bifurcation, then in steps of 0.25 % of L.
    let mut shortenings = vec![1e-6, 1e-5, 1e-4, 1e-3];
    shortenings.extend((1..=8).map(|i| 0.0025 * i as f64));
    let targets: Vec<EndCondition> = shortenings
        .iter()
        .map(|d| EndCondition::clamped(rest_end.translated(&Vector3::new(-d * l, 0.0, 0.0))))
        .collect();
    let start = std::time::Instant::now();
    let solutions = solver.solve_path(&targets).unwrap();
    eprintln!(
        "buckling path ({} targets): {:?}",
        targets.len(),
        start.elapsed()
    );

    let p_cr = 4.0 * PI * PI * EI / (l * l);
    let mut previous_load = 0.0;
    let mut previous_deflection = 0.0;
    for (d, solution) in shortenings.iter().zip(&solutions) {
        let load = -solution.end_reaction().force.x;
        let ratio = load / p_cr;
        let deflection = solution.sample(&[0.5 * l]).unwrap()[0].position.z;
        let elastica = elastica_load_ratio(*d);
        eprintln!(
            "Δ/L = {d:.4}: P/P_cr = {ratio:.6} (perfect elastica {elastica:.6}), \
             mid-span w/L = {:.5}",
            deflection / l
        );
        assert!(load > previous_load, "axial load must grow with shortening");
        assert!(
            deflection > previous_deflection,
            "deflection grows along +z"
        );
        if *d <= 2e-3 {
            assert!(ratio < 1.0, "approach from below: P/P_cr = {ratio}");
        }
        if *d >= 0.005 - 1e-12 {
            assert!((ratio - 1.0).abs() < 0.01, "P/P_cr = {ratio} at Δ/L = {d}");
            // The imperfect path lies just below the perfect post-buckling path.
            assert!(ratio < elastica && elastica - ratio < 2.5e-3);
        }
        // Lateral forces and moments stay in the x–z plane.
        assert!(solution.end_reaction().force.y.abs() < 1e-9 * load);
        previous_load = load;
        previous_deflection = deflection;
    }
}
