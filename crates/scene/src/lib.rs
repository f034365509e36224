//! Pliant scene files (SPEC §5, M1–M4, L1–L7, I1, I3): a versioned TOML (or JSON) format
//! with a JSON Schema, the built-in material library, centre-line discretisation and
//! thorough validation. Loading is a pure function from text to a [`LoadedScene`] in SI
//! units — a core [`pliant_core::WorldSpec`], a [`pliant_assembly::Timeline`] (hands
//! included), stubs, clips and an ergonomic profile — or a
//! [`SceneError`] that names the field, the value and the reason. Nothing is ever
//! half-loaded.
//!
//! The format is documented in `docs/scene-format.md`; its schema is
//! `docs/scene.schema.json` (see [`scene_schema_json`]).

mod action_de;
pub mod budget;
pub mod centerline;
pub mod checks;
pub mod clip;
pub mod connectors;
pub mod delivered;
pub mod document;
pub mod ergonomics;
pub mod error;
mod fastener_sites;
pub mod fasteners;
pub mod files;
pub mod format;
pub mod glb_solids;
pub mod hoses;
pub mod junctions;
pub mod library;
pub mod load;
pub mod materials;
pub mod mesh;
pub mod part_motion;
pub mod parts;
pub mod protections;
pub mod ranges;
pub mod route;
pub mod scene;
pub mod schema;
pub mod settings;
pub mod step_cache;
pub mod step_parts;
pub mod sweep;
pub mod timeline;
pub mod units;
pub mod validate;
mod workcell;
pub mod worker;

pub use budget::{Estimate, Limits};
pub use document::scene_document;
pub use error::{FieldError, SceneError};
pub use files::FileAccess;
pub use library::{Library, LibraryEntry, LibraryValue, Provenance};
pub use load::{
    base_dir_of, demo_scene, load_scene_file, load_scene_file_with, load_scene_json_str,
    load_scene_json_str_in, load_scene_json_str_with, load_scene_str, load_scene_str_in,
    load_scene_str_with, LoadOptions, DEMO_SCENE_TOML, FORMAT_TAG, FORMAT_VERSION,
};
pub use mesh::{TriMesh, MAX_TRIANGLES};
pub use scene::{HoseDiscretisation, HoseEnd, LoadedScene, PartInfo, SceneClip, SceneStub};
pub use schema::scene_schema_json;
pub use units::LengthUnit;
