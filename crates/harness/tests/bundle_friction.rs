//! The default friction between a bundle's wires (data/bundle.toml, modelling choices):
//! the taped bundle's law traces the closed-form Dahl loop energy per cycle, and
//! `import` writes it into the scene only when asked (`bundle_friction`).

use std::path::{Path, PathBuf};

use pliant_calibrate::synthetic_laws::{cycles, cyclic_moments, hysteretic_material};
use pliant_core::material::{DahlLaw, Hysteresis};
use pliant_core::Section;
use pliant_harness::bundle::{
    bundle_friction, bundle_section, BundleData, ProtectionCover, WireSection,
};
use pliant_harness::model::ProtectionKind;
use pliant_harness::{import_kbl_opts, ImportOptions};

mod common;
use common::*;

fn out_dir(name: &str) -> PathBuf {
    common::out_dir("harness-tests", name)
}

/// Dahl's steady loop between ±κ_a dissipates W = 4 M_s κ_s (a − tanh a), a = κ_a/κ_s:
/// on the rising branch z = M_s − (M_s + z_a) e^{−(κ+κ_a)/κ_s} with z_a = M_s tanh a
/// at the turning points, and W = 2 ∫ z dκ over it (the elastic part stores and returns).
fn loop_energy(law: DahlLaw, amplitude: f64) -> f64 {
    let a = amplitude / law.curvature;
    4.0 * law.moment * law.curvature * (a - a.tanh())
}

#[test]
fn the_taped_bundles_loop_dissipates_the_closed_form_energy() {
    let data = BundleData::builtin();
    // twenty 0.35 mm² FLRY-like wires of 1.3 mm under full-wrap tape
    let wires: Vec<WireSection> = (0..20)
        .map(|_| WireSection::new(&data, 1.3e-3, 0.35e-6, None, None))
        .collect();
    let cover = ProtectionCover {
        kind: ProtectionKind::Tape,
        coverage: 1.0,
        outer_diameter: None,
        mass_per_length: None,
    };
    let sec = bundle_section(&data, &wires, Some(cover));
    let f = bundle_friction(&data, &sec).expect("tape has friction");
    // the data's rule: κ_s = 0.01/D, M_s/κ_s = 1.0 EI
    assert!((f.bending.curvature * sec.d_outer - 0.01).abs() < 1e-12);
    assert!((f.bending.moment / f.bending.curvature / sec.ei - 1.0).abs() < 1e-12);
    let law = Hysteresis {
        bending: DahlLaw {
            moment: f.bending.moment,
            curvature: f.bending.curvature,
        },
        torsion: Some(DahlLaw {
            moment: f.torsion.moment,
            curvature: f.torsion.curvature,
        }),
    };
    let material = hysteretic_material(10e6, law);
    let section = Section::new(0.0, sec.d_outer);
    // bent between ± 3 κ_s, a routing curvature: four cycles, the last one measured
    // (the loop settles by e^{−2a} = 2.5e-3 per half cycle from the virgin start)
    for (axis, pair, name) in [
        (1, law.bending, "bending"),
        (0, law.torsion.unwrap(), "torsion"),
    ] {
        let amplitude = 3.0 * pair.curvature;
        let per_cycle = 40_000;
        let kappa = cycles(amplitude, 4, per_cycle);
        let m = cyclic_moments(&material, &section, &kappa, axis);
        let last = kappa.len() - per_cycle - 1;
        // trapezoidal ∮ M dκ over the last cycle: the element's moments are exact at the
        // points (the law integrates in closed form), the rule's error O(Δκ²)
        let w: f64 = (last..kappa.len() - 1)
            .map(|i| 0.5 * (m[i] + m[i + 1]) * (kappa[i + 1] - kappa[i]))
            .sum();
        let exact = loop_energy(pair, amplitude);
        let error = (w.abs() - exact).abs() / exact;
        println!(
            "{name}: loop energy {:.6e} J/m, closed form {exact:.6e}, relative error {error:.2e}",
            w.abs()
        );
        // measured 3.7e-9 (both); the trapezoid's own error at this step is about that
        assert!(error < 1e-7, "{name}: {error}");
    }
}

#[test]
fn protections_without_friction_get_none() {
    let data = BundleData::builtin();
    let wires: Vec<WireSection> = (0..5)
        .map(|_| WireSection::new(&data, 1.3e-3, 0.35e-6, None, None))
        .collect();
    let bare = bundle_section(&data, &wires, None);
    assert!(bundle_friction(&data, &bare).is_none());
    // a calibrated bundle.toml without the friction keys: none either
    let text = pliant_harness::bundle::BUNDLE_TOML
        .lines()
        .filter(|l| !l.starts_with("dahl_"))
        .collect::<Vec<_>>()
        .join("\n");
    let old = BundleData::from_toml(&text).unwrap();
    let cover = ProtectionCover {
        kind: ProtectionKind::Tape,
        coverage: 1.0,
        outer_diameter: None,
        mass_per_length: None,
    };
    assert!(bundle_friction(&old, &bundle_section(&old, &wires, Some(cover))).is_none());
}

fn import(dir: &Path, friction: bool) -> pliant_scene::LoadedScene {
    let _ = std::fs::remove_dir_all(dir);
    let options = ImportOptions {
        bundle_friction: friction,
        ..ImportOptions::default()
    };
    import_kbl_opts(&data(MAIN), dir, &options).unwrap();
    pliant_scene::load_scene_file(&dir.join("scene.toml")).unwrap()
}

#[test]
fn import_writes_the_friction_only_when_asked() {
    let plain = import(&out_dir("friction-off"), false);
    assert!(plain
        .world
        .hoses
        .iter()
        .all(|h| h.material.hysteresis.is_none()));
    let rubbing = import(&out_dir("friction-on"), true);
    let with: Vec<_> = rubbing
        .world
        .hoses
        .iter()
        .filter(|h| h.material.hysteresis.is_some())
        .collect();
    assert!(!with.is_empty(), "no hose got friction");
    // the taped Segment_3 gets tape's rule on its own section
    let s3 = rubbing
        .world
        .hoses
        .iter()
        .find(|h| h.name == "Segment_3")
        .unwrap();
    let h = s3.material.hysteresis.expect("Segment_3 is taped");
    assert!(h.torsion.is_some());
    println!(
        "{} of {} hoses rub; Segment_3: M_s = {:.4e} N·m over κ_s = {:.4} 1/m",
        with.len(),
        rubbing.world.hoses.len(),
        h.bending.moment,
        h.bending.curvature
    );
    let text = std::fs::read_to_string(out_dir("friction-on").join("scene.toml")).unwrap();
    assert!(
        text.contains("modelling choices"),
        "the scene says what the values are"
    );
    // install.toml too (when written), and it loads
    let install = out_dir("friction-on").join("install.toml");
    if install.is_file() {
        let t = std::fs::read_to_string(&install).unwrap();
        assert!(t.contains("hysteresis ="));
        pliant_scene::load_scene_file(&install).unwrap();
    }
}
