//! `pliant calibrate` for bundles: a cantilever test and a torsion test of a bundle, made
//! with Pliant's own beam (the static solver) at known coupling factors, give the factors
//! back; bad input gives errors that name the file and the reason, and writes nothing.

use std::fmt::Write as _;
use std::path::Path;

use pliant_harness::bundle::{bundle_section, BundleData, WireSection};
use pliant_harness::bundle_calibration::{calibrate_bundle_file, is_bundle_spec};
use pliant_harness::Stiffness;

/// The tested bundle: 7 wires of 0.5 mm² (1.6 mm) and 3 of 2.5 mm² (2.9 mm).
const WIRES: &str = "wires = [{ outer_diameter_mm = 1.6, cross_section_mm2 = 0.5, count = 7 }, { outer_diameter_mm = 2.9, cross_section_mm2 = 2.5, count = 3 }]";

fn tested_wires(data: &BundleData) -> Vec<WireSection> {
    let mut w = vec![WireSection::new(data, 1.6e-3, 0.5e-6, None, None); 7];
    w.extend(vec![WireSection::new(data, 2.9e-3, 2.5e-6, None, None); 3]);
    w
}

/// The end state of Pliant's beam (static solver, 20 elements, no gravity) of length `l`
/// \[m\], clamped at node 0, with a bundle's section (`gj` \[N·m²\] if given, else the
/// material's), under the load `load` at its free end (a `force_n` or `moment_nm` line).
fn pliant_beam(l: f64, d_outer: f64, ei: f64, gj: Option<f64>, load: &str) -> pliant_core::State {
    let gj = gj.map(|gj| format!(", gj_n_m2 = {gj}")).unwrap_or_default();
    let scene = format!(
        r#"
format = "pliant-scene"
version = 1
name = "bundle_test"
length_unit = "mm"

[simulation]
gravity = [0, 0, 0]
solver = "static"

[materials.m]
e_tension_mpa = 500
e_compression_mpa = 500
poisson = 0.4
density_kg_m3 = 2000

[[hoses]]
name = "bundle"
material = "m"
section = {{ d_inner = 0, d_outer = {d}, ei1_n_m2 = {ei}, ei2_n_m2 = {ei}{gj} }}
start = [0, 0, 0]
path = [{{ line = {{ to = [{l}, 0, 0] }} }}]
elements = 20

[[timeline]]
action = "fix"
hose = "bundle"
node = 0

[[timeline]]
action = "load"
hose = "bundle"
node = -1
{load}

[[timeline]]
action = "run"
duration_s = 0.05
"#,
        d = d_outer * 1e3,
        l = l * 1e3,
    );
    let scene = pliant_scene::load_scene_str_in(&scene, "bundle.toml", Path::new("."))
        .unwrap_or_else(|e| panic!("{e}"));
    let (cell, run) = pliant_runs::run_with(&scene, Some(pliant_core::SolverKind::Static)).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    cell.state().clone()
}

/// Tip deflection \[m\] of Pliant's cantilever of length `l` \[m\] and bending stiffness
/// `ei` \[N·m²\] under a tip force `f` \[N\].
fn pliant_cantilever_tip(l: f64, d_outer: f64, ei: f64, f: f64) -> f64 {
    let state = pliant_beam(l, d_outer, ei, None, &format!("force_n = [0, 0, {}]", -f));
    -state.x[20].z
}

