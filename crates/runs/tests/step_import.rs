//! STEP import on real files from seven CAD writers (`data/cad/` in the repository, see
//! its README for sources and licences): solids, names, placements,
//! units, tessellation tolerance, errors on broken files, skipped-solid warnings. Needs
//! the importer (`scripts/install-cad.sh`, which `scripts/test.sh` runs); without it
//! these tests fail and say so.

use glam::DVec3;
use pliant_runs::cad_converter::find_python;
use pliant_runs::load::load_scene_str_in;
use pliant_scene::LoadedScene;
use std::path::{Path, PathBuf};

/// The real STEP files: `PLIANT_CAD_FILES`, else the repository's `data/cad`.
fn cad_dir() -> PathBuf {
    let dir = std::env::var_os("PLIANT_CAD_FILES")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/cad"));
    assert!(
        dir.join("README.md").is_file(),
        "the real STEP files are missing: expected {} (data/cad in the repository), or set PLIANT_CAD_FILES",
        dir.display()
    );
    dir
}

fn require_importer() {
    if let Err(e) = find_python() {
        panic!("{e}");
    }
}

/// A fresh folder for a scene (its `.pliant-cache/` goes there).
fn scene_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pliant-step-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A scene with one STEP part (extra keys in `part`) and a short hose far away.
fn scene_text(step: &Path, part: &str) -> String {
    format!(
        r#"format = "pliant-scene"
version = 1
length_unit = "mm"

[[parts]]
name = "cad"
step = "{}"
{part}

[[hoses]]
name = "h"
material = "hose1"
start = [0, 0, 5000]
path = [{{ line = {{ to = [300, 0, 5000] }} }}]
"#,
        step.display()
    )
}

fn load(dir: &Path, step: &Path, part: &str) -> Result<LoadedScene, String> {
    load_scene_str_in(&scene_text(step, part), "scene.toml", dir).map_err(|e| e.to_string())
}

/// Bounding box of all parts \[m\].
fn bbox(s: &LoadedScene) -> (DVec3, DVec3) {
    s.parts.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.bounds.0), hi.max(p.bounds.1)),
    )
}

fn triangles(s: &LoadedScene) -> usize {
    s.parts.iter().map(|p| p.triangles).sum()
}

#[test]
fn all_seven_files_load_with_their_solids() {
    require_importer();
    let cad = cad_dir();
    let dir = scene_dir("seven");
    // file, solid occurrences
    let files = [
        ("nist_ctc_02_asme1_ap242-1.stp", 1),
        ("as1-oc-214.stp", 18),
        ("sg1-c5-214.stp", 1),
        ("as1_pe_203.stp", 18),
        ("cylinder_block.stp", 1),
        ("lower_leg_structure_fork.STEP", 1),
        ("linkrods.step", 1),
    ];
    for (file, solids) in files {
        let s = load(&dir, &cad.join(file), "").unwrap_or_else(|e| panic!("{file}: {e}"));
        assert_eq!(
            s.parts.len(),
            solids,
            "{file}: {:?}",
            s.parts.iter().map(|p| &p.name).collect::<Vec<_>>()
        );
        assert!(s.warnings.is_empty(), "{file}: {:?}", s.warnings);
        for p in &s.parts {
            assert!(p.name.starts_with("cad/"), "{}", p.name);
            assert!(p.triangles > 0, "{file}: {}", p.name);
        }
        let (lo, hi) = bbox(&s);
        let size = (hi - lo).max_element();
        assert!(size > 1e-3 && size < 10.0, "{file}: {size} m");
        eprintln!(
            "{file}: {} solids, {} triangles, {size:.4} m",
            s.parts.len(),
            triangles(&s)
        );
    }
}

