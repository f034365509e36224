//! The tests past yield beyond moment–curvature: `plastic_torsion` against the
//! simulator's own fibre section twisted and unloaded; `plastic_cantilever` and
//! `plastic_three_point_bending` against curves of their beam theory (exact and noisy)
//! and, in `plastic_cantilever_solver.rs`, against the static solver's cantilever.

use pliant_calibrate::beam_deflection::{Beam, Support};
use pliant_calibrate::csv_input;
use pliant_calibrate::synthetic_laws::{self as syn, two_column_csv};
use pliant_calibrate::{fit_law, CalibError, Geometry, LawFit, TestKind};
use pliant_core::material::YieldLaw;

/// The aluminium AC line of the library: EN AW-6063 T6, 10/12 mm.
const D_INNER: f64 = 0.010;
const D_OUTER: f64 = 0.012;
const E_ALU: f64 = 70e9;
const POISSON: f64 = 0.3;
const YIELD: YieldLaw = YieldLaw {
    yield_stress: 170e6,
    hardening_modulus: 580e6,
};

fn g_alu() -> f64 {
    E_ALU / (2.0 * (1.0 + POISSON))
}

fn fit(kind: TestKind, csv: &str, d_inner: f64, length: f64) -> Result<LawFit, CalibError> {
    let table = csv_input::parse(csv, "test.csv")?;
    let g = Geometry {
        d_inner,
        d_outer: D_OUTER,
        length: Some(length),
    };
    fit_law(kind, "test.csv", &table, g)
}

