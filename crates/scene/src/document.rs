//! A scene file's text as a plain JSON value of its raw structure (the shape of
//! [`crate::format::SceneFile`]: lengths still in the file's `length_unit`, nothing
//! checked or converted). The viewer's scene authoring (docs/authoring.md) edits this
//! document and writes it back as TOML; the loader then checks it as any other file.

/// The text of a scene file (TOML, or JSON) as a JSON value, or why it cannot be read.
/// TOML is tried first; text that is not TOML is read as JSON.
pub fn scene_document(text: &str) -> Result<serde_json::Value, String> {
    match toml::from_str::<serde_json::Value>(text) {
        Ok(v) => Ok(v),
        Err(toml_error) => match serde_json::from_str::<serde_json::Value>(text) {
            Ok(v) => Ok(v),
            Err(_) => Err(format!(
                "not a TOML or JSON document: {}",
                toml_error.message()
            )),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toml_and_json_scenes_read_as_the_same_document() {
        let toml = "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\
                    [[hoses]]\nname = \"a\"\nmaterial = \"hose3\"\nstart = [0, 0, 0.5]\n\
                    path = [{ line = { to = [300, 0, 0] } }]\n";
        let a = scene_document(toml).unwrap();
        assert_eq!(a["hoses"][0]["path"][0]["line"]["to"][0], 300);
        assert_eq!(a["hoses"][0]["start"][2], 0.5);
        let b = scene_document(&a.to_string()).unwrap();
        assert_eq!(a, b);
        assert!(scene_document("= = =").is_err());
        // the built-in demo reads too
        let d = scene_document(crate::DEMO_SCENE_TOML).unwrap();
        assert!(d["hoses"].as_array().is_some_and(|h| !h.is_empty()));
    }
}
