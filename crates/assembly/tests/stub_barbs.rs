//! A stub with a profile of two barbs — push-on and pull-off peak forces
//! against the hand calculation of the press fit over the profile (docs/physics.md,
//! "Stub profile"): at depth d the axial force is the cylinder's friction, plus N_i γ for
//! every crest the lip has passed, plus N_j (tan α + γ)/(1 − γ tan α) on the flank of barb
//! j under the lip (the entry flank pushing on, the back flank pulling off).

use glam::DVec3;
use pliant_assembly::stub::{Bead, Friction, PressFit, Sense, StubSpec, MAX_PROFILE};
use std::f64::consts::PI;

const G: f64 = 0.4; // sliding friction γ_G

/// Two barbs (gentle 15° ramp, 1 mm crest, steep 55° back), 1.2 and 1.0 mm high, at 4 and
/// 13 mm on a 28 mm stub, 30 mm long; library hose 3 (d 27/35 mm, E_t 6.9442 MPa, ν 0.49).
fn barbs() -> [Bead; 2] {
    let (a, b) = (15f64.to_radians(), 55f64.to_radians());
    [
        Bead::new(0.004, 0.0012, 0.001, a, b).unwrap(),
        Bead::new(0.013, 0.0010, 0.001, a, b).unwrap(),
    ]
}

fn fit() -> PressFit {
    let (material, section) = pliant_testkit::hose3();
    let stub = StubSpec::new(DVec3::ZERO, DVec3::Z, 0.030, 0.028, 0.6, G).unwrap();
    let [b1, b2] = barbs();
    PressFit::new(&stub, &section, &material)
        .unwrap()
        .with_bead(b1)
        .unwrap()
        .with_bead(b2)
        .unwrap()
}

/// Lamé contact pressure of hose 3 on a shaft of radius r, typed out on its own.
fn lame(r: f64) -> f64 {
    let (e, nu, ri, ra) = (6.9442e6, 0.49, 0.0135, 0.0175);
    let q2 = (ri / ra) * (ri / ra);
    e * ((r - ri) / r) * (1.0 - q2) / ((1.0 + q2) + nu * (1.0 - q2))
}

fn wedge(deg: f64) -> f64 {
    let t = f64::tan(deg * PI / 180.0);
    (t + G) / (1.0 - G * t)
}

/// Radial force of the lip on barb i's flank, N_i = p(r_s + h_i) 2π (r_s + h_i) w_i.
fn radial(h: f64) -> f64 {
    let rb = 0.014 + h;
    lame(rb) * 2.0 * PI * rb * 0.001
}

fn cyl(l: f64) -> f64 {
    lame(0.014) * G * 2.0 * PI * 0.014 * l
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

/// Hand calculation of the peaks: pushing on, the force on an entry flank grows with the
/// depth (the cylinder's friction), so barb j's peak is at its crest's start; pulling off,
/// barb j's back flank peaks at its deep end; at full depth (30 mm) the cylinder and both
/// crests rub, either way. Returns (push peak, pull peak) over the whole stroke.
fn hand_peaks() -> (f64, f64) {
    let (n1, n2) = (radial(0.0012), radial(0.0010));
    let t15 = f64::tan(15.0 * PI / 180.0);
    let t55 = f64::tan(55.0 * PI / 180.0);
    let crest1 = 0.004 + 0.0012 / t15;
    let end1 = crest1 + 0.001 + 0.0012 / t55;
    let crest2 = 0.013 + 0.0010 / t15;
    let end2 = crest2 + 0.001 + 0.0010 / t55;
    let push1 = cyl(crest1) + n1 * wedge(15.0);
    let push2 = cyl(crest2) + n1 * G + n2 * wedge(15.0);
    let pull1 = cyl(end1) + n1 * G + n1 * wedge(55.0);
    let pull2 = cyl(end2) + (n1 + n2) * G + n2 * wedge(55.0);
    let full = cyl(0.030) + (n1 + n2) * G;
    (push1.max(push2).max(full), pull1.max(pull2).max(full))
}

#[test]
fn peaks_over_two_barbs_match_the_hand_calculation() {
    let f = fit();
    let (push, pull) = hand_peaks();
    let [b1, b2] = barbs();
    // at the peaks' depths the fit gives the hand calculation to round-off
    let on = |d| f.axial_force_moving(d, Friction::Sliding, Sense::On);
    let off = |d| f.axial_force_moving(d, Friction::Sliding, Sense::Off);
    let model_push = on(b1.crest_start())
        .max(on(b2.crest_start()))
        .max(on(0.030));
    let model_pull = off(b1.end()).max(off(b2.end())).max(off(0.030));
    assert!(close(model_push, push), "{model_push} vs {push}");
    assert!(close(model_pull, pull), "{model_pull} vs {pull}");
    // a scan over the whole stub (0.01 mm) finds nothing above the hand peaks
    let scan = |sense| {
        (0..=3000)
            .map(|k| f.axial_force_moving(1e-5 * k as f64, Friction::Sliding, sense))
            .fold(0.0, f64::max)
    };
    let (scan_on, scan_off) = (scan(Sense::On), scan(Sense::Off));
    assert!(
        scan_on <= push * (1.0 + 1e-12) && scan_on >= 0.99 * push,
        "{scan_on}"
    );
    assert!(
        scan_off <= pull * (1.0 + 1e-12) && scan_off >= 0.99 * pull,
        "{scan_off}"
    );
    println!("two barbs: push-on peak {push:.1} N, pull-off peak {pull:.1} N");
    // barbs: pulling off takes more than pushing on (here the push peak is at full depth,
    // the pull peak on the second barb's back flank)
    assert!(pull > 1.5 * push, "{pull} vs {push}");
}

#[test]
fn between_the_barbs_only_friction_acts_and_it_is_the_same_both_ways() {
    let f = fit();
    let [b1, b2] = barbs();
    let d = 0.5 * (b1.end() + b2.at);
    let expected = cyl(d) + radial(0.0012) * G;
    for sense in [Sense::On, Sense::Off] {
        let got = f.axial_force_moving(d, Friction::Sliding, sense);
        assert!(close(got, expected), "{sense:?}: {got} vs {expected}");
    }
}

#[test]
fn overlapping_or_too_many_barbs_are_refused() {
    let [b1, _] = barbs();
    let f = fit();
    // a third barb starting inside the second
    let inside = Bead::new(0.0135, 0.001, 0.001, 0.3, 0.9).unwrap();
    let err = f.with_bead(inside).unwrap_err().to_string();
    assert!(err.contains("bead.at"), "{err}");
    let (material, section) = pliant_testkit::hose3();
    let mut many = PressFit::new(f.stub(), &section, &material).unwrap();
    for k in 0..MAX_PROFILE {
        let b = Bead::new(0.003 * k as f64, 0.0005, 0.0005, 0.5, 1.0).unwrap();
        many = many.with_bead(b).unwrap();
    }
    let err = many.with_bead(b1).unwrap_err().to_string();
    assert!(err.contains("profile"), "{err}");
}
