//! End-to-end tests of the `pliant` binary, as a user runs it.

use pliant_testkit::files::cad_file;
use std::path::Path;
use std::process::Command;

fn pliant() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
}

/// `pliant ARGS`, which must succeed, and what it printed, read as JSON.
fn json_of(args: &[&str]) -> serde_json::Value {
    let o = pliant().args(args).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// `pliant run --quiet [extra…] SCENE --out OUT`, waited for.
fn run_scene(scene: &Path, out: &Path, extra: &[&str]) -> std::process::Output {
    pliant()
        .args(["run", "--quiet"])
        .args(extra)
        .arg(scene)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// The run's summary.json, after asserting the run succeeded (its stderr otherwise).
fn summary_of(status: &std::process::Output, out: &Path) -> serde_json::Value {
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap()
}

fn examples() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"))
}

/// Writes a scene file with one hose `h` of library hose 1 along +x, fixed at node 0,
/// with extra `settings` TOML before the hose and further timeline `actions` after the fix.
fn write_line_scene(
    dir: &Path,
    name: &str,
    elements: usize,
    length_mm: f64,
    settings: &str,
    actions: &str,
) -> std::path::PathBuf {
    let path = dir.join(name);
    let text = format!(
        r#"format = "pliant-scene"
version = 1
length_unit = "mm"
{settings}
[[hoses]]
name = "h"
material = "hose1"
elements = {elements}
start = [0, 0, 0]
path = [ {{ line = {{ to = [{length_mm}, 0, 0] }} }} ]
[[timeline]]
action = "fix"
hose = "h"
node = 0
{actions}"#
    );
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn demo_run_writes_finite_outputs_and_summary() {
    let out = tempfile::tempdir().unwrap();
    let status = pliant()
        .args(["run", "--quiet", "--out"])
        .arg(out.path())
        .output()
        .unwrap();
    let summary = summary_of(&status, out.path());
    assert_eq!(summary["completed"], true);
    assert!(summary["steps"].as_u64().unwrap() > 1000);
    assert!(summary["time_step_s"].as_f64().unwrap() > 0.0);
    assert!(summary["wall_time_s"].as_f64().is_some());
    let peaks = summary["peaks"].as_array().unwrap();
    assert!(peaks
        .iter()
        .all(|p| p["max_force_n"].as_f64().unwrap() > 0.0));
    assert_eq!(summary["settles"][0]["at_rest"], true);
    // the engine bay demo: the hand fits the lower hose onto its stub and into two clips
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("report.json")).unwrap())
            .unwrap();
    let fasteners = report["run"]["fasteners"].as_array().unwrap();
    assert_eq!(fasteners.len(), 3);
    assert!(
        fasteners.iter().all(|f| f["assembled"] == true),
        "{fasteners:?}"
    );
    assert!(
        report["run"]["hand_peaks"][0]["max_force"]
            .as_f64()
            .unwrap()
            > 10.0
    );
    assert!(report["verdict"]["feasible"].is_boolean());
    let html = std::fs::read_to_string(out.path().join("report.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("FEASIBLE"));
    // the picture of the worst instant shows the parts (SPEC V7), in three views
    for view in ["from above", "from the side", "from the front right"] {
        assert!(html.contains(view), "{view}");
    }
    for part in ["floor", "engine block"] {
        assert!(
            html.contains(&format!("<title>{part}</title></polygon>")),
            "part '{part}' drawn"
        );
    }
    for file in [
        "nodes.csv",
        "reactions.csv",
        "energy.csv",
        "hands.csv",
        "colours.csv",
        "vtk/hoses.pvd",
        "vtk/frame_00000.vtp",
    ] {
        let text = std::fs::read_to_string(out.path().join(file)).unwrap();
        assert!(!text.to_lowercase().contains("nan"), "{file} contains NaN");
        assert!(text.lines().count() > 2, "{file} is empty");
    }
    let header = std::fs::read_to_string(out.path().join("reactions.csv")).unwrap();
    assert!(header.starts_with("time_s,hose,node,kind,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm"));
}

/// The demo under the static solver: where a stub holds the hose end, explicit
/// relaxation (the snap of a failed Newton step) cannot reach the static limit and stops
/// moving; it gives up then instead of taking its 2 million steps for each such input
/// (before: 30 000 912 steps and 4.6 minutes). The peaks stay those of a converged run.
#[test]
fn the_static_demo_gives_up_relaxations_that_stopped_moving() {
    let out = tempfile::tempdir().unwrap();
    let status = run_scene(
        &examples().join("engine_bay.toml"),
        out.path(),
        &["--solver", "static", "--threads", "1"],
    );
    let summary = summary_of(&status, out.path());
    assert_eq!(summary["completed"], true);
    assert_eq!(summary["solver"], "static");
    let steps = summary["steps"].as_u64().unwrap();
    // 912 inputs of 10 ms plus the relaxations: a frozen one stops after 8 windows of 64
    assert!(steps < 100_000, "{steps} steps");
    let upper_root = &summary["peaks"][0];
    assert_eq!(upper_root["hose"], "upper");
    // the radiator end of the upper hose carries about its weight share (0.95 N)
    let f = upper_root["max_force_n"].as_f64().unwrap();
    assert!((0.5..2.0).contains(&f), "{f} N");
}

#[test]
fn hanging_hose_reaction_equals_its_weight() {
    // thesis-like hose, gravity on, fixed at one end, settles hanging: the support
    // carries the full weight m g (sum of lumped masses) — checked through the outputs.
    let dir = tempfile::tempdir().unwrap();
    let scene = write_line_scene(
        dir.path(),
        "hang.toml",
        20,
        400.0,
        "[simulation]\ndamping_mass_per_s = 5.0",
        "[[timeline]]\naction = \"settle\"\nkinetic_energy_j = 1e-14\nmax_duration_s = 60\n",
    );
    let out = dir.path().join("out");
    let o = run_scene(&scene, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let f = &s["peaks"][0]["final_force_n"];
    // hose 1: d 10/16 mm, ρ = 940 kg/m³, 0.4 m
    let weight =
        940.0 * std::f64::consts::PI / 4.0 * (0.016f64.powi(2) - 0.010f64.powi(2)) * 0.4 * 9.81;
    let fz = f[2].as_f64().unwrap();
    assert!(
        (fz - weight).abs() < 1e-3 * weight,
        "support force {fz} N vs weight {weight} N"
    );
}

#[test]
fn bad_scene_names_the_field_and_fails() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    let text = std::fs::read_to_string(examples().join("thesis_1.toml"))
        .unwrap()
        .replace("d_inner = 30", "d_inner = 45");
    std::fs::write(&scene, text).unwrap();
    let o = run_scene(&scene, &dir.path().join("o"), &[]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("d_inner") && err.contains("d_outer"), "{err}");
}

#[test]
fn missing_scene_file_is_a_clear_error() {
    let o = pliant()
        .args(["run", "--quiet", "/nonexistent/scene.toml"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/scene.toml"));
}

#[test]
fn diverging_run_stops_with_step_and_cause_and_no_nan() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_line_scene(
        dir.path(),
        "fast.toml",
        10,
        200.0,
        "",
        "[[timeline]]\naction = \"move\"\nhose = \"h\"\nnode = -1\nby = [0, 0, 50000]\nduration_s = 0.001\n",
    );
    let out = dir.path().join("out");
    let o = run_scene(&scene, &out, &[]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("diverged at step") && err.contains("too fast"),
        "{err}"
    );
    let nodes = std::fs::read_to_string(out.join("nodes.csv")).unwrap();
    assert!(!nodes.to_lowercase().contains("nan") && !nodes.contains("inf"));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["completed"], false);
}

#[test]
fn validate_json_prints_the_documented_fields() {
    let v = json_of(&["validate", "--json", "--case", "torsion"]);
    let rows = v.as_array().unwrap();
    assert!(!rows.is_empty());
    for key in [
        "case",
        "quantity",
        "computed",
        "reference",
        "error",
        "tolerance",
        "pass",
    ] {
        assert!(rows[0].get(key).is_some(), "missing {key}");
    }
}

/// `bench --only contact --json` prints the time-boxed rows and both fixed windows, at
/// the steps documented, without, with the floor, with it swaying and with it frozen in
/// its pose at the window's start (the swaying world's state there), and the hose–hose
/// rows of the crossed grid, with finite positive times (no timing is judged here) and
/// its layers touching.
#[test]
fn contact_bench_reports_its_fixed_windows() {
    let v = json_of(&["bench", "--only", "contact", "--quick", "--json"]);
    assert!(v["ratio"]
        .as_f64()
        .is_some_and(|r| r.is_finite() && r > 0.0));
    let phases = v["phases"].as_array().unwrap();
    let names: Vec<_> = phases.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["sliding", "lying"]);
    for p in phases {
        for key in [
            "ns_per_step_free",
            "ns_per_step_contact",
            "ratio",
            "ns_per_step_moving",
            "moving_ratio",
            "ns_per_step_frozen",
            "moving_over_frozen",
        ] {
            let x = p[key].as_f64().unwrap();
            assert!(x.is_finite() && x > 0.0, "{key} = {x}");
        }
        assert!(p["first_step"].as_u64().unwrap() > 0 && p["steps"].as_u64().unwrap() > 0);
    }
    let grid = &v["hose_hose"];
    assert_eq!(grid["hoses"].as_u64(), Some(10));
    let phases = grid["phases"].as_array().unwrap();
    let names: Vec<_> = phases.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["falling", "lying"]);
    for p in phases {
        for key in ["ns_per_step_free", "ns_per_step_contact", "ratio"] {
            let x = p[key].as_f64().unwrap();
            assert!(x.is_finite() && x > 0.0, "{key} = {x}");
        }
        let pairs = p["pairs_in_contact_per_step"].as_f64().unwrap();
        assert!(pairs > 0.0, "{pairs} pairs in contact");
    }
}

