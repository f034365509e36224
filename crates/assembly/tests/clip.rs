//! SPEC L7: the clip's force law along its opening and its state machine.

use glam::DVec3;
use pliant_assembly::clip::{ClipError, ClipObservation, ClipSpec, ClipState, ClipTolerance};

/// Opening d₁ = 12 mm, inner diameter d₂ = 16 mm, snap force k = 20 N; seat at
/// (0, 0, 0.1), opening towards +y, seated hose along +x.
fn clip() -> ClipSpec {
    ClipSpec::new(
        DVec3::new(0.0, 0.0, 0.1),
        DVec3::new(0.0, 3.0, 0.0),
        DVec3::new(1.0, 0.5, 0.0), // not perpendicular: its part along n is removed
        0.012,
        0.016,
        20.0,
    )
    .unwrap()
}

/// A hose of d_a = 16 mm.
const R: f64 = 0.008;

#[test]
fn geometry_follows_eq_4_108_and_4_109() {
    let c = clip();
    assert_eq!(c.opening(), DVec3::Y);
    assert_eq!(c.orientation(), DVec3::X);
    // |n| = √(16² − 12²)/2 mm = √112 / 2 = 5.2915 mm.
    let n = (0.016f64.powi(2) - 0.012f64.powi(2)).sqrt() / 2.0;
    assert!((c.opening_distance() - n).abs() < 1e-15);
    // h = √(8² − 6²) mm = √28 = 5.2915 mm.
    let h = (R * R - 0.006f64 * 0.006).sqrt();
    assert!((c.touch_height(R).unwrap() - h).abs() < 1e-15);
    assert!((c.first_touch(R).unwrap() - (n + h)).abs() < 1e-15);
    assert_eq!(c.touch_height(0.006), None);
    assert_eq!(c.touch_height(0.005), None);
}

#[test]
fn force_profile_peaks_at_the_opening_and_vanishes_at_first_touch_and_seat() {
    let c = clip();
    let k = c.snap_force();
    let n = c.opening_distance();
    let touch = c.first_touch(R).unwrap();
    // No touch at and beyond first touch.
    assert_eq!(c.force_along_opening(touch, R), 0.0);
    assert_eq!(c.force_along_opening(touch + 0.01, R), 0.0);
    // Peak k exactly at the opening, resisting (along +n).
    assert!((c.force_along_opening(n, R) - k).abs() < 1e-12);
    // Rising monotonically from first touch to the opening, always resisting.
    let mut last = 0.0;
    for i in 1..=100 {
        let s = touch - (touch - n) * i as f64 / 100.0;
        let f = c.force_along_opening(s, R);
        assert!(f > 0.0 && f <= k + 1e-12, "s = {s}: {f}");
        assert!(f >= last, "not rising at s = {s}");
        last = f;
    }
    // Just past the opening: snaps to a pull-in of magnitude k.
    let just_in = c.force_along_opening(n * (1.0 - 1e-9), R);
    assert!((just_in + k).abs() < 1e-6, "{just_in}");
    // Pulling in (along −n) all the way, falling linearly to 0 at the seat.
    for i in 1..100 {
        let s = n * i as f64 / 100.0;
        let f = c.force_along_opening(s, R);
        assert!((f + k * s / n).abs() < 1e-12, "s = {s}: {f}");
    }
    assert_eq!(c.force_along_opening(0.0, R), 0.0);
    // Behind the seat: pushed back towards it, capped at k.
    assert!(c.force_along_opening(-0.5 * n, R) > 0.0);
    assert!((c.force_along_opening(-0.5 * n, R) - 0.5 * k).abs() < 1e-12);
    assert_eq!(c.force_along_opening(-3.0 * n, R), k);
}

#[test]
fn a_hose_thinner_than_the_opening_feels_nothing() {
    let c = clip();
    let n = c.opening_distance();
    for r in [0.004, 0.006] {
        for s in [-n, 0.0, 0.5 * n, n, 1.5 * n, 3.0 * n] {
            assert_eq!(c.force_along_opening(s, r), 0.0);
        }
    }
    assert_eq!(c.force_along_opening(f64::NAN, R), 0.0);
}

#[test]
fn force_vector_points_along_the_opening() {
    let c = clip();
    let n = c.opening_distance();
    let above = c.origin() + DVec3::new(0.003, 1.2 * n, 0.0);
    let f = c.force_on_hose(above, R);
    assert!(f.y > 0.0 && f.x == 0.0 && f.z == 0.0);
    let inside = c.origin() + DVec3::new(0.0, 0.5 * n, 0.0);
    let f = c.force_on_hose(inside, R);
    assert!((f - DVec3::new(0.0, -10.0, 0.0)).length() < 1e-12);
}

#[test]
fn beam_crossing_the_clip_plane_gives_the_hose_centre() {
    let c = clip();
    let a = DVec3::new(-0.01, 0.002, 0.1);
    let b = DVec3::new(0.03, 0.006, 0.1);
    let m = c.centre_on_segment(a, b).unwrap();
    assert!((m - DVec3::new(0.0, 0.003, 0.1)).length() < 1e-15);
    assert_eq!(c.centre_on_segment(a, DVec3::new(-0.002, 0.0, 0.1)), None);
}

