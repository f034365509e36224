//! A cable tie bundling two hoses ([`pliant_core::loads::Tie`], timeline
//! action `tie`). Two identical cantilevers of hose 3 side by side, clamped at their roots
//! and tied at their tips; one tip is pulled away from the other along the line between
//! them. The tie carries the load across: the two tips move together, so the two
//! identical cantilevers carry the pull in equal halves — the tie's force is F/2, on the
//! two tips equal and opposite, and the tips stay at the tied distance to within the tie's
//! give T/k. Checked under the quasi-static, implicit and explicit solvers (the explicit
//! one through the workcell's runner and the `tie` action).

use glam::{DQuat, DVec3};
use pliant_assembly::{Action, NoObserver, NodeRef, Runner, Timeline};
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{DeadLoad, Fix, LoadCase, Tie};
use pliant_core::{HoseSpec, Model, SimSettings, State, WorldSpec};

const N: usize = 12; // elements per hose, 25 mm each
const GAP: f64 = 0.05; // centre-line distance of the two hoses [m]
const F: f64 = 0.5; // pull on hose a's tip [N]: tip deflection ≈ 3 % of the length

/// Hoses a (along X from the origin) and b (the same, GAP further along +Y), no gravity,
/// no hose contact (the tie alone couples them).
fn model() -> Model {
    let (material, section) = pliant_testkit::hose3();
    let hose = |name: &str, y: f64| HoseSpec {
        name: name.into(),
        material: material.clone(),
        nodes: (0..=N)
            .map(|i| DVec3::new(0.025 * i as f64, y, 0.0))
            .collect(),
        sections: vec![section],
        normal_hint: Some(DVec3::Z),
    };
    let mut model = Model::build(&WorldSpec {
        hoses: vec![hose("a", 0.0), hose("b", GAP)],
        rigid_parts: vec![],
        settings: SimSettings {
            gravity: DVec3::ZERO,
            damping_mass: 20.0,
            ..Default::default()
        },
    })
    .unwrap();
    model.hose_contact.active = false;
    model
}

/// Global tip nodes of a and b.
fn tips(model: &Model) -> (usize, usize) {
    (model.hoses[0].node(N), model.hoses[1].node(N))
}

/// At rest, roots clamped, tips tied.
fn clamped_and_tied(model: &Model) -> State {
    let mut state = State::at_rest(model);
    for h in &model.hoses {
        let i = h.node(0);
        state.loads.add(LoadCase::Fix(Fix {
            node: i,
            position: state.x[i],
            orientation: DQuat::IDENTITY,
        }));
    }
    let (a, b) = tips(model);
    state.loads.add(LoadCase::Tie(Tie {
        nodes: [a, b],
        length: GAP,
    }));
    state
}

/// Hose a's tip pulled along −Y (away from b).
fn pull(model: &Model, state: &mut State) {
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node: tips(model).0,
        force: -DVec3::Y * F,
        moment: DVec3::ZERO,
        ramp: None,
    }));
}

/// Roots clamped, tips tied, hose a's tip pulled.
fn set_up(model: &Model) -> State {
    let mut state = clamped_and_tied(model);
    pull(model, &mut state);
    state
}

/// The tie's stiffness k between the two tips (as the core computes it).
fn tie_stiffness(model: &Model) -> f64 {
    let (a, b) = tips(model);
    Tie::constants(model.mass[a], model.mass[b], model.time_step).0
}

/// Checks an equilibrium: the tie's force on b is ≈ F/2 towards a (to `tol` relative), the
/// two reactions are equal and opposite, the tips keep their distance to within the tie's
/// give and both moved by the same amount; returns b's tip displacement \[m\].
fn check(model: &Model, state: &State, tol: f64, what: &str) -> f64 {
    let (a, b) = tips(model);
    let (ra, rb) = (state.reaction_force[a], state.reaction_force[b]);
    println!("{what}: tie on a {ra}, on b {rb}");
    assert!(
        (ra + rb).length() <= 1e-12 * F,
        "{what}: not opposite: {ra} {rb}"
    );
    // the tie gives by T/k_t, so a's tip moves that much further than b's: with the
    // cantilevers' tip stiffness k_c = 3 EI / L³, F − T − T = k_c T / k_t
    let k_c = 1.0 / cantilever_deflection(1.0);
    let t = F / (2.0 + k_c / tie_stiffness(model));
    println!(
        "{what}: k_c / k_t = {:e}, T = {t} N",
        k_c / tie_stiffness(model)
    );
    let expected = -DVec3::Y * t;
    assert!(
        (rb - expected).length() <= tol * F,
        "{what}: tie force on b {rb}, expected {expected}"
    );
    let distance = (state.x[b] - state.x[a]).length();
    let give = rb.length() / tie_stiffness(model);
    println!("{what}: distance {distance} m (tied at {GAP}, give T/k = {give:e} m)");
    assert!(
        (distance - GAP).abs() <= 1.01 * give + 1e-12,
        "{what}: distance {distance}"
    );
    assert!(give < 1e-5, "{what}: the tie gives {give} m");
    let rest = State::at_rest(model);
    let (da, db) = (state.x[a] - rest.x[a], state.x[b] - rest.x[b]);
    assert!(db.y < -1e-3, "{what}: b was not dragged: {db}");
    assert!(
        (da - db).length() <= 2.0 * give + 1e-9,
        "{what}: {da} vs {db}"
    );
    db.y
}

