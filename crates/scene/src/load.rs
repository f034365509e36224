//! Loading a scene: text → checked header (format, version) → raw [`SceneFile`] (typed,
//! with line/column on any shape error) → [`LoadedScene`] (checked, SI). A pure function
//! of the text: it returns a complete scene or an error, never part of one.

use crate::action_de::INNER_PATH_PREFIX;
use crate::budget::{Budget, Limits};
use crate::ergonomics::build_ergonomics;
use crate::error::{FieldError, SceneError};
use crate::fasteners::build_fasteners;
use crate::files::{FileAccess, DEFAULT_MAX_FILE_BYTES};
use crate::format::SceneFile;
use crate::hoses::build_hose;
use crate::library::Library;
use crate::materials::Materials;
use crate::parts::build_parts;
use crate::scene::LoadedScene;
use crate::settings::{build_record_interval, build_settings};
use crate::step_cache::ConverterChoice;
use crate::timeline::{build_timeline, HoseNodes};
use pliant_core::WorldSpec;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The format tag every scene file starts with.
pub const FORMAT_TAG: &str = "pliant-scene";
/// The scene format version this build reads.
pub const FORMAT_VERSION: i64 = 1;

/// The built-in demo scene's text (`examples/demo.toml`).
pub const DEMO_SCENE_TOML: &str = include_str!("../../../examples/engine_bay.toml");

/// How a scene is loaded: the resource limits it must stay within and where its files
/// may come from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadOptions {
    /// Memory limit, checked while the scene loads ([`crate::budget`]).
    pub limits: Limits,
    /// Largest mesh file read \[bytes\].
    pub max_file_bytes: u64,
    /// Confine mesh files to the scene's folder, and keep paths and file contents out of
    /// errors (scenes sent by clients of `pliant serve`, [`FileAccess::sandbox`]).
    pub sandboxed: bool,
    /// What converts a STEP part or route the cache lacks (and names the cache's
    /// entries); none refuses STEP files.
    pub converter: ConverterChoice,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            limits: Limits::default(),
            max_file_bytes: DEFAULT_MAX_FILE_BYTES,
            sandboxed: false,
            converter: ConverterChoice::default(),
        }
    }
}

impl LoadOptions {
    /// The file access for a scene whose relative names start at `base_dir`.
    pub fn files(&self, base_dir: &Path) -> FileAccess {
        let access = if self.sandboxed {
            FileAccess::sandbox(base_dir)
        } else {
            FileAccess::local(base_dir)
        };
        access
            .with_max_file_bytes(self.max_file_bytes)
            .with_converter(self.converter)
    }
}

/// Loads a scene file; `.json` files are read as JSON, everything else as TOML. Relative
/// mesh paths are resolved against the file's directory.
pub fn load_scene_file(path: &Path) -> Result<LoadedScene, SceneError> {
    load_scene_file_with(path, &LoadOptions::default())
}

/// [`load_scene_file`] with explicit limits.
pub fn load_scene_file_with(path: &Path, options: &LoadOptions) -> Result<LoadedScene, SceneError> {
    let origin = path.display().to_string();
    let io = |source| SceneError::Io {
        path: origin.clone(),
        source,
    };
    // a regular file (never a FIFO or a device) of at most MAX_SCENE_FILE_BYTES
    let text = pliant_files::read_regular_text(path, MAX_SCENE_FILE_BYTES).map_err(|e| {
        io(std::io::Error::other(match e.kind {
            pliant_files::FileErrorKind::TooLarge { len, max } => format!(
                "the file has {len} bytes; a scene file may have at most {max} (meshes belong in mesh files)"
            ),
            kind => return io(kind.into_io()),
        }))
    })?;
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let file = if is_json {
        parse_json(&text, &origin)?
    } else {
        parse_toml(&text, &origin)?
    };
    build_scene_with(&file, &text, &origin, &dir, options)
}

