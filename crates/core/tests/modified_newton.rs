//! The implicit solver's modified Newton steps ([`pliant_core::newton::modified`]): a
//! step uses its last factorised Jacobian again while the residual contracts, and
//! converges to the same tolerance as with a Jacobian factorised at every iteration. Two
//! clamped hoses crossing 0.1 mm apart, the hose–hose contact on, the upper one sagging
//! under gravity, check both.

use pliant_core::integrators::{ImplicitOptions, ImplicitSolver};
use pliant_core::{Model, State};
use pliant_testkit::models::crossing_hoses;

const ELEMENTS: usize = 20;
const STEPS: usize = 60;

/// Runs `STEPS` steps of 10 ms; returns the final state, the Newton iterations and the
/// factorisations over all steps.
fn run(model: &Model, mut state: State, modified_newton: bool) -> (State, usize, usize) {
    let options = ImplicitOptions {
        modified_newton,
        ..Default::default()
    };
    let mut solver = ImplicitSolver::new(model, options).unwrap();
    let (mut iterations, mut factorisations) = (0, 0);
    for k in 0..STEPS {
        let r = solver
            .step(model, &mut state)
            .unwrap_or_else(|e| panic!("step {k} (modified {modified_newton}): {e}"));
        assert!(r.converged);
        iterations += r.iterations;
        factorisations += r.factorisations;
    }
    (state, iterations, factorisations)
}

#[test]
fn modified_steps_reach_the_same_states_with_fewer_factorisations() {
    let (model, state) = crossing_hoses(0.1e-3, ELEMENTS);
    assert!(model.hose_contact.active);
    let (full, full_iterations, full_factorisations) = run(&model, state.clone(), false);
    let (modified, iterations, factorisations) = run(&model, state, true);
    println!(
        "full Newton: {full_iterations} iterations, {full_factorisations} factorisations; \
         modified: {iterations} iterations, {factorisations} factorisations"
    );
    // full Newton factorises once per iteration
    assert_eq!(full_factorisations, full_iterations);
    assert!(
        4 * factorisations <= 3 * full_factorisations,
        "{factorisations} factorisations against {full_factorisations}"
    );
    // both converged every step to the same tolerance: the states agree to far below
    // the hoses' size (0.4 m) and the gap (7.5e-11 m when written)
    let worst = full
        .x
        .iter()
        .zip(&modified.x)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0_f64, f64::max);
    println!("largest difference of a node's position: {worst:.3e} m");
    assert!(worst < 1e-7, "states differ by {worst:.3e} m");
}
