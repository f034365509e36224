//! The scene loader's entry points with the STEP converter handed in
//! ([`crate::load_options`]): what a program loading the user's own scenes calls.

use crate::cad_converter::load_options;
use pliant_scene::{LoadedScene, SceneError};
use std::path::Path;

/// [`pliant_scene::load_scene_file`], converting STEP files the cache lacks.
pub fn load_scene_file(path: &Path) -> Result<LoadedScene, SceneError> {
    pliant_scene::load_scene_file_with(path, &load_options())
}

/// [`pliant_scene::load_scene_str_in`], converting STEP files the cache lacks.
pub fn load_scene_str_in(
    text: &str,
    origin: &str,
    base_dir: &Path,
) -> Result<LoadedScene, SceneError> {
    pliant_scene::load_scene_str_with(text, origin, base_dir, &load_options())
}

/// [`pliant_scene::load_scene_json_str_in`], converting STEP files the cache lacks.
pub fn load_scene_json_str_in(
    text: &str,
    origin: &str,
    base_dir: &Path,
) -> Result<LoadedScene, SceneError> {
    pliant_scene::load_scene_json_str_with(text, origin, base_dir, &load_options())
}