/// Largest scene file read \[bytes\] (the text; meshes are separate files).
pub const MAX_SCENE_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// The directory relative mesh paths are resolved against for a scene from `origin`:
/// the directory of `origin` if it names an existing file, else the current directory
/// (the empty path).
pub fn base_dir_of(origin: &str) -> PathBuf {
    let p = Path::new(origin);
    if p.is_file() {
        p.parent().map(Path::to_path_buf).unwrap_or_default()
    } else {
        PathBuf::new()
    }
}

/// Loads a scene from TOML text; `origin` names it in errors (e.g. the file name).
/// Relative mesh paths are resolved as by [`base_dir_of`].
pub fn load_scene_str(text: &str, origin: &str) -> Result<LoadedScene, SceneError> {
    load_scene_str_in(text, origin, &base_dir_of(origin))
}

/// Loads a scene from TOML text, resolving relative mesh paths against `base_dir`.
pub fn load_scene_str_in(
    text: &str,
    origin: &str,
    base_dir: &Path,
) -> Result<LoadedScene, SceneError> {
    load_scene_str_with(text, origin, base_dir, &LoadOptions::default())
}

/// [`load_scene_str_in`] with explicit limits and file access.
pub fn load_scene_str_with(
    text: &str,
    origin: &str,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<LoadedScene, SceneError> {
    let file = parse_toml(text, origin)?;
    build_scene_with(&file, text, origin, base_dir, options)
}

/// Loads a scene from JSON text (same structure as the TOML format). Relative mesh
/// paths are resolved as by [`base_dir_of`].
pub fn load_scene_json_str(text: &str, origin: &str) -> Result<LoadedScene, SceneError> {
    load_scene_json_str_in(text, origin, &base_dir_of(origin))
}

/// Loads a scene from JSON text, resolving relative mesh paths against `base_dir`.
pub fn load_scene_json_str_in(
    text: &str,
    origin: &str,
    base_dir: &Path,
) -> Result<LoadedScene, SceneError> {
    load_scene_json_str_with(text, origin, base_dir, &LoadOptions::default())
}

/// [`load_scene_json_str_in`] with explicit limits and file access.
pub fn load_scene_json_str_with(
    text: &str,
    origin: &str,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<LoadedScene, SceneError> {
    let file = parse_json(text, origin)?;
    build_scene_with(&file, text, origin, base_dir, options)
}

/// The built-in demo scene.
pub fn demo_scene() -> Result<LoadedScene, SceneError> {
    // its engine block mesh is read from the repository's examples folder
    let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
    load_scene_str_in(
        DEMO_SCENE_TOML,
        "examples/engine_bay.toml (built in)",
        examples,
    )
}

/// 1-based line and column of a byte offset.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// The header's two values in a form common to TOML and JSON.
enum HeaderValue {
    Str(String),
    Int(i64),
    Other(String),
}

/// Checks `format` and `version` before anything else, so that a file of another kind or
/// version gets a clear error rather than a list of unknown fields.
fn check_header(
    origin: &str,
    format: Option<(HeaderValue, Option<(usize, usize)>)>,
    version: Option<(HeaderValue, Option<(usize, usize)>)>,
) -> Result<(), SceneError> {
    let structure = |location, field: &str, message: String| SceneError::Structure {
        origin: origin.to_string(),
        location,
        field: field.to_string(),
        message,
    };
    match format {
        None => {
            return Err(structure(
                None,
                "format",
                format!("missing; a scene file must contain format = \"{FORMAT_TAG}\""),
            ))
        }
        Some((HeaderValue::Str(s), _)) if s == FORMAT_TAG => {}
        Some((value, location)) => {
            let found = match value {
                HeaderValue::Str(s) => format!("\"{s}\""),
                HeaderValue::Int(i) => i.to_string(),
                HeaderValue::Other(o) => o,
            };
            return Err(structure(
                location,
                "format",
                format!("expected \"{FORMAT_TAG}\", found {found}: not a Pliant scene file"),
            ));
        }
    }
    match version {
        None => Err(structure(
            None,
            "version",
            format!("missing; this build reads version = {FORMAT_VERSION}"),
        )),
        Some((HeaderValue::Int(v), _)) if v == FORMAT_VERSION => Ok(()),
        Some((HeaderValue::Int(v), location)) => Err(structure(
            location,
            "version",
            format!(
                "unsupported scene format version {v}; this build reads version {FORMAT_VERSION}"
            ),
        )),
        Some((value, location)) => {
            let found = match value {
                HeaderValue::Str(s) => format!("\"{s}\""),
                HeaderValue::Int(i) => i.to_string(),
                HeaderValue::Other(o) => o,
            };
            Err(structure(
                location,
                "version",
                format!("expected the integer {FORMAT_VERSION}, found {found}"),
            ))
        }
    }
}

/// Makes serde's messages name the field itself where they name it only in the text.
fn refine(path: String, message: String) -> (String, String) {
    // Errors inside a timeline action carry their inner path (see `action_de`).
    let (path, message) = match message
        .strip_prefix(INNER_PATH_PREFIX)
        .and_then(|rest| rest.split_once("`: "))
    {
        Some((inner, rest)) if path == "." => (inner.to_string(), rest.to_string()),
        Some((inner, rest)) => (format!("{path}.{inner}"), rest.to_string()),
        None => (path, message),
    };
    let named = ["missing field `", "unknown field `"]
        .iter()
        .find_map(|p| message.strip_prefix(p))
        .and_then(|rest| rest.split('`').next())
        .map(str::to_string);
    let field = match named {
        Some(name) if path == "." => name,
        Some(name) if !path.ends_with(&name) => format!("{path}.{name}"),
        _ if path == "." => "(top level)".to_string(),
        _ => path,
    };
    let message = if message.contains("untagged enum Points") {
        "expected a point [x, y, z] or a list of points [[x, y, z], …]".to_string()
    } else if message.contains("wanted exactly 1 element") {
        // Only path segments are externally tagged enums written as tables.
        "a segment is a table with exactly one of `line`, `arc`, `spline`".to_string()
    } else {
        message
    };
    (field, message)
}

/// TOML header: only `format` and `version`, with their spans; other keys ignored.
#[derive(Deserialize)]
struct TomlHeader {
    format: Option<toml::Spanned<toml::Value>>,
    version: Option<toml::Spanned<toml::Value>>,
}

/// Parses TOML text into the raw scene structure (header checked first).
pub fn parse_toml(text: &str, origin: &str) -> Result<SceneFile, SceneError> {
    let header: TomlHeader = toml::from_str(text).map_err(|e| SceneError::Syntax {
        origin: origin.to_string(),
        location: e.span().map(|s| line_column(text, s.start)),
        message: e.message().trim().to_string(),
    })?;
    let convert = |v: toml::Spanned<toml::Value>| {
        let location = Some(line_column(text, v.span().start));
        let value = match v.into_inner() {
            toml::Value::String(s) => HeaderValue::Str(s),
            toml::Value::Integer(i) => HeaderValue::Int(i),
            other => HeaderValue::Other(other.to_string()),
        };
        (value, location)
    };
    check_header(
        origin,
        header.format.map(convert),
        header.version.map(convert),
    )?;
    serde_path_to_error::deserialize(toml::Deserializer::new(text)).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let (field, message) = refine(path, inner.message().trim().to_string());
        SceneError::Structure {
            origin: origin.to_string(),
            location: inner.span().map(|s| line_column(text, s.start)),
            field,
            message,
        }
    })
}