/// Tip deflection of a cantilever of hose 3 under a tip load P, linear beam theory
/// P L³ / (3 EI).
fn cantilever_deflection(p: f64) -> f64 {
    let (et, ec) = (6.9442e6f64, 8.6913e6f64);
    let eb = 4.0 * et * ec / (et.sqrt() + ec.sqrt()).powi(2);
    let ei = eb * std::f64::consts::PI / 64.0 * (0.035f64.powi(4) - 0.027f64.powi(4));
    p * (0.025 * N as f64).powi(3) / (3.0 * ei)
}

#[test]
fn static_solver_the_tie_carries_half_the_pull_to_the_other_hose() {
    let model = model();
    let mut state = set_up(&model);
    let report = StaticSolver::new(&model)
        .unwrap()
        .solve(&model, &mut state)
        .unwrap();
    assert!(report.converged, "{report:?}");
    let db = check(&model, &state, 1e-6, "static");
    // and b's tip moved as a cantilever under F/2 (beam theory, 3 % deflection: 1 %)
    let theory = cantilever_deflection(F / 2.0);
    println!("static: b's tip moved {db} m, beam theory {theory} m");
    assert!((db.abs() / theory - 1.0).abs() < 0.01, "{db} vs {theory}");
}

#[test]
fn implicit_solver_settles_to_the_same_tie_force() {
    let model = model();
    let mut state = set_up(&model);
    let mut solver = ImplicitSolver::new(
        &model,
        ImplicitOptions {
            time_step: 2e-3,
            ..Default::default()
        },
    )
    .unwrap();
    // step until at rest (kinetic energy of the nodes), at most 20 s simulated
    let kinetic = |s: &State| {
        (0..s.v.len())
            .map(|i| 0.5 * model.mass[i] * s.v[i].length_squared())
            .sum::<f64>()
    };
    let mut steps = 0;
    loop {
        solver.step(&model, &mut state).unwrap();
        steps += 1;
        if (steps > 50 && kinetic(&state) < 1e-14) || steps >= 10_000 {
            break;
        }
    }
    println!("implicit: {steps} steps");
    check(&model, &state, 1e-5, "implicit");
}

#[test]
fn explicit_solver_through_the_tie_action() {
    let model = model();
    let mut state = State::at_rest(&model);
    let node = |hose, node| NodeRef { hose, node };
    let timeline = Timeline {
        actions: vec![
            Action::Fix { node: node(0, 0) },
            Action::Fix { node: node(1, 0) },
            Action::Tie {
                node: node(0, N),
                to: node(1, N),
            },
            Action::Load {
                node: node(0, N),
                force: -DVec3::Y * F,
                moment: DVec3::ZERO,
                ramp: 0.0,
                name: None,
            },
            Action::Settle {
                kinetic_energy_threshold: 1e-14,
                force_tolerance: 1e-3,
                moment_tolerance: 1e-4,
                max_duration: 30.0,
                finish: pliant_assembly::SettleFinish::Dynamic,
            },
        ],
    };
    let summary = Runner::new(&model)
        .run(&timeline, &mut state, &mut NoObserver)
        .unwrap();
    assert!(summary.settles[0].at_rest, "{:?}", summary.settles);
    check(&model, &state, 1e-5, "explicit");
}

/// Sleeping (SPEC I6): two tied hoses at rest fall asleep; a load on one wakes it, and
/// the tie wakes the other as soon as the first moves.
#[test]
fn a_moving_hose_wakes_the_hose_tied_to_it() {
    use pliant_core::integrators::explicit;
    let model = model();
    let mut state = clamped_and_tied(&model);
    state.sleep.enabled = true;
    let b = tips(&model).1;
    // at rest from the start: wait until both sleep
    let mut steps = 0;
    while state.sleep.hose_asleep != [true, true] {
        explicit::step(&model, &mut state);
        steps += 1;
        assert!(steps < 100_000, "the hoses never fell asleep");
    }
    pull(&model, &mut state);
    state.sleep.wake(&model, 0); // as the workcell does when a load case changes
    explicit::step(&model, &mut state);
    assert_eq!(state.sleep.hose_asleep, [false, false]);
    let before = state.x[b];
    for _ in 0..200 {
        explicit::step(&model, &mut state);
    }
    assert!(
        (state.x[b] - before).y < 0.0,
        "b was not dragged after waking"
    );
}