#[test]
fn bad_clips_are_errors() {
    let make =
        |n: DVec3, l: DVec3, d1: f64, d2: f64, k: f64| ClipSpec::new(DVec3::ZERO, n, l, d1, d2, k);
    assert!(matches!(
        make(DVec3::ZERO, DVec3::X, 0.012, 0.016, 20.0),
        Err(ClipError::Spec {
            field: "opening",
            ..
        })
    ));
    assert!(matches!(
        make(DVec3::Y, DVec3::Y, 0.012, 0.016, 20.0),
        Err(ClipError::Spec {
            field: "orientation",
            ..
        })
    ));
    assert!(matches!(
        make(DVec3::Y, DVec3::X, 0.016, 0.012, 20.0),
        Err(ClipError::Spec {
            field: "inner_diameter",
            ..
        })
    ));
    assert!(make(DVec3::Y, DVec3::X, 0.0, 0.016, 20.0).is_err());
    assert!(make(DVec3::Y, DVec3::X, 0.012, 0.016, -1.0).is_err());
    assert!(make(DVec3::Y, DVec3::X, 0.012, 0.016, f64::NAN).is_err());
}

fn at(s: f64, grabbed: bool) -> ClipObservation {
    ClipObservation {
        centre: Some(clip().origin() + s * DVec3::Y),
        radius: R,
        grabbed,
        crossed_seat: false,
    }
}

#[test]
fn snap_in_seat_and_pull_out() {
    let c = clip();
    let tol = ClipTolerance::for_clip(&c);
    let step = |s: ClipState, o: ClipObservation| s.next(&c, &tol, &o).unwrap();
    let n = c.opening_distance();
    let touch = c.first_touch(R).unwrap();

    // Above the clip, not touching: free, no force.
    let s = step(ClipState::Free, at(touch + 0.001, true));
    assert_eq!(s, ClipState::Free);
    assert_eq!(s.force(&c, &at(n, true)), DVec3::ZERO);
    // Touching the jaws: snapping, the clip resists.
    let s = step(s, at(n + 0.5 * (touch - n), true));
    assert_eq!(s, ClipState::Snapping);
    assert!(s.force(&c, &at(n + 0.5 * (touch - n), true)).y > 0.0);
    // Let go between the opening and first touch: still snapping (pushed back out).
    assert_eq!(
        step(s, at(n + 0.5 * (touch - n), false)),
        ClipState::Snapping
    );
    // Past the opening and released half-way in: still snapping, pulled towards the seat.
    let s = step(s, at(0.5 * n, false));
    assert_eq!(s, ClipState::Snapping);
    assert!(s.force(&c, &at(0.5 * n, false)).y < 0.0);
    // In the seat tolerance and released: seated.
    let s = step(s, at(0.05 * n, false));
    assert_eq!(s, ClipState::Seated);
    assert_eq!(s.force(&c, &at(0.05 * n, false)), DVec3::ZERO);
    assert_eq!(step(s, at(0.0, false)), ClipState::Seated);
    // Grabbed again: the force law acts; pulled out past first touch: free.
    let s = step(s, at(0.0, true));
    assert_eq!(s, ClipState::Snapping);
    let s = step(s, at(0.9 * n, true));
    assert_eq!(s, ClipState::Snapping);
    let s = step(s, at(n + 0.9 * (touch - n), true));
    assert_eq!(s, ClipState::Snapping);
    let s = step(s, at(touch, true));
    assert_eq!(s, ClipState::Free);
}

#[test]
fn a_thin_or_misplaced_hose_never_engages() {
    let c = clip();
    let tol = ClipTolerance::for_clip(&c);
    let n = c.opening_distance();
    let thin = ClipObservation {
        radius: 0.005,
        ..at(0.5 * n, true)
    };
    assert_eq!(
        ClipState::Free.next(&c, &tol, &thin).unwrap(),
        ClipState::Free
    );
    let beside = ClipObservation {
        centre: Some(c.origin() + DVec3::new(0.0, 0.5 * n, 0.02)),
        ..at(0.0, true)
    };
    assert_eq!(
        ClipState::Free.next(&c, &tol, &beside).unwrap(),
        ClipState::Free
    );
    let nowhere = ClipObservation {
        centre: None,
        ..at(0.0, true)
    };
    assert_eq!(
        ClipState::Free.next(&c, &tol, &nowhere).unwrap(),
        ClipState::Free
    );
    assert_eq!(
        ClipState::Snapping.next(&c, &tol, &nowhere).unwrap(),
        ClipState::Free
    );
}

#[test]
fn bad_observations_are_errors() {
    let c = clip();
    let tol = ClipTolerance::for_clip(&c);
    let zero_r = ClipObservation {
        radius: 0.0,
        ..at(0.0, true)
    };
    assert!(ClipState::Free.next(&c, &tol, &zero_r).is_err());
    let nan_centre = ClipObservation {
        centre: Some(DVec3::splat(f64::NAN)),
        ..at(0.0, true)
    };
    assert!(ClipState::Free.next(&c, &tol, &nan_centre).is_err());
    let bad_tol = ClipTolerance { seat: -1.0, ..tol };
    assert!(ClipState::Free.next(&c, &bad_tol, &at(0.0, true)).is_err());
}

/// A hose springing back through the seat within one step (a long implicit step, or the
/// static solver's jump to the next equilibrium) has been in the seat: it is seated, as
/// one that stops within the seat tolerance is.
#[test]
fn a_hose_passing_through_the_seat_is_seated() {
    let c = clip();
    let tol = ClipTolerance::for_clip(&c);
    let n = c.opening_distance();
    let outside_seat = at(3.0 * tol.seat, false);
    assert!(3.0 * tol.seat < n);
    assert_eq!(
        ClipState::Snapping.next(&c, &tol, &outside_seat).unwrap(),
        ClipState::Snapping
    );
    let passed = ClipObservation {
        crossed_seat: true,
        ..outside_seat
    };
    assert_eq!(
        ClipState::Snapping.next(&c, &tol, &passed).unwrap(),
        ClipState::Seated
    );
    // not while a hand still holds it there
    let held = ClipObservation {
        grabbed: true,
        ..passed
    };
    assert_eq!(
        ClipState::Snapping.next(&c, &tol, &held).unwrap(),
        ClipState::Snapping
    );
}
