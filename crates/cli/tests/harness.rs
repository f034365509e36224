//! End-to-end: a real wire harness (the generator cable of the VOBES sample data, KBL 2.3:
//! three segments at one Y-junction) imported, inspected, settled and exported, as a
//! user runs `pliant import`, `inspect`, `run` and `export`; the installation by a worker's
//! hands is in `harness_install.rs`.

use std::path::{Path, PathBuf};

mod common;

use common::{harness_file as data, ok, pliant, GENERATOR, MAIN};

/// `pliant import` of the generator cable into `dir/generator`: the folder and what the
/// import printed.
fn import_generator(dir: &Path) -> (PathBuf, String) {
    let scene_dir = dir.join("generator");
    let text = ok(&pliant()
        .arg("import")
        .arg(data(GENERATOR))
        .arg("--out")
        .arg(&scene_dir)
        .output()
        .unwrap());
    (scene_dir, text)
}

#[test]
fn a_harness_is_imported_inspected_installed_and_exported() {
    let dir = tempfile::tempdir().unwrap();
    let (scene_dir, text) = import_generator(dir.path());
    assert!(text.contains("3 segments"), "{text}");
    let scene = scene_dir.join("scene.toml");

    // inspect: three hoses meeting at one junction of degree 3, on the KBL node
    let json: serde_json::Value = serde_json::from_str(&ok(&pliant()
        .args(["inspect", "--json"])
        .arg(&scene)
        .output()
        .unwrap()))
    .unwrap();
    let hoses = json["hoses"].as_array().unwrap();
    assert_eq!(hoses.len(), 3);
    let junctions = json["junctions"].as_array().unwrap();
    assert_eq!(junctions.len(), 1);
    assert_eq!(junctions[0]["degree"], 3);
    // Node_2 of the file lies at (2500, 100, 500) mm
    let p: Vec<f64> = junctions[0]["position"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let expected = [2.5, 0.1, 0.5];
    for k in 0..3 {
        assert!((p[k] - expected[k]).abs() < 1e-7, "{p:?}");
    }
    for h in hoses {
        let nodes = h["nodes"].as_array().unwrap();
        assert_eq!(nodes.len() as u64, h["elements"].as_u64().unwrap() + 1);
    }

    // run: the installed state is reached (the static solver, the scene's own)
    let out = dir.path().join("run");
    ok(&pliant()
        .args(["run", "--quiet"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["completed"], true, "{summary}");
    let settles = summary["settles"].as_array().unwrap();
    assert!(
        !settles.is_empty() && settles.iter().all(|s| s["at_rest"] == true),
        "{summary}"
    );

    // the settling run of an export is planned against --max-steps like `pliant run`:
    // beyond it, refused before it starts, naming the scene and the estimate
    let refused = pliant()
        .arg("export")
        .arg(&scene_dir)
        .arg("--out")
        .arg(dir.path().join("refused"))
        .args(["--max-steps", "10"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(!refused.status.success(), "{err}");
    assert!(
        err.contains("scene.toml") && err.contains("at most 10") && err.contains("--max-steps"),
        "{err}"
    );
    assert!(!dir.path().join("refused").join("harness.kbl").exists());

    // export: the settled route as KBL and STEP; the KBL imports again with the same
    // topology and its segments where the run left them
    let export = dir.path().join("export");
    let text = ok(&pliant()
        .arg("export")
        .arg(&scene_dir)
        .arg("--out")
        .arg(&export)
        .output()
        .unwrap());
    assert!(text.contains("3 with the settled route"), "{text}");
    let step = std::fs::read_to_string(export.join("harness.step")).unwrap();
    assert!(step.starts_with("ISO-10303-21;") && step.contains("B_SPLINE_CURVE_WITH_KNOTS"));
    let again = dir.path().join("again");
    ok(&pliant()
        .arg("import")
        .arg(export.join("harness.kbl"))
        .arg("--out")
        .arg(&again)
        .output()
        .unwrap());
    let reimported: serde_json::Value = serde_json::from_str(&ok(&pliant()
        .args(["inspect", "--json"])
        .arg(again.join("scene.toml"))
        .output()
        .unwrap()))
    .unwrap();
    assert_eq!(reimported["junctions"].as_array().unwrap().len(), 1);
    // the exported centre curves against the settled route (the polyline through the last
    // recorded nodes of each hose, nodes.csv): every point sampled on an exported curve
    // lies within 0.1 mm of the route
    let csv = std::fs::read_to_string(out.join("nodes.csv")).unwrap();
    let last_time = csv
        .lines()
        .skip(1)
        .filter_map(|l| l.split(',').next()?.parse::<f64>().ok())
        .fold(f64::MIN, f64::max);
    let exported = pliant_harness::read_kbl(&export.join("harness.kbl")).unwrap();
    let sampled = pliant_harness::SettledHarness::from_harness(&exported, 0.002);
    let mut checked = 0;
    for (h, hose) in hoses.iter().enumerate() {
        let name = hose["name"].as_str().unwrap();
        let settled: Vec<[f64; 3]> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect::<Vec<_>>())
            .filter(|c| {
                c[0].parse::<f64>().ok() == Some(last_time) && c[1].parse::<usize>().ok() == Some(h)
            })
            .map(|c| {
                [
                    c[3].parse().unwrap(),
                    c[4].parse().unwrap(),
                    c[5].parse().unwrap(),
                ]
            })
            .collect();
        assert!(settled.len() >= 2, "no settled nodes of {name}");
        let curve = sampled
            .get(name)
            .unwrap_or_else(|| panic!("{name} not exported"));
        for p in curve {
            let d = distance_to_polyline(&settled, p.to_array());
            assert!(
                d < 1e-4,
                "{name}: exported point {p:?} is {d} m from the settled route"
            );
        }
        checked += 1;
    }
    assert_eq!(checked, 3);
}

#[test]
fn a_vec_file_with_3d_geometry_is_imported_and_inspected() {
    let dir = tempfile::tempdir().unwrap();
    let vec = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../harness/tests/data/y_harness_3d.vec"
    ));
    let scene_dir = dir.path().join("y");
    let text = ok(&pliant()
        .arg("import")
        .arg(vec)
        .arg("--out")
        .arg(&scene_dir)
        .output()
        .unwrap());
    println!("{text}");
    assert!(text.contains("VEC 2.0.2"), "{text}");
    let inspect = ok(&pliant()
        .arg("inspect")
        .arg(scene_dir.join("scene.toml"))
        .arg("--json")
        .output()
        .unwrap());
    let json: serde_json::Value = serde_json::from_str(&inspect).unwrap();
    let hoses = json["hoses"].as_array().unwrap();
    assert_eq!(hoses.len(), 3);
    let mut lengths: Vec<f64> = hoses
        .iter()
        .map(|h| h["length_m"].as_f64().unwrap())
        .collect();
    lengths.sort_by(f64::total_cmp);
    println!("{lengths:?}");
    // 100 mm, the quarter circle (50 π mm as 64 chords), 200 mm.
    assert!((lengths[0] - 0.1).abs() < 1e-6 && (lengths[2] - 0.2).abs() < 1e-6);
    assert!((lengths[1] / (0.05 * std::f64::consts::PI) - 1.0).abs() < 1e-3);
    assert_eq!(json["junctions"].as_array().unwrap().len(), 1);
    // Topology only: refused saying so.
    let topo = dir.path().join("topology.vec");
    std::fs::write(&topo, "<?xml version=\"1.0\"?><vec:VecContent xmlns:vec=\"http://www.prostep.org/ecad-if/2011/vec\"><VecVersion>2.0.2</VecVersion></vec:VecContent>").unwrap();
    let out = pliant().arg("import").arg(&topo).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("topology.vec: VEC file") && err.contains("topology only"),
        "{err}"
    );
}

#[test]
fn a_vec_file_without_geometry_and_a_broken_kbl_are_refused_clearly() {
    let dir = tempfile::tempdir().unwrap();
    let broken = dir.path().join("broken.kbl");
    let text = std::fs::read_to_string(data(GENERATOR)).unwrap();
    std::fs::write(&broken, &text[..text.len() / 2]).unwrap();
    let out = pliant()
        .arg("import")
        .arg(&broken)
        .arg("--out")
        .arg(dir.path().join("x"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("broken.kbl:"), "{err}");
}

fn distance_to_polyline(line: &[[f64; 3]], p: [f64; 3]) -> f64 {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    line.windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let ab = sub(b, a);
            let t = (dot(sub(p, a), ab) / dot(ab, ab).max(1e-300)).clamp(0.0, 1.0);
            let q = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
            dot(sub(p, q), sub(p, q)).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The main harness (183 segments, 51 junctions, 16 fixings) settles in its installed
/// state with the timeline `pliant import` writes: every static solve converges, the
/// settle ends at rest, every clip holds its segment, and the verdict speaks of the
/// harness's checks, not of a failed solve or a clip left open.
#[test]
fn the_main_harness_settles_in_its_installed_state() {
    let dir = tempfile::tempdir().unwrap();
    let scene_dir = dir.path().join("main");
    ok(&pliant()
        .arg("import")
        .arg(data(MAIN))
        .arg("--out")
        .arg(&scene_dir)
        .output()
        .unwrap());
    let out = dir.path().join("out");
    let run = pliant()
        .args(["run", "--quiet"])
        .arg(scene_dir.join("scene.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let read = |name: &str| -> serde_json::Value {
        let text = std::fs::read_to_string(out.join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}\n{}", String::from_utf8_lossy(&run.stderr)));
        serde_json::from_str(&text).unwrap()
    };
    let summary = read("summary.json");
    assert_eq!(summary["completed"], true, "{summary}");
    assert!(summary["diverged"].is_null(), "{}", summary["diverged"]);
    assert_eq!(summary["newton"]["unconverged_steps"], 0);
    assert_eq!(summary["settles"][0]["at_rest"], true);
    let report = read("report.json");
    let fasteners = report["run"]["fasteners"].as_array().unwrap();
    assert_eq!(fasteners.len(), 16);
    for f in fasteners {
        assert_eq!(f["final_state"], "seated", "{f}");
    }
    let reasons = report["verdict"]["reasons"].as_array().unwrap();
    for r in reasons {
        let r = r.as_str().unwrap();
        assert!(
            r.contains("bend_radius check") || r.contains("no hand acted"),
            "unexpected reason: {r}"
        );
    }
}

/// A clip the hose is drawn through (an installed route: 2 mm from the seat, inside the
/// jaws 5.3 mm deep) holds it from the first step — seated, its snap force never pulling;
/// a clip the hose passes 30 mm outside stays open.
#[test]
fn a_clip_the_hose_is_drawn_through_starts_seated() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(
        &scene,
        r#"format = "pliant-scene"
version = 1
length_unit = "mm"

[[hoses]]
name = "hose"
material = "hose1"
start = [0, 0, 0]
path = [{ line = { to = [600, 0, 0] } }]
elements = 24

[[clips]]
name = "drawn through"
origin = [200, 0, 2]
opening = [0, 0, 1]
orientation = [1, 0, 0]
opening_width = 12
inner_diameter = 16
snap_force_n = 30

[[clips]]
name = "beside"
origin = [400, 0, -30]
opening = [0, 0, 1]
orientation = [1, 0, 0]
opening_width = 12
inner_diameter = 16
snap_force_n = 30

[[timeline]]
action = "fix"
hose = "hose"
node = 0

[[timeline]]
action = "fix"
hose = "hose"
node = 24

[[timeline]]
action = "run"
duration_s = 0.02
"#,
    )
    .unwrap();
    let out = dir.path().join("out");
    let _ = pliant()
        .args(["run", "--quiet", "--solver", "static"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let fasteners = report["run"]["fasteners"].as_array().unwrap();
    let clip = |name: &str| fasteners.iter().find(|f| f["name"] == name).unwrap();
    assert_eq!(clip("drawn through")["final_state"], "seated");
    assert_eq!(clip("drawn through")["max_force"], 0.0);
    assert_eq!(clip("beside")["final_state"], "free");
}

/// `pliant import --bundle-friction` gives the protected bundles their protection's
/// default friction (a material each, with `hysteresis`); without it the scene has none.
#[test]
fn bundle_friction_is_opt_in() {
    let dir = tempfile::tempdir().unwrap();
    for (flag, want) in [(false, false), (true, true)] {
        let out = dir.path().join(if flag { "on" } else { "off" });
        let mut c = pliant();
        c.arg("import").arg(data(MAIN)).arg("--out").arg(&out);
        if flag {
            c.arg("--bundle-friction");
        }
        ok(&c.output().unwrap());
        let scene = std::fs::read_to_string(out.join("scene.toml")).unwrap();
        assert_eq!(
            scene.contains("hysteresis = {"),
            want,
            "--bundle-friction {flag}"
        );
        if want {
            assert!(scene.contains("material = \"bundle_Segment_3\""));
            let inspect = pliant()
                .arg("inspect")
                .arg(out.join("scene.toml"))
                .output()
                .unwrap();
            ok(&inspect);
        }
    }
}
