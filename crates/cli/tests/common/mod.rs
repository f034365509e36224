//! What the CLI's end-to-end tests share: the binary, the real harness files of
//! `data/harness/`, and a check that a command succeeded.
// Each test binary compiles this module and uses only some of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The VOBES generator cable (KBL 2.3: three segments at a Y-junction).
pub const GENERATOR: &str = "kblxml_2.3sr-1_000971230_ltgs_generator_170718.kbl";
/// The VOBES battery cable (KBL 2.3: one segment).
pub const BATTERY: &str = "kblxml_2.3sr-1_000971228_ltgs_batterie_plus_170718.kbl";
/// The VOBES main harness (KBL 2.4: 183 segments).
pub const MAIN: &str = "kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl";

/// The `pliant` binary built with these tests.
pub fn pliant() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
}

/// A file of the repository's `data/harness/`.
pub fn harness_file(name: &str) -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/harness")).join(name)
}

/// The command's standard output; fails the test with both streams if it failed.
pub fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}
