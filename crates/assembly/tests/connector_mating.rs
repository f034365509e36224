//! The connector's mating law: the measured curve interpolated linearly, held outside its
//! points; pulling out needs the curve before the latch and the retention force after; a
//! released plug is assembled only when latched; bad curves are refused.

use glam::DVec3;
use pliant_assembly::stub::{
    AxialLaw, Friction, Mating, Sense, StubError, StubObservation, StubSpec, StubState,
    StubTolerance,
};

fn counterpart() -> StubSpec {
    StubSpec::new(DVec3::ZERO, DVec3::X, 0.008, 0.02, 0.0, 0.0).unwrap()
}

fn mating() -> Mating {
    let curve = [(0.001, 10.0), (0.005, 50.0), (0.006, 20.0)];
    Mating::new(counterpart(), &curve, 0.0055, 110.0).unwrap()
}

#[test]
fn the_curve_is_linear_between_its_points_and_held_outside() {
    let m = mating();
    assert_eq!(m.mating_force(0.0), 10.0);
    assert!((m.mating_force(0.003) - 30.0).abs() < 1e-12);
    assert!((m.mating_force(0.0055) - 35.0).abs() < 1e-12);
    assert_eq!(m.mating_force(0.008), 20.0);
    assert_eq!(m.mating_force(f64::NAN), 10.0);
    assert_eq!(m.peak_force(), 50.0);
}

#[test]
fn pulling_needs_the_curve_before_the_latch_and_the_retention_after() {
    let m = mating();
    let pull = |s| m.axial_force_moving(s, Friction::Static, Sense::Off);
    assert!((pull(0.003) - 30.0).abs() < 1e-12);
    assert_eq!(pull(0.0055), 110.0);
    assert_eq!(pull(0.007), 110.0);
    assert!(!m.assembled_at(0.005) && m.assembled_at(0.0055));
}

#[test]
fn a_latched_plug_breaks_loose_only_above_its_retention_force() {
    let m = mating();
    let tolerance = StubTolerance::for_stub(m.counterpart());
    let fixed = StubState::Fixed { depth: 0.007 };
    let pulled = |force: f64| StubObservation {
        end_position: DVec3::new(0.007, 0.0, 0.0),
        end_direction: DVec3::X,
        axial_force: -force,
        grabbed: true,
    };
    assert_eq!(fixed.next(&m, &tolerance, &pulled(100.0)).unwrap(), fixed);
    assert_eq!(
        fixed.next(&m, &tolerance, &pulled(120.0)).unwrap(),
        StubState::Inserting { depth: 0.007 }
    );
    // short of the latch, the curve holds it: 30 N at 3 mm
    let half = StubState::Fixed { depth: 0.003 };
    let at_half = StubObservation {
        end_position: DVec3::new(0.003, 0.0, 0.0),
        ..pulled(31.0)
    };
    assert!(matches!(
        half.next(&m, &tolerance, &at_half).unwrap(),
        StubState::Inserting { .. }
    ));
}

#[test]
fn bad_curves_latches_and_retentions_are_refused() {
    let refused = |curve: &[(f64, f64)], latch: f64, retention: f64| match Mating::new(
        counterpart(),
        curve,
        latch,
        retention,
    ) {
        Err(StubError::Spec { field, .. }) => field,
        other => panic!("accepted: {other:?}"),
    };
    assert_eq!(refused(&[], 0.005, 1.0), "mating_force");
    assert_eq!(
        refused(&[(0.0, 1.0), (0.0, 2.0)], 0.005, 1.0),
        "mating_force"
    );
    assert_eq!(
        refused(&[(0.0, 1.0), (0.009, 2.0)], 0.005, 1.0),
        "mating_force"
    );
    assert_eq!(refused(&[(0.0, -1.0)], 0.005, 1.0), "mating_force");
    assert_eq!(refused(&[(0.0, f64::NAN)], 0.005, 1.0), "mating_force");
    assert_eq!(refused(&[(0.0, 1.0)], 0.0, 1.0), "latch_at");
    assert_eq!(refused(&[(0.0, 1.0)], 0.009, 1.0), "latch_at");
    assert_eq!(
        refused(&[(0.0, 1.0)], 0.005, f64::INFINITY),
        "retention_force"
    );
    let many: Vec<(f64, f64)> = (0..17).map(|k| (k as f64 * 1e-4, 1.0)).collect();
    assert_eq!(refused(&many, 0.005, 1.0), "mating_force");
}

#[test]
fn a_plug_found_past_the_mouth_is_not_taken_as_plugged_it_must_come_through_the_mouth() {
    let m = mating();
    let tolerance = StubTolerance::for_stub(m.counterpart());
    let at = |s: f64| StubObservation {
        end_position: DVec3::new(s, 0.0, 0.0),
        end_direction: DVec3::X,
        axial_force: 0.0,
        grabbed: true,
    };
    // drawn home (a harness's route is its plugged shape) and grabbed: still approaching
    let state = StubState::Approach
        .next(&m, &tolerance, &at(0.0075))
        .unwrap();
    assert_eq!(state, StubState::Approach);
    // brought out in front of the mouth, then pushed in
    let state = state.next(&m, &tolerance, &at(-0.002)).unwrap();
    assert_eq!(state, StubState::Aligned);
    let state = state.next(&m, &tolerance, &at(0.001)).unwrap();
    assert_eq!(state, StubState::Inserting { depth: 0.001 });
}
