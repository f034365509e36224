//! The STEP cache: the second load of an unchanged STEP file reads the cached mesh and
//! starts no converter; a changed file is converted again; scenes sent to the server
//! (sandboxed) never start the converter; a machine without the importer gets a clear
//! message. One test, run alone in this binary, as it counts conversions and sets
//! PLIANT_PYTHON.

use pliant_runs::cad_converter::{conversions, find_python};
use pliant_scene::{load_scene_str_with, LoadOptions, LoadedScene};
use pliant_testkit::files::cad_file;
use std::path::{Path, PathBuf};
use std::time::Instant;

fn scene(step: &str) -> String {
    format!(
        r#"format = "pliant-scene"
version = 1
length_unit = "mm"

[[parts]]
name = "bay"
step = "{step}"

[[hoses]]
name = "h"
material = "hose1"
start = [0, 0, 5000]
path = [{{ line = {{ to = [300, 0, 5000] }} }}]
"#
    )
}

fn load(dir: &Path, step: &str, sandboxed: bool) -> Result<LoadedScene, String> {
    let options = LoadOptions {
        sandboxed,
        ..pliant_runs::load_options()
    };
    load_scene_str_with(&scene(step), "scene.toml", dir, &options).map_err(|e| e.to_string())
}

fn cache_entries(dir: &Path) -> Vec<PathBuf> {
    match std::fs::read_dir(dir.join(".pliant-cache")) {
        Ok(r) => r.map(|e| e.unwrap().path()).collect(),
        Err(_) => Vec::new(),
    }
}

#[test]
fn second_load_reads_the_cache_and_sandboxes_never_convert() {
    if let Err(e) = find_python() {
        panic!("{e}");
    }
    let dir = std::env::temp_dir().join(format!("pliant-step-cache-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(cad_file("as1-oc-214.stp"), dir.join("as1.stp")).unwrap();

    // a sandboxed scene (sent to `pliant serve`) may not convert
    let before = conversions();
    let e = load(&dir, "as1.stp", true).unwrap_err();
    assert!(
        e.contains("pliant import") && e.contains("never start the converter"),
        "{e}"
    );
    assert!(
        !e.contains(&dir.display().to_string()),
        "no server path in a client's error: {e}"
    );
    assert_eq!(conversions(), before);

    // first local load converts, the second reads the cache
    let first = load(&dir, "as1.stp", false).unwrap();
    assert_eq!(conversions(), before + 1);
    let entries = cache_entries(&dir);
    assert_eq!(entries.len(), 1, "{entries:?}");
    let modified = std::fs::metadata(&entries[0]).unwrap().modified().unwrap();
    let t = Instant::now();
    let second = load(&dir, "as1.stp", false).unwrap();
    let cached_load = t.elapsed().as_secs_f64();
    assert_eq!(
        conversions(),
        before + 1,
        "the second load ran the converter"
    );
    assert_eq!(
        std::fs::metadata(&entries[0]).unwrap().modified().unwrap(),
        modified
    );
    assert_eq!(first.world.rigid_parts, second.world.rigid_parts);
    eprintln!("cached load: {cached_load:.3} s");

    // now the sandboxed scene finds the entry and loads without converting
    let served = load(&dir, "as1.stp", true).unwrap();
    assert_eq!(served.parts.len(), 18);
    assert_eq!(conversions(), before + 1);

    // a changed STEP file is converted again (its hash is the key)
    let mut bytes = std::fs::read(dir.join("as1.stp")).unwrap();
    bytes.extend_from_slice(b"\n");
    std::fs::write(dir.join("as1.stp"), bytes).unwrap();
    load(&dir, "as1.stp", false).unwrap();
    assert_eq!(conversions(), before + 2);
    assert_eq!(cache_entries(&dir).len(), 2);

    // without the importer: cached entries still load, new ones say how to install it
    std::env::set_var("PLIANT_PYTHON", dir.join("no-such-python"));
    load(&dir, "as1.stp", false).unwrap();
    std::fs::copy(cad_file("sg1-c5-214.stp"), dir.join("sg1.stp")).unwrap();
    let e = load(&dir, "sg1.stp", false).unwrap_err();
    assert!(
        e.contains("parts[0].step") && e.contains("scripts/install-cad.sh"),
        "{e}"
    );
    std::env::remove_var("PLIANT_PYTHON");
}