/// `bench --only worker --json` prices a posed instant with and without hoses across the
/// body: both finite and positive, the ratio their quotient (no timing is judged here).
#[test]
fn worker_bench_reports_both_instants() {
    let v = json_of(&["bench", "--only", "worker", "--quick", "--json"]);
    let without = v["us_per_instant_without"].as_f64().unwrap();
    let with = v["us_per_instant_with"].as_f64().unwrap();
    assert!(without.is_finite() && without > 0.0 && with.is_finite() && with > 0.0);
    assert!((v["ratio"].as_f64().unwrap() - with / without).abs() <= 1e-12 * with / without);
    assert!(v["hoses"].as_u64().unwrap() > 0);
}

#[test]
fn validate_unknown_case_fails_clearly() {
    let o = pliant()
        .args(["validate", "--case", "nope"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown validation case"));
}

/// `pliant serve` on a network address requires a token, prints it in the URL and warns
/// that the session is exposed; a token unfit for a URL is refused before serving.
#[test]
fn serve_on_the_network_prints_a_token_and_a_warning() {
    use std::io::{BufRead, BufReader, Read};
    let dir = tempfile::tempdir().unwrap();
    let mut child = pliant()
        .args(["serve", "--host", "0.0.0.0", "--port", "0"])
        .current_dir(dir.path())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // wait for the line, not for a duration
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    let url = loop {
        line.clear();
        assert!(
            stdout.read_line(&mut line).unwrap() > 0,
            "serve ended early"
        );
        if line.starts_with("Pliant serving") {
            break line.trim().rsplit(' ').next().unwrap().to_string();
        }
    };
    child.kill().unwrap();
    child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    let token = url.split("?token=").nth(1).expect("a token in the URL");
    assert_eq!(token.len(), 32, "{url}");
    assert!(token.bytes().all(|b| b.is_ascii_hexdigit()), "{url}");
    assert!(
        stderr.contains("WARNING") && stderr.contains("reachable from the network"),
        "{stderr}"
    );

    let refused = pliant()
        .args(["serve", "--port", "0", "--token", "a b"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(!refused.status.success());
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--token"));
}

/// Hardening item 4: a scene beyond `--max-memory` is refused while it loads, naming
/// the hose and the estimate, with exit code 2; a run says its cost before it starts.
#[test]
fn memory_limit_refuses_before_allocating_and_runs_state_their_cost() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_line_scene(dir.path(), "big.toml", 20_000, 20_000.0, "", "");
    let o = run_scene(&scene, &dir.path().join("o"), &["--max-memory", "50M"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("hoses[0]") && err.contains("20000 elements"),
        "{err}"
    );
    assert!(
        err.contains("≈ 99 MB") && err.contains("50 MB") && err.contains("--max-memory"),
        "{err}"
    );
    let o = pliant()
        .args(["run", "--quiet", "--max-memory", "lots"])
        .arg(&scene)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("not a size"));

    let small = write_line_scene(
        dir.path(),
        "small.toml",
        8,
        200.0,
        "",
        "[[timeline]]\naction = \"run\"\nduration_s = 0.01\n",
    );
    let o = run_scene(&small, &dir.path().join("s"), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("element-steps") && err.contains("memory ≈"),
        "{err}"
    );
}

/// A mesh path naming a FIFO or a device is refused at once, not read forever.
#[cfg(unix)]
#[test]
fn meshes_that_are_not_regular_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.stl")).unwrap();
    let fifo = dir.path().join("fifo.obj");
    let made = Command::new("mkfifo").arg(&fifo).status();
    let mut names = vec!["zero.stl"];
    if made.is_ok_and(|s| s.success()) {
        names.push("fifo.obj");
    }
    for name in names {
        let parts = format!("[[parts]]\nname = \"p\"\nmesh = \"{name}\"\n");
        let scene = write_line_scene(dir.path(), "m.toml", 4, 200.0, &parts, "");
        let o = pliant()
            .args(["run", "--quiet"])
            .arg(&scene)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains("parts[0].mesh") && err.contains("not a regular file"),
            "{err}"
        );
    }
}

/// Every output file of a run, as text (CSV, JSON, HTML, VTK).
fn output_texts(out: &Path) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let mut dirs = vec![out.to_path_buf()];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if let Ok(t) = std::fs::read_to_string(&p) {
                files.push((p.display().to_string(), t));
            }
        }
    }
    files
}

