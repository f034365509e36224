//! The coolant T-piece example (`examples/coolant_tee.toml`): a junction body with a
//! shape, the heater return hose resting on it. `pliant run` settles it and gives a
//! verdict under each solver, all three agreeing on the clamps' load and on the weight the
//! tee's body carries; `pliant inspect` names the body's shape.

use std::path::{Path, PathBuf};
use std::process::Command;

fn example() -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/coolant_tee.toml"
    ))
    .into()
}

fn pliant() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
}

/// Σ of `column` over the rows of `file` (a CSV the run wrote) at its last time, for the
/// rows `keep` accepts (by their `hose` column).
fn last_sum(file: &Path, column: &str, keep: impl Fn(&str) -> bool) -> f64 {
    let text = std::fs::read_to_string(file).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (time, hose, value) = (at("time_s"), at("hose"), at(column));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let last = rows.last().expect("rows")[time];
    rows.iter()
        .filter(|r| r[time] == last && keep(r[hose]))
        .map(|r| r[value].parse::<f64>().unwrap())
        .sum()
}

#[test]
fn the_coolant_tee_settles_with_the_heater_hose_on_the_tee_under_every_solver() {
    let mut loads = Vec::new();
    for solver in ["static", "implicit", "explicit"] {
        let out = tempfile::tempdir().unwrap();
        let o = pliant()
            .args(["run", "--quiet", "--solver", solver])
            .arg(example())
            .arg("--out")
            .arg(out.path())
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{solver}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let read = |name: &str| -> serde_json::Value {
            serde_json::from_str(&std::fs::read_to_string(out.path().join(name)).unwrap()).unwrap()
        };
        let (report, summary) = (read("report.json"), read("summary.json"));
        assert!(
            report["verdict"]["reasons"].is_array(),
            "{solver}: {report}"
        );
        assert!(
            summary["diverged"].is_null(),
            "{solver}: {}",
            summary["diverged"]
        );
        assert_eq!(summary["settles"][0]["at_rest"], true, "{solver}");
        // the clamps carry every weight; the heater return (hose 3) rests on the body
        let clamps = last_sum(&out.path().join("reactions.csv"), "fz_n", |_| true);
        let on_tee = last_sum(&out.path().join("contacts.csv"), "fz_n", |h| h == "3");
        loads.push((solver, clamps, on_tee));
    }
    let (_, clamps, on_tee) = loads[0];
    assert!(
        on_tee > 0.1 * clamps,
        "static: the tee holds {on_tee} N of {clamps} N"
    );
    for &(solver, c, t) in &loads[1..] {
        // the dynamic solvers settle to a kinetic energy of 1e-6 J, not to balance
        assert!(
            (c - clamps).abs() < 2e-2 * clamps,
            "{solver}: clamps {c} N vs static {clamps} N"
        );
        assert!(
            (t - on_tee).abs() < 5e-2 * on_tee,
            "{solver}: on the tee {t} N vs static {on_tee} N"
        );
    }
}

#[test]
fn inspect_names_the_tee_bodys_shape() {
    let o = pliant()
        .args(["inspect", "--json"])
        .arg(example())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let tee = &json["junctions"][0];
    assert_eq!(tee["name"], "tee");
    assert_eq!(tee["degree"], 3);
    let shape = &tee["shape"];
    assert_eq!(shape["part"], "tee_body", "{tee}");
    assert_eq!(shape["kind"], "box");
    let size: Vec<f64> = shape["size_m"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    for (got, want) in size.iter().zip([0.03, 0.03, 0.02]) {
        assert!((got - want).abs() < 1e-12, "{size:?}");
    }
    let text = pliant().arg("inspect").arg(example()).output().unwrap();
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("shape: part tee_body (box, 30.0 × 30.0 × 20.0 mm)"),
        "{text}"
    );
}

#[test]
fn inspect_gives_a_junction_without_a_shape_none() {
    let dir = tempfile::tempdir().unwrap();
    let scene = std::fs::read_to_string(example())
        .unwrap()
        .replace(", part = \"tee_body\" }", " }");
    let path = dir.path().join("plain_tee.toml");
    std::fs::write(&path, scene).unwrap();
    let o = pliant()
        .args(["inspect", "--json"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!(json["junctions"][0]["shape"].is_null(), "{json}");
}
