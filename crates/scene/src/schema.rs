//! The scene format's JSON Schema, generated from [`crate::format`]. The committed copy
//! is `docs/scene.schema.json`; a test keeps it in sync (regenerate with
//! `PLIANT_UPDATE_SCHEMA=1 cargo test --release -p pliant-scene schema`).

use crate::format::SceneFile;

/// The scene format's JSON Schema (draft 7), pretty-printed, with a final newline.
pub fn scene_schema_json() -> String {
    // Optional fields are omitted, never `null`.
    let settings =
        schemars::gen::SchemaSettings::draft07().with(|s| s.option_add_null_type = false);
    let schema = settings
        .into_generator()
        .into_root_schema_for::<SceneFile>();
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}
