//! SPEC V4: a stub with a bead — pulling off takes more than pushing on — against a hand
//! calculation of the press fit over the bead's flanks (a sleeve driven up a cone with
//! Coulomb friction).

use glam::DVec3;
use pliant_assembly::stub::{
    Bead, Friction, PressFit, Sense, StubObservation, StubSpec, StubState, StubTolerance,
};
use std::f64::consts::PI;

/// Library hose 3 (d 27/35 mm, E_t 6.9442 MPa, ν 0.49) on a 28 mm stub, 30 mm long,
/// γ_H 0.6, γ_G 0.4, with a bead 1.5 mm high starting 8 mm from the mouth: entry flank
/// 20°, crest 3 mm, back flank 60°.
fn fit() -> PressFit {
    let (material, section) = pliant_testkit::hose3();
    let stub = StubSpec::new(DVec3::ZERO, DVec3::Z, 0.030, 0.028, 0.6, 0.4).unwrap();
    let bead = Bead::new(0.008, 0.0015, 0.003, 20f64.to_radians(), 60f64.to_radians()).unwrap();
    PressFit::new(&stub, &section, &material)
        .unwrap()
        .with_bead(bead)
        .unwrap()
}

/// The hand calculation, typed out on its own: Lamé pressure at radius r, radial force on
/// the crest band, wedge factor.
fn lame(r: f64) -> f64 {
    let (e, nu, ri, ra) = (6.9442e6, 0.49, 0.0135, 0.0175);
    let q2 = (ri / ra) * (ri / ra);
    e * ((r - ri) / r) * (1.0 - q2) / ((1.0 + q2) + nu * (1.0 - q2))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

#[test]
fn forces_over_the_bead_match_the_hand_calculation() {
    let f = fit();
    let (rs, rb, w, g) = (0.014, 0.0155, 0.003, 0.4);
    let n = lame(rb) * 2.0 * PI * rb * w; // radial force of the lip on a flank
    let cyl = |l: f64| lame(rs) * g * 2.0 * PI * rs * l; // eq. 4.107
    let wedge = |deg: f64| {
        let t = f64::tan(deg * PI / 180.0);
        (t + g) / (1.0 - g * t)
    };
    let crest_start = 0.008 + 0.0015 / f64::tan(20.0 * PI / 180.0); // 12.12 mm
    let back = crest_start + w; // back flank from here
    let end = back + 0.0015 / f64::tan(60.0 * PI / 180.0); // to here
                                                           // before the bead: the cylinder alone, either way
    let l = 0.005;
    assert!(close(
        f.axial_force_moving(l, Friction::Sliding, Sense::On),
        cyl(l)
    ));
    assert!(close(
        f.axial_force_moving(l, Friction::Sliding, Sense::Off),
        cyl(l)
    ));
    // pushing on up the entry flank: + N (tan 20° + γ)/(1 − γ tan 20°)
    let l = 0.010;
    let on = f.axial_force_moving(l, Friction::Sliding, Sense::On);
    assert!(close(on, cyl(l) + n * wedge(20.0)), "{on}");
    // pulling off up the back flank: + crest friction + N (tan 60° + γ)/(1 − γ tan 60°)
    let l = 0.5 * (back + end);
    let off = f.axial_force_moving(l, Friction::Sliding, Sense::Off);
    assert!(close(off, cyl(l) + n * g + n * wedge(60.0)), "{off}");
    // the bead's part: pull-off over push-on = the wedge factors' ratio, ≈ 7.8 here
    let bead_on = on - cyl(0.010);
    let bead_off = off - cyl(l) - n * g;
    assert!(close(bead_off / bead_on, wedge(60.0) / wedge(20.0)));
    assert!(bead_off / bead_on > 7.0);
    // the largest force to pull it off exceeds the largest to push it on
    let peak = |sense| {
        (0..=300)
            .map(|k| f.axial_force_moving(1e-4 * k as f64, Friction::Sliding, sense))
            .fold(0.0, f64::max)
    };
    assert!(
        peak(Sense::Off) > 2.0 * peak(Sense::On),
        "{} vs {}",
        peak(Sense::Off),
        peak(Sense::On)
    );
}

#[test]
fn a_fixed_hose_behind_the_bead_breaks_loose_only_under_the_pull_off_force() {
    let f = fit();
    let tol = StubTolerance::for_stub(f.stub());
    let depth = 0.020; // past the bead, lip not on a flank
    let fixed = StubState::Fixed { depth };
    let obs = |axial_force: f64| StubObservation {
        end_position: DVec3::new(0.0, 0.0, depth),
        end_direction: DVec3::Z,
        axial_force,
        grabbed: true,
    };
    let hold_off = f.holding_force_moving(depth, Sense::Off);
    let hold_on = f.holding_force_moving(depth, Sense::On);
    // the crest's friction holds both ways: more than the plain cylinder
    assert!(hold_off > f.holding_force(depth));
    assert_eq!(hold_on, hold_off);
    let stays = fixed.next(&f, &tol, &obs(-0.99 * hold_off)).unwrap();
    assert_eq!(stays, fixed);
    let slides = fixed.next(&f, &tol, &obs(-1.01 * hold_off)).unwrap();
    assert!(matches!(slides, StubState::Inserting { .. }));
    // sliding back, the lip meets the back flank: the resistance jumps there
    let at_flank = StubState::Inserting { depth: 0.0155 }; // back flank: 15.1–16.0 mm
    let r = at_flank.resisting_force_moving(&f, Sense::Off);
    assert!(
        r > 3.0 * at_flank.resisting_force_moving(&f, Sense::On),
        "{r}"
    );
}

#[test]
fn bad_beads_are_refused() {
    assert!(Bead::new(-0.001, 0.001, 0.002, 0.3, 1.0).is_err());
    assert!(Bead::new(0.0, 0.0, 0.002, 0.3, 1.0).is_err());
    assert!(Bead::new(0.0, 0.001, 0.002, 0.0, 1.0).is_err());
    assert!(Bead::new(0.0, 0.001, 0.002, 0.3, std::f64::consts::FRAC_PI_2).is_err());
}