#[test]
fn assemblies_keep_names_placements_and_the_file_unit() {
    require_importer();
    let cad = cad_dir();
    let dir = scene_dir("as1");
    let oc = load(&dir, &cad.join("as1-oc-214.stp"), "").unwrap();
    let pe = load(&dir, &cad.join("as1_pe_203.stp"), "").unwrap();
    // 13 assembly occurrences (NEXT_ASSEMBLY_USAGE_OCCURRENCE) of 5 distinct solids
    // (plate, L-bracket, bolt, nut, rod) place 18 solids: 1 plate, 2 brackets, 6 bolts,
    // 8 nuts, 1 rod; every one a part of its own, named by its path in the assembly.
    for s in [&oc, &pe] {
        assert_eq!(s.parts.len(), 18);
        // the leaf's name: the last path element, or the one before Pro/E's "SOLID"
        let leaf = |name: &str| {
            let parts: Vec<String> = name.split('/').map(str::to_ascii_lowercase).collect();
            let last = parts.len() - 1;
            if parts[last].starts_with("solid") {
                parts[last - 1].clone()
            } else {
                parts[last].clone()
            }
        };
        let count = |what: &str| {
            s.parts
                .iter()
                .filter(|p| leaf(&p.name).starts_with(what))
                .count()
        };
        assert_eq!(count("bolt"), 6);
        assert_eq!(count("nut"), 8);
        assert_eq!(count("plate"), 1);
        assert_eq!(count("l-bracket"), 2);
        assert_eq!(count("rod"), 1);
    }
    assert!(oc
        .parts
        .iter()
        .any(|p| p.name == "cad/as1/rod-assembly_1/nut_1"));
    // placements differ per instance: the six bolts sit at six places
    let bolts: Vec<DVec3> = oc
        .parts
        .iter()
        .filter(|p| p.name.contains("bolt"))
        .map(|p| (p.bounds.0 + p.bounds.1) * 0.5)
        .collect();
    for i in 0..bolts.len() {
        for j in 0..i {
            assert!(
                (bolts[i] - bolts[j]).length() > 1e-3,
                "bolts {i} and {j} coincide"
            );
        }
    }
    // The same model from two writers: Open CASCADE in millimetres, Pro/ENGINEER with
    // INCH as the unit of every representation context. The Pro/E file's numbers are the
    // same as the OCC file's (its plate spans 180 units, its bolts have radius 5 units),
    // so read with the file's unit it is 25.4 times larger: the unit comes from the
    // file, not from an assumption. (The two differ in orientation, and Pro/E's bolts
    // are 40 units long against OCC's 37, so parts are compared, not the whole.)
    let leaf = |name: &str| {
        let parts: Vec<String> = name.split('/').map(str::to_ascii_lowercase).collect();
        let last = parts.len() - 1;
        if parts[last].starts_with("solid") {
            parts[last - 1].clone()
        } else {
            parts[last].clone()
        }
    };
    let extents = |s: &LoadedScene, what: &str| {
        let p = s
            .parts
            .iter()
            .find(|p| leaf(&p.name).starts_with(what))
            .unwrap();
        let mut e = (p.bounds.1 - p.bounds.0).to_array();
        e.sort_by(f64::total_cmp);
        e
    };
    for what in ["plate", "l-bracket", "rod", "nut"] {
        let (a, b) = (extents(&oc, what), extents(&pe, what));
        for k in 0..3 {
            let ratio = b[k] / a[k];
            assert!(
                (ratio - 25.4).abs() < 0.05,
                "{what}, extent {k}: {} m (inch file) vs {} m (mm file), ratio {ratio}",
                b[k],
                a[k]
            );
        }
    }
    let plate = extents(&oc, "plate");
    assert!(
        (plate[2] - 0.18).abs() < 1e-4 && (plate[1] - 0.15).abs() < 1e-4,
        "{plate:?}"
    );
    let (lo, hi) = bbox(&oc);
    let (plo, phi) = bbox(&pe);
    let ratio = (phi - plo).max_element() / (hi - lo).max_element();
    assert!(
        (ratio - 25.4).abs() < 0.05,
        "whole assemblies: ratio {ratio}"
    );
}

