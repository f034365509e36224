//! A bending test past yield and a torsion test past yield in one calibration: one
//! material whose E, σ_y and H come from bending and G from torsion, the torsion test's
//! √3 τ_y checked against σ_y (von Mises). Curves of a known material in the fitter's
//! closed form (the section's moment and torque with linear hardening, unloaded by
//! Masing's rule), exact and with noise; and a torsion test of another yield stress,
//! refused.

use pliant_calibrate::load_unload::masing;
use pliant_calibrate::synthetic_laws::{load_unload, two_column_csv};
use pliant_calibrate::{calibrate_texts, CalibError, Calibration, Spec};
use pliant_core::rod::plastic_moment::{hardening_bending_moment, hardening_torque};

/// The aluminium AC line of the library: EN AW-6063 T6, 10/12 mm, 200 mm grip length.
const RI: f64 = 0.005;
const RO: f64 = 0.006;
const E: f64 = 70e9;
const POISSON: f64 = 0.3;
const SIGMA_Y: f64 = 170e6;
const H: f64 = 580e6;
const GRIP: f64 = 0.2;

fn shear_modulus() -> f64 {
    E / (2.0 * (1.0 + POISSON))
}

/// Moment against curvature to 5 κ_e and back to 2 κ_e.
fn bending_csv(noise: f64, seed: u64) -> String {
    let ke = SIGMA_Y / (E * RO);
    let kappa = load_unload(5.0 * ke, 2.0 * ke, 80, 60);
    let mono = |k: f64| hardening_bending_moment(RI, RO, E, SIGMA_Y, H, k);
    let m: Vec<f64> = (0..kappa.len())
        .map(|i| masing(mono, kappa[80], kappa[i], i > 80))
        .collect();
    two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, noise, seed)
}

/// Torque against the angle over the grip length, twist rate to 5 θ′_e and back to
/// θ′_e, of a material of yield stress `sigma_y`.
fn torsion_csv(sigma_y: f64, noise: f64, seed: u64) -> String {
    let g = shear_modulus();
    let rate_e = sigma_y / 3f64.sqrt() / (g * RO);
    let rate = load_unload(5.0 * rate_e, rate_e, 80, 60);
    let mono = |r: f64| hardening_torque(RI, RO, g, sigma_y, H, r);
    let torque: Vec<f64> = (0..rate.len())
        .map(|i| masing(mono, rate[80], rate[i], i > 80))
        .collect();
    let angle_deg: Vec<f64> = rate.iter().map(|r| (r * GRIP).to_degrees()).collect();
    two_column_csv(
        "angle_deg,torque_Nm",
        &angle_deg,
        &torque,
        noise,
        seed + 1000,
    )
}

fn calibrate(bending: String, torsion: String) -> Result<Calibration, CalibError> {
    let spec = Spec::parse(
        &format!(
            "name = \"alu\"\nd_inner_mm = 10\nd_outer_mm = 12\ndensity_kg_m3 = 2700\n\
             [[tests]]\nkind = \"plastic_bending\"\ncsv = \"bend.csv\"\n\
             [[tests]]\nkind = \"plastic_torsion\"\ncsv = \"twist.csv\"\nlength_mm = {}\n",
            GRIP * 1e3
        ),
        "alu.toml",
    )?;
    calibrate_texts(
        spec,
        &[("bend.csv".into(), bending), ("twist.csv".into(), torsion)],
        "alu.toml",
    )
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The number written after `key` in `text`.
fn number_after(text: &str, key: &str) -> f64 {
    let rest = &text[text
        .find(key)
        .unwrap_or_else(|| panic!("{key:?} in {text}"))
        + key.len()..];
    let end = rest.find(' ').unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|e| panic!("{e}: {rest}"))
}

fn inside(ci: Option<[f64; 2]>, truth: f64) -> bool {
    ci.is_some_and(|c| c[0] <= truth && truth <= c[1])
}

