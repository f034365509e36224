//! Validation of the inelastic law fits against curves the simulator's own laws make
//! (`synthetic_laws`: the yielding fibre section, a relaxing and a hysteretic beam
//! element, committed step by step): exact curves give the parameters back within a
//! stated relative error, noisy ones within their 95 % intervals; curves of another law
//! are reported as such, and malformed curves name file, line and reason.

use pliant_calibrate::csv_input;
use pliant_calibrate::synthetic_laws::{self as syn, two_column_csv};
use pliant_calibrate::{fit_law, CalibError, Geometry, LawFit, TestKind};
use pliant_core::material::{DahlLaw, Hysteresis, PronyTerm, YieldLaw};
use pliant_core::Section;

/// The aluminium AC line of the library: EN AW-6063 T6, 10/12 mm.
const D_INNER: f64 = 0.010;
const D_OUTER: f64 = 0.012;
const E_ALU: f64 = 70e9;
const POISSON: f64 = 0.3;
const YIELD: YieldLaw = YieldLaw {
    yield_stress: 170e6,
    hardening_modulus: 580e6,
};

/// Relative errors (E, σ_y, H) of a fit to the simulator's section as built (16 × 32
/// fibres): the quadrature's own error past yield (second order at the elastic core's
/// kink), which H, a small slope past yield, feels most. Measured 5.8e-4, 2.8e-4, 2.6e-2.
const SECTION_TOLERANCE: [f64; 3] = [1e-3, 1e-3, 4e-2];
/// The same against the fibre law on a fine grid (64 × 4 radial, 4096 angular points),
/// whose limit is the closed form the fitter uses. Measured 4.4e-10, 3.9e-10, 3.9e-9.
const FINE_TOLERANCE: [f64; 3] = [1e-6; 3];
/// Relative error on exact curves of the relaxing and hysteretic elements (their laws
/// integrate in closed form: no discretisation error).
const EXACT_TOLERANCE: f64 = 1e-6;

fn geometry(length: Option<f64>) -> Geometry {
    Geometry {
        d_inner: D_INNER,
        d_outer: D_OUTER,
        length,
    }
}

fn fit(kind: TestKind, csv: &str, length: Option<f64>) -> Result<LawFit, CalibError> {
    let table = csv_input::parse(csv, "test.csv")?;
    fit_law(kind, "test.csv", &table, geometry(length))
}

fn value(f: &LawFit, name: &str) -> f64 {
    f.estimate(name).unwrap().value
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Seeds of the noisy curves, and the share of them whose 95 % interval must hold the
/// truth: of 40 draws at nominal 95 % coverage, fewer than 34 covered has probability
/// 1.4 % (binomial) — a fit whose intervals are too narrow fails.
const SEEDS: u64 = 40;
const MIN_COVERAGE: f64 = 0.85;

/// Fits `curve(seed)` for each seed and checks that every parameter of `truths` is
/// identified and inside its interval for at least [`MIN_COVERAGE`] of the seeds.
fn assert_coverage(kind: TestKind, curve: impl Fn(u64) -> String, truths: &[(&str, f64)]) {
    let mut covered = vec![0usize; truths.len()];
    for seed in 0..SEEDS {
        let f = fit(kind, &curve(seed), None)
            .unwrap_or_else(|e| panic!("{} seed {seed}: {e}", kind.name()));
        for ((name, truth), c) in truths.iter().zip(covered.iter_mut()) {
            let e = f.estimate(name).unwrap();
            assert!(e.identified, "seed {seed}: {e:?}");
            if e.ci95[0] <= *truth && *truth <= e.ci95[1] {
                *c += 1;
            }
        }
    }
    for ((name, _), c) in truths.iter().zip(&covered) {
        let share = *c as f64 / SEEDS as f64;
        println!(
            "{}: {name} inside its 95 % interval for {c} of {SEEDS} seeds",
            kind.name()
        );
        assert!(share >= MIN_COVERAGE, "{name}: coverage {share}");
    }
}

fn kappa_e() -> f64 {
    YIELD.yield_stress / (E_ALU * 0.5 * D_OUTER)
}

fn plastic_curve(section: &pliant_core::rod::fibre_section::FibreSection) -> (Vec<f64>, Vec<f64>) {
    let ke = kappa_e();
    let kappa = syn::load_unload(5.0 * ke, 2.0 * ke, 80, 60);
    let m = syn::bend_section(section, &kappa);
    (kappa, m)
}

const PLASTIC_HEADER: &str = "curvature_1_m,moment_Nm";

#[test]
fn the_yield_law_is_recovered_from_the_simulators_section() {
    for (name, section, tolerance) in [
        (
            "simulator's section",
            syn::simulator_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD),
            SECTION_TOLERANCE,
        ),
        (
            "fine section",
            syn::fine_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD, (64, 4096)),
            FINE_TOLERANCE,
        ),
    ] {
        let (kappa, m) = plastic_curve(&section);
        let csv = two_column_csv(PLASTIC_HEADER, &kappa, &m, 0.0, 1);
        let f = fit(TestKind::PlasticBending, &csv, None).unwrap();
        let errors = [
            rel(value(&f, "E"), E_ALU),
            rel(value(&f, "sigma_y"), YIELD.yield_stress),
            rel(value(&f, "H"), YIELD.hardening_modulus),
        ];
        println!("{name}: relative errors E, σ_y, H = {errors:?}");
        assert!(
            errors.iter().zip(tolerance).all(|(e, t)| *e < t),
            "{name}: {errors:?}"
        );
        assert!(f.checks.iter().any(|c| c.contains("springback")));
    }
}

