//! The static solver with Coulomb friction from a hose's first contact with a part: a
//! 0.6 m hose of library hose 1 in 30 elements, clamped at one end, its other end held by a
//! hand, sags onto a block under its middle; the hand then takes the end 2 cm down onto the
//! block and walks it sideways 0.1 mm and 0.4 mm per update (the quasi-static update of
//! `pliant bench`'s Newton rows). The nodes that land on the block do so slipping, from no
//! normal force: the start at which the static solver's friction is weakest. Every update
//! must converge to the solver's residual limit, and the result must be an equilibrium
//! against the block: the contact forces carry the hose's weight less what the clamp and
//! the hand hold, no node's friction exceeds its cone, and no node lies inside the block
//! (the first update's linear predictor carried nodes through its top when taken whole).

use glam::DVec3;
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{Model, RigidPartSpec, SimSettings, State, WorldSpec};
use pliant_testkit::models::{fix_in_place, straight_hose1};

/// A block 0.2 m long (x from 0.2 to 0.4 m) under the hose's middle, its top 2 cm below
/// the hose's straight rest line; μ_s 0.5, μ_k 0.4.
fn block() -> RigidPartSpec {
    let (lo, hi) = (DVec3::new(0.2, -0.3, -0.12), DVec3::new(0.4, 0.5, -0.02));
    RigidPartSpec::cuboid("block", lo, hi, (MU_STATIC, 0.4))
}

const ELEMENTS: usize = 30;
const MU_STATIC: f64 = 0.5;

fn hose_over_block() -> (Model, State) {
    let mut hose = straight_hose1("hose", DVec3::ZERO, DVec3::new(0.6, 0.0, 0.0), ELEMENTS);
    hose.normal_hint = Some(DVec3::Z);
    let mut model = Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: vec![block()],
        settings: SimSettings::default(),
    })
    .unwrap();
    model.hose_contact.active = false;
    let mut state = State::at_rest(&model);
    fix_in_place(&mut state, [0]);
    (model, state)
}

#[test]
fn hand_takes_the_end_down_onto_a_block_and_walks_it() {
    let (model, mut state) = hose_over_block();
    let hand = state.loads.add(LoadCase::Fix(Fix {
        node: ELEMENTS,
        position: state.x[ELEMENTS],
        orientation: state.q[ELEMENTS],
    }));
    let mut solver = StaticSolver::new(&model).unwrap();
    let sag = solver.solve(&model, &mut state).unwrap();
    assert!(sag.converged && !sag.unstable, "sag: {sag:?}");
    let weight = model.mass.iter().sum::<f64>() * 9.81;
    for k in 0..50 {
        let t = k as f64 * 0.002;
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(hand) {
            f.position = DVec3::new(0.6 - 0.05 * t, 0.2 * t, -0.02);
        }
        let r = solver.solve(&model, &mut state).unwrap();
        assert!(r.converged && !r.unstable, "update {k}: {r:?}");
        assert!(
            r.residual_force <= r.force_limit.max(1e-9) * 10.0,
            "update {k}: {r:?}"
        );
        // the hose lies on the block
        let touching = state
            .contact_force
            .iter()
            .filter(|f| **f != DVec3::ZERO)
            .count();
        assert!(
            touching >= 1,
            "update {k}: {touching} nodes touch the block"
        );
        // on the block, not through it: no node's centre below its top over its length
        // (balanced there, a node is pushed deeper by a normal pointing the wrong way)
        for (i, x) in state.x.iter().enumerate() {
            if (0.2..=0.4).contains(&x.x) {
                assert!(x.z >= -0.02, "update {k}: node {i} inside the block at {x}");
            }
        }
        // vertical balance of the whole hose: supports + contact = weight (to 1e-6 of it)
        let support: f64 = state.reaction_force.iter().map(|f| f.z).sum();
        let contact: f64 = state.contact_force.iter().map(|f| f.z).sum();
        assert!(
            (support + contact - weight).abs() <= 1e-6 * weight,
            "update {k}: supports {support} N + contact {contact} N against weight {weight} N"
        );
        // Coulomb: no node's tangential contact force exceeds μ_s times its normal force
        for (i, f) in state.contact_force.iter().enumerate() {
            let (normal, tangential) = (f.z, f.truncate().length());
            assert!(
                tangential <= MU_STATIC * normal * (1.0 + 1e-9) + 1e-12,
                "update {k}, node {i}: |f_t| {tangential} N against μ_s f_n {} N",
                MU_STATIC * normal
            );
        }
    }
}