/// JSON header: only `format` and `version`; other keys ignored.
#[derive(Deserialize)]
struct JsonHeader {
    format: Option<serde_json::Value>,
    version: Option<serde_json::Value>,
}

/// Parses JSON text into the raw scene structure (header checked first).
pub fn parse_json(text: &str, origin: &str) -> Result<SceneFile, SceneError> {
    let header: JsonHeader = serde_json::from_str(text).map_err(|e| SceneError::Syntax {
        origin: origin.to_string(),
        location: Some((e.line(), e.column())),
        message: e.to_string(),
    })?;
    let convert = |v: serde_json::Value| {
        let value = match v {
            serde_json::Value::String(s) => HeaderValue::Str(s),
            serde_json::Value::Number(n) if n.is_i64() => {
                HeaderValue::Int(n.as_i64().unwrap_or_default())
            }
            other => HeaderValue::Other(other.to_string()),
        };
        (value, None)
    };
    check_header(
        origin,
        header.format.map(convert),
        header.version.map(convert),
    )?;
    let mut de = serde_json::Deserializer::from_str(text);
    serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        let location = Some((inner.line(), inner.column()));
        // serde_json appends " at line L column C"; the location is reported separately.
        let message = inner.to_string();
        let message = message
            .rsplit_once(" at line ")
            .map_or(message.clone(), |(m, _)| m.to_string());
        let (field, message) = refine(path, message);
        SceneError::Structure {
            origin: origin.to_string(),
            location,
            field,
            message,
        }
    })
}

