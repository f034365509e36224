//! The example calibration in examples/calibration/ (synthetic curves with known
//! answers) recovers its answers. Regenerate the files with
//! `PLIANT_WRITE_EXAMPLES=1 cargo test --release -p pliant-calibrate --test examples`.

use pliant_calibrate::synthetic::{example_files, Truth};
use std::path::Path;

/// Noise (relative to each curve's largest value) and seed of the shipped example.
const NOISE: f64 = 0.002;
const SEED: u64 = 1;

fn folder() -> &'static Path {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/calibration"
    ))
}

#[test]
fn the_example_recovers_its_known_stiffness() {
    let truth = Truth::EXAMPLE;
    if std::env::var_os("PLIANT_WRITE_EXAMPLES").is_some() {
        std::fs::create_dir_all(folder()).unwrap();
        let (files, _) = example_files(&truth, NOISE, SEED);
        for (name, text) in files {
            std::fs::write(folder().join(name), text).unwrap();
        }
    }
    let c = pliant_calibrate::calibrate_file(&folder().join("hose.toml")).unwrap();
    let want = [
        truth.e_tension,
        truth.e_compression,
        truth.ei(),
        truth.gj(),
        truth.ei(),
    ];
    assert_eq!(c.fits.len(), want.len());
    for (f, w) in c.fits.iter().zip(want) {
        let rel = (f.value - w) / w;
        eprintln!(
            "{:>20}: {} = {:.6e} (truth {w:.6e}, error {:+.3} %), 95 % CI [{:.6e}, {:.6e}] {}, range rows {}-{}",
            f.kind.name(),
            f.symbol,
            f.value,
            100.0 * rel,
            f.ci95[0],
            f.ci95[1],
            if f.ci95[0] <= w && w <= f.ci95[1] { "covers" } else { "MISSES" },
            f.range.first_row,
            f.range.last_row
        );
        assert!(rel.abs() < 0.01, "{:?}: {} vs {w}", f.kind, f.value);
    }
    let m = &c.material;
    assert!((m.e_tension_mpa.value - 11.583).abs() < 0.1);
    assert!((m.poisson.value - 0.45).abs() < 0.02);
}

