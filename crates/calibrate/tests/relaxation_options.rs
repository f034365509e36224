//! A relaxation test's options: `terms = N` forces the Prony term count, `held_strain`
//! gives the instantaneous modulus E₀ (so a relaxation test alone makes a material).

use pliant_calibrate::synthetic_laws::{self as syn, two_column_csv};
use pliant_calibrate::{calibrate_texts, Spec};
use pliant_core::material::PronyTerm;
use pliant_core::Section;

const E0: f64 = 10e6;
const STRAIN: f64 = 0.05;
const TERMS: [PronyTerm; 2] = [
    PronyTerm {
        weight: 0.3,
        time: 2.0,
    },
    PronyTerm {
        weight: 0.2,
        time: 60.0,
    },
];

/// The held force of the relaxing element (10/16 mm section) at 91 times over 4.6
/// decades.
fn curve() -> String {
    let t: Vec<f64> = std::iter::once(0.0)
        .chain((0..90).map(|i| 0.05 * 10f64.powf(i as f64 / 89.0 * 4.6)))
        .collect();
    let material = syn::relaxing_material(E0, &TERMS);
    let f = syn::held_strain_force(&material, &Section::new(0.010, 0.016), STRAIN, &t);
    two_column_csv("time_s,force_N", &t, &f, 0.0, 1)
}

fn calibrate(options: &str) -> Result<pliant_calibrate::Calibration, pliant_calibrate::CalibError> {
    let spec = Spec::parse(
        &format!(
            "name = \"rubber\"\nd_inner_mm = 10\nd_outer_mm = 16\ndensity_kg_m3 = 1100\n\
             [[tests]]\nkind = \"relaxation\"\ncsv = \"r.csv\"\n{options}"
        ),
        "r.toml",
    )?;
    calibrate_texts(spec, &[("r.csv".into(), curve())], "r.toml")
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn the_held_strain_gives_the_instantaneous_modulus() {
    let c = calibrate("held_strain = 0.05\n").unwrap();
    let f = &c.laws[0];
    let e0 = f.estimate("E0").unwrap();
    println!("E0 = {} (95 % CI {:?})", e0.value, e0.ci95);
    // the element's law integrates in closed form: the fit's convergence is what is left
    assert!(rel(e0.value, E0) < 1e-6, "{e0:?}");
    assert!(rel(c.material.e_tension_mpa.value, E0 * 1e-6) < 1e-6);
    assert_eq!(c.material.laws.relaxation.len(), 2);
    // without it, a relaxation test alone is refused, naming the option
    let e = calibrate("").unwrap_err();
    assert!(e.message.contains("held_strain"), "{e}");
    // a torque curve takes none
    let spec = Spec::parse(
        "name = \"r\"\nd_inner_mm = 10\nd_outer_mm = 16\ndensity_kg_m3 = 1100\n[[tests]]\nkind = \"relaxation\"\ncsv = \"r.csv\"\nheld_strain = 0.05\n",
        "r.toml",
    )
    .unwrap();
    let torque = curve().replacen("force_N", "torque_Nm", 1);
    let e = calibrate_texts(spec, &[("r.csv".into(), torque)], "r.toml").unwrap_err();
    assert!(e.message.contains("torque"), "{e}");
}

#[test]
fn terms_forces_the_count() {
    // BIC chooses the two terms the element has
    let c = calibrate("held_strain = 0.05\n").unwrap();
    assert_eq!(c.material.laws.relaxation.len(), 2);
    // one term asked for: one term, though two fit better
    let c = calibrate("held_strain = 0.05\nterms = 1\n").unwrap();
    assert_eq!(c.material.laws.relaxation.len(), 1);
    assert!(
        c.laws[0].checks[0].contains("asked for"),
        "{:?}",
        c.laws[0].checks
    );
    // two asked for: the element's own terms
    let c = calibrate("held_strain = 0.05\nterms = 2\n").unwrap();
    for (got, want) in c.material.laws.relaxation.iter().zip(TERMS) {
        assert!(rel(got.weight.value, want.weight) < 1e-6, "{got:?}");
        assert!(rel(got.time_s.value, want.time) < 1e-6, "{got:?}");
    }
    // four asked for from a two-term curve: not identified, an error naming the count
    let e = calibrate("held_strain = 0.05\nterms = 4\n").unwrap_err();
    assert!(e.message.contains("4 Prony term"), "{e}");
    // out of range, or on another kind
    let e = calibrate("terms = 9\n").unwrap_err();
    assert!(e.message.contains("terms = 9"), "{e}");
    let e = Spec::parse(
        "name = \"r\"\nd_inner_mm = 10\nd_outer_mm = 16\ndensity_kg_m3 = 1100\n[[tests]]\nkind = \"tension\"\ncsv = \"r.csv\"\nterms = 2\n",
        "r.toml",
    )
    .unwrap_err();
    assert!(e.message.contains("terms is for a relaxation test"), "{e}");
}
