//! The static solver keeps the factors of the tangent it checked for stability at an
//! equilibrium, and the next input step's first iteration — at the same configuration —
//! uses them instead of factorising the same matrix again. A hand moves a node 2 mm per
//! input step along a chain and along a Y network (its junction condensed): the shapes
//! are the same to the last bit as those of a solver that factorises every time, and
//! the factors are reused once per step.

use glam::DVec3;
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseEnd, JunctionSpec, Model, SimSettings, State, WorldSpec};

use pliant_testkit::straight_hose1 as hose;

/// A trunk along x, clamped at its root; with `branches`, two branches leave its end at
/// ±45° from a junction.
fn world(branches: bool) -> Model {
    let j = DVec3::new(0.3, 0.0, 0.0);
    let mut hoses = vec![hose("trunk", DVec3::ZERO, j, 12)];
    if branches {
        hoses.push(hose("left", j, j + DVec3::new(0.2, 0.2, 0.0), 8));
        hoses.push(hose("right", j, j + DVec3::new(0.2, -0.2, 0.0), 8));
    }
    let model = Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    if branches {
        model
            .with_junctions(&[JunctionSpec {
                name: "Y".into(),
                ends: vec![(0, HoseEnd::End), (1, HoseEnd::Start), (2, HoseEnd::Start)],
                body_mass: 0.0,
                body_centre: None,
                body_inertia: None,
                shape: None,
            }])
            .unwrap()
    } else {
        model
    }
}

/// The positions after each of `steps` input steps, a hand on node 6 of the trunk moving
/// 2 mm up per step; `refactorise` makes the solver forget its factors before each one.
/// Returns them with the number of factorisations reused.
fn hand_steps(model: &Model, steps: usize, refactorise: bool) -> (Vec<Vec<DVec3>>, u64) {
    let mut state = State::at_rest(model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: state.x[0],
        orientation: state.q[0],
    }));
    let (node, start) = (6, state.x[6]);
    let hand = state.loads.add(LoadCase::Fix(Fix {
        node,
        position: start,
        orientation: state.q[node],
    }));
    let mut solver = StaticSolver::new(model).unwrap();
    solver.options.max_iterations = 500;
    let mut shapes = Vec::new();
    for k in 0..steps {
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) {
            f.position = start + DVec3::Z * 0.002 * k as f64;
        }
        if refactorise {
            solver.system.reuse.forget();
        }
        let r = solver.solve(model, &mut state).unwrap();
        assert!(r.converged && !r.unstable, "step {k}: {r:?}");
        shapes.push(state.x.clone());
    }
    (shapes, solver.system.reuse.reused)
}

#[test]
fn reused_factors_give_the_same_bits_once_per_step() {
    for branches in [false, true] {
        let model = world(branches);
        let steps = 12;
        let (reusing, reused) = hand_steps(&model, steps, false);
        let (fresh, not_reused) = hand_steps(&model, steps, true);
        assert_eq!(not_reused, 0, "branches {branches}");
        // every step after the first starts where the last one checked its stability
        assert!(reused >= steps as u64 - 1, "branches {branches}: {reused}");
        for (k, (a, b)) in reusing.iter().zip(&fresh).enumerate() {
            let bits = |s: &[DVec3]| -> Vec<u64> {
                s.iter()
                    .flat_map(|p| p.to_array().map(f64::to_bits))
                    .collect()
            };
            assert_eq!(bits(a), bits(b), "branches {branches}, step {k}");
        }
        // the hand moved the hose: the steps were not all the same equilibrium
        let last = reusing.last().unwrap();
        assert!((last[6] - reusing[0][6]).length() > 0.02);
    }
}