/// Whether `text` holds a non-finite number as written by Rust, JSON or CSV writers.
fn has_non_finite(text: &str) -> Option<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-' || c == '+'))
        .find(|w| {
            let w = w.trim_start_matches(['-', '+']).to_ascii_lowercase();
            w == "nan" || w == "inf" || w == "infinity"
        })
        .map(str::to_string)
}

/// The engine-bay demo with `edit` applied to its text, in `dir` (meshes from examples/).
fn demo_variant(dir: &Path, name: &str, edit: impl Fn(&str) -> String) -> std::path::PathBuf {
    let text = std::fs::read_to_string(examples().join("engine_bay.toml")).unwrap();
    let meshes = examples().join("meshes").display().to_string();
    let text = edit(&text).replace("mesh = \"meshes", &format!("mesh = \"{meshes}"));
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// Hardening item 5: values that would make the model meaningless are refused at load
/// with the field named; runs that diverge or carry extreme loads write no NaN or inf
/// into any output file.
#[test]
fn meaningless_values_are_refused_and_outputs_never_hold_non_finite_numbers() {
    let dir = tempfile::tempdir().unwrap();
    let refused: [(&str, &str, &str, &str); 3] = [
        (
            "length = 50\n",
            "length = 1e-300\n",
            "stubs[0].length",
            "1e-300 mm",
        ),
        (
            "snap_force_n = 40\n",
            "snap_force_n = 1e300\n",
            "clips[0].snap_force_n",
            "1e300 N",
        ),
        (
            "gravity = [0, 0, -9.81]\n",
            "gravity = [0, 0, -9.81]\ndamping_stiffness_s = 1e300\n",
            "damping_stiffness_s",
            "no stable time step",
        ),
    ];
    for (from, to, field, value) in refused {
        let scene = demo_variant(dir.path(), "refused.toml", |t| t.replacen(from, to, 1));
        let o = run_scene(&scene, &dir.path().join("r"), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(field) && err.contains(value), "{err}");
    }
    // strong mass damping: the explicit step shrinks to stay stable, the run completes
    let damped = demo_variant(dir.path(), "damped.toml", |t| {
        t.replacen(
            "gravity = [0, 0, -9.81]\n",
            "gravity = [0, 0, -9.81]\ndamping_mass_per_s = 2e4\n",
            1,
        )
    });
    let out = dir.path().join("damped");
    let o = run_scene(&damped, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // a hand that yanks the hose end 50 m in 1 ms: the run diverges (exit 3)
    let yank = demo_variant(dir.path(), "yank.toml", |t| {
        format!("{t}\n[[timeline]]\naction = \"move\"\nhose = \"upper\"\nnode = -1\nby = [0, 0, 50000]\nduration_s = 0.001\n")
    });
    let yanked = dir.path().join("yank");
    let o = run_scene(&yank, &yanked, &[]);
    assert_eq!(
        o.status.code(),
        Some(3),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for out in [out, yanked] {
        let files = output_texts(&out);
        assert!(files.len() > 8, "{files:?}");
        for (name, text) in files {
            assert_eq!(has_non_finite(&text), None, "{name}");
        }
    }
}

/// Members of report.json and summary.json that are `null` when they have nothing to say
/// (an optional value, never a number that was not finite).
const OPTIONAL_MEMBERS: [&str; 6] = [
    "first_unconverged",
    "worst_unconverged",
    "first_explicit_fallback",
    "at",
    "worst_kind",
    "diverged",
];

/// Where `value` holds a `null` that is not an optional member left empty: a NaN or an
/// infinity written by serde_json.
fn null_number(value: &serde_json::Value, path: &str) -> Option<String> {
    match value {
        serde_json::Value::Array(items) => items.iter().enumerate().find_map(|(k, v)| {
            if v.is_null() {
                Some(format!("{path}[{k}]"))
            } else {
                null_number(v, &format!("{path}[{k}]"))
            }
        }),
        serde_json::Value::Object(map) => map.iter().find_map(|(key, v)| {
            let here = format!("{path}.{key}");
            if v.is_null() {
                (!OPTIONAL_MEMBERS.contains(&key.as_str())).then_some(here)
            } else {
                null_number(v, &here)
            }
        }),
        _ => None,
    }
}

/// Every file written into `out` holds no non-finite number: no NaN or inf in any text,
/// no `null` standing for one in any JSON file.
fn assert_all_finite(out: &Path) {
    let files = output_texts(out);
    assert!(files.len() > 8, "{files:?}");
    for (name, text) in files {
        assert_eq!(has_non_finite(&text), None, "{name}");
        if name.ends_with(".json") {
            let value: serde_json::Value = serde_json::from_str(&text).unwrap();
            assert_eq!(null_number(&value, ""), None, "{name}");
        }
    }
}

/// A run that diverges — under every solver — says so (exit 3, the
/// divergence in summary.json) and writes no non-finite number into any file, JSON
/// included (a hose whose final state is not finite has it omitted, with the reason).
#[test]
fn diverged_runs_under_every_solver_write_no_non_finite_number() {
    let dir = tempfile::tempdir().unwrap();
    let yank = demo_variant(dir.path(), "yank.toml", |t| {
        format!("{t}\n[[timeline]]\naction = \"move\"\nhose = \"upper\"\nnode = -1\nby = [0, 0, 50000]\nduration_s = 0.001\n")
    });
    for solver in ["explicit", "implicit", "static"] {
        let out = dir.path().join(solver);
        let o = run_scene(&yank, &out, &["--solver", solver]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(3), "{solver}: {err}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(summary["completed"], false, "{solver}");
        // the divergence is typed — `kind` with its numbers, where and when — beside the
        // message `pliant run` prints
        let d = &summary["diverged"];
        let kind = d["kind"]
            .as_str()
            .unwrap_or_else(|| panic!("{solver}: {d}"));
        let message = d["message"].as_str().unwrap();
        assert!(err.contains(message), "{solver}: {err}");
        assert!(
            d["step"].as_u64().is_some() && d["time_s"].as_f64().is_some(),
            "{d}"
        );
        assert!(
            ["upper", "lower"].contains(&d["hose"].as_str().unwrap()),
            "{d}"
        );
        match kind {
            "speed" => assert!(
                d["speed_m_s"].as_f64().unwrap() > d["wave_speed_m_s"].as_f64().unwrap(),
                "{d}"
            ),
            "support_load" => assert_eq!(d["limit"], 1e9, "{d}"),
            "not_converged" => assert!(d["halvings"].as_u64().is_some(), "{d}"),
            "non_finite_iteration" => assert!(d["iteration"].as_u64().is_some(), "{d}"),
            "non_finite_state" | "non_finite_velocity" | "singular" => {}
            other => panic!("{solver}: unexpected kind {other}: {d}"),
        }
        assert_all_finite(&out);
    }
}

/// A gravity, load or rotation of 1e300 is refused at load, naming the
/// field, instead of running into NaN.
#[test]
fn absurd_gravity_load_and_rotation_are_refused_at_load() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str); 3] = [
        ("", "simulation.gravity"),
        (
            "\n[[timeline]]\naction = \"load\"\nhose = \"upper\"\nnode = -1\nforce_n = [0, 0, 1e300]\n",
            "force_n",
        ),
        (
            "\n[[timeline]]\naction = \"move\"\nhose = \"upper\"\nnode = -1\nrotate = { axis = [0, 0, 1], angle_deg = 1e300 }\nduration_s = 1\n",
            "rotate.angle_deg",
        ),
    ];
    for (extra, field) in cases {
        let scene = demo_variant(dir.path(), "absurd.toml", |t| {
            let t = if extra.is_empty() {
                t.replacen("gravity = [0, 0, -9.81]", "gravity = [0, 0, -1e300]", 1)
            } else {
                t.to_string()
            };
            format!("{t}{extra}")
        });
        let o = run_scene(&scene, &dir.path().join("r"), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(field) && err.contains("1e300") && err.contains("out of range"),
            "{err}"
        );
    }
}

/// `pliant calibrate` never exits 0 with a non-finite number in what
/// it writes: a 1e308 mm specimen is refused before fitting, and curves that overflow
/// the fit give an error, not `e_bending_mpa = NaN`.
#[test]
fn calibrate_refuses_out_of_range_specimens_and_non_finite_results() {
    let dir = tempfile::tempdir().unwrap();
    let huge = dir.path().join("huge.csv");
    let lines: String = (0..20)
        .map(|k| format!("{},{}\n", k as f64 * 5e306, k as f64 * 1e-3))
        .collect();
    std::fs::write(&huge, format!("force_N,deflection_mm\n{lines}")).unwrap();
    let cases = [
        (
            "1e308",
            examples().join("calibration/bending.csv"),
            "d_outer_mm",
        ),
        // refused by the fit or by the check of the derived values: never written
        ("10", huge, "error"),
    ];
    for (d_outer, csv, expected) in cases {
        let out = dir.path().join("out");
        let o = pliant()
            .args([
                "calibrate",
                "--kind",
                "three_point_bending",
                "--length",
                "200",
            ])
            .args(["--d-outer", d_outer, "--csv"])
            .arg(&csv)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(expected), "{err}");
        assert!(!out.join("material.toml").exists());
    }
}