/// Twist \[rad\] between the clamped and the free end node's material frame of Pliant's
/// beam of length `l` \[m\] and torsional stiffness `gj` \[N·m²\] under a torque `t`
/// \[N·m\] about its axis at the free end.
fn pliant_twist(l: f64, d_outer: f64, gj: f64, ei: f64, t: f64) -> f64 {
    let state = pliant_beam(
        l,
        d_outer,
        ei,
        Some(gj),
        &format!("moment_nm = [{t}, 0, 0]"),
    );
    let q = &state.q;
    let (axis, angle) = (q[q.len() - 1] * q[0].conjugate()).to_axis_angle();
    angle * axis.x.signum()
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

fn spec(csv: &str, kind: &str, length_mm: f64, protection: &str, wires: &str) -> String {
    format!(
        "format = \"pliant-bundle-calibration\"\nkind = \"{kind}\"\ncsv = \"{csv}\"\nlength_mm = {length_mm}\nprotection = \"{protection}\"\n{wires}\n"
    )
}

#[test]
fn a_cantilever_of_pliants_own_beam_gives_its_factor_back() {
    let data = BundleData::builtin();
    let wires = tested_wires(&data);
    let b = bundle_section(&data, &wires, None);
    let f_true = 0.35;
    let ei = b.ei_slip + f_true * (b.ei_bond - b.ei_slip);
    println!(
        "bundle: EI slip {:.4e}, bonded {:.4e}, at f = {f_true}: {ei:.4e} N·m², D = {:.2} mm",
        b.ei_slip,
        b.ei_bond,
        b.d_outer * 1e3
    );
    // 12 loads up to a tip deflection of 0.5 % of the length (the linear range).
    let l = 0.2;
    let f_max = 0.005 * 3.0 * ei / (l * l);
    let mut csv = String::from("force_N,deflection_mm\n");
    for k in 1..=12 {
        let f = f_max * k as f64 / 12.0;
        let delta = pliant_cantilever_tip(l, b.d_outer, ei, f);
        writeln!(csv, "{f:.9e},{:.9e}", delta * 1e3).unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bend.csv", &csv);
    let text = spec("bend.csv", "cantilever", l * 1e3, "tape", WIRES);
    assert!(is_bundle_spec(&text));
    write(dir.path(), "bundle.toml", &text);
    let c = calibrate_bundle_file(&dir.path().join("bundle.toml")).unwrap();
    println!(
        "fitted f_ei = {:.6} (95 % CI {:.6} – {:.6}), EI = {:.6e} N·m² ({:+.3e} relative); {} of {} points",
        c.fit.factor,
        c.factor_ci95[0],
        c.factor_ci95[1],
        c.fit.measured,
        c.fit.measured / ei - 1.0,
        c.test.range.points,
        c.test.range.total_points
    );
    // The bounds are the model's own; the factor comes back within 10⁻⁴ (measured:
    // 2·10⁻⁶; Pliant's beam of 20 elements at ≤ 0.5 % deflection against δ = F L³/(3 EI)).
    assert!((c.fit.slip / b.ei_slip - 1.0).abs() < 1e-12);
    assert!((c.fit.bond / b.ei_bond - 1.0).abs() < 1e-12);
    assert!(
        (c.fit.factor - f_true).abs() < 1e-4,
        "f_ei = {} (true {f_true})",
        c.fit.factor
    );
    assert!((c.section.ei / ei - 1.0).abs() < 1e-4);
    assert!(c.factor_ci95[0] <= c.fit.factor && c.fit.factor <= c.factor_ci95[1]);
    assert_eq!(c.fit.key(), "tape");

    // Written: bundle.toml loads as the bundle model's data and carries the factor.
    let out = dir.path().join("out");
    let paths = c.write(&out).unwrap();
    assert_eq!(paths.len(), 3);
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    let back = BundleData::from_toml(&read("bundle.toml")).unwrap();
    assert_eq!(back.protection["tape"].f_ei.value, c.fit.factor);
    assert!(back.protection["tape"]
        .f_ei
        .source
        .starts_with("calibrated"));
    assert_eq!(
        back.protection["fleece_tape"].f_ei.value,
        data.protection["fleece_tape"].f_ei.value
    );
    let json: serde_json::Value = serde_json::from_str(&read("calibration.json")).unwrap();
    assert_eq!(json["kind"], "bundle");
    assert_eq!(json["f_ei"].as_f64().unwrap(), c.fit.factor);
    let html = read("calibration.html");
    assert_eq!(html.matches("<svg").count(), 2);
}

#[test]
fn a_torsion_test_of_pliants_own_beam_gives_its_factor_back() {
    let data = BundleData::builtin();
    let wires = tested_wires(&data);
    let b = bundle_section(&data, &wires, None);
    let f_true = 0.35;
    let gj = b.gj_slip + f_true * (b.gj_bond - b.gj_slip);
    println!(
        "bundle: GJ slip {:.4e}, bonded {:.4e}, at f = {f_true}: {gj:.4e} N·m²",
        b.gj_slip, b.gj_bond
    );
    // 12 torques up to 5° of twist over 200 mm, the twist read between the material
    // frames of the end nodes (the grips).
    let l = 0.2;
    let grips = l;
    let t_max = 5f64.to_radians() * gj / grips;
    let mut csv = String::from("torque_Nm,angle_deg\n");
    for k in 1..=12 {
        let t = t_max * k as f64 / 12.0;
        let theta = pliant_twist(l, b.d_outer, gj, b.ei, t);
        writeln!(csv, "{t:.9e},{:.9e}", theta.to_degrees()).unwrap();
    }
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "twist.csv", &csv);
    let text = spec("twist.csv", "torsion", grips * 1e3, "tape", WIRES);
    write(dir.path(), "bundle.toml", &text);
    let c = calibrate_bundle_file(&dir.path().join("bundle.toml")).unwrap();
    println!(
        "fitted f_gj = {:.6} (95 % CI {:.6} – {:.6}), GJ = {:.6e} N·m² ({:+.3e} relative); {} of {} points",
        c.fit.factor,
        c.factor_ci95[0],
        c.factor_ci95[1],
        c.fit.measured,
        c.fit.measured / gj - 1.0,
        c.test.range.points,
        c.test.range.total_points
    );
    // Uniform torsion of Pliant's rod is linear in its twist: θ = T L / GJ holds to
    // rounding (measured: GJ −1.3·10⁻¹⁰ relative), so the factor comes back within 10⁻⁸.
    assert_eq!(c.fit.stiffness, Stiffness::Torsion);
    assert!((c.fit.slip / b.gj_slip - 1.0).abs() < 1e-12);
    assert!((c.fit.bond / b.gj_bond - 1.0).abs() < 1e-12);
    assert!(
        (c.fit.factor - f_true).abs() < 1e-8,
        "f_gj = {} (true {f_true})",
        c.fit.factor
    );
    assert!((c.section.gj / gj - 1.0).abs() < 1e-8);
    assert!(c.factor_ci95[0] <= c.fit.factor && c.fit.factor <= c.factor_ci95[1]);
    // Written: f_gj replaced with its source, f_ei as it was.
    let out = dir.path().join("out");
    c.write(&out).unwrap();
    let read = |name: &str| std::fs::read_to_string(out.join(name)).unwrap();
    let back = BundleData::from_toml(&read("bundle.toml")).unwrap();
    assert_eq!(back.protection["tape"].f_gj.value, c.fit.factor);
    assert!(back.protection["tape"]
        .f_gj
        .source
        .starts_with("calibrated: torsion test"));
    assert_eq!(
        back.protection["tape"].f_ei.value,
        data.protection["tape"].f_ei.value
    );
    let json: serde_json::Value = serde_json::from_str(&read("calibration.json")).unwrap();
    assert_eq!(json["f_gj"].as_f64().unwrap(), c.fit.factor);
    assert_eq!(json["stiffness"], "torsion");
    assert!(json.get("f_ei").is_none());
}

/// Error text of a calibration that must fail; checks that nothing was written.
fn refused(csv_name: &str, csv: &str, spec_text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), csv_name, csv);
    write(dir.path(), "bundle.toml", spec_text);
    let e = calibrate_bundle_file(&dir.path().join("bundle.toml")).unwrap_err();
    assert!(!dir.path().join("out").exists());
    e.to_string()
}

