//! What the harness tests share: the real KBL files of data/harness/ (CC BY-SA 4.0, see
//! the README there) and a scratch folder per test.
#![allow(dead_code, unused_imports)] // each test file uses part of it

use std::path::{Path, PathBuf};

pub use pliant_testkit::files::{harness_file as data, BATTERY, GENERATOR, MAIN};

/// A scratch folder `name` of the test suite `suite`.
pub fn out_dir(suite: &str, name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(suite)
        .join(name)
}
