//! The static solver's line search compares residuals and slopes along a Newton step;
//! those need the loads at the trial state, not the tangent. Its trial states are
//! assembled without the elements' tangents ([`NewtonSystem::assemble_loads`]), which
//! must give the loads of the full assembly to round-off, and a solve then assembles the
//! tangent once per Newton iteration and once at the equilibrium, however often its line
//! searches shorten their steps. A hose pressed by a hand onto another one below it — the
//! contact coming on during the solve, as on the harness bench — checks both.

use glam::{DQuat, DVec3};
use pliant_core::integrators::{StaticOptions, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::newton::system::NewtonSystem;
use pliant_core::{Model, State};
use pliant_testkit::models::crossing_hoses;

const ELEMENTS: usize = 20;

/// The crossing hoses ([`crossing_hoses`]), the hose–hose contact on.
fn crossing(gap: f64) -> (Model, State) {
    let (model, state) = crossing_hoses(gap, ELEMENTS);
    assert!(model.hose_contact.active);
    (model, state)
}

#[test]
fn loads_alone_are_the_full_assemblys_loads() {
    let (model, mut state) = crossing(-0.5e-3);
    // bend and twist the hoses off their straight shape: every element loaded
    for i in 0..state.x.len() {
        let s = i as f64;
        state.x[i] += 1e-3 * DVec3::new((0.7 * s).sin(), (1.3 * s).cos(), (0.4 * s).sin());
        state.q[i] = (DQuat::from_scaled_axis(0.05 * DVec3::new(s.sin(), 0.3, s.cos()))
            * state.q[i])
            .normalize();
    }
    let mut full = NewtonSystem::new(&model).unwrap();
    let mut loads = NewtonSystem::new(&model).unwrap();
    full.set_prescribed(&model, &state, 0.0);
    loads.set_prescribed(&model, &state, 0.0);
    full.assemble(&model, &mut state, 0.0);
    loads.assemble_loads(&model, &mut state, 0.0);
    assert!(state.hose_contact.pairs_in_contact > 0, "the hoses touch");
    let (f_scale, m_scale) = (full.scale.force, full.scale.moment);
    assert!(f_scale > 1.0, "loaded: {f_scale} N");
    for i in 0..state.x.len() {
        let df = (full.force[i] - loads.force[i]).length();
        let dm = (full.moment[i] - loads.moment[i]).length();
        assert!(df <= 1e-10 * f_scale, "node {i}: force {df} N apart");
        assert!(dm <= 1e-10 * m_scale, "node {i}: moment {dm} N·m apart");
    }
    assert!((full.scale.force - loads.scale.force).abs() <= 1e-10 * f_scale);
    assert_eq!(full.assemblies.with_tangent, 1);
    assert_eq!(loads.assemblies.with_tangent, 0);
    assert_eq!(loads.assemblies.loads_only, 1);
    assert!(
        loads.pairs.is_empty(),
        "no pair's tangent without the tangent"
    );
}

#[test]
fn a_solve_assembles_the_tangent_once_per_iteration() {
    let (model, mut state) = crossing(1e-3);
    let node = ELEMENTS / 2;
    let start = state.x[node];
    let hand = state.loads.add(LoadCase::Fix(Fix {
        node,
        position: start,
        orientation: state.q[node],
    }));
    let mut solver = StaticSolver::new(&model).unwrap();
    // one system, so that its counts are the solve's
    solver.options = StaticOptions {
        split: false,
        ..solver.options
    };
    let (mut trials, mut shortened) = (0, 0);
    for k in 1..=6 {
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) {
            f.position = start - DVec3::Z * 1e-3 * k as f64;
        }
        let before = solver.system.assemblies;
        let r = solver.solve(&model, &mut state).unwrap();
        assert!(
            r.converged && !r.unstable && r.escapes == 0,
            "update {k}: {r:?}"
        );
        let after = solver.system.assemblies;
        // the loop's assembly of each iterate, the last one the equilibrium
        assert_eq!(
            after.with_tangent - before.with_tangent,
            r.iterations + 1,
            "update {k}: {r:?}"
        );
        trials += after.loads_only - before.loads_only;
        shortened += r.shortened_steps;
    }
    // the hand pressed A into B (which sags 2.2 mm under its weight): contact came on,
    // and line searches checked residuals
    assert!(state.hose_contact.pairs_in_contact > 0);
    assert!(
        trials > 0,
        "{trials} trial assemblies, {shortened} shortened steps"
    );
    eprintln!("{trials} trial assemblies, {shortened} shortened steps");
}
