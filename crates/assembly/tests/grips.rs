//! Grips. A hand holding a clamped hose near its tip
//! turns by 0.3 rad about the hose's axis and 0.2 rad across it; at static equilibrium
//! the firm grip carries a twist (and bending) moment, the axial grip carries no moment
//! about the hose's axis, and the ball grip no moment at all.

use glam::{DQuat, DVec3};
use pliant_assembly::{Grip, Hand, HandLoad};
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{SimSettings, State};

/// Library hose 3, 0.3 m along X in 12 elements, clamped at the root, no gravity; a hand
/// with `grip` grabs the last beam's middle, turns, and the hose settles.
fn turned(grip: Grip) -> HandLoad {
    let mut model = pliant_testkit::hose3_along_x(
        12,
        SimSettings {
            gravity: DVec3::ZERO,
            ..Default::default()
        },
    );
    model.hose_contact.active = false;
    let mut state = State::at_rest(&model);
    state.loads.add(LoadCase::Fix(Fix {
        node: 0,
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
    }));
    let mut hand = Hand::grab_with(&model, &mut state, DVec3::new(0.2875, 0.0, 0.004), grip)
        .expect("a beam to grab");
    assert_eq!(hand.grip(), grip);
    hand.move_along(&[], DVec3::new(0.3, 0.0, 0.2), 0.0, 1.0);
    hand.update(&mut state, 1.0);
    state.time = 1.0;
    let report = StaticSolver::new(&model)
        .unwrap()
        .solve(&model, &mut state)
        .unwrap();
    assert!(report.converged, "{grip:?}: {report:?}");
    hand.load(&model, &state)
}

#[test]
fn loose_grips_carry_no_moment_about_their_free_axes() {
    let firm = turned(Grip::Firm);
    let twist = |l: &HandLoad| l.torque.dot(l.direction);
    let bending = |l: &HandLoad| (l.torque - twist(l) * l.direction).length();
    println!(
        "firm: twist {:.4} N m, bending {:.4} N m",
        twist(&firm),
        bending(&firm)
    );
    assert!(
        twist(&firm).abs() > 0.05,
        "the firm grip twists the hose: {firm:?}"
    );
    let axial = turned(Grip::Axial);
    println!(
        "axial: twist {:.2e} N m, bending {:.4} N m",
        twist(&axial),
        bending(&axial)
    );
    assert!(
        twist(&axial).abs() <= 1e-6 * twist(&firm).abs(),
        "{axial:?}"
    );
    assert!(
        bending(&axial) > 0.05 * bending(&firm),
        "the axial grip bends: {axial:?}"
    );
    let ball = turned(Grip::Ball);
    println!("ball: |moment| {:.2e} N m", ball.torque.length());
    assert!(
        ball.torque.length() <= 1e-6 * firm.torque.length(),
        "{ball:?}"
    );
}