#[test]
fn chord_tolerance_sets_the_triangle_count() {
    require_importer();
    let cad = cad_dir();
    let dir = scene_dir("tolerance");
    let file = cad.join("lower_leg_structure_fork.STEP");
    let coarse = load(&dir, &file, "chord_tolerance = 1.0").unwrap();
    let fine = load(&dir, &file, "chord_tolerance = 0.02").unwrap();
    let (c, f) = (triangles(&coarse), triangles(&fine));
    assert!(f > 2 * c, "0.02 mm gives {f} triangles, 1 mm {c}");
    // both entries are cached side by side
    let entries = std::fs::read_dir(dir.join(".pliant-cache"))
        .unwrap()
        .count();
    assert!(entries >= 2);
    let e = load(&dir, &file, "chord_tolerance = 0").unwrap_err();
    assert!(e.contains("parts[0].chord_tolerance"), "{e}");
    let e = load(&dir, &file, "chord_tolerance = 1.0\nmesh_unit = \"mm\"").unwrap_err();
    assert!(
        e.contains("parts[0].mesh_unit") && e.contains("own length unit"),
        "{e}"
    );
}

#[test]
fn a_truncated_file_is_refused_naming_the_entity_and_line() {
    require_importer();
    let cad = cad_dir();
    let dir = scene_dir("truncated");
    let bytes = std::fs::read(cad.join("sg1-c5-214.stp")).unwrap();
    let cut = dir.join("cut.stp");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let e = load(&dir, &cut, "").unwrap_err();
    assert!(e.contains("parts[0].step"), "{e}");
    assert!(
        e.contains("truncated") && e.contains("#") && e.contains("line "),
        "{e}"
    );
    // not a STEP file at all
    let junk = dir.join("junk.step");
    std::fs::write(&junk, "solid cube\nendsolid\n").unwrap();
    let e = load(&dir, &junk, "").unwrap_err();
    assert!(e.contains("not a STEP file"), "{e}");
    // a STEP file without solids (only curves) says what it holds
    let curves = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cad/route.step");
    let e = load(&dir, &curves, "").unwrap_err();
    assert!(
        e.contains("no solid could be read") && e.contains("PRODUCT_DEFINITION"),
        "{e}"
    );
    // a missing one names the path
    let e = load(&dir, &dir.join("missing.step"), "").unwrap_err();
    assert!(e.contains("missing.step"), "{e}");
}

/// Rewrites a cached GLB's `extras.pliant.skipped` (the converter's list of solids it
/// could not read), keeping the binary chunk.
fn with_skipped(glb: &[u8], skipped: &[&str]) -> Vec<u8> {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let mut json: serde_json::Value = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    json["asset"]["extras"]["pliant"]["skipped"] = serde_json::json!(skipped);
    let mut text = serde_json::to_vec(&json).unwrap();
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let bin = &glb[20 + len..];
    let mut out = Vec::new();
    out.extend_from_slice(&glb[0..8]);
    out.extend_from_slice(&((12 + 8 + text.len() + bin.len()) as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    out.extend_from_slice(&text);
    out.extend_from_slice(bin);
    out
}

#[test]
fn skipped_solids_reach_the_user() {
    require_importer();
    let cad = cad_dir();
    let dir = scene_dir("skipped");
    let file = cad.join("sg1-c5-214.stp");
    load(&dir, &file, "").unwrap();
    let entry = std::fs::read_dir(dir.join(".pliant-cache"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "glb"))
        .unwrap();
    let glb = std::fs::read(&entry).unwrap();
    std::fs::write(
        &entry,
        with_skipped(&glb, &["SG1/bad solid: tessellation failed (BRepMesh)"]),
    )
    .unwrap();
    let s = load(&dir, &file, "").unwrap();
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(
        s.warnings[0].contains("parts[0]") && s.warnings[0].contains("SG1/bad solid"),
        "{:?}",
        s.warnings
    );
}