/// `pliant import` fills the cache a scene beside the STEP file reads (then the scene
/// runs with no importer at all), writes a plain GLB with --out, and the solids the
/// converter skipped reach stderr and summary.json.
#[test]
fn import_fills_the_cache_that_run_reads() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(cad_file("sg1-c5-214.stp"), dir.path().join("sg1.stp")).unwrap();
    let out = pliant()
        .args(["import", "--tolerance", "0.2mm"])
        .arg(dir.path().join("sg1.stp"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("1 solid(s)") && stdout.contains("SG1") && stdout.contains(".pliant-cache"),
        "{stdout}"
    );
    let scene = dir.path().join("scene.toml");
    let text = |part: &str| {
        format!(
            r#"format = "pliant-scene"
version = 1
length_unit = "mm"

[[parts]]
name = "sg1"
{part}
position = [0, 0, -500]

[[hoses]]
name = "h"
material = "hose1"
start = [0, 0, 300]
path = [{{ line = {{ to = [300, 0, 300] }} }}]

[[timeline]]
action = "fix"
hose = "h"
node = 0

[[timeline]]
action = "run"
duration_s = 0.002
"#
        )
    };
    std::fs::write(&scene, text("step = \"sg1.stp\"\nchord_tolerance = 0.2")).unwrap();
    let no_python = dir.path().join("no-python");
    let run = |scene: &Path| {
        pliant()
            .args(["run", "--quiet"])
            .arg(scene)
            .arg("--out")
            .arg(dir.path().join("out"))
            .env("PLIANT_PYTHON", &no_python)
            .output()
            .unwrap()
    };
    let r = run(&scene);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // another tolerance is another entry: without the importer, a clear error
    std::fs::write(&scene, text("step = \"sg1.stp\"\nchord_tolerance = 0.3")).unwrap();
    let r = run(&scene);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(
        !r.status.success() && err.contains("install-cad.sh") && err.contains("parts[0].step"),
        "{err}"
    );
    // --out writes a GLB that works as an ordinary mesh
    let glb = dir.path().join("sg1.glb");
    let out = pliant()
        .arg("import")
        .arg(dir.path().join("sg1.stp"))
        .arg("--out")
        .arg(&glb)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    std::fs::write(&scene, text("mesh = \"sg1.glb\"")).unwrap();
    let r = run(&scene);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    // skipped solids (recorded by the converter in the entry) reach the user
    let entry = std::fs::read_dir(dir.path().join(".pliant-cache"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "glb"))
        .unwrap();
    let bytes = std::fs::read(&entry).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = String::from_utf8(bytes[20..20 + len].to_vec()).unwrap();
    let patched = json.replacen("\"skipped\":[]", "\"skipped\":[\"SG1/x: broken\"]", 1);
    assert_ne!(patched, json);
    let mut text_bytes = patched.into_bytes();
    while text_bytes.len() % 4 != 0 {
        text_bytes.push(b' ');
    }
    let bin = &bytes[20 + len..];
    let mut glb2 = bytes[0..8].to_vec();
    glb2.extend_from_slice(&((20 + text_bytes.len() + bin.len()) as u32).to_le_bytes());
    glb2.extend_from_slice(&(text_bytes.len() as u32).to_le_bytes());
    glb2.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    glb2.extend_from_slice(&text_bytes);
    glb2.extend_from_slice(bin);
    std::fs::write(&entry, glb2).unwrap();
    std::fs::write(&scene, text("step = \"sg1.stp\"\nchord_tolerance = 0.2")).unwrap();
    let r = run(&scene);
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(
        r.status.success() && err.contains("warning: parts[0]") && err.contains("SG1/x: broken"),
        "{err}"
    );
    let summary = std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap();
    assert!(
        summary.contains("scene_warnings") && summary.contains("SG1/x: broken"),
        "{summary}"
    );
}

