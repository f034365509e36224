//! The static solver solves only the components out of balance
//! (crates/core/src/integrators/split.rs), exactly: a hose fixed at its ends and its
//! middle falls apart into two spans; a hand (a fix) moved in one span gives the state
//! the whole-model solve gives, to the solver's tolerance, and leaves the other span's
//! nodes bit for bit as they were; a hose lying across the moved span within contact
//! reach is solved with it; a load put on a span in balance gets that span solved.

use glam::DVec3;
use pliant_core::integrators::{StaticReport, StaticSolver};
use pliant_core::loads::{DeadLoad, Fix, LoadCase, LoadCaseId};
use pliant_core::{Model, SimSettings, State, WorldSpec};
use pliant_testkit::straight_hose1 as hose;

/// Elements of the split hose: fixed at nodes 0, [`MIDDLE`] and [`ELEMENTS`].
const ELEMENTS: usize = 24;
const MIDDLE: usize = 12;
/// The hand's node, in the first span.
const HAND: usize = 6;

/// The split hose along x (0.6 m, under gravity), and with `across` a short hose fixed
/// at both ends crossing over its first span 0.5 mm above it (within contact reach).
fn model(across: bool) -> Model {
    let mut hoses = vec![hose(
        "split",
        DVec3::ZERO,
        DVec3::new(0.6, 0.0, 0.0),
        ELEMENTS,
    )];
    if across {
        // hose 1: d_a 16 mm, so 16.5 mm between the axes leaves a 0.5 mm gap
        let z = 0.0165;
        hoses.push(hose(
            "across",
            DVec3::new(0.1, -0.05, z),
            DVec3::new(0.1, 0.05, z),
            8,
        ));
    }
    Model::build(&WorldSpec {
        hoses,
        rigid_parts: vec![],
        settings: SimSettings {
            gravity: DVec3::new(0.0, 0.0, -9.81),
            ..Default::default()
        },
    })
    .unwrap()
}

/// Fixes `node` where it is in `state`.
fn fix_in_place(state: &mut State, node: usize) -> LoadCaseId {
    state.loads.add(LoadCase::Fix(Fix {
        node,
        position: state.x[node],
        orientation: state.q[node],
    }))
}

/// The model at rest under gravity, the split hose fixed at its ends, its middle and the
/// hand's node, every other hose at its ends; the hand's load case.
fn settled(across: bool) -> (Model, State, LoadCaseId) {
    let model = model(across);
    let mut state = State::at_rest(&model);
    for node in [0, MIDDLE, ELEMENTS] {
        fix_in_place(&mut state, node);
    }
    for h in &model.hoses[1..] {
        fix_in_place(&mut state, h.first_node);
        fix_in_place(&mut state, h.first_node + h.node_count - 1);
    }
    let hand = fix_in_place(&mut state, HAND);
    let mut solver = whole(&model);
    solver.options.max_iterations = 200;
    let r = solver.solve(&model, &mut state).unwrap();
    assert!(r.converged && !r.unstable, "{r:?}");
    (model, state, hand)
}

/// A solver of the whole model every time.
fn whole(model: &Model) -> StaticSolver {
    let mut solver = StaticSolver::new(model).unwrap();
    solver.options.split = false;
    solver
}

/// Moves the hand by `by`.
fn move_hand(state: &mut State, hand: LoadCaseId, by: DVec3) {
    let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) else {
        panic!("the hand is a fix");
    };
    f.position += by;
}

/// Solves `state` with the split (the default) and a copy with the whole model; returns
/// both reports and states.
fn both(model: &Model, state: &State) -> ((StaticReport, State), (StaticReport, State)) {
    let mut split = state.clone();
    let mut solver = StaticSolver::new(model).unwrap();
    assert!(solver.options.split, "the split is the default");
    let r_split = solver.solve(model, &mut split).unwrap();
    let mut all = state.clone();
    let r_all = whole(model).solve(model, &mut all).unwrap();
    assert!(r_split.converged && !r_split.unstable, "{r_split:?}");
    assert!(r_all.converged && !r_all.unstable, "{r_all:?}");
    ((r_split, split), (r_all, all))
}

/// The largest distance between the two states' nodes \[m\].
fn largest_difference(a: &State, b: &State) -> f64 {
    a.x.iter()
        .zip(&b.x)
        .map(|(p, q)| (*p - *q).length())
        .fold(0.0, f64::max)
}

