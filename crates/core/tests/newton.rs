//! The Newton solvers: quasi-static equilibrium against the exact elastica and
//! against the explicit solver's relaxed state; implicit HHT-α at large steps.

use glam::{DQuat, DVec3};
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{DeadLoad, Fix, LoadCase};
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};
use pliant_testkit::hose1;
use pliant_testkit::models::fix_in_place;

fn cantilever(n: usize, material: Material, section: Section, gravity: DVec3) -> (Model, State) {
    let nodes = (0..=n)
        .map(|i| DVec3::new(i as f64 / n as f64, 0.0, 0.0))
        .collect();
    let model = Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "h".into(),
            material,
            nodes,
            sections: vec![section],
            normal_hint: Some(DVec3::Y),
        }],
        rigid_parts: vec![],
        settings: SimSettings {
            gravity,
            damping_mass: 4.0,
            ..Default::default()
        },
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
    }));
    (model, state)
}

/// Library hose 1, 0.5 m in 8 elements along x from `start`, nodes 3–5 a stiffened
/// section (SPEC M6), under `gravity`.
fn stiffened_hose(start: DVec3, gravity: DVec3) -> Model {
    use pliant_core::rod::stiffened::StiffenedSpan;
    let (mat, sec) = hose1();
    let n = 8;
    let nodes = (0..=n)
        .map(|i| start + DVec3::new(0.5 * i as f64 / n as f64, 0.0, 0.0))
        .collect();
    Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "h".into(),
            material: mat,
            nodes,
            sections: vec![sec],
            normal_hint: Some(DVec3::Y),
        }],
        rigid_parts: vec![],
        settings: SimSettings {
            gravity,
            ..Default::default()
        },
    })
    .unwrap()
    .with_stiffened_spans(&[StiffenedSpan {
        hose: 0,
        first: 3,
        last: 5,
    }])
    .unwrap()
}

/// λ = PL²/EI = 2: exact w/L = 0.493457 (Mattiasson 1981), in one static solve from the
/// straight rest shape.
#[test]
fn static_tip_load_matches_the_elastica() {
    let (mat, sec) = hose1();
    let (mut model, mut state) = cantilever(40, mat.clone(), sec, DVec3::ZERO);
    model.hose_contact.active = false;
    let ei = mat.bending_modulus() * sec.second_moment();
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node: 40,
        force: DVec3::new(0.0, -2.0 * ei, 0.0),
        moment: DVec3::ZERO,
        ramp: None,
    }));
    let mut solver = StaticSolver::new(&model).unwrap();
    let report = solver.solve(&model, &mut state).unwrap();
    println!("{report:?}");
    assert!(report.converged, "{report:?}");
    let w = -state.x[40].y;
    assert!((w - 0.493457).abs() < 0.005 * 0.493457, "w/L = {w}");
    // the support carries the load
    assert!((state.reaction_force[0].y - 2.0 * ei).abs() < 1e-6 * ei);
    // an ordinary hose's round-off floor stays under the limit (1/75–1/10 of it here,
    // under a light tip load of 0.07 N on an axially stiff hose): the floor only excuses
    // stiff nodes (a_stiff_section_far_from_the_origin_converges_to_the_same_shape)
    let sys = &mut solver.system;
    sys.assemble(&model, &mut state, 0.0);
    for i in 1..=40 {
        let (floor, _) = sys.noise_floor(&state, i);
        assert!(
            floor < 0.2 * report.force_limit,
            "node {i}: floor {floor:e} N, limit {:e} N",
            report.force_limit
        );
    }
}