#[test]
fn bending_and_torsion_past_yield_make_one_material() {
    let c = calibrate(bending_csv(0.0, 1), torsion_csv(SIGMA_Y, 0.0, 1)).unwrap();
    let m = &c.material;
    let sy = m.laws.yield_stress_mpa.as_ref().unwrap();
    let h = m.laws.hardening_modulus_mpa.as_ref().unwrap();
    let e_b = m.e_bending_mpa.as_ref().unwrap();
    let errors = [
        rel(sy.value, SIGMA_Y * 1e-6),
        rel(h.value, H * 1e-6),
        rel(e_b.value, E * 1e-6),
        rel(m.poisson.value, POISSON),
    ];
    println!("relative errors σ_y, H, E_b, ν = {errors:?}");
    // the curves are the fitter's own law: what is left is its convergence
    assert!(errors.iter().all(|e| *e < 1e-6), "{errors:?}");
    assert!(
        m.gj_held_by_material,
        "G comes from the torsion test through ν"
    );
    // the output says how the two were combined, and σ_y's source names both tests
    let note = m
        .warnings
        .iter()
        .find(|w| w.contains("yield law from two tests"))
        .unwrap_or_else(|| panic!("{:?}", m.warnings));
    assert!(
        note.contains("bend.csv") && note.contains("twist.csv"),
        "{note}"
    );
    assert!(note.contains("agrees"), "{note}");
    let source = sy.source.as_deref().unwrap();
    assert!(
        source.contains("bend.csv") && source.contains("twist.csv"),
        "{source}"
    );
    // material.toml carries the law
    let toml = c.material_toml();
    assert!(toml.contains("yield_stress_mpa = 170"), "{toml}");
}

/// Seeds of the noisy curves and the share whose 95 % intervals must hold the truth:
/// of 40 draws at nominal 95 % coverage, fewer than 34 has probability 1.4 % (binomial).
const SEEDS: u64 = 40;
const MIN_COVERAGE: f64 = 0.85;
/// Noise: standard deviation 0.3 % of the largest moment (torque).
const NOISE: f64 = 0.003;

#[test]
fn noisy_bending_and_torsion_hold_the_truth_in_their_intervals() {
    let mut covered = [0usize; 4];
    for seed in 0..SEEDS {
        let c = calibrate(bending_csv(NOISE, seed), torsion_csv(SIGMA_Y, NOISE, seed))
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        let m = &c.material;
        let torsion = c
            .laws
            .iter()
            .find(|l| l.kind.name() == "plastic_torsion")
            .unwrap();
        let g = torsion.estimate("G").unwrap();
        let tau = torsion.estimate("tau_y").unwrap();
        for (k, hit) in [
            inside(
                m.laws.yield_stress_mpa.as_ref().unwrap().ci95,
                SIGMA_Y * 1e-6,
            ),
            inside(
                m.laws.hardening_modulus_mpa.as_ref().unwrap().ci95,
                H * 1e-6,
            ),
            inside(Some(g.ci95), shear_modulus()),
            inside(Some(tau.ci95), SIGMA_Y / 3f64.sqrt()),
        ]
        .into_iter()
        .enumerate()
        {
            covered[k] += usize::from(hit);
        }
    }
    for (name, c) in ["σ_y", "H", "G", "τ_y"].iter().zip(covered) {
        println!("{name} inside its 95 % interval for {c} of {SEEDS} seeds");
        assert!(
            c as f64 >= MIN_COVERAGE * SEEDS as f64,
            "{name}: {c} of {SEEDS}"
        );
    }
}

#[test]
fn a_torsion_test_of_another_yield_stress_is_refused_naming_both() {
    // 20 % above the bending test's: far outside either interval, with or without noise
    for noise in [0.0, NOISE] {
        let e = calibrate(bending_csv(noise, 3), torsion_csv(1.2 * SIGMA_Y, noise, 3)).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("bend.csv") && text.contains("twist.csv"),
            "{text}"
        );
        let bending = number_after(&text, "bend.csv gives σ_y = ");
        let torsion = number_after(&text, "twist.csv gives √3 τ_y = ");
        assert!(rel(bending, SIGMA_Y * 1e-6) < 0.01, "{text}");
        assert!(rel(torsion, 1.2 * SIGMA_Y * 1e-6) < 0.01, "{text}");
        assert!(text.contains("do not overlap"), "{text}");
    }
}

#[test]
fn two_bending_tests_past_yield_are_still_one_too_many() {
    let spec = Spec::parse(
        "name = \"alu\"\nd_inner_mm = 10\nd_outer_mm = 12\ndensity_kg_m3 = 2700\n\
         [[tests]]\nkind = \"plastic_bending\"\ncsv = \"a.csv\"\n\
         [[tests]]\nkind = \"plastic_bending\"\ncsv = \"b.csv\"\n",
        "alu.toml",
    )
    .unwrap();
    let e = calibrate_texts(
        spec,
        &[
            ("a.csv".into(), bending_csv(0.0, 1)),
            ("b.csv".into(), bending_csv(0.0, 2)),
        ],
        "alu.toml",
    )
    .unwrap_err();
    assert!(e.message.contains("two bending tests past yield"), "{e}");
}
