//! The repository's real data files the tests read: the VOBES wire harnesses of
//! `data/harness/` (KBL; CC BY-SA 4.0, see the README there) and the STEP files of
//! `data/cad/` (each under its own licence, see the README there).

use std::path::{Path, PathBuf};

/// The VOBES main harness (KBL 2.4: 183 segments).
pub const MAIN: &str = "kblxml_2.4sr-1_tab016120_modulare_ltgs._160718.kbl";
/// The VOBES generator cable (KBL 2.3: three segments at a Y-junction).
pub const GENERATOR: &str = "kblxml_2.3sr-1_000971230_ltgs_generator_170718.kbl";
/// The VOBES battery cable (KBL 2.3: one segment).
pub const BATTERY: &str = "kblxml_2.3sr-1_000971228_ltgs_batterie_plus_170718.kbl";

/// The repository's root folder.
pub fn repository() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A file of the repository's `data/harness/`.
pub fn harness_file(name: &str) -> PathBuf {
    repository().join("data/harness").join(name)
}

/// A real STEP file of the repository's `data/cad/`, or of the folder
/// `PLIANT_CAD_FILES` names; fails the test if it is not there.
pub fn cad_file(name: &str) -> PathBuf {
    let dir = std::env::var_os("PLIANT_CAD_FILES")
        .map(PathBuf::from)
        .unwrap_or_else(|| repository().join("data/cad"));
    let path = dir.join(name);
    assert!(
        path.is_file(),
        "missing real STEP file {} (data/cad in the repository, or PLIANT_CAD_FILES)",
        path.display()
    );
    path
}

/// A fresh, empty scratch folder `name` of the test suite `suite` under the system's
/// temporary folder, unique to this test process.
pub fn scratch_dir(suite: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pliant-{suite}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch folder in the temporary folder");
    dir
}
