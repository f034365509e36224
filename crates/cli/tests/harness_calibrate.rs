//! End-to-end: `pliant calibrate --kind bundle` fits the tape factor of a segment of the
//! generator cable (KBL) from a three-point bending curve, and `pliant import --bundle-data` builds
//! the harness with it; a curve stiffer than the bonded bound is refused, naming it.

use std::path::{Path, PathBuf};

use pliant_harness::bundle::BundleData;

mod common;

use common::{harness_file, pliant, GENERATOR};
use pliant_calibrate::synthetic::cantilever_line;

fn generator() -> PathBuf {
    harness_file(GENERATOR)
}

/// A cantilever curve (free length 200 mm) of bending stiffness `ei` \[N·m²\].
fn three_point_csv(ei: f64) -> String {
    cantilever_line(ei, 0.2)
}

/// `pliant calibrate --kind bundle` of Segment_1 (fleece tape) with a cantilever curve.
fn calibrate(csv: &Path, out: &Path) -> std::process::Output {
    pliant()
        .args([
            "calibrate",
            "--kind",
            "bundle",
            "--bending-test",
            "cantilever",
        ])
        .arg("--csv")
        .arg(csv)
        .args(["--length", "200", "--segment", "Segment_1"])
        .arg("--kbl")
        .arg(generator())
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

#[test]
fn a_bundle_factor_is_calibrated_and_used_by_the_import() {
    let h = pliant_harness::read_kbl(&generator()).unwrap();
    let data = BundleData::builtin();
    let b = pliant_harness::bundle_of_segment(&h, &data, "Segment_1").unwrap();
    let s = &b.section;
    let ei = s.ei_slip + 0.2 * (s.ei_bond - s.ei_slip);
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("bend.csv");
    std::fs::write(&csv, three_point_csv(ei)).unwrap();
    let out = dir.path().join("cal");
    let run = calibrate(&csv, &out);
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    println!("{text}");
    assert!(
        text.contains("protection fleece_tape: f_ei = 0.2 "),
        "{text}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("calibration.json")).unwrap())
            .unwrap();
    assert!((json["f_ei"].as_f64().unwrap() - 0.2).abs() < 1e-9);
    assert_eq!(json["protection"], "fleece_tape");

    // The import with the calibrated data writes the measured EI for the segment.
    let import = |extra: &[&Path], name: &str| {
        let scene = dir.path().join(name);
        let mut cmd = pliant();
        cmd.arg("import").arg(generator());
        if let Some(p) = extra.first() {
            cmd.arg("--bundle-data").arg(p);
        }
        let run = cmd.arg("--out").arg(&scene).output().unwrap();
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        segment_1_taped_ei(&std::fs::read_to_string(scene.join("scene.toml")).unwrap())
    };
    let calibrated = import(&[&out.join("bundle.toml")], "calibrated");
    let builtin = import(&[], "builtin");
    println!("Segment_1 EI: calibrated {calibrated:e}, built-in {builtin:e}, measured {ei:e}");
    assert!((calibrated / ei - 1.0).abs() < 1e-5, "{calibrated} vs {ei}");
    assert!((builtin / ei - 1.0).abs() > 0.1);
}

/// The `ei1_n_m2` of Segment_1's taped stretch (the span its fleece tape covers; the rest
/// of the segment is bare wires) in an imported scene.toml.
fn segment_1_taped_ei(scene: &str) -> f64 {
    let at = scene
        .find("# KBL Segment Segment_1 ")
        .expect("Segment_1 in scene.toml");
    let rest = &scene[at..];
    let spans = &rest[rest.find("spans = [").expect("Segment_1's taped span")..];
    let v = &spans[spans.find("ei1_n_m2 = ").unwrap() + 11..];
    v[..v.find(',').unwrap()].trim().parse().unwrap()
}

#[test]
fn a_curve_stiffer_than_the_bonded_bound_is_refused() {
    let h = pliant_harness::read_kbl(&generator()).unwrap();
    let b = pliant_harness::bundle_of_segment(&h, &BundleData::builtin(), "Segment_1").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("bend.csv");
    std::fs::write(&csv, three_point_csv(3.0 * b.section.ei_bond)).unwrap();
    let out = dir.path().join("cal");
    let run = calibrate(&csv, &out);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("bend.csv") && err.contains("above the bonded bound"),
        "{err}"
    );
    assert!(!out.exists());
    let bad = pliant()
        .args(["calibrate", "--kind", "bundle", "--csv"])
        .arg(&csv)
        .args(["--length", "200"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--kbl FILE and --segment ID"));
}
