//! What the harness tests share: the real KBL files of data/harness/ (CC BY-SA 4.0, see
//! the README there) and a scratch folder per test.
#![allow(dead_code)] // each test file uses part of it

use std::path::{Path, PathBuf};

pub const MAIN: &str = "kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl";
pub const GENERATOR: &str = "kblxml_2.3sr-1_000971230_ltgs_generator_170718.kbl";
pub const BATTERY: &str = "kblxml_2.3sr-1_000971228_ltgs_batterie_plus_170718.kbl";

/// A file of data/harness/.
pub fn data(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/harness")
        .join(file)
}

/// A scratch folder `name` of the test suite `suite`.
pub fn out_dir(suite: &str, name: &str) -> PathBuf {
    Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(suite)
        .join(name)
}