#[test]
fn a_noisy_yield_curve_holds_the_truth_in_its_intervals() {
    let section = syn::fine_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD, (64, 4096));
    let (kappa, m) = plastic_curve(&section);
    assert_coverage(
        TestKind::PlasticBending,
        |seed| two_column_csv(PLASTIC_HEADER, &kappa, &m, 0.003, seed),
        &[
            ("E", E_ALU),
            ("sigma_y", YIELD.yield_stress),
            ("H", YIELD.hardening_modulus),
        ],
    );
}

#[test]
fn an_elastic_curve_is_not_given_a_yield_stress() {
    let ei = E_ALU * Section::new(D_INNER, D_OUTER).second_moment();
    // bent to 0.8 of first yield and back: the law's own elastic range
    let kappa = syn::load_unload(0.8 * kappa_e(), 0.0, 60, 40);
    let section = syn::simulator_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD);
    let m = syn::bend_section(&section, &kappa);
    assert!(m
        .iter()
        .zip(&kappa)
        .all(|(m, k)| rel(*m, ei * k) < 1e-9 || *k == 0.0));
    for noise in [0.0, 0.003] {
        let csv = two_column_csv(PLASTIC_HEADER, &kappa, &m, noise, 4);
        let e = fit(TestKind::PlasticBending, &csv, None).unwrap_err();
        assert!(e.message.contains("never yields"), "{e}");
    }
}

#[test]
fn a_yield_curve_without_unloading_is_an_error() {
    let ke = kappa_e();
    let kappa = syn::load_unload(4.0 * ke, 4.0 * ke, 50, 0);
    let section = syn::simulator_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD);
    let m = syn::bend_section(&section, &kappa);
    let csv = two_column_csv(PLASTIC_HEADER, &kappa, &m, 0.0, 1);
    let e = fit(TestKind::PlasticBending, &csv, None).unwrap_err();
    assert!(e.message.contains("unloading missing"), "{e}");
    assert_eq!(e.line, Some(52), "{e}"); // the header, then rows 0..=50
                                         // a wobble in the loading branch names its line
    let mut rows: Vec<&str> = csv.lines().collect();
    rows.swap(10, 11);
    let e = fit(TestKind::PlasticBending, &rows.join("\n"), None).unwrap_err();
    assert!(e.message.contains("not monotonic"), "{e}");
    assert_eq!(e.line, Some(12), "{e}"); // row 10 now on line 12 falls from line 11's

    let e = fit(
        TestKind::PlasticBending,
        "curvature_1_m,force_N\n0,0\n",
        None,
    )
    .unwrap_err();
    assert!(
        e.message.contains("moment_Nm") || e.message.contains("torque"),
        "{e}"
    );
}

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

fn relaxation_times() -> Vec<f64> {
    std::iter::once(0.0)
        .chain((0..90).map(|i| 0.05 * 10f64.powf(i as f64 / 89.0 * 4.6)))
        .collect()
}