/// A straight force–deflection line of a cantilever of EI `ei`, 200 mm.
fn line_csv(ei: f64) -> String {
    pliant_calibrate::synthetic::cantilever_line(ei, 0.2)
}

#[test]
fn measurements_outside_the_bounds_name_the_bound_and_the_values() {
    let data = BundleData::builtin();
    let b = bundle_section(&data, &tested_wires(&data), None);
    let text = spec("bend.csv", "cantilever", 200.0, "tape", WIRES);
    let e = refused("bend.csv", &line_csv(2.0 * b.ei_bond), &text);
    println!("{e}");
    assert!(e.contains("bend.csv"), "{e}");
    assert!(e.contains("above the bonded bound"), "{e}");
    assert!(e.contains(&format!("{:.4e}", b.ei_bond)), "{e}");
    let e = refused("bend.csv", &line_csv(0.5 * b.ei_slip), &text);
    println!("{e}");
    assert!(e.contains("below the slip bound"), "{e}");
    assert!(e.contains(&format!("{:.4e}", b.ei_slip)), "{e}");
}

#[test]
fn bad_curves_and_specs_are_clear_errors() {
    let text = spec("bend.csv", "cantilever", 200.0, "tape", WIRES);
    let e = refused("bend.csv", "", &text);
    assert!(e.contains("bend.csv") && e.contains("empty file"), "{e}");
    let nan = "force_N,deflection_mm\n0.1,0.1\nNaN,0.2\n";
    let e = refused("bend.csv", nan, &text);
    assert!(e.contains("bend.csv:3") && e.contains("not finite"), "{e}");
    let e = refused("bend.csv", "force_N,deflection_mm\n", &text);
    assert!(e.contains("too few points"), "{e}");
    // The spec itself: (kind, length, protection, wires, extra lines) → the message.
    let both = format!("{WIRES}\nkbl = \"h.kbl\"\nsegment = \"Segment_1\"");
    let one_nan = "wires = [{ outer_diameter_mm = nan, cross_section_mm2 = 0.5 }]";
    let too_many =
        "wires = [{ outer_diameter_mm = 1.6, cross_section_mm2 = 0.5, count = 10000000 }]";
    let cases: [(&str, &str, &str, &str, &str); 7] = [
        (
            "tension",
            "200",
            "tape",
            WIRES,
            "three_point_bending or cantilever, or a torsion test",
        ),
        ("cantilever", "nan", "tape", WIRES, "length_mm = NaN"),
        ("cantilever", "200", "glue", WIRES, "protection = \"glue\""),
        (
            "cantilever",
            "200",
            "tape",
            one_nan,
            "wires[0].outer_diameter_mm = NaN",
        ),
        ("cantilever", "200", "tape", "", "the bundle is missing"),
        ("cantilever", "200", "tape", &both, "not both"),
        ("cantilever", "200", "tape", too_many, "at most 100000"),
    ];
    for (kind, length, protection, wires, message) in cases {
        let text = spec("bend.csv", kind, 200.0, protection, wires).replace("200", length);
        let e = refused("bend.csv", "", &text);
        assert!(e.contains(message), "{e}\n{text}");
    }
    // A single wire has no factor.
    let e = refused(
        "bend.csv",
        &line_csv(1e-3),
        &spec(
            "bend.csv",
            "cantilever",
            200.0,
            "tape",
            "wires = [{ outer_diameter_mm = 1.6, cross_section_mm2 = 0.5 }]",
        ),
    );
    assert!(e.contains("bounds coincide"), "{e}");
}