/// A steel tube (E = 200 GPa) hanging under gravity at Δt = 10 ms: every step converges
/// and it comes to rest at the static solution.
#[test]
fn implicit_steel_tube_at_10_ms_reaches_the_static_state() {
    let mat = Material::isotropic(200e9, 0.3, 7850.0);
    let sec = Section::new(0.008, 0.010);
    let g = DVec3::new(0.0, 0.0, -9.81);
    let (model, mut state) = cantilever(30, mat.clone(), sec, g);
    let mut statics = state.clone();
    StaticSolver::new(&model)
        .unwrap()
        .solve(&model, &mut statics)
        .unwrap();
    let mut solver = ImplicitSolver::new(
        &model,
        ImplicitOptions {
            time_step: 0.01,
            ..Default::default()
        },
    )
    .unwrap();
    let mut iters = 0;
    for _ in 0..1000 {
        let r = solver.step(&model, &mut state).unwrap();
        iters += r.iterations;
        assert_eq!(r.substeps, 1);
    }
    println!("mean iterations {}", iters as f64 / 1000.0);
    let tip = state.x[30];
    let exact = statics.x[30];
    println!("implicit {tip:?} static {exact:?}");
    assert!((tip - exact).length() < 1e-3 * exact.z.abs());
}

/// Roll-up under an end moment, in eight load steps to a full circle: the tip returns
/// to the root (an exact circle of curvature M/EI).
#[test]
fn static_rollup_closes_the_circle() {
    let (mat, sec) = hose1();
    let (mut model, mut state) = cantilever(40, mat.clone(), sec, DVec3::ZERO);
    // the full circle brings the tip back onto the root: this tests the element, not
    // self contact (which would rightly stop the tip short)
    model.hose_contact.active = false;
    let ei = mat.bending_modulus() * sec.second_moment();
    let mut solver = StaticSolver::new(&model).unwrap();
    let mut id = None;
    for k in 1..=8 {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        let m = 2.0 * std::f64::consts::PI * ei * k as f64 / 8.0;
        id = Some(state.loads.add(LoadCase::DeadLoad(DeadLoad {
            node: 40,
            force: DVec3::ZERO,
            moment: DVec3::new(0.0, 0.0, m),
            ramp: None,
        })));
        let r = solver.solve(&model, &mut state).unwrap();
        println!("{k}: {r:?}");
        assert!(r.converged, "{r:?}");
    }
    assert!(state.x[40].length() < 1e-3, "tip at {:?}", state.x[40]);
}

/// The soft library hose 1 released horizontally swings down under gravity at Δt = 10 ms
/// — large rotations per step — and every step converges.
#[test]
fn implicit_soft_hose_swings_at_10_ms() {
    let (mat, sec) = hose1();
    let (model, mut state) = cantilever(30, mat, sec, DVec3::new(0.0, 0.0, -9.81));
    let mut solver = ImplicitSolver::new(&model, ImplicitOptions::default()).unwrap();
    let mut worst = 0;
    for k in 0..400 {
        let r = solver
            .step(&model, &mut state)
            .unwrap_or_else(|e| panic!("step {k}: {e}"));
        worst = worst.max(r.iterations);
    }
    println!("worst iterations {worst}, tip {:?}", state.x[30]);
    assert!(
        state.x[30].z < -0.5,
        "the hose hangs down: {:?}",
        state.x[30]
    );
}

/// A hand lifts a stiffened section by two of its nodes, 2 cm per 10 ms step (the
/// server's hand speed limit): every implicit step converges without halving, and the
/// span stays rigid.
#[test]
fn implicit_hand_lifts_a_stiffened_section() {
    let n = 8;
    let model = stiffened_hose(DVec3::ZERO, SimSettings::default().gravity);
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: state.x[0],
        orientation: state.q[0],
    }));
    let held = [4usize, 5];
    let ids: Vec<_> = held
        .iter()
        .map(|&i| {
            state.loads.add(LoadCase::Fix(Fix {
                node: i,
                position: state.x[i],
                orientation: state.q[i],
            }))
        })
        .collect();
    let mut solver = ImplicitSolver::new(&model, ImplicitOptions::default()).unwrap();
    for k in 0..10 {
        for (&id, &i) in ids.iter().zip(&held) {
            if let Some(LoadCase::Fix(f)) = state.loads.get_mut(id) {
                f.position = model.rest_x[i] + DVec3::new(0.0, 0.0, 0.02 * (k + 1) as f64);
            }
        }
        let r = solver
            .step(&model, &mut state)
            .unwrap_or_else(|e| panic!("step {k}: {e}"));
        assert_eq!(r.substeps, 1, "step {k}: {r:?}");
    }
    let spacing = |a: usize, b: usize| (state.x[b] - state.x[a]).length();
    let rest = 0.5 / n as f64;
    assert!((spacing(3, 4) - rest).abs() < 1e-4 * rest);
    assert!((state.x[4].z - 0.2).abs() < 1e-12);
}

