//! SPEC L6: the press fit of a hose end on a connector stub and its state machine.

use glam::DVec3;
use pliant_assembly::stub::{
    contact_pressure, Friction, PressFit, StubError, StubObservation, StubSpec, StubState,
    StubTolerance,
};
use std::f64::consts::PI;

/// A 28 mm stub, 30 mm long, mouth at the origin, pushed on along +z; friction
/// coefficients γ_H = 0.6, γ_G = 0.4 (test values: dry elastomer on plastic).
fn stub28() -> StubSpec {
    StubSpec::new(
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 3.0),
        0.030,
        0.028,
        0.6,
        0.4,
    )
    .unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

#[test]
fn hose3_on_a_28mm_stub_matches_the_hand_calculation() {
    let (material, section) = pliant_testkit::hose3();
    let fit = PressFit::new(&stub28(), &section, &material).unwrap();

    // r_i = 13.5 mm, r_a = 17.5 mm, r_s = 14 mm.
    // Q = r_i / r_a = 13.5 / 17.5 = 0.771428…;  Q² = 729 / 1225 = 0.595102…
    // 1 − Q² = 496 / 1225 = 0.404898…;  1 + Q² = 1954 / 1225 = 1.595102…
    // ν (1 − Q²) = 0.49 · 0.404898 = 0.198400
    // (1 − Q²) / ((1 + Q²) + ν (1 − Q²)) = 0.404898 / 1.793502 = 6200 / 27463 = 0.2257583
    // δ = r_s − r_i = 0.5 mm;  δ / r_s = 0.5 / 14 = 0.0357143
    // E = E_t = 6.9442 MPa (the wall is stretched circumferentially)
    // p = 6.9442e6 Pa · 0.0357143 · 0.2257583 = 55 989.67 Pa ≈ 56.0 kPa
    let q2 = (13.5f64 / 17.5).powi(2);
    let shape = (1.0 - q2) / ((1.0 + q2) + 0.49 * (1.0 - q2));
    let p_hand = 6.9442e6 * (0.5 / 14.0) * shape;
    assert!(close(p_hand, 55_989.669_217, 1e-10), "hand value {p_hand}");
    assert!(
        close(fit.pressure(), p_hand, 1e-12),
        "{} vs {p_hand}",
        fit.pressure()
    );
    assert!(close(fit.interference(), 0.0005, 1e-12));

    // Contact area at depth l = 20 mm: 2π · r_s · l = 2π · 0.014 · 0.020 = 1.759292e-3 m².
    // f_static  = p · 0.6 · 1.759292e-3 = 59.10 N
    // f_sliding = p · 0.4 · 1.759292e-3 = 39.40 N
    let area = 2.0 * PI * 0.014 * 0.020;
    let f_static = p_hand * 0.6 * area;
    let f_sliding = p_hand * 0.4 * area;
    assert!(close(f_static, 59.101_302, 1e-7), "{f_static}");
    assert!(close(f_sliding, 39.400_868, 1e-7), "{f_sliding}");
    assert!(close(
        fit.axial_force(0.020, Friction::Static),
        f_static,
        1e-12
    ));
    assert!(close(
        fit.axial_force(0.020, Friction::Sliding),
        f_sliding,
        1e-12
    ));
    assert!(close(fit.holding_force(0.020), f_static, 1e-12));
}

#[test]
fn the_modulus_is_a_choice_and_can_be_given() {
    let (material, section) = pliant_testkit::hose3();
    let with_ec =
        PressFit::with_modulus(&stub28(), &section, material.e_compression, 0.49).unwrap();
    let with_et = PressFit::new(&stub28(), &section, &material).unwrap();
    // p is linear in E.
    assert!(close(
        with_ec.pressure() / with_et.pressure(),
        8.6913 / 6.9442,
        1e-12
    ));
}

