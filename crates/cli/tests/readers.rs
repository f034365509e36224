//! Every file reader reads regular files only and the STEP converter has a time limit,
//! as a user runs `pliant`.

use std::path::Path;
use std::process::{Command, Output};

fn pliant(args: &[&str], files: &[&Path]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
        .args(args)
        .args(files)
        .output()
        .unwrap()
}

/// A link to `/dev/zero` and (where `mkfifo` exists) a FIFO named `name` in `dir`.
fn special_files(dir: &Path, name: &str) -> Vec<std::path::PathBuf> {
    let zero = dir.join(format!("zero-{name}"));
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let mut files = vec![zero];
    let fifo = dir.join(format!("fifo-{name}"));
    if Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        files.push(fifo);
    }
    files
}

fn assert_refused(o: &Output) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("not a regular file"), "{err}");
}

#[test]
fn step_kbl_calibration_and_scene_files_that_are_not_regular_files_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for f in special_files(dir.path(), "part.stp") {
        assert_refused(&pliant(&["import"], &[&f]));
    }
    for f in special_files(dir.path(), "harness.kbl") {
        assert_refused(&pliant(&["import"], &[&f]));
    }
    for f in special_files(dir.path(), "curve.csv") {
        let out = dir.path().join("out");
        let o = Command::new(env!("CARGO_BIN_EXE_pliant"))
            .args(["calibrate", "--kind", "torsion", "--length", "300"])
            .args(["--d-outer", "16", "--d-inner", "10", "--csv"])
            .arg(&f)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert_refused(&o);
    }
    for f in special_files(dir.path(), "hose.toml") {
        assert_refused(&pliant(&["calibrate"], &[&f]));
        assert_refused(&pliant(&["run", "--quiet"], &[&f]));
    }
}

/// A converter that never finishes (as OpenCASCADE on some files with absurd
/// coordinates) is stopped at the time limit and the import fails, naming it.
#[test]
fn a_step_converter_that_hangs_is_stopped_at_the_time_limit() {
    let dir = tempfile::tempdir().unwrap();
    // an interpreter that passes the importer's probe, then never finishes converting
    let python = dir.path().join("python");
    std::fs::write(
        &python,
        "#!/bin/sh\nif [ \"$1\" = \"-c\" ]; then exit 0; fi\nexec sleep 1000\n",
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&python, std::fs::Permissions::from_mode(0o755)).unwrap();
    let step = dir.path().join("part.stp");
    std::fs::write(&step, "ISO-10303-21;\nEND-ISO-10303-21;\n").unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_pliant"))
        .arg("import")
        .arg(&step)
        .arg("--out")
        .arg(dir.path().join("part.glb"))
        .env("PLIANT_PYTHON", &python)
        .env("PLIANT_CONVERTER_TIME_LIMIT_S", "0.5")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("did not finish within 0.5 s")
            && err.contains("PLIANT_CONVERTER_TIME_LIMIT_S"),
        "{err}"
    );
}