/// A step Newton cannot converge is taken from its start by
/// the explicit solver in ⌈h/Δt⌉ equal pieces — the same numbers as those pieces taken
/// directly — with a hand's target approached over the pieces (the held node moves at
/// the hand's speed, not in one jump), and the implicit solver goes on from there.
#[test]
fn an_implicit_step_newton_cannot_converge_is_taken_explicitly() {
    use pliant_core::integrators::{explicit, Solver, SolverKind, SolverSettings};
    let (mat, sec) = hose1();
    let (model, mut start) = cantilever(10, mat, sec, DVec3::new(0.0, 0.0, -9.81));
    // a hand holds the free end and lifts it 1 cm in this step
    start.loads.add(LoadCase::Fix(Fix {
        node: 10,
        position: DVec3::new(1.0, 0.0, 0.01),
        orientation: DQuat::IDENTITY,
    }));
    let h = 0.01;
    let mut solver = Solver::new(
        &model,
        SolverSettings {
            kind: SolverKind::Implicit,
            implicit_time_step: h,
            ..Default::default()
        },
    )
    .unwrap();
    let options = *solver.implicit_options_mut().unwrap();
    // one iteration, no halving: this first step cannot converge
    solver.implicit_options_mut().unwrap().max_iterations = 1;
    solver.implicit_options_mut().unwrap().max_halvings = 0;
    let mut state = start.clone();
    let stats = solver.step(&model, &mut state).unwrap();
    let pieces = (h / model.time_step).ceil() as usize;
    assert_eq!(stats.explicit_fallback, pieces);
    assert_eq!((state.time, state.step), (h, 1));
    assert_eq!(
        state.x[10],
        DVec3::new(1.0, 0.0, 0.01),
        "the hand's target reached"
    );
    let speed = state.v[10].z;
    assert!(
        (speed - 1.0).abs() < 0.1,
        "the held node moved at the hand's 1 m/s, not in one jump: {speed} m/s"
    );
    // the same numbers as the explicit pieces taken directly, the target interpolated
    let mut reference = start.clone();
    for k in 1..=pieces {
        let s = k as f64 / pieces as f64;
        if let Some((_, LoadCase::Fix(f))) = reference.loads.iter_mut().nth(1) {
            f.position = DVec3::new(1.0, 0.0, 0.0).lerp(DVec3::new(1.0, 0.0, 0.01), s);
        }
        explicit::step_by(&model, &mut reference, h / pieces as f64);
    }
    assert_eq!(state.x, reference.x);
    assert_eq!(state.q, reference.q);
    // with its usual options the implicit solver goes on converging from there
    *solver.implicit_options_mut().unwrap() = options;
    for k in 0..50 {
        let stats = solver.step(&model, &mut state).unwrap();
        assert_eq!(stats.explicit_fallback, 0, "step {k}");
        assert!(stats.converged);
    }
    assert!(state.x[5].z < -0.01, "the hose sags between its ends");
}

/// A snap relaxation asked for a balance the arithmetic cannot reach (limits 0) stops once
/// no node moves any more (snap.rs, FROZEN_WINDOWS) instead of taking its 2 million
/// explicit steps; it has relaxed the hose to rest by then.
#[test]
fn a_relaxation_that_stopped_moving_gives_up() {
    let (outcome, state, taken) = relaxed_cantilever(u64::MAX);
    assert!(!outcome.reached);
    assert_eq!(outcome.steps, taken);
    assert!(taken < 200_000, "{taken} explicit steps");
    let (f, m) = pliant_core::relax::residual(&state);
    assert!(f < 1e-9 && m < 1e-9, "residual {f} N, {m} N·m");
    assert!(state.x[10].z < -0.5, "the tip hangs: {}", state.x[10]);
}

