//! `pliant replay` of damaged and torn session logs (evidence is never
//! silently lost), as a user runs it.

use pliant_assembly::workcell::NoObserver;
use pliant_assembly::{Input, WorkcellOptions};
use pliant_runs::session::start_session_folder;
use std::path::Path;
use std::process::{Command, Output};

/// A session folder of the demo scene: 12 resets, 10 steps apart, then a mark.
fn session_folder(dir: &Path) -> String {
    let scene = pliant_scene::load_scene_file(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/demo.toml"
    )))
    .unwrap();
    let mut cell = scene.workcell(WorkcellOptions::default()).unwrap();
    let file = start_session_folder(dir, &scene, &cell).unwrap();
    cell.log_to(Box::new(file));
    for _ in 0..12 {
        cell.apply(Input::Reset).unwrap();
        for _ in 0..10 {
            cell.step(&mut NoObserver).unwrap();
        }
    }
    cell.log_mark();
    assert!(cell.log_error().is_none());
    std::fs::read_to_string(dir.join("inputs.jsonl")).unwrap()
}

fn replay(dir: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
        .args(["replay", "--quiet"])
        .args(extra)
        .arg(dir)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap()
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap()
}

#[test]
fn a_damaged_line_stops_the_replay_unless_told_to_replay_up_to_it() {
    let dir = tempfile::tempdir().unwrap();
    let text = session_folder(dir.path());
    // line 6 is the fifth reset, at tick 40: one digit changed, still a valid line
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    assert!(lines[5].contains("\"tick\":40"), "{}", lines[5]);
    lines[5] = lines[5].replacen("\"tick\":40", "\"tick\":41", 1);
    std::fs::write(dir.path().join("inputs.jsonl"), lines.join("\n") + "\n").unwrap();

    let o = replay(dir.path(), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("line 6 is damaged")
            && err.contains("checksum")
            && err.contains("7 input(s)")
            && err.contains("--up-to-damage"),
        "{err}"
    );
    assert!(!dir.path().join("out/summary.json").exists());

    let o = replay(dir.path(), &["--up-to-damage"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(4), "{err}");
    assert!(err.contains("up to tick 30"), "{err}");
    let s = summary(dir.path());
    assert_eq!(s["log_damage"]["line"], 6, "{s}");
    assert_eq!(s["log_damage"]["inputs_lost"], 7, "{s}");
    assert_eq!(s["log_damage"]["replayed_to_tick"], 30, "{s}");
}

#[test]
fn a_torn_last_line_replays_up_to_the_kill_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = session_folder(dir.path());
    text.push_str("{\"tick\":120,\"input\":\"res"); // killed mid-line
    std::fs::write(dir.path().join("inputs.jsonl"), text).unwrap();
    let o = replay(dir.path(), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("line 15") && err.contains("cut short"),
        "{err}"
    );
    let s = summary(dir.path());
    assert_eq!(s["log_torn_tail"]["line"], 15, "{s}");
}

#[test]
fn a_log_with_an_absurd_tick_is_refused_not_replayed_for_ever() {
    let dir = tempfile::tempdir().unwrap();
    let text = session_folder(dir.path());
    for tick in ["1000000000000", "9223372036854775808"] {
        // an old (version 1) log cannot be checked by checksum: its tick is still refused
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        let last = lines.len() - 1;
        lines[last] = format!("{{\"tick\":{tick}}}");
        let unsealed: Vec<String> = lines
            .iter()
            .map(|l| match l.find(",\"crc32\"") {
                Some(at) => format!("{}}}", &l[..at]),
                None => l.clone(),
            })
            .map(|l| l.replace("\"version\":2", "\"version\":1"))
            .collect();
        std::fs::write(dir.path().join("inputs.jsonl"), unsealed.join("\n") + "\n").unwrap();
        let o = replay(dir.path(), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("tick {tick} is beyond")), "{err}");
    }
}

/// A replay is planned at its log's last tick and checked against `--max-steps` as `pliant
/// run` checks its timeline: beyond it, refused before it starts with the estimate.
#[test]
fn a_replay_beyond_the_step_limit_is_refused_with_its_estimate() {
    let dir = tempfile::tempdir().unwrap();
    session_folder(dir.path()); // 120 steps
    let o = replay(dir.path(), &["--max-steps", "119"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("inputs.jsonl")
            && err.contains("last tick 120")
            && err.contains("at most 119")
            && err.contains("--max-steps"),
        "{err}"
    );
    assert!(!dir.path().join("out/summary.json").exists());
    let o = replay(dir.path(), &["--max-steps", "120"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.path().join("out/summary.json").exists());
}

#[test]
fn a_log_that_is_not_a_regular_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    session_folder(dir.path());
    let log = dir.path().join("inputs.jsonl");
    std::fs::remove_file(&log).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &log).unwrap();
    let o = replay(dir.path(), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("not a regular file"), "{err}");
}