#[test]
fn insertion_depth_is_clamped_to_the_stub() {
    let (material, section) = pliant_testkit::hose3();
    let fit = PressFit::new(&stub28(), &section, &material).unwrap();
    let full = fit.axial_force(0.030, Friction::Static);
    assert_eq!(fit.axial_force(0.050, Friction::Static), full);
    assert_eq!(fit.axial_force(f64::INFINITY, Friction::Static), full);
    assert_eq!(fit.axial_force(-0.01, Friction::Static), 0.0);
    assert_eq!(fit.axial_force(f64::NAN, Friction::Static), 0.0);
    assert!(close(
        fit.axial_force(0.015, Friction::Sliding) * 2.0,
        fit.axial_force(0.030, Friction::Sliding),
        1e-12
    ));
}

#[test]
fn no_press_fit_when_the_bore_is_as_wide_as_the_stub() {
    let (material, section) = pliant_testkit::hose3();
    for d_s in [0.027, 0.020] {
        let stub = StubSpec::new(DVec3::ZERO, DVec3::Z, 0.03, d_s, 0.6, 0.4).unwrap();
        let fit = PressFit::new(&stub, &section, &material).unwrap();
        assert_eq!(fit.pressure(), 0.0);
        assert!(fit.interference() <= 0.0);
        assert_eq!(fit.holding_force(0.02), 0.0);
    }
    assert_eq!(
        contact_pressure(6.9442e6, 0.49, 0.0135, 0.0175, 0.0135),
        Ok(0.0)
    );
}

#[test]
fn bad_stubs_and_materials_are_errors() {
    assert!(matches!(
        StubSpec::new(DVec3::ZERO, DVec3::ZERO, 0.03, 0.028, 0.6, 0.4),
        Err(StubError::Spec { field: "axis", .. })
    ));
    assert!(StubSpec::new(DVec3::ZERO, DVec3::Z, -0.03, 0.028, 0.6, 0.4).is_err());
    assert!(StubSpec::new(DVec3::ZERO, DVec3::Z, 0.03, f64::NAN, 0.6, 0.4).is_err());
    assert!(StubSpec::new(DVec3::ZERO, DVec3::Z, 0.03, 0.028, -0.1, 0.4).is_err());
    assert!(contact_pressure(0.0, 0.49, 0.0135, 0.0175, 0.014).is_err());
    assert!(contact_pressure(1e6, 0.6, 0.0135, 0.0175, 0.014).is_err());
    assert!(contact_pressure(1e6, 0.49, 0.0, 0.0175, 0.014).is_err());
    assert!(contact_pressure(1e6, 0.49, 0.02, 0.0175, 0.014).is_err());
    let err = contact_pressure(1e6, f64::NAN, 0.0135, 0.0175, 0.014).unwrap_err();
    assert_eq!(err.to_string(), "press fit poisson: must lie in (-1, 0.5]");
}

#[test]
fn stub_specs_read_from_toml_are_checked() {
    let text = "origin = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 2.0]\nlength = 0.03\ndiameter = 0.028\nfriction_static = 0.6\nfriction_sliding = 0.4\n";
    let stub: StubSpec = toml::from_str(text).unwrap();
    assert_eq!(stub.axis(), DVec3::Z);
    let bad = text.replace("diameter = 0.028", "diameter = -1.0");
    let err = toml::from_str::<StubSpec>(&bad).unwrap_err();
    assert!(err.to_string().contains("diameter"), "{err}");
}

fn observe(z: f64, force: f64, grabbed: bool) -> StubObservation {
    StubObservation {
        end_position: DVec3::new(0.001, 0.0, z),
        end_direction: DVec3::Z,
        axial_force: force,
        grabbed,
    }
}

