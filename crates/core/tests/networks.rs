//! Networks (SPEC N1): hose ends joined at junctions. A Y of three hoses hanging from
//! the trunk's clamped root balances its weight under every solver, the solvers agree
//! on its shape, a hand (a fix) on a branch's end node holds the whole junction, a loop
//! is refused by the Newton solvers with a clear error and stepped by the explicit one,
//! and the joined ends stay together.

use glam::{DQuat, DVec3};
use pliant_core::integrators::{Solver, SolverKind, SolverSettings, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::relax::{relax, RelaxOptions};
use pliant_core::{HoseEnd, JunctionSpec, Model, SimSettings, State, WorldSpec};

use pliant_testkit::straight_hose1 as hose;

/// A trunk along x from the origin, two branches leaving its end in the x–y plane at
/// ±45°, under gravity; the trunk's root clamped.
fn y_network() -> (Model, State) {
    let j = DVec3::new(0.3, 0.0, 0.0);
    let model = Model::build(&WorldSpec {
        hoses: vec![
            hose("trunk", DVec3::ZERO, j, 8),
            hose("left", j, j + DVec3::new(0.2, 0.2, 0.0), 8),
            hose("right", j, j + DVec3::new(0.2, -0.2, 0.0), 8),
        ],
        rigid_parts: vec![],
        settings: SimSettings {
            damping_mass: 4.0,
            ..Default::default()
        },
    })
    .unwrap()
    .with_junctions(&[JunctionSpec {
        name: "Y".into(),
        ends: vec![(0, HoseEnd::End), (1, HoseEnd::Start), (2, HoseEnd::Start)],
        body_mass: 0.0,
        body_centre: None,
        body_inertia: None,
        shape: None,
    }])
    .unwrap();
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: model.rest_q[0],
    }));
    (model, state)
}

fn weight(model: &Model) -> DVec3 {
    model.mass.iter().map(|m| *m * model.gravity).sum()
}

/// The positions of the nodes after reaching rest with `kind`.
fn at_rest(kind: SolverKind) -> (Model, State) {
    let (model, mut state) = y_network();
    match kind {
        SolverKind::Explicit => {
            let r = relax(
                &model,
                &mut state,
                &RelaxOptions {
                    force_tolerance: 1e-9,
                    moment_tolerance: 1e-10,
                    max_steps: 2_000_000,
                    kinetic_damping: false,
                },
            )
            .unwrap();
            assert!(r.converged, "explicit did not settle: {r:?}");
        }
        SolverKind::Static => {
            let mut solver = StaticSolver::new(&model).unwrap();
            // a large sag from the straight rest shape: more iterations than one input
            // step of a session takes
            solver.options.max_iterations = 1000;
            let r = solver.solve(&model, &mut state).unwrap();
            assert!(r.converged, "{r:?}");
            assert!(!r.unstable);
        }
        SolverKind::Implicit => {
            let mut solver = Solver::new(
                &model,
                SolverSettings {
                    kind,
                    ..Default::default()
                },
            )
            .unwrap();
            for _ in 0..400 {
                solver.step(&model, &mut state).unwrap();
            }
        }
    }
    (model, state)
}

#[test]
fn a_y_network_carries_its_weight_and_the_solvers_agree() {
    let (model, explicit) = at_rest(SolverKind::Explicit);
    let w = weight(&model);
    // the clamp carries the whole weight (the explicit step reports its reaction)
    let r = explicit.reaction_force[0];
    assert!(
        (r + w).length() < 1e-4 * w.length(),
        "{r:?} vs weight {w:?}"
    );
    let size = 0.5;
    for kind in [SolverKind::Static, SolverKind::Implicit] {
        let (_, other) = at_rest(kind);
        let worst = explicit
            .x
            .iter()
            .zip(&other.x)
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        assert!(
            worst < 1e-3 * size,
            "{kind:?} differs from explicit by {worst} m"
        );
        // the static solver is at balance; the implicit run, 4 s of damped motion, close
        let balance = if kind == SolverKind::Static {
            1e-6
        } else {
            1e-3
        };
        let r = other.reaction_force[0];
        assert!(
            (r + w).length() < balance * w.length(),
            "{kind:?}: {r:?} vs {w:?}"
        );
        // the joined ends stay together and keep their relative rotation
        let ends = &model.junctions[0].nodes;
        for &k in &ends[1..] {
            assert!((other.x[k] - other.x[ends[0]]).length() < 1e-12);
            let rel_now = other.q[ends[0]].conjugate() * other.q[k];
            let rel_rest = model.rest_q[ends[0]].conjugate() * model.rest_q[k];
            assert!(rel_now.angle_between(rel_rest) < 1e-6);
        }
    }
    // the ends hang below the junction (gravity along −z) and the branches stay mirror
    // images of each other
    let (l, r) = (model.hoses[1].node(8), model.hoses[2].node(8));
    assert!(explicit.x[l].z < explicit.x[model.junctions[0].nodes[0]].z);
    assert!((explicit.x[l].y + explicit.x[r].y).abs() < 1e-6);
}