#[test]
fn a_segment_of_the_main_harness_is_calibrated_by_its_kbl_id() {
    use pliant_harness::model::ProtectionKind;
    let kbl = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/harness/kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl");
    let h = pliant_harness::read_kbl(&kbl).unwrap();
    let data = BundleData::builtin();
    let best = h
        .segments
        .iter()
        .map(|s| pliant_harness::bundle_of_segment(&h, &data, &s.kbl_id).unwrap())
        .filter(|b| {
            b.warnings.is_empty() && b.protection.map(|p| p.kind) == Some(ProtectionKind::Tape)
        })
        .max_by_key(|b| b.wires.len())
        .unwrap();
    let s = &best.section;
    let ei = s.ei_slip + 0.1 * (s.ei_bond - s.ei_slip);
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "bend.csv", &line_csv(ei));
    let text = format!(
        "format = \"pliant-bundle-calibration\"\nkind = \"cantilever\"\ncsv = \"bend.csv\"\nlength_mm = 200\nkbl = \"{}\"\nsegment = \"{}\"\n",
        kbl.display(),
        best.kbl_id
    );
    write(dir.path(), "bundle.toml", &text);
    let c = calibrate_bundle_file(&dir.path().join("bundle.toml")).unwrap();
    // A noise-free line: the factor exactly, the protection from the segment.
    assert!((c.fit.factor - 0.1).abs() < 1e-9, "{}", c.fit.factor);
    assert_eq!(c.fit.key(), "tape");
    assert_eq!(c.fit.wire_count, best.wires.len());
    assert!(c.bundle.starts_with(&best.kbl_id));
    let e = refused(
        "bend.csv",
        &line_csv(ei),
        &text.replace(&best.kbl_id, "Segment_999"),
    );
    assert!(e.contains("no segment \"Segment_999\""), "{e}");
}