/// Checks a raw scene and converts it to SI (relative mesh paths as by [`base_dir_of`]).
pub fn build_scene(file: &SceneFile, text: &str, origin: &str) -> Result<LoadedScene, SceneError> {
    build_scene_in(file, text, origin, &base_dir_of(origin))
}

/// Checks a raw scene and converts it to SI, resolving relative mesh paths against
/// `base_dir`.
pub fn build_scene_in(
    file: &SceneFile,
    text: &str,
    origin: &str,
    base_dir: &Path,
) -> Result<LoadedScene, SceneError> {
    build_scene_with(file, text, origin, base_dir, &LoadOptions::default())
}

/// [`build_scene_in`] with explicit limits and file access.
pub fn build_scene_with(
    file: &SceneFile,
    text: &str,
    origin: &str,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<LoadedScene, SceneError> {
    build(file, text, origin, base_dir, options).map_err(|e| e.at(origin))
}

/// [`build_scene_with`] without the origin attached to errors.
fn build(
    file: &SceneFile,
    text: &str,
    origin: &str,
    base_dir: &Path,
    options: &LoadOptions,
) -> Result<LoadedScene, FieldError> {
    let mut budget = Budget::new(options.limits);
    let library = Library::builtin().map_err(|e| FieldError::about("materials", e.to_string()))?;
    let materials = Materials::build(&file.materials, library)?;
    let mut settings = build_settings(file.simulation.as_ref())?;
    let record_interval = build_record_interval(file.output.as_ref())?;
    if file.hoses.is_empty() {
        return Err(FieldError::about(
            "hoses",
            "a scene needs at least one hose",
        ));
    }
    let files = options.files(base_dir);
    let mut hoses = Vec::with_capacity(file.hoses.len());
    let mut infos = Vec::with_capacity(file.hoses.len());
    for (i, raw) in file.hoses.iter().enumerate() {
        if let Some(first) = file.hoses[..i].iter().position(|h| h.name == raw.name) {
            return Err(FieldError::new(
                format!("hoses[{i}].name"),
                format!("\"{}\"", raw.name),
                format!("duplicate hose name (also hoses[{first}].name)"),
            ));
        }
        let (spec, info) = build_hose(i, raw, file.length_unit, &materials, &files)?;
        budget.add_elements(
            &format!("hoses[{i}]"),
            spec.nodes.len().saturating_sub(1) as u64,
        )?;
        hoses.push(spec);
        infos.push(info);
    }
    budget.add_contact_pairs("hoses", &hoses)?;
    let nodes: Vec<HoseNodes> = hoses
        .iter()
        .map(|h| HoseNodes {
            name: &h.name,
            nodes: h.nodes.len(),
        })
        .collect();
    let timeline = build_timeline(&file.timeline, &nodes, file.length_unit)?;
    let mut parts = build_parts(&file.parts, file.length_unit, &files, &mut budget)?;
    crate::timeline::make_moved_parts_movable(&timeline, &mut parts.specs)?;
    let junctions =
        crate::junctions::build_junctions(&file.junctions, &hoses, &parts.specs, file.length_unit)?;
    let part_names: Vec<&str> = parts.specs.iter().map(|p| p.name.as_str()).collect();
    let (stubs, connectors, clips) = build_fasteners(file, &hoses, &part_names)?;
    let ergonomics = build_ergonomics(file.ergonomics.as_ref())?;
    let mut checks = crate::checks::build_checks(file.checks.as_ref(), &infos, record_interval)?;
    checks.sweep = crate::sweep::build_sweep(
        file.sweep.as_ref(),
        &hoses,
        &parts.specs,
        &timeline,
        file.length_unit,
    )?;
    let worker = crate::worker::build_worker(
        file.worker.as_ref(),
        file.length_unit,
        settings.gravity,
        record_interval,
    )?;
    let name = match &file.name {
        Some(n) if !n.trim().is_empty() => n.clone(),
        _ => Path::new(origin)
            .file_stem()
            .map_or_else(|| origin.to_string(), |s| s.to_string_lossy().into_owned()),
    };
    settings.max_contact_pairs = budget.contact_pair_room();
    let mut warnings = parts.warnings;
    warnings.extend(time_step_warning(settings.time_step_safety));
    Ok(LoadedScene {
        name,
        hose_names: hoses.iter().map(|h| h.name.clone()).collect(),
        world: WorldSpec {
            hoses,
            rigid_parts: parts.specs,
            settings,
        },
        junction_bodies: file
            .junctions
            .iter()
            .enumerate()
            .filter(|(_, j)| j.body.is_some())
            .map(|(i, _)| i)
            .collect(),
        junctions,
        timeline,
        record_interval,
        hoses: infos,
        parts: parts.infos,
        warnings,
        stubs,
        connectors,
        clips,
        ergonomics,
        checks,
        worker,
        length_unit: file.length_unit,
        source: origin.to_string(),
        text: text.to_string(),
        base_dir: base_dir.to_path_buf(),
        estimate: budget.estimate,
        limits: options.limits,
    })
}

/// What a time-step safety factor above the defaults' design puts at risk: hoses pressing
/// on each other above [`SAFETY_FOR_HOSE_CONTACT`] (0.5), and above
/// [`largest_safety_with_supports`] (≈ 0.65) the support springs too.
fn time_step_warning(safety: f64) -> Option<String> {
    let contact = pliant_core::contact::SAFETY_FOR_HOSE_CONTACT;
    let supports = pliant_core::loads::largest_safety_with_supports();
    if safety <= contact {
        return None;
    }
    let springs = if safety > supports {
        format!(
            "; above {supports:.2} so can the springs that hold nodes in fixings, loose grips \
             and clips seated as supports (k = 0.5 m/Δt²)"
        )
    } else {
        String::new()
    };
    Some(format!(
        "simulation.time_step_safety = {safety}: above {contact} hoses pressing on each other \
         (hose–hose contact, whose stiffness is capped for that step) can ring or go \
         unstable{springs}; keep it at or below {contact} unless no hose touches another \
         (a divergence is reported, never a wrong number)"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_column_counts_from_one() {
        let t = "ab\ncdé\nf";
        assert_eq!(line_column(t, 0), (1, 1));
        assert_eq!(line_column(t, 3), (2, 1));
        assert_eq!(line_column(t, 5), (2, 3));
        assert_eq!(line_column(t, 6), (2, 3));
        assert_eq!(line_column(t, 999), (3, 2));
    }
}
