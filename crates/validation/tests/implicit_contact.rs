//! Regression (the `solvers` case's crossing hoses): two hoses crossing
//! at right angles, clamped at both ends, the upper pressed onto the lower by 2 N at its
//! middle, reach rest under the implicit solver in a few 50 ms steps, each started from
//! rest (the harness's "implicit, damped to rest"). Before the Newton solvers solved the
//! contact coupling exactly (GMRES instead of a fixed-point iteration converging at
//! 1 − 4·10⁻⁴ per sweep), weighted it by 1 + α, and the implicit Newton got its line
//! search and contact step control, every step was halved to 1/512 and rest took
//! thousands of steps; now 21. Step counts, not times: nothing here depends on the
//! machine's speed.

use glam::DVec3;
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver};
use pliant_core::newton::Tolerance;
use pliant_validation::cases::hose_contact::{contact_force_on, crossing_hoses, LOAD, N};

#[test]
fn crossing_hoses_reach_rest_in_a_few_implicit_steps() {
    let (model, mut state) = crossing_hoses().unwrap();
    let f = LOAD;
    // the harness's settings: residual 1e-7 f at rest, Newton to 1e-3 of that
    let (force_tol, moment_tol) = (1e-7 * f, 1e-7 * f * 0.5);
    let options = ImplicitOptions {
        time_step: 0.05,
        alpha: -1.0 / 3.0,
        tolerance: Tolerance::absolute(1e-3 * force_tol, 1e-3 * moment_tol),
        max_halvings: 10,
        ..Default::default()
    };
    let mut solver = ImplicitSolver::new(&model, options).unwrap();
    let mut halved = 0;
    let rest = (1..=60).find(|_| {
        let report = solver
            .step(&model, &mut state)
            .expect("every step converges");
        halved += report.substeps - 1;
        let (rf, rm) = pliant_core::integrators::free_node_residual(&state);
        state.v.fill(DVec3::ZERO);
        state.w.fill(DVec3::ZERO);
        state.implicit.restart_at_rest();
        rf <= force_tol && rm <= moment_tol
    });
    let steps = rest.expect("at rest within 60 steps of 50 ms");
    assert!(halved <= 10, "{halved} extra sub-steps (was 511 per step)");
    // at rest the upper hose lies on the lower one: equal and opposite contact forces,
    // the load carried through the contact
    let (on_lower, on_upper) = (
        contact_force_on(&model, &state, 0),
        contact_force_on(&model, &state, 1),
    );
    assert!((on_lower + on_upper).length() <= 1e-9 * on_lower.length());
    // about half the load goes through the contact into the lower hose (the crossing
    // hoses are alike), and the lower hose's supports carry exactly that
    assert!(
        on_lower.z < -0.4 * f && on_lower.z > -0.6 * f,
        "the lower hose carries half the load: {on_lower}"
    );
    let supports: f64 = [0, N].iter().map(|&i| state.reaction_force[i].z).sum();
    assert!(
        (supports + on_lower.z).abs() <= 1e-3 * on_lower.z.abs(),
        "supports {supports} N against the contact force {} N",
        on_lower.z
    );
    println!("rest after {steps} steps, {halved} extra sub-steps");
}