#[test]
fn calibrate_fits_the_example_and_writes_the_material() {
    let out = tempfile::tempdir().unwrap();
    let o = pliant()
        .arg("calibrate")
        .arg(examples().join("calibration/hose.toml"))
        .arg("--out")
        .arg(out.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for kind in [
        "tension",
        "compression",
        "three_point_bending",
        "torsion",
        "iso10619",
    ] {
        assert!(stdout.contains(kind), "{stdout}");
    }
    assert!(stdout.contains("E_t = 11.5"), "{stdout}");
    for f in [
        "material.toml",
        "library_entry.toml",
        "calibration.json",
        "calibration.html",
    ] {
        assert!(out.path().join(f).is_file(), "{f}");
    }
    let material = std::fs::read_to_string(out.path().join("material.toml")).unwrap();
    assert!(
        material.contains("[materials.calibrated_hose]"),
        "{material}"
    );
    // a scene using the calibrated material runs
    let scene = out.path().join("scene.toml");
    std::fs::write(
        &scene,
        format!(
            "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\n{material}\n\
             [[hoses]]\nname = \"h\"\nmaterial = \"calibrated_hose\"\nsection = {{ d_inner = 10, d_outer = 16 }}\n\
             elements = 8\nstart = [0, 0, 0]\npath = [{{ line = {{ to = [300, 0, 0] }} }}]\n\
             [[timeline]]\naction = \"fix\"\nhose = \"h\"\nnode = 0\n\
             [[timeline]]\naction = \"run\"\nduration_s = 0.02\n"
        ),
    )
    .unwrap();
    let run = run_scene(&scene, &out.path().join("run"), &[]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );

    // one test from the command line
    let one = pliant()
        .args([
            "calibrate",
            "--kind",
            "torsion",
            "--length",
            "300",
            "--d-outer",
            "16",
            "--d-inner",
            "10",
            "--csv",
        ])
        .arg(examples().join("calibration/torsion.csv"))
        .arg("--out")
        .arg(out.path().join("one"))
        .arg("--json")
        .output()
        .unwrap();
    assert!(
        one.status.success(),
        "{}",
        String::from_utf8_lossy(&one.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&one.stdout).unwrap();
    let gj = json["tests"][0]["value"].as_f64().unwrap();
    assert!((gj - 0.022561).abs() < 0.0003, "{gj}");

    // bad input: the error names the file and line, exit code 2
    let bad = out.path().join("bad.csv");
    std::fs::write(&bad, "force_N,deflection_mm\n0,0\n1,oops\n").unwrap();
    let e = pliant()
        .args([
            "calibrate",
            "--kind",
            "cantilever",
            "--length",
            "100",
            "--d-outer",
            "10",
            "--csv",
        ])
        .arg(&bad)
        .arg("--out")
        .arg(out.path().join("bad"))
        .output()
        .unwrap();
    assert_eq!(e.status.code(), Some(2));
    let err = String::from_utf8_lossy(&e.stderr);
    assert!(
        err.contains("bad.csv:3:2") && err.contains("not a number"),
        "{err}"
    );
}

/// Ties and EN 1005-3 through `pliant run`: a second hose tied to the first by the
/// timeline's `tie`, a hand pulling the first hose's tip sideways, judged by EN 1005-3
/// from `--ergonomics` — and from the scene's `[ergonomics]`; a bad profile is refused
/// naming the key.
#[test]
fn en1005_profile_and_a_tie_through_pliant_run() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_line_scene(
        dir.path(),
        "tied.toml",
        8,
        200.0,
        "[simulation]\ngravity = [0, 0, 0]\n",
        r#"[[timeline]]
action = "fix"
hose = "g"
node = 0
[[timeline]]
action = "tie"
hose = "h"
node = 4
to = { hose = "g", node = 4 }
[[timeline]]
action = "grab"
hand = 0
at = [200, 0, 0]
[[timeline]]
action = "move_hand"
hand = 0
by = [0, -10, 0]
duration_s = 0.2
"#,
    );
    // a second hose g, 30 mm beside h
    let text = std::fs::read_to_string(&scene).unwrap().replacen(
        "[[timeline]]",
        "[[hoses]]\nname = \"g\"\nmaterial = \"hose1\"\nelements = 8\nstart = [0, 30, 0]\npath = [ { line = { to = [200, 30, 0] } } ]\n[[timeline]]",
        1,
    );
    std::fs::write(&scene, &text).unwrap();
    let out = dir.path().join("out");
    let o = run_scene(
        &scene,
        &out,
        &[
            "--ergonomics",
            "standard=en1005-3, action=whole_body, frequency_per_min=1",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let verdict = &report["verdict"];
    assert_eq!(verdict["standard"], "EN 1005-3:2002+A1:2008");
    let zones = verdict["zones"].as_array().unwrap();
    assert!(!zones.is_empty(), "{verdict}");
    assert!(
        zones[0].as_str().unwrap().contains("m_r = F/F_R"),
        "{zones:?}"
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("EN 1005-3 risk zones"));
    // the tie's reactions on its two nodes, equal and opposite, in reactions.csv
    let reactions = std::fs::read_to_string(out.join("reactions.csv")).unwrap();
    let last: Vec<Vec<f64>> = reactions
        .lines()
        .rev()
        .filter(|l| l.contains(",tie,"))
        .take(2)
        .map(|l| {
            l.split(',')
                .skip(4)
                .take(3)
                .map(|x| x.parse().unwrap())
                .collect()
        })
        .collect();
    assert_eq!(last.len(), 2, "{reactions}");
    let size = last[0].iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(size > 1e-3, "the tie carries nothing: {last:?}");
    for k in 0..3 {
        assert!((last[0][k] + last[1][k]).abs() <= 1e-9 * size, "{last:?}");
    }
    // the scene's own [ergonomics] does the same
    let text = text.replacen(
        "[[hoses]]",
        "[ergonomics]\nstandard = \"en1005-3\"\nfrequency_per_min = 1\n\n[[hoses]]",
        1,
    );
    std::fs::write(&scene, &text).unwrap();
    let o = run_scene(&scene, &dir.path().join("out2"), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let again: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("out2/report.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(again["verdict"]["zones"], verdict["zones"]);
    // a bad value is refused naming the key
    let o = run_scene(
        &scene,
        &dir.path().join("out3"),
        &["--ergonomics", "standard=en1005-3, duration_h=12"],
    );
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("`duration_h` must lie in [0, 8] h"), "{err}");
}

/// `pliant serve --help` says that each session is recorded, where, and how to get its
/// report.
#[test]
fn serve_help_says_where_sessions_are_recorded_and_how_to_report_them() {
    let out = pliant().args(["serve", "--help"]).output().unwrap();
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    for needle in [
        "out/sessions/session-",
        "Report button",
        "Ctrl-C",
        "pliant replay",
        "report.html",
    ] {
        assert!(help.contains(needle), "missing {needle:?} in:\n{help}");
    }
}

/// A run planned beyond the step limit is refused before it starts, with its
/// estimate (a scene planned at 1.6·10¹² steps used to start); `--max-steps` allows
/// more. A `time_step_safety` of 1e-300 (4.6·10³⁰⁴ steps) is refused at load, naming
/// the field.
#[test]
fn runs_beyond_the_step_limit_are_refused_with_their_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write_line_scene(
        dir.path(),
        "steps.toml",
        4,
        200.0,
        "",
        "[[timeline]]\naction = \"run\"\nduration_s = 0.05\n",
    );
    let o = run_scene(&scene, &dir.path().join("a"), &["--max-steps", "10"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("steps") && err.contains("at most 10") && err.contains("--max-steps"),
        "{err}"
    );
    assert!(!dir.path().join("a").join("summary.json").exists());
    let o = run_scene(&scene, &dir.path().join("b"), &["--max-steps", "100000000"]);
    summary_of(&o, &dir.path().join("b"));

    let tiny = write_line_scene(
        dir.path(),
        "tiny.toml",
        4,
        200.0,
        "[simulation]\ntime_step_safety = 1e-300\n",
        "[[timeline]]\naction = \"run\"\nduration_s = 1\n",
    );
    let o = run_scene(&tiny, &dir.path().join("c"), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("simulation.time_step_safety") && err.contains("[0.001, 1]"),
        "{err}"
    );
}

/// The processes descended from `pid` (Linux, from /proc).
#[cfg(target_os = "linux")]
fn descendants(pid: u32) -> Vec<u32> {
    let parent_of = |p: u32| -> Option<u32> {
        let stat = std::fs::read_to_string(format!("/proc/{p}/stat")).ok()?;
        // "pid (comm) state ppid …": the comm may hold spaces, so split after its ')'
        stat.rsplit_once(')')?
            .1
            .split_whitespace()
            .nth(1)?
            .parse()
            .ok()
    };
    let all: Vec<u32> = std::fs::read_dir("/proc")
        .unwrap()
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse().ok())
        .collect();
    let mut found = vec![pid];
    let mut k = 0;
    while k < found.len() {
        let p = found[k];
        found.extend(all.iter().filter(|&&c| parent_of(c) == Some(p)));
        k += 1;
    }
    found.remove(0);
    found
}

/// `kill -9` of `pliant study` stops its Python driver and the Dask workers
/// (they used to run on). Needs a Python with the study extras (PLIANT_PYTHON or the
/// repository's .venv); without one the test says so and passes. Waits for conditions
/// (workers started, processes gone), never for durations.
#[cfg(target_os = "linux")]
#[test]
fn killing_pliant_study_stops_its_driver_and_workers() {
    let probe = "import pliant.studies, distributed, pyarrow, pandas, scipy, skimage";
    let has_extras = |p: &std::path::Path| {
        Command::new(p)
            .args(["-c", probe])
            .output()
            .is_ok_and(|o| o.status.success())
    };
    let Some(python) = pliant_runs::cad_converter::python_candidates()
        .into_iter()
        .find(|p| has_extras(p))
    else {
        eprintln!("skipped: no Python with pliant's study extras (set PLIANT_PYTHON)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("long.toml");
    std::fs::write(
        &study,
        format!(
            "format = \"pliant-study\"\nversion = 1\nscene = \"{}\"\nlength_unit = \"mm\"\n\
             [sampling]\nruns = 100000\nseed = 1\n\
             [[parameters]]\nname = \"stiffness\"\nvary = \"material\"\nmaterial = \"hose3\"\n\
             property = \"e_mpa\"\ndistribution = \"uniform\"\nmin = 0.9\nmax = 1.1\n",
            examples().join("demo.toml").display()
        ),
    )
    .unwrap();
    let mut child = pliant()
        .args(["study", "--quiet", "--workers", "2", "--out"])
        .arg(dir.path().join("out"))
        .arg(&study)
        .env("PLIANT_PYTHON", &python)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let hang_guard = std::time::Duration::from_secs(300);
    let deadline = std::time::Instant::now() + hang_guard;
    // the driver and at least one worker process under it
    let started = loop {
        let d = descendants(child.id());
        if d.len() >= 3 {
            break d;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "the study never started its workers"
        );
        assert!(child.try_wait().unwrap().is_none(), "pliant study ended");
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let alive = |p: &u32| {
        std::path::Path::new(&format!("/proc/{p}")).exists() && {
            // a zombie waiting for its (dead) parent's reaper has stopped too
            std::fs::read_to_string(format!("/proc/{p}/stat")).is_ok_and(|s| {
                s.rsplit_once(')')
                    .is_some_and(|(_, r)| !r.trim_start().starts_with('Z'))
            })
        }
    };
    loop {
        let left: Vec<u32> = started.iter().copied().filter(alive).collect();
        if left.is_empty() {
            break;
        }
        assert!(
            std::time::Instant::now() < deadline,
            "still running {hang_guard:?} after kill -9 of pliant study: {left:?}"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

/// The law kinds through `pliant calibrate`: a test-bench cantilever past yield from its
/// example file (the law table and the springback check printed), and one relaxation
/// test on the command line — refused without `--held-strain` (it gives moduli ratios
/// only), and with it and `--terms 1` fitted with exactly one Prony term.
#[test]
fn calibrate_prints_the_fitted_laws_and_takes_relaxation_options() {
    let out = tempfile::tempdir().unwrap();
    let o = pliant()
        .arg("calibrate")
        .arg(examples().join("calibration/metal_line_cantilever.toml"))
        .arg("--out")
        .arg(out.path().join("beam"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    for want in [
        "plastic_cantilever",
        "sigma_y = ",
        "H = ",
        "springback measured",
    ] {
        assert!(stdout.contains(want), "{want}: {stdout}");
    }
    let material = std::fs::read_to_string(out.path().join("beam/material.toml")).unwrap();
    assert!(material.contains("yield_stress_mpa = 170."), "{material}");

    let relaxation = |extra: &[&str], dir: &str| {
        pliant()
            .args([
                "calibrate",
                "--kind",
                "relaxation",
                "--d-inner",
                "10",
                "--d-outer",
                "16",
            ])
            .args(extra)
            .arg("--csv")
            .arg(examples().join("calibration/relaxation.csv"))
            .arg("--out")
            .arg(out.path().join(dir))
            .output()
            .unwrap()
    };
    let refused = relaxation(&[], "none");
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(err.contains("--held-strain"), "{err}");
    let one = relaxation(&["--held-strain", "0.05", "--terms", "1"], "one");
    let stdout = String::from_utf8_lossy(&one.stdout);
    assert!(
        one.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&one.stderr)
    );
    assert!(
        stdout.contains("E0 = ") && stdout.contains("g1 = "),
        "{stdout}"
    );
    assert!(!stdout.contains("g2 = "), "{stdout}");
    assert!(stdout.contains("asked for"), "{stdout}");
    let material = std::fs::read_to_string(out.path().join("one/material.toml")).unwrap();
    assert_eq!(material.matches("time_s =").count(), 1, "{material}");
    // the options belong to a lone relaxation test
    let mixed = pliant()
        .arg("calibrate")
        .arg(examples().join("calibration/rubber_relaxation.toml"))
        .args(["--terms", "2"])
        .output()
        .unwrap();
    assert_eq!(mixed.status.code(), Some(2));
}