fn relaxation_curve(terms: &[PronyTerm]) -> (Vec<f64>, Vec<f64>) {
    let material = syn::relaxing_material(10e6, terms);
    let t = relaxation_times();
    let f = syn::held_strain_force(&material, &Section::new(0.010, 0.016), 0.05, &t);
    (t, f)
}

#[test]
fn the_prony_series_is_recovered_from_a_relaxing_element() {
    let (t, force) = relaxation_curve(&TERMS);
    assert_eq!(force.len(), t.len());
    let csv = two_column_csv("time_s,force_N", &t, &force, 0.0, 1);
    let f = fit(TestKind::Relaxation, &csv, None).unwrap();
    assert_eq!(f.fit.estimates.len(), 5, "{:?}", f.fit.estimates);
    let errors = [
        rel(value(&f, "g1"), TERMS[0].weight),
        rel(value(&f, "tau1"), TERMS[0].time),
        rel(value(&f, "g2"), TERMS[1].weight),
        rel(value(&f, "tau2"), TERMS[1].time),
    ];
    println!("relaxation: relative errors g1, τ1, g2, τ2 = {errors:?}");
    assert!(errors.iter().all(|e| *e < EXACT_TOLERANCE), "{errors:?}");
    // two terms are found from noisy curves too
    for seed in 0..SEEDS {
        let csv = two_column_csv("time_s,force_N", &t, &force, 0.002, seed);
        let f = fit(TestKind::Relaxation, &csv, None).unwrap();
        assert_eq!(
            f.fit.estimates.len(),
            5,
            "seed {seed}: {:?}",
            f.fit.estimates
        );
    }
    assert_coverage(
        TestKind::Relaxation,
        |seed| two_column_csv("time_s,force_N", &t, &force, 0.002, seed),
        &[
            ("g1", TERMS[0].weight),
            ("tau1", TERMS[0].time),
            ("g2", TERMS[1].weight),
            ("tau2", TERMS[1].time),
        ],
    );
}

#[test]
fn a_curve_that_does_not_relax_is_not_given_a_series() {
    let t = relaxation_times();
    let force = vec![12.5; t.len()];
    for noise in [0.0, 0.002] {
        let csv = two_column_csv("time_s,force_N", &t, &force, noise, 9);
        let e = fit(TestKind::Relaxation, &csv, None).unwrap_err();
        assert!(
            e.message.contains("does not relax") || e.message.contains("not identified"),
            "{e}"
        );
    }
}

#[test]
fn time_must_increase() {
    let e = fit(
        TestKind::Relaxation,
        "time_s,force_N\n0,10\n1,9\n2,8.5\n2,8.4\n3,8.3\n4,8.2\n5,8.1\n",
        None,
    )
    .unwrap_err();
    assert!(e.message.contains("not monotonic"), "{e}");
    assert_eq!(e.line, Some(5));
    let e = fit(TestKind::Relaxation, "time_s,force_N\n0,10\n1,x\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (Some(3), Some(2)), "{e}");
}

const DAHL: DahlLaw = DahlLaw {
    moment: 0.02,
    curvature: 0.5,
};

fn hysteresis() -> Hysteresis {
    Hysteresis {
        bending: DAHL,
        torsion: None,
    }
}

#[test]
fn dahls_pair_is_recovered_from_a_hysteretic_element() {
    let section = Section::new(D_INNER, D_OUTER);
    let e_rubber = 10e6;
    let ei = e_rubber * section.second_moment();
    let kappa = syn::cycles(5.0, 2, 120);
    let m = syn::cyclic_moments(
        &syn::hysteretic_material(e_rubber, hysteresis()),
        &section,
        &kappa,
        1,
    );
    let csv = two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, 0.0, 1);
    let f = fit(TestKind::CyclicBending, &csv, None).unwrap();
    let errors = [
        rel(value(&f, "EI"), ei),
        rel(value(&f, "M_s"), DAHL.moment),
        rel(value(&f, "kappa_s"), DAHL.curvature),
    ];
    println!("cyclic bending: relative errors EI, M_s, κ_s = {errors:?}");
    assert!(errors.iter().all(|e| *e < EXACT_TOLERANCE), "{errors:?}");
    assert_coverage(
        TestKind::CyclicBending,
        |seed| two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, 0.003, seed),
        &[
            ("EI", ei),
            ("M_s", DAHL.moment),
            ("kappa_s", DAHL.curvature),
        ],
    );
}