/// The law examples: a metal line past yield (moment–curvature, torsion, cantilever,
/// three-point bending), a relaxing rubber and a bundle with friction, each a calibration
/// file of its own with curves from the simulator's own laws (the aluminium AC line of
/// the library, EN AW-6063 T6 12 × 1 mm; an EPDM-like rubber of E₀ 10 MPa; a
/// hysteretic element) and 0.2 % noise. Regenerated with the other examples. Each file
/// runs, and its truth lies within a few of its intervals' half-widths — the fibre
/// grid's own error included for the metal line (tests/yield_tests.rs, laws.rs).
#[test]
fn the_law_examples_give_their_laws_back() {
    use pliant_calibrate::beam_deflection::{Beam, Support};
    use pliant_calibrate::synthetic_laws::{self as syn, two_column_csv};
    use pliant_core::material::{DahlLaw, Hysteresis, PronyTerm, YieldLaw};
    use pliant_core::Section;
    let (di, da, e, nu) = (0.010, 0.012, 70e9, 0.3);
    let law = YieldLaw {
        yield_stress: 170e6,
        hardening_modulus: 580e6,
    };
    let section = syn::simulator_section(di, da, e, nu, &law);
    let kappa_e = law.yield_stress / (e * 0.5 * da);
    let g = e / (2.0 * (1.0 + nu));
    let rate_e = law.yield_stress / 3f64.sqrt() / (g * 0.5 * da);
    let p = [e, law.yield_stress, law.hardening_modulus];
    let beam_curve = |support: Support, length: f64| {
        let beam = Beam {
            support,
            ri: 0.5 * di,
            ro: 0.5 * da,
            length,
        };
        let (lever, _) = beam.lever_and_factor();
        let i = Section::new(di, da).second_moment();
        let f_max = 1.3 * law.yield_stress * i / (0.5 * da * lever);
        let force = syn::load_unload(f_max, 0.0, 50, 30);
        let d_mm: Vec<f64> = force
            .iter()
            .enumerate()
            .map(|(k, f)| {
                1e3 * if k <= 50 {
                    beam.deflection(p, *f)
                } else {
                    beam.deflection(p, f_max) - 2.0 * beam.deflection(p, 0.5 * (f_max - f))
                }
            })
            .collect();
        two_column_csv("force_N,deflection_mm", &force, &d_mm, NOISE, SEED)
    };
    let kappa = syn::load_unload(5.0 * kappa_e, 0.0, 60, 40);
    let rate = syn::load_unload(5.0 * rate_e, -rate_e, 60, 40);
    let grips = 0.2;
    let angle: Vec<f64> = rate.iter().map(|r| (r * grips).to_degrees()).collect();
    let terms = [
        PronyTerm {
            weight: 0.3,
            time: 2.0,
        },
        PronyTerm {
            weight: 0.2,
            time: 60.0,
        },
    ];
    let t: Vec<f64> = std::iter::once(0.0)
        .chain((0..90).map(|i| 0.05 * 10f64.powf(i as f64 / 89.0 * 4.6)))
        .collect();
    let rubber = syn::relaxing_material(10e6, &terms);
    let held = syn::held_strain_force(&rubber, &Section::new(0.010, 0.016), 0.05, &t);
    let dahl = Hysteresis {
        bending: DahlLaw {
            moment: 0.02,
            curvature: 0.5,
        },
        torsion: Some(DahlLaw {
            moment: 0.01,
            curvature: 0.8,
        }),
    };
    let bundle = syn::hysteretic_material(10e6, dahl);
    let bundle_section = Section::new(0.0, 0.012);
    let cycles = syn::cycles(5.0, 2, 120);
    let bent = syn::cyclic_moments(&bundle, &bundle_section, &cycles, 1);
    let twist = syn::cycles(6.0, 2, 120);
    let twisted = syn::cyclic_moments(&bundle, &bundle_section, &twist, 0);
    let twist_deg: Vec<f64> = twist.iter().map(|r| (r * 0.25).to_degrees()).collect();
    let files = [
        (
            "plastic_bending.csv",
            two_column_csv(
                "curvature_1_m,moment_Nm",
                &kappa,
                &syn::bend_section(&section, &kappa),
                NOISE,
                SEED,
            ),
        ),
        (
            "plastic_torsion.csv",
            two_column_csv(
                "angle_deg,torque_Nm",
                &angle,
                &syn::twist_section(&section, &rate),
                NOISE,
                SEED,
            ),
        ),
        (
            "plastic_cantilever.csv",
            beam_curve(Support::Cantilever, 0.15),
        ),
        (
            "plastic_three_point_bending.csv",
            beam_curve(Support::ThreePoint, 0.4),
        ),
        (
            "relaxation.csv",
            two_column_csv("time_s,force_N", &t, &held, NOISE, SEED),
        ),
        (
            "cyclic_bending.csv",
            two_column_csv("curvature_1_m,moment_Nm", &cycles, &bent, NOISE, SEED),
        ),
        (
            "cyclic_torsion.csv",
            two_column_csv("angle_deg,torque_Nm", &twist_deg, &twisted, NOISE, SEED),
        ),
    ];
    if std::env::var_os("PLIANT_WRITE_EXAMPLES").is_some() {
        for (name, text) in &files {
            std::fs::write(folder().join(name), text).unwrap();
        }
    }
    // (file, parameter, truth) of each example
    let sy = law.yield_stress;
    let checks: [(&str, &[(&str, f64)]); 8] = [
        ("metal_line.toml", &[("E", e), ("sigma_y", sy)]),
        (
            "metal_line_torsion.toml",
            &[("G", g), ("tau_y", sy / 3f64.sqrt())],
        ),
        (
            "metal_line_bending_and_torsion.toml",
            &[("E", e), ("sigma_y", sy), ("G", g)],
        ),
        ("metal_line_cantilever.toml", &[("E", e), ("sigma_y", sy)]),
        ("metal_line_three_point.toml", &[("E", e), ("sigma_y", sy)]),
        (
            "rubber_relaxation.toml",
            &[("E0", 10e6), ("g1", 0.3), ("tau2", 60.0)],
        ),
        ("bundle_friction.toml", &[("M_s", 0.02), ("kappa_s", 0.5)]),
        (
            "bundle_friction.toml",
            &[("M_s_torsion", 0.01), ("kappa_s_torsion", 0.8)],
        ),
    ];
    for (file, truths) in checks {
        let c = pliant_calibrate::calibrate_file(&folder().join(file))
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        for (name, truth) in truths {
            let est = c
                .laws
                .iter()
                .find_map(|f| f.estimate(name))
                .unwrap_or_else(|| panic!("{file}: no {name}"));
            let half = 0.5 * (est.ci95[1] - est.ci95[0]);
            let off = (est.value - truth).abs();
            eprintln!(
                "{file}: {name} = {:.6e} (truth {truth:.6e}), off by {:.2} half-widths of its 95 % interval",
                est.value,
                off / half
            );
            assert!(off < 3.0 * half.max(2e-3 * truth.abs()), "{file}: {name}");
        }
    }
}