#[test]
fn a_fixed_branch_end_at_the_junction_holds_the_whole_junction() {
    let (model, mut state) = y_network();
    let slave = model.junctions[0].nodes[2];
    // hold the right branch's first node, a quarter turn about z away, 5 cm up
    let turn = DQuat::from_rotation_z(0.3);
    state.loads.add(LoadCase::Fix(Fix {
        node: slave,
        position: state.x[slave] + DVec3::new(0.0, 0.0, 0.05),
        orientation: turn * state.q[slave],
    }));
    let mut solver = StaticSolver::new(&model).unwrap();
    let r = solver.solve(&model, &mut state).unwrap();
    assert!(r.converged, "{r:?}");
    let ends = &model.junctions[0].nodes;
    for &k in ends {
        assert!((state.x[k] - (model.rest_x[slave] + DVec3::new(0.0, 0.0, 0.05))).length() < 1e-12);
        let rel = (state.q[k] * model.rest_q[k].conjugate()) * turn.conjugate();
        assert!(
            rel.angle_between(DQuat::IDENTITY) < 1e-6,
            "end {k} not turned with the junction"
        );
    }
}

#[test]
fn a_loop_is_refused_by_the_newton_solvers_and_stepped_by_the_explicit_one() {
    let (a, b, c) = (
        DVec3::ZERO,
        DVec3::new(0.3, 0.0, 0.0),
        DVec3::new(0.15, 0.2, 0.0),
    );
    let model = Model::build(&WorldSpec {
        hoses: vec![
            hose("ab", a, b, 4),
            hose("bc", b, c, 4),
            hose("ca", c, a, 4),
        ],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap()
    .with_junctions(&[
        JunctionSpec {
            name: "b".into(),
            ends: vec![(0, HoseEnd::End), (1, HoseEnd::Start)],
            body_mass: 0.0,
            body_centre: None,
            body_inertia: None,
            shape: None,
        },
        JunctionSpec {
            name: "c".into(),
            ends: vec![(1, HoseEnd::End), (2, HoseEnd::Start)],
            body_mass: 0.0,
            body_centre: None,
            body_inertia: None,
            shape: None,
        },
        JunctionSpec {
            name: "a".into(),
            ends: vec![(2, HoseEnd::End), (0, HoseEnd::Start)],
            body_mass: 0.0,
            body_centre: None,
            body_inertia: None,
            shape: None,
        },
    ])
    .unwrap();
    let err = StaticSolver::new(&model).unwrap_err().to_string();
    assert!(err.contains("closed loop"), "{err}");
    let mut state = State::at_rest(&model);
    for _ in 0..1000 {
        pliant_core::integrators::explicit::step(&model, &mut state);
    }
    assert!(state.x.iter().all(|x| x.is_finite()));
    // the ring falls freely, its joints closed
    for j in &model.junctions {
        assert!((state.x[j.nodes[0]] - state.x[j.nodes[1]]).length() < 1e-12);
    }
}

#[test]
fn junction_errors_name_the_junction() {
    let j = DVec3::new(0.3, 0.0, 0.0);
    let model = Model::build(&WorldSpec {
        hoses: vec![hose("a", DVec3::ZERO, j, 4), hose("b", j, 2.0 * j, 4)],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    let twice = model.clone().with_junctions(&[
        JunctionSpec {
            name: "one".into(),
            ends: vec![(0, HoseEnd::End), (1, HoseEnd::Start)],
            body_mass: 0.0,
            body_centre: None,
            body_inertia: None,
            shape: None,
        },
        JunctionSpec {
            name: "two".into(),
            ends: vec![(1, HoseEnd::Start), (0, HoseEnd::Start)],
            body_mass: 0.0,
            body_centre: None,
            body_inertia: None,
            shape: None,
        },
    ]);
    let e = twice.unwrap_err().to_string();
    assert!(
        e.contains("junction 'two'") && e.contains("junction 'one'"),
        "{e}"
    );
    let lonely = model.with_junctions(&[JunctionSpec {
        name: "lonely".into(),
        ends: vec![(0, HoseEnd::End)],
        body_mass: 0.0,
        body_centre: None,
        body_inertia: None,
        shape: None,
    }]);
    assert!(lonely.unwrap_err().to_string().contains("at least 2"));
}