#[test]
fn an_elastic_loop_is_not_given_friction() {
    let section = Section::new(D_INNER, D_OUTER);
    let kappa = syn::cycles(5.0, 2, 120);
    let mat = pliant_core::Material::isotropic(10e6, 0.45, 1100.0);
    let ei = pliant_core::SectionProperties::of(&section, &mat).bending[0];
    let m: Vec<f64> = kappa.iter().map(|k| ei * k).collect();
    for noise in [0.0, 0.003] {
        let csv = two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, noise, 2);
        let e = fit(TestKind::CyclicBending, &csv, None).unwrap_err();
        assert!(
            e.message.contains("not identified") || e.message.contains("no hysteresis"),
            "{e}"
        );
    }
    let one_way: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
    let m: Vec<f64> = one_way.iter().map(|k| ei * k).collect();
    let csv = two_column_csv("curvature_1_m,moment_Nm", &one_way, &m, 0.0, 2);
    let e = fit(TestKind::CyclicBending, &csv, None).unwrap_err();
    assert!(e.message.contains("no reversal"), "{e}");
}

#[test]
fn no_fit_of_a_law_yields_a_non_finite_number() {
    // degenerate inputs: all zeros, a single repeated point
    for (kind, csv) in [
        (
            TestKind::PlasticBending,
            "curvature_1_m,moment_Nm\n0,0\n0,0\n0,0\n0,0\n0,0\n0,0\n0,0\n0,0\n0,0\n",
        ),
        (
            TestKind::CyclicBending,
            "curvature_1_m,moment_Nm\n0,0\n1,0\n0,0\n1,0\n0,0\n1,0\n0,0\n1,0\n0,0\n",
        ),
        (
            TestKind::Relaxation,
            "time_s,force_N\n0,0\n1,0\n2,0\n3,0\n4,0\n5,0\n6,0\n",
        ),
    ] {
        match fit(kind, csv, None) {
            Ok(f) => panic!("{}: {:?}", kind.name(), f.fit.estimates),
            Err(e) => assert!(!e.message.contains("NaN"), "{e}"),
        }
    }
}

/// A calibration of `tests` (kind, CSV text) on the 10/12 mm tube, its material.toml
/// loaded into a scene: the hose's material as the simulator gets it.
fn calibrated_material(tests: &[(TestKind, String)]) -> pliant_core::Material {
    let mut toml = format!(
        "name = \"calibrated\"\nd_inner_mm = {}\nd_outer_mm = {}\ndensity_kg_m3 = 2700\n",
        D_INNER * 1e3,
        D_OUTER * 1e3
    );
    let mut curves = Vec::new();
    for (i, (kind, csv)) in tests.iter().enumerate() {
        toml.push_str(&format!(
            "[[tests]]\nkind = \"{}\"\ncsv = \"c{i}.csv\"\n",
            kind.name()
        ));
        curves.push((format!("c{i}.csv"), csv.clone()));
    }
    let spec = pliant_calibrate::Spec::parse(&toml, "cal.toml").unwrap();
    let c = pliant_calibrate::calibrate_texts(spec, &curves, "cal.toml").unwrap();
    let scene = format!(
        "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\n{}\n\
         [[hoses]]\nname = \"h\"\nmaterial = \"calibrated\"\nsection = {{ d_inner = 10, d_outer = 12 }}\n\
         elements = 10\nstart = [0, 0, 0]\npath = [{{ line = {{ to = [500, 0, 0] }} }}]\n",
        c.material_toml()
    );
    assert!(c.html().matches("<svg").count() >= 2 * tests.len());
    let loaded = pliant_scene::load_scene_str(&scene, "calibrated.toml")
        .unwrap_or_else(|e| panic!("{e}\n{scene}"));
    loaded.world.hoses[0].material.clone()
}

