//! What the CLI's end-to-end tests share: the binary, the real harness files of
//! `data/harness/` (from the workspace's test kit), and a check that a command succeeded.
// Each test binary compiles this module and uses only some of it.
#![allow(dead_code, unused_imports)]

use std::process::{Command, Output};

pub use pliant_testkit::files::{harness_file, BATTERY, GENERATOR, MAIN};

/// The `pliant` binary built with these tests.
pub fn pliant() -> Command {
    Command::new(env!("CARGO_BIN_EXE_pliant"))
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