fn value(f: &LawFit, name: &str) -> f64 {
    f.estimate(name).unwrap().value
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Twist rates to 5 θ′_e and back to 2 θ′_e, as angles over `length`, and the section's
/// torques.
fn torsion_curve(d_inner: f64, length: f64) -> (Vec<f64>, Vec<f64>) {
    torsion_curve_of(
        &syn::simulator_section(d_inner, D_OUTER, E_ALU, POISSON, &YIELD),
        length,
    )
}

fn torsion_curve_of(
    section: &pliant_core::rod::fibre_section::FibreSection,
    length: f64,
) -> (Vec<f64>, Vec<f64>) {
    let tau_y = YIELD.yield_stress / 3f64.sqrt();
    let rate_e = tau_y / (g_alu() * 0.5 * D_OUTER);
    let rate = syn::load_unload(5.0 * rate_e, -rate_e, 80, 60);
    let torque = syn::twist_section(section, &rate);
    let angle_deg = rate.iter().map(|r| (r * length).to_degrees()).collect();
    (angle_deg, torque)
}

/// The simulator's fibre section (16 × 32 fibres for the tube, 4 × 4 × 32 for the rod)
/// twisted past yield and unloaded gives G, τ_y, H back to the grid's quadrature error
/// (Gauss points in r, second order at the elastic radius ρ where the shear stress
/// kinks), and a fine grid (64 × 4 radial points) to the fitter's own: the fitter is exact
/// and what is left is the simulator's grid.
#[test]
fn the_torsion_yield_law_is_recovered_from_the_simulators_section() {
    let length = 0.2;
    for (name, d_inner) in [("tube", D_INNER), ("solid rod", 0.0)] {
        for (grid, section, tolerance) in [
            (
                "simulator's grid",
                syn::simulator_section(d_inner, D_OUTER, E_ALU, POISSON, &YIELD),
                SECTION_TOLERANCE,
            ),
            (
                "fine grid",
                syn::fine_section(d_inner, D_OUTER, E_ALU, POISSON, &YIELD, (64, 8)),
                FINE_TOLERANCE,
            ),
        ] {
            let (angle, torque) = torsion_curve_of(&section, length);
            let csv = two_column_csv("angle_deg,torque_Nm", &angle, &torque, 0.0, 1);
            let f = fit(TestKind::PlasticTorsion, &csv, d_inner, length).unwrap();
            let errors = [
                rel(value(&f, "G"), g_alu()),
                rel(value(&f, "tau_y"), YIELD.yield_stress / 3f64.sqrt()),
                rel(value(&f, "H"), YIELD.hardening_modulus),
            ];
            println!("{name}, {grid}: relative errors G, τ_y, H = {errors:?}");
            assert!(
                errors.iter().zip(tolerance).all(|(e, t)| *e < t),
                "{name}, {grid}: {errors:?}"
            );
            assert!(f.checks.iter().any(|c| c.contains("springback measured")));
        }
    }
}

/// Relative errors (G, τ_y, H) of the torsion fit to the simulator's grid, about three
/// times the largest measured: tube 6.1e-5, 2.2e-6, 1.6e-3; rod 1.9e-5, 7.2e-5, 8.5e-3.
const SECTION_TOLERANCE: [f64; 3] = [3e-4, 3e-4, 3e-2];
/// The same on the fine grid (64 × 4 radial points; second order in the radial step):
/// tube 1.6e-8, 6.2e-9, 1.6e-7; rod 4.3e-7, 4.6e-7, 3.5e-5.
const FINE_TOLERANCE: [f64; 3] = [2e-6, 2e-6, 1.5e-4];

#[test]
fn a_torsion_curve_without_unloading_or_length_is_refused() {
    let (angle, torque) = torsion_curve(D_INNER, 0.2);
    let csv = two_column_csv("angle_deg,torque_Nm", &angle[..81], &torque[..81], 0.0, 1);
    let e = fit(TestKind::PlasticTorsion, &csv, D_INNER, 0.2).unwrap_err();
    assert!(e.message.contains("unloading missing"), "{e}");
    let csv = two_column_csv("angle_deg,torque_Nm", &angle, &torque, 0.0, 1);
    let table = csv_input::parse(&csv, "test.csv").unwrap();
    let g = Geometry {
        d_inner: D_INNER,
        d_outer: D_OUTER,
        length: None,
    };
    let e = fit_law(TestKind::PlasticTorsion, "test.csv", &table, g).unwrap_err();
    assert!(e.message.contains("length_mm"), "{e}");
}

/// Forces rising to `up_to` times the first-yield force and back to zero, and the beam
/// theory's deflections (Masing on unloading).
fn beam_curve(support: Support, length: f64) -> (Vec<f64>, Vec<f64>) {
    let beam = Beam {
        support,
        ri: 0.5 * D_INNER,
        ro: 0.5 * D_OUTER,
        length,
    };
    let (lever, _) = beam.lever_and_factor();
    let i = std::f64::consts::FRAC_PI_4 * ((0.5 * D_OUTER).powi(4) - (0.5 * D_INNER).powi(4));
    let f_e = YIELD.yield_stress * i / (0.5 * D_OUTER * lever);
    let force = syn::load_unload(1.25 * f_e, 0.0, 60, 40);
    let p = [E_ALU, YIELD.yield_stress, YIELD.hardening_modulus];
    let f_max = 1.25 * f_e;
    let deflection = force
        .iter()
        .enumerate()
        .map(|(k, f)| {
            if k <= 60 {
                beam.deflection(p, *f)
            } else {
                beam.deflection(p, f_max) - 2.0 * beam.deflection(p, 0.5 * (f_max - f))
            }
        })
        .collect();
    (force, deflection)
}

fn beam_cases() -> [(TestKind, Support, f64); 2] {
    [
        (TestKind::PlasticCantilever, Support::Cantilever, 0.15),
        (TestKind::PlasticThreePointBending, Support::ThreePoint, 0.4),
    ]
}

/// The beam kinds give the law back from curves of their own theory (written with 13
/// digits): what is left is the fit's convergence. Measured at most 4e-10.
#[test]
fn the_beam_tests_give_the_law_back_from_their_theory() {
    for (kind, support, length) in beam_cases() {
        let (force, deflection) = beam_curve(support, length);
        let csv = two_column_csv("force_N,deflection_m", &force, &deflection, 0.0, 1);
        let f = fit(kind, &csv, D_INNER, length).unwrap();
        let errors = [
            rel(value(&f, "E"), E_ALU),
            rel(value(&f, "sigma_y"), YIELD.yield_stress),
            rel(value(&f, "H"), YIELD.hardening_modulus),
        ];
        println!("{}: relative errors E, σ_y, H = {errors:?}", kind.name());
        assert!(
            errors.iter().all(|e| *e < 1e-6),
            "{}: {errors:?}",
            kind.name()
        );
        assert!(f.checks.iter().any(|c| c.contains("springback measured")));
    }
}

/// Noisy curves (0.3 % of the largest deflection, 10 seeds): the truth lies inside the
/// 95 % intervals for at least 8 of 10 seeds (fewer than 8 at nominal 95 % coverage has
/// probability 1.2 %, binomial).
#[test]
fn noisy_beam_tests_hold_the_truth_in_their_intervals() {
    const SEEDS: u64 = 10;
    const MIN_COVERED: usize = 8;
    for (kind, support, length) in beam_cases() {
        let (force, deflection) = beam_curve(support, length);
        let truths = [
            ("E", E_ALU),
            ("sigma_y", YIELD.yield_stress),
            ("H", YIELD.hardening_modulus),
        ];
        let mut covered = [0usize; 3];
        for seed in 0..SEEDS {
            let csv = two_column_csv("force_N,deflection_m", &force, &deflection, 0.003, seed);
            let f = fit(kind, &csv, D_INNER, length)
                .unwrap_or_else(|e| panic!("{} seed {seed}: {e}", kind.name()));
            for ((name, truth), c) in truths.iter().zip(covered.iter_mut()) {
                let e = f.estimate(name).unwrap();
                if e.ci95[0] <= *truth && *truth <= e.ci95[1] {
                    *c += 1;
                }
            }
        }
        println!("{}: covered {covered:?} of {SEEDS}", kind.name());
        assert!(covered.iter().all(|c| *c >= MIN_COVERED), "{covered:?}");
    }
}

#[test]
fn an_elastic_beam_curve_is_not_given_a_yield_stress() {
    let length = 0.15;
    let beam = Beam {
        support: Support::Cantilever,
        ri: 0.5 * D_INNER,
        ro: 0.5 * D_OUTER,
        length,
    };
    let c = beam.elastic_compliance(E_ALU);
    let force = syn::load_unload(100.0, 0.0, 40, 20);
    let deflection: Vec<f64> = force.iter().map(|f| f * c).collect();
    let csv = two_column_csv("force_N,deflection_m", &force, &deflection, 0.002, 3);
    let e = fit(TestKind::PlasticCantilever, &csv, D_INNER, length).unwrap_err();
    assert!(e.message.contains("never yields"), "{e}");
}