#[test]
fn the_fitted_laws_load_into_a_scene() {
    // yield: the material as written (6 significant digits) is the truth
    let section = syn::fine_section(D_INNER, D_OUTER, E_ALU, POISSON, &YIELD, (64, 4096));
    let (kappa, m) = plastic_curve(&section);
    let mat = calibrated_material(&[(
        TestKind::PlasticBending,
        two_column_csv(PLASTIC_HEADER, &kappa, &m, 0.0, 1),
    )]);
    let law = mat.plasticity.expect("yields");
    assert!(rel(law.yield_stress, YIELD.yield_stress) < 1e-5, "{law:?}");
    assert!(
        rel(law.hardening_modulus, YIELD.hardening_modulus) < 1e-5,
        "{law:?}"
    );
    assert!(rel(mat.bending_modulus(), E_ALU) < 1e-5);
    // Dahl friction, with EI
    let sec = Section::new(D_INNER, D_OUTER);
    let kappa = syn::cycles(5.0, 2, 120);
    let m = syn::cyclic_moments(
        &syn::hysteretic_material(10e6, hysteresis()),
        &sec,
        &kappa,
        1,
    );
    let mat = calibrated_material(&[(
        TestKind::CyclicBending,
        two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, 0.0, 1),
    )]);
    let h = mat.hysteresis.expect("rubs");
    assert!(
        rel(h.bending.moment, DAHL.moment) < 1e-5
            && rel(h.bending.curvature, DAHL.curvature) < 1e-5
    );
    assert!(rel(mat.bending_modulus(), 10e6) < 1e-5);
    // relaxation, with a tension test for the instantaneous modulus
    let (t, force) = relaxation_curve(&TERMS);
    let strain: Vec<f64> = (0..50).map(|i| i as f64 * 1e-3).collect();
    let stress: Vec<f64> = strain.iter().map(|e| 10e6 * e * 1e-6).collect();
    let mat = calibrated_material(&[
        (
            TestKind::Tension,
            two_column_csv("strain,stress_MPa", &strain, &stress, 1e-4, 2),
        ),
        (
            TestKind::Relaxation,
            two_column_csv("time_s,force_N", &t, &force, 0.0, 1),
        ),
    ]);
    assert_eq!(mat.relaxation.len(), 2);
    for (got, want) in mat.relaxation.iter().zip(TERMS) {
        assert!(
            rel(got.weight, want.weight) < 1e-5 && rel(got.time, want.time) < 1e-5,
            "{got:?}"
        );
    }
    // two laws in one material: an error naming the rule
    let e = pliant_calibrate::calibrate_texts(
        pliant_calibrate::Spec::parse(
            "name = \"x\"\nd_inner_mm = 10\nd_outer_mm = 12\ndensity_kg_m3 = 1\n[[tests]]\nkind = \"cyclic_bending\"\ncsv = \"a.csv\"\n[[tests]]\nkind = \"relaxation\"\ncsv = \"b.csv\"\n",
            "two.toml",
        )
        .unwrap(),
        &[
            ("a.csv".into(), two_column_csv("curvature_1_m,moment_Nm", &kappa, &m, 0.0, 1)),
            ("b.csv".into(), two_column_csv("time_s,force_N", &t, &force, 0.0, 1)),
        ],
        "two.toml",
    )
    .unwrap_err();
    assert!(e.message.contains("not two of these"), "{e}");
}

#[test]
fn dahls_pair_in_torsion_is_recovered_from_a_twisted_element() {
    let section = Section::new(D_INNER, D_OUTER);
    let torsion = DahlLaw {
        moment: 0.01,
        curvature: 0.8,
    };
    let law = Hysteresis {
        bending: DAHL,
        torsion: Some(torsion),
    };
    let material = syn::hysteretic_material(10e6, law);
    let gj = pliant_core::SectionProperties::of(&section, &material).torsion;
    let rate = syn::cycles(6.0, 2, 120);
    let torque = syn::cyclic_moments(&material, &section, &rate, 0);
    // the rig's angle over grips 250 mm apart, in degrees
    let length = 0.25;
    let angle: Vec<f64> = rate
        .iter()
        .map(|r| r * length * 180.0 / std::f64::consts::PI)
        .collect();
    let csv = two_column_csv("angle_deg,torque_Nm", &angle, &torque, 0.0, 1);
    let f = fit(TestKind::CyclicTorsion, &csv, Some(length)).unwrap();
    let errors = [
        rel(value(&f, "GJ"), gj),
        rel(value(&f, "M_s_torsion"), torsion.moment),
        rel(value(&f, "kappa_s_torsion"), torsion.curvature),
    ];
    println!("cyclic torsion: relative errors GJ, M_s, κ_s = {errors:?}");
    assert!(errors.iter().all(|e| *e < EXACT_TOLERANCE), "{errors:?}");
    let e = fit(TestKind::CyclicTorsion, &csv, None).unwrap_err();
    assert!(e.message.contains("length_mm"), "{e}");
}