/// A hose with a stiffened section (stiffness × 10⁴ in Newton) hanging between two fixed
/// ends, once at the origin and once 40 m away: both static solves converge to the same
/// shape. Far out, coordinates of 40 m carry round-off of 40 m × 2⁻⁵³ ≈ 4e-15 m, which
/// the stiff elements turn into residual forces above the relative limit (1e-8 of the
/// largest element force) that no Newton step can remove; a node within that floor
/// (`NewtonSystem::noise_floor`) counts as balanced. Before, the solve reported no
/// convergence (the engine-bay demo under the static solver: "uncertain").
#[test]
fn a_stiff_section_far_from_the_origin_converges_to_the_same_shape() {
    let n = 8;
    let solve = |offset: DVec3| {
        let model = stiffened_hose(offset, DVec3::new(0.0, 0.0, -9.81));
        let mut state = State::at_rest(&model);
        fix_in_place(&mut state, [0, n]);
        let mut solver = StaticSolver::new(&model).unwrap();
        let report = solver.solve(&model, &mut state).unwrap();
        let shape: Vec<DVec3> = state.x.iter().map(|x| *x - offset).collect();
        (report, shape)
    };
    let (near, at_origin) = solve(DVec3::ZERO);
    let (far, far_out) = solve(DVec3::new(40.0, -30.0, 20.0));
    println!("{near:?}\n{far:?}");
    assert!(near.converged && far.converged, "{near:?}\n{far:?}");
    assert!(at_origin[4].z < -1e-3, "it sags: {}", at_origin[4].z);
    for (a, b) in at_origin.iter().zip(&far_out) {
        // 2.4e-15 m measured: the coordinates' own round-off at 40 m is 4e-15 m
        assert!((*a - *b).length() < 1e-12, "{a} against {b}");
    }
}

/// A snap relaxation stops at the steps it is given, and says how many it took: the run's
/// budget ([`pliant_core::SolverSettings::static_relaxation_budget`]) is spent by them.
#[test]
fn a_relaxation_takes_no_more_steps_than_it_is_given() {
    let (outcome, _, taken) = relaxed_cantilever(1000);
    assert!(!outcome.reached);
    assert_eq!(outcome.steps, 1000);
    assert_eq!(taken, 1000);
}

/// A 10-element hose-1 cantilever sagging under gravity, relaxed by the snap relaxation
/// towards a balance it cannot reach (limits 0) with at most `steps` explicit steps: the
/// outcome, the state after it and the steps the state took.
fn relaxed_cantilever(steps: u64) -> (pliant_core::integrators::snap::Relaxation, State, u64) {
    let (mat, sec) = hose1();
    let (model, mut state) = cantilever(10, mat, sec, DVec3::new(0.0, 0.0, -9.81));
    let (time, before) = (state.time, state.step);
    let mut anchor = Vec::new();
    let outcome = pliant_core::integrators::snap::relax(
        &model,
        &mut state,
        time,
        (0.0, 0.0),
        steps,
        &mut anchor,
    );
    let taken = state.step - before;
    (outcome, state, taken)
}

/// The snap relaxation's budget holds across a run: a static solver allowed one Newton
/// iteration per equilibrium cannot converge the first sag of a cantilever and falls
/// back on relaxation; with a budget of 0 it relaxes not at all, with 500 steps it takes
/// those and then, spent, reports the next unconverged step without relaxing.
#[test]
fn the_relaxation_budget_is_spent_once_per_run() {
    use pliant_core::integrators::Solver;
    use pliant_core::{SolverKind, SolverSettings};
    let (mat, sec) = hose1();
    for budget in [0, 500] {
        let (model, mut state) = cantilever(10, mat.clone(), sec, DVec3::new(0.0, 0.0, -9.81));
        let settings = SolverSettings {
            kind: SolverKind::Static,
            static_max_iterations: 1,
            static_relaxation_budget: budget,
            ..Default::default()
        };
        let mut solver = Solver::new(&model, settings).unwrap();
        let mut explicit_steps = 0;
        for k in 0..3 {
            let before = state.step;
            let stats = solver.step(&model, &mut state).unwrap();
            assert!(!stats.converged, "budget {budget}, step {k}");
            // the static step counts one, each explicit step of the relaxation one
            explicit_steps += state.step - before - 1;
        }
        assert_eq!(explicit_steps, budget, "budget {budget}");
    }
}