/// How far the two solves may land apart: both are balanced to the tolerance
/// (1e-8 of the load scale); what that leaves of a span's position, its compliance
/// times the residual, is far below a nanometre here — 1e-9 m is 1e-6 of the hand's
/// 1 mm … 5 mm moves.
const SAME_STATE: f64 = 1e-9;

#[test]
fn a_hand_moved_in_one_span_solves_that_span_alone() {
    let (model, mut state, hand) = settled(false);
    let before = state.clone();
    move_hand(&mut state, hand, DVec3::new(0.0, 0.003, 0.005));
    let ((r_split, split), (r_all, all)) = both(&model, &state);
    // the hand's span: nodes 0 … 12 (its held ends included)
    assert_eq!(r_split.solved_nodes, MIDDLE + 1, "{r_split:?}");
    assert_eq!(r_all.solved_nodes, model.node_count());
    let d = largest_difference(&split, &all);
    eprintln!("split and whole solves {d:e} m apart");
    assert!(d <= SAME_STATE, "split and whole solves {d:e} m apart");
    assert!(split.x[HAND - 2].z > before.x[HAND - 2].z + 1e-3);
    for i in MIDDLE..=ELEMENTS {
        assert_eq!(split.x[i], before.x[i], "node {i} moved");
        assert_eq!(split.q[i], before.q[i], "node {i} turned");
    }
    // the whole model's residual, checked by the split solve itself
    assert!(r_split.residual_force <= r_split.force_limit, "{r_split:?}");
    // the reactions of the span not solved are the whole solve's too
    let reaction = |s: &State| s.reaction_force[ELEMENTS];
    let dr = (reaction(&split) - reaction(&all)).length();
    assert!(dr <= 1e-8 * reaction(&all).length(), "{dr:e} N");
}

#[test]
fn a_hose_within_contact_reach_is_solved_with_the_span() {
    let (model, mut state, hand) = settled(true);
    assert!(model.hose_contact.active);
    let before = state.clone();
    // the hand lifts the span into the hose lying across it
    move_hand(&mut state, hand, DVec3::new(0.0, 0.0, 0.005));
    let ((r_split, split), (_, all)) = both(&model, &state);
    let across = &model.hoses[1];
    assert_eq!(
        r_split.solved_nodes,
        MIDDLE + 1 + across.node_count,
        "{r_split:?}"
    );
    let d = largest_difference(&split, &all);
    eprintln!("split and whole solves {d:e} m apart");
    assert!(d <= SAME_STATE, "split and whole solves {d:e} m apart");
    let middle = across.first_node + across.node_count / 2;
    let lifted = split.x[middle].z - before.x[middle].z;
    assert!(lifted > 5e-4, "the hose across was lifted {lifted:e} m");
    assert!(split.hose_contact_force[middle].z > 0.0);
    for i in MIDDLE + 1..ELEMENTS {
        assert_eq!(split.x[i], before.x[i], "node {i} moved");
    }
}

#[test]
fn a_load_on_a_span_in_balance_gets_it_solved() {
    let (model, mut state, _) = settled(false);
    let before = state.clone();
    // nothing moved: nothing is solved
    let mut solver = StaticSolver::new(&model).unwrap();
    let mut same = state.clone();
    let r = solver.solve(&model, &mut same).unwrap();
    assert!(r.converged && r.iterations == 0, "{r:?}");
    assert_eq!(same.x, before.x);
    // a load in the second span
    let loaded = MIDDLE + 4;
    state.loads.add(LoadCase::DeadLoad(DeadLoad {
        node: loaded,
        force: DVec3::new(0.0, 0.0, -0.5),
        moment: DVec3::ZERO,
        ramp: None,
    }));
    let ((r_split, split), (_, all)) = both(&model, &state);
    assert_eq!(r_split.solved_nodes, ELEMENTS - MIDDLE + 1, "{r_split:?}");
    assert!(r_split.iterations > 0);
    let d = largest_difference(&split, &all);
    eprintln!("split and whole solves {d:e} m apart");
    assert!(d <= SAME_STATE, "split and whole solves {d:e} m apart");
    assert!(split.x[loaded].z < before.x[loaded].z - 1e-3);
    for i in 0..=MIDDLE {
        assert_eq!(split.x[i], before.x[i], "node {i} moved");
        assert_eq!(split.q[i], before.q[i], "node {i} turned");
    }
}
