//! End-to-end: real wire harnesses installed by a worker's hands, as a user
//! runs it — `pliant import FILE.kbl --out DIR [--branch ID]`, then `pliant run
//! DIR/install.toml` — on the VOBES sample files of `data/harness/`: the generator cable
//! (three segments at a Y-junction, one fixing, three connectors) and a branch of the main
//! harness with its three fixings and four connectors. Every connector must end plugged and
//! latched, every fixing seated, and the verdict must say why it is (not) feasible: the hand
//! that could not give a connector's or fixing's force, naming it, and any segment bent below
//! its minimum radius. Nothing here depends on the machine's speed.

use std::path::{Path, PathBuf};

mod common;

use common::{harness_file as data, ok, pliant, BATTERY, GENERATOR, MAIN};

/// `pliant import FILE --out dir/name [extra…]`: the folder and what the import printed.
fn import(dir: &Path, file: &str, name: &str, extra: &[&str]) -> (PathBuf, String) {
    let out = dir.join(name);
    let text = ok(&pliant()
        .arg("import")
        .arg(data(file))
        .arg("--out")
        .arg(&out)
        .args(extra)
        .output()
        .unwrap());
    (out, text)
}

/// `pliant run --quiet SCENE --out OUT`: the exit code and report.json.
fn run(scene: &Path, out: &Path) -> (Option<i32>, serde_json::Value) {
    let o = pliant()
        .args(["run", "--quiet"])
        .arg(scene)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let report = std::fs::read_to_string(out.join("report.json")).unwrap_or_else(|e| {
        panic!(
            "no report.json ({e}):\n{}\n{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        )
    });
    (o.status.code(), serde_json::from_str(&report).unwrap())
}

/// The verdict's shape: `feasible` a boolean, `reasons` strings (a feasible verdict says
/// that every hand load stayed within its limit), the solves trusted.
fn verdict(report: &serde_json::Value) -> (bool, Vec<String>) {
    let v = &report["verdict"];
    let feasible = v["feasible"]
        .as_bool()
        .expect("verdict.feasible is a boolean");
    let reasons: Vec<String> = v["reasons"]
        .as_array()
        .expect("verdict.reasons is a list")
        .iter()
        .map(|r| r.as_str().expect("a reason is a string").to_owned())
        .collect();
    if feasible {
        assert!(
            reasons
                .iter()
                .any(|r| r.starts_with("every hand load stayed within its ergonomic limit")),
            "{reasons:?}"
        );
    }
    assert_eq!(v["uncertain"], false, "{v}");
    (feasible, reasons)
}

/// Not feasible for `hose` bent below its minimum radius (`minimum_mm`, as the reason
/// rounds it), with every hand within its limits.
fn assert_only_bent_below(report: &serde_json::Value, hose: &str, minimum_mm: u32) {
    let (feasible, reasons) = verdict(report);
    assert!(!feasible);
    assert!(
        reasons.iter().all(|r| !r.starts_with("hand")),
        "{reasons:?}"
    );
    assert!(
        reasons.iter().any(
            |r| r.starts_with(&format!("hose '{hose}': bend_radius check"))
                && r.contains(&format!("breaks the minimum {minimum_mm} mm"))
        ),
        "{reasons:?}"
    );
}

/// The fasteners of a run by kind: (name, final state, largest force).
fn fasteners(report: &serde_json::Value, kind: &str) -> Vec<(String, String, f64)> {
    report["run"]["fasteners"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["kind"] == kind)
        .map(|f| {
            (
                f["name"].as_str().unwrap().to_owned(),
                f["final_state"].as_str().unwrap().to_owned(),
                f["max_force"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// Every connector latched, its force at the peak of its mating curve (60 N: the
/// product specification's limit for up to 24 positions, `data/installation.toml`) and
/// the latch's drop passed — the force falls to the curve's value behind the latch while
/// the hand still pushes; every fixing seated at its snap force (30 N).
fn assert_plugged_and_seated(report: &serde_json::Value, connectors: usize, clips: usize) {
    let plugged = fasteners(report, "connector");
    assert_eq!(plugged.len(), connectors, "{plugged:?}");
    for (name, state, peak) in &plugged {
        assert_eq!(state, "latched", "connector {name}");
        assert!(
            *peak > 0.95 * 60.0 && *peak <= 60.0 + 1e-9,
            "{name}: {peak}"
        );
    }
    let names: Vec<&str> = report["run"]["fasteners"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    let series = report["run"]["fastener_series"].as_array().unwrap();
    for (name, _, peak) in &plugged {
        let k = names.iter().position(|n| n == name).unwrap();
        let forces: Vec<f64> = series
            .iter()
            .filter(|s| s["fastener"].as_u64() == Some(k as u64))
            .map(|s| s["force"].as_f64().unwrap())
            .collect();
        let at_peak = forces.iter().position(|f| f == peak).unwrap();
        // behind the latch the curve is 0.3–0.375 of its peak: 18–22.5 N
        assert!(
            forces[at_peak..]
                .iter()
                .any(|&f| f > 0.25 * peak && f < 0.4 * peak),
            "{name}: no drop behind the latch in {forces:?}"
        );
    }
    let seated = fasteners(report, "clip");
    assert_eq!(seated.len(), clips, "{seated:?}");
    for (name, state, force) in &seated {
        assert_eq!(state, "seated", "clip {name}");
        assert!(
            *force > 0.95 * 30.0 && *force < 30.0 + 1e-9,
            "{name}: {force}"
        );
    }
}

/// The generator cable: the left hand holds it at one connector's end, the right hand
/// plugs the other two, presses the bundle into its clip, and the left hand plugs its own.
/// Every connector ends latched (its force through the mating curve's 60 N peak and the
/// latch's drop), the clip seated, no hand over its limit — and the verdict names the one
/// segment the route itself bends below its minimum radius (Segment_3 turns at 7 mm into
/// its connector XB.C.1; its wires allow 15.3 mm). Then a connector that needs 150 N, and
/// a clip that needs 140 N: the verdict names each as what the hand could not give.
#[test]
fn the_generator_cable_is_installed_connectors_plugged_and_its_fixing_pressed_in() {
    let dir = tempfile::tempdir().unwrap();
    let (scene_dir, text) = import(dir.path(), GENERATOR, "generator", &[]);
    assert!(
        text.contains("wrote") && text.contains("install.toml"),
        "{text}"
    );
    let install = scene_dir.join("install.toml");
    let scene = std::fs::read_to_string(&install).unwrap();
    // the connector data's source goes into the scene with the values
    assert!(
        scene.contains("108-15299"),
        "no source for the mating force"
    );
    assert!(scene.contains("solver = \"static\""));

    let (code, report) = run(&install, &dir.path().join("run"));
    assert_eq!(code, Some(0));
    assert_eq!(
        report["run"]["actions_completed"].as_u64(),
        Some(scene.matches("[[timeline]]").count() as u64)
    );
    assert_eq!(report["run"]["solver"]["unconverged_steps"], 0);
    assert_plugged_and_seated(&report, 3, 1);
    assert_only_bent_below(&report, "Segment_3", 15);
    // both hands pushed at least the mating force, and within the push limit (94 N)
    let pushes: Vec<f64> = report["run"]["hand_peaks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|h| h["push"]["magnitude"].as_f64().unwrap())
        .collect();
    assert_eq!(pushes.len(), 2);
    assert!(
        pushes.iter().all(|&p| p > 0.9 * 60.0 && p < 94.0),
        "{pushes:?}"
    );

    // a connector of 150 N, then a clip of 140 N: more than a hand may push (94 N here);
    // the verdict names the hand's worst push and what it was working
    let first = scene
        .split("[[connectors]]\nname = \"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .unwrap();
    for (name, hard, working) in [
        (
            "connector",
            scene.replacen("[6, 60]", "[6, 150]", 1),
            format!("— plugging connector '{first}'"),
        ),
        (
            "clip",
            scene.replace("snap_force_n = 30", "snap_force_n = 140"),
            "— pressing the hose into clip 'CL_01_Gen'".to_string(),
        ),
    ] {
        let hard_scene = scene_dir.join(format!("install_hard_{name}.toml"));
        std::fs::write(&hard_scene, hard).unwrap();
        let (code, report) = run(&hard_scene, &dir.path().join(name));
        // the run completes (the exit code is about the run, the verdict about the work)
        assert_eq!(code, Some(0));
        let (feasible, reasons) = verdict(&report);
        assert!(!feasible);
        // (a clip is pressed across the bundle: the force counts as a push or a pull by
        // its small part along the bundle, and the whole of it is judged)
        assert!(
            reasons.iter().any(|r| (r.starts_with("hand 0: push of")
                || r.starts_with("hand 0: pull of"))
                && r.contains("exceeds the limit")
                && r.ends_with(&working)),
            "{reasons:?}"
        );
        // and still every connector ended latched, the clip seated: the hand gave what
        // it had to, the verdict says it was too much
        for (name, state, _) in fasteners(&report, "connector") {
            assert_eq!(state, "latched", "{name}");
        }
        assert_eq!(fasteners(&report, "clip")[0].1, "seated");
    }
}

/// A branch of the main harness (`--branch Segment_163`: that segment and all beyond it,
/// seven segments, held where it was cut off at Node_117) with its three clips and four
/// connectors is installed to the end: feasible, every connector latched, every clip
/// seated. The whole main harness gets no `install.toml`, and the import says why and
/// what to do; an id that names nothing is refused.
#[test]
fn a_branch_of_the_main_harness_is_installed_with_its_fixings() {
    let dir = tempfile::tempdir().unwrap();
    let (scene_dir, text) = import(dir.path(), MAIN, "branch", &["--branch", "Segment_163"]);
    assert!(
        text.contains("branch beyond segment Segment_163: 7 of 183 segments, held at Node_117"),
        "{text}"
    );
    assert!(
        text.contains("3 fixings") && text.contains("4 connectors"),
        "{text}"
    );
    // the installed state of the branch (scene.toml) holds the cut too
    let scene = std::fs::read_to_string(scene_dir.join("scene.toml")).unwrap();
    assert_eq!(scene.matches("action = \"fix\"").count(), 3 + 4 + 1);
    let (code, report) = run(&scene_dir.join("install.toml"), &dir.path().join("run"));
    assert_eq!(code, Some(0));
    assert_eq!(report["run"]["solver"]["unconverged_steps"], 0);
    assert_plugged_and_seated(&report, 4, 3);
    let (feasible, reasons) = verdict(&report);
    assert!(feasible, "{reasons:?}");

    let (_, text) = import(dir.path(), MAIN, "main", &[]);
    assert!(
        text.contains("no install.toml: 128 connectors and 16 fixings, but the bundle reaches 2.70 m from every fixing")
            && text.contains("--branch"),
        "{text}"
    );
    assert!(!dir.path().join("main").join("install.toml").exists());
    let refused = pliant()
        .arg("import")
        .arg(data(MAIN))
        .arg("--out")
        .arg(dir.path().join("nothing"))
        .args(["--branch", "Segment_999"])
        .output()
        .unwrap();
    assert!(!refused.status.success());
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        err.contains("--branch Segment_999: no node or segment"),
        "{err}"
    );
}

/// The battery cable (one segment, a connector at each end, no fixing): the left hand
/// holds one end loosely, the right plugs the other, then the left plugs its own. Both
/// latch at their peak; the verdict names the route's own bend into connector XB.B.1
/// (21 mm where its 25 mm² wire allows 29.4 mm) and no hand.
#[test]
fn a_cable_without_fixings_is_plugged_at_both_ends() {
    let dir = tempfile::tempdir().unwrap();
    let (scene_dir, _) = import(dir.path(), BATTERY, "battery", &[]);
    let (code, report) = run(&scene_dir.join("install.toml"), &dir.path().join("run"));
    assert_eq!(code, Some(0));
    assert_plugged_and_seated(&report, 2, 0);
    assert_only_bent_below(&report, "Segment_1", 29);
}
