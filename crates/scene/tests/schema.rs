//! The committed JSON Schema (`docs/scene.schema.json`) matches the format types, every
//! example scene satisfies it, and bad scenes do not.
//!
//! Regenerate the committed schema with
//! `PLIANT_UPDATE_SCHEMA=1 cargo test --release -p pliant-scene --test schema`.

use pliant_scene::scene_schema_json;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn schema_path() -> PathBuf {
    repo_root().join("docs/scene.schema.json")
}

fn validator() -> jsonschema::Validator {
    let schema: Value = serde_json::from_str(&scene_schema_json()).expect("schema is JSON");
    jsonschema::validator_for(&schema).expect("schema compiles")
}

/// A TOML scene as the equivalent JSON document.
fn toml_to_json(text: &str) -> Value {
    let value: toml::Value = toml::from_str(text).expect("valid TOML");
    serde_json::to_value(value).expect("converts to JSON")
}

#[test]
fn committed_schema_is_up_to_date() {
    let fresh = scene_schema_json();
    let path = schema_path();
    if std::env::var_os("PLIANT_UPDATE_SCHEMA").is_some() {
        std::fs::write(&path, &fresh).expect("writes docs/scene.schema.json");
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "docs/scene.schema.json is out of date; regenerate it with\n  \
         PLIANT_UPDATE_SCHEMA=1 cargo test --release -p pliant-scene --test schema"
    );
}

#[test]
fn every_example_satisfies_the_schema() {
    let validator = validator();
    let mut count = 0;
    for entry in std::fs::read_dir(repo_root().join("examples")).expect("examples/ exists") {
        let path = entry.expect("readable").path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("readable");
        if text.contains("format = \"pliant-study\"") {
            continue; // a study (docs/study.schema.json), not a scene
        }
        let json = toml_to_json(&text);
        let errors: Vec<String> = validator
            .iter_errors(&json)
            .map(|e| format!("{} at {}", e, e.instance_path()))
            .collect();
        assert!(
            errors.is_empty(),
            "{}: {}",
            path.display(),
            errors.join("; ")
        );
        count += 1;
    }
    assert!(count >= 5);
}

#[test]
fn bad_scenes_fail_the_schema() {
    let validator = validator();
    let demo = include_str!("../../../examples/demo.toml");
    let bad = [
        (
            "unknown field",
            demo.replacen("normal_hint", "normal_hnt", 1),
        ),
        (
            "wrong unit",
            demo.replacen("length_unit = \"mm\"", "length_unit = \"cm\"", 1),
        ),
        (
            "wrong version",
            demo.replacen("version = 1", "version = 2", 1),
        ),
        (
            "unknown action",
            demo.replacen("action = \"settle\"", "action = \"sette\"", 1),
        ),
        (
            "unknown field in an action",
            demo.replacen("max_duration_s", "max_duration", 1),
        ),
        (
            "two-component point",
            demo.replacen("start = [0, 0, 300]", "start = [0, 0]", 1),
        ),
        (
            "missing hose field",
            demo.replacen("material = \"hose3\"", "", 1),
        ),
    ];
    for (what, text) in bad {
        assert_ne!(text, demo, "{what}: edit did not apply");
        assert!(
            !validator.is_valid(&toml_to_json(&text)),
            "{what}: passed the schema"
        );
    }
}