#[test]
fn push_on_release_and_pull_off() {
    let (material, section) = pliant_testkit::hose3();
    let stub = stub28();
    let fit = PressFit::new(&stub, &section, &material).unwrap();
    let tol = StubTolerance::for_stub(&stub);
    let step = |s: StubState, obs: StubObservation| s.next(&fit, &tol, &obs).unwrap();

    // Far away, or not grabbed: nothing happens.
    assert_eq!(
        step(StubState::Approach, observe(-0.1, 0.0, true)),
        StubState::Approach
    );
    assert_eq!(
        step(StubState::Approach, observe(-0.01, 0.0, false)),
        StubState::Approach
    );
    // Tilted by 45° (> 30°): not aligned.
    let tilted = StubObservation {
        end_direction: DVec3::new(1.0, 0.0, 1.0),
        ..observe(-0.01, 0.0, true)
    };
    assert_eq!(step(StubState::Approach, tilted), StubState::Approach);
    // Off to the side by more than r_s: not aligned.
    let aside = StubObservation {
        end_position: DVec3::new(0.02, 0.0, -0.01),
        ..observe(0.0, 0.0, true)
    };
    assert_eq!(step(StubState::Approach, aside), StubState::Approach);

    let s = step(StubState::Approach, observe(-0.01, 0.0, true));
    assert_eq!(s, StubState::Aligned);
    assert_eq!(s.resisting_force(&fit), 0.0);
    let s = step(s, observe(0.020, 40.0, true));
    assert_eq!(s, StubState::Inserting { depth: 0.020 });
    assert_eq!(s.friction(), Some(Friction::Sliding));
    assert_eq!(
        s.resisting_force(&fit),
        fit.axial_force(0.020, Friction::Sliding)
    );
    // Past the stop: depth stays at the stub's length.
    let s = step(s, observe(0.045, 80.0, true));
    assert_eq!(s, StubState::Inserting { depth: 0.030 });
    // Back to 20 mm and let go: fixed there.
    let s = step(s, observe(0.020, 0.0, true));
    let s = step(s, observe(0.020, 0.0, false));
    assert_eq!(s, StubState::Fixed { depth: 0.020 });
    assert_eq!(s.friction(), Some(Friction::Static));

    // Grabbed again and pulled with less than the holding force (59.10 N): stays fixed.
    let hold = fit.holding_force(0.020);
    assert_eq!(step(s, observe(0.020, -0.99 * hold, true)), s);
    // Pulled with more: breaks loose, slides, and comes off.
    let s = step(s, observe(0.020, -1.01 * hold, true));
    assert_eq!(s, StubState::Inserting { depth: 0.020 });
    let s = step(s, observe(0.005, -40.0, true));
    assert_eq!(s, StubState::Inserting { depth: 0.005 });
    let s = step(s, observe(-0.002, -5.0, true));
    assert_eq!(s, StubState::PulledOff);
    assert_eq!(s.depth(), 0.0);
    // One step later it is an ordinary approach again.
    assert_eq!(step(s, observe(-0.1, 0.0, true)), StubState::Approach);
    assert_eq!(step(s, observe(-0.002, 0.0, true)), StubState::Aligned);
}

#[test]
fn a_push_at_the_stop_cannot_move_a_fixed_hose() {
    let (material, section) = pliant_testkit::hose3();
    let stub = stub28();
    let fit = PressFit::new(&stub, &section, &material).unwrap();
    let tol = StubTolerance::for_stub(&stub);
    let fixed = StubState::Fixed { depth: 0.030 };
    let hard_push = observe(0.030, 10.0 * fit.holding_force(0.030), true);
    assert_eq!(fixed.next(&fit, &tol, &hard_push).unwrap(), fixed);
    let hard_push_midway = observe(0.010, 10.0 * fit.holding_force(0.010), true);
    assert_eq!(
        StubState::Fixed { depth: 0.010 }
            .next(&fit, &tol, &hard_push_midway)
            .unwrap(),
        StubState::Inserting { depth: 0.010 }
    );
}

#[test]
fn bad_observations_are_errors() {
    let (material, section) = pliant_testkit::hose3();
    let stub = stub28();
    let fit = PressFit::new(&stub, &section, &material).unwrap();
    let tol = StubTolerance::for_stub(&stub);
    let zero_dir = StubObservation {
        end_direction: DVec3::ZERO,
        ..observe(0.0, 0.0, true)
    };
    assert!(StubState::Approach.next(&fit, &tol, &zero_dir).is_err());
    assert!(StubState::Approach
        .next(&fit, &tol, &observe(f64::NAN, 0.0, true))
        .is_err());
    assert!(StubState::Approach
        .next(&fit, &tol, &observe(0.0, f64::INFINITY, true))
        .is_err());
    let bad_tol = StubTolerance { angle: -1.0, ..tol };
    assert!(StubState::Approach
        .next(&fit, &bad_tol, &observe(0.0, 0.0, true))
        .is_err());
}
