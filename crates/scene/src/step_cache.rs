//! The STEP cache: a STEP file is converted once (by a [`StepConverter`], the program's
//! choice) into a GLB in `.pliant-cache/` beside the scene, named after the STEP file and
//! a key — the SHA-256 of the STEP file's bytes, the chord tolerance and the converter's
//! own identity ([`StepConverter::id`]) — and reused while all three are unchanged, so
//! the second load reads only the GLB.
//!
//! A scene from the user's disk converts a missing or stale entry; a sandboxed scene
//! (sent to `pliant serve`) never starts the converter: it reads an existing entry, or
//! is refused with a message saying how to make one (`pliant import`). This crate only
//! names and reads the entries; the process that converts lives with the programs that
//! run scenes (`pliant-runs`), which hand it to the loader in [`crate::LoadOptions`].

use crate::files::FileAccess;
use glam::DVec3;
use serde::Deserialize;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// What converts STEP files into the cache's entries: a mesh (GLB, one named node per
/// solid, metres, recording the STEP file's SHA-256) or one curve's samples (JSON
/// `{"points": [[x, y, z], …]}` in metres). Both write `out` atomically.
pub trait StepConverter: Send + Sync {
    /// The converter's identity (e.g. a hash of its source): part of every cache key,
    /// so a changed converter never reuses old entries.
    fn id(&self) -> &str;
    /// Converts `step` to the GLB `out` with a chord tolerance \[m\].
    fn convert_mesh(&self, step: &Path, out: &Path, tolerance_m: f64) -> Result<(), String>;
    /// Samples one curve of `step` within `tolerance_m` \[m\] into the JSON file `out`.
    fn sample_curve(
        &self,
        step: &Path,
        pick: &CurvePick,
        tolerance_m: f64,
        out: &Path,
    ) -> Result<(), String>;
}

/// The converter a load may use, if any: a reference the loader's options can copy.
/// Options compare equal when their converters have the same [`StepConverter::id`].
#[derive(Clone, Copy, Default)]
pub struct ConverterChoice(pub Option<&'static dyn StepConverter>);

impl ConverterChoice {
    /// The converter, or the refusal of a load that was given none.
    pub fn converter(&self) -> Result<&'static dyn StepConverter, String> {
        self.0.ok_or_else(|| NO_CONVERTER.to_string())
    }
}

impl std::fmt::Debug for ConverterChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some(c) => write!(f, "ConverterChoice({})", c.id()),
            None => f.write_str("ConverterChoice(none)"),
        }
    }
}

impl PartialEq for ConverterChoice {
    fn eq(&self, other: &Self) -> bool {
        self.0.map(|c| c.id()) == other.0.map(|c| c.id())
    }
}

/// Why a load without a converter cannot read a STEP file.
const NO_CONVERTER: &str = "this program loads scenes without a STEP converter, so it cannot read STEP files (load the scene with `pliant run`, or through `pliant_runs::load_options`)";

/// Which curve of a STEP file.
#[derive(Clone, Debug, PartialEq)]
pub enum CurvePick {
    Name(String),
    Index(usize),
}

/// What the converter writes for a curve.
#[derive(Deserialize)]
struct CurveFile {
    points: Vec<[f64; 3]>,
}

/// The points of a curve file written by the converter.
pub fn parse_curve(bytes: &[u8]) -> Result<Vec<DVec3>, String> {
    let c: CurveFile = serde_json::from_slice(bytes)
        .map_err(|e| format!("the sampled curve is not readable: {e}"))?;
    Ok(c.points.into_iter().map(DVec3::from_array).collect())
}

/// Lower-case hex of bytes.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The cache folder, beside the scene (relative to its base folder).
pub const CACHE_DIR: &str = ".pliant-cache";

/// Default chord tolerance of a STEP tessellation \[m\] (0.5 mm: a hose of 10–40 mm
/// diameter meets a surface within 2–5 % of its radius).
pub const DEFAULT_CHORD_TOLERANCE: f64 = 0.5e-3;

/// Default tolerance of a sampled STEP route curve \[m\] (largest distance of the
/// polyline through the samples from the CAD curve).
pub const DEFAULT_CURVE_TOLERANCE: f64 = 0.01e-3;

/// The cache key of `what` (e.g. "mesh", "curve name=…") made from a STEP file's bytes
/// with a tolerance \[m\] by the converter `converter_id`: 16 hex digits.
pub fn cache_key(step_bytes: &[u8], tolerance_m: f64, converter_id: &str, what: &str) -> String {
    let mut h = Sha256::new();
    h.update(Sha256::digest(step_bytes));
    h.update(tolerance_m.to_bits().to_le_bytes());
    h.update(converter_id.as_bytes());
    h.update(what.as_bytes());
    hex(&h.finalize())[..16].to_string()
}

/// SHA-256 (hex) of a STEP file's bytes, as the converter records it.
pub fn source_sha256(step_bytes: &[u8]) -> String {
    hex(&Sha256::digest(step_bytes))
}

/// The cache entry's name relative to the scene's folder.
pub fn cache_name(step_name: &str, key: &str, extension: &str) -> String {
    let stem = Path::new(step_name)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "step".to_string());
    let stem: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{CACHE_DIR}/{stem}-{key}.{extension}")
}

/// The mesh cache entry of a STEP file (relative to the scene's folder) made by the
/// converter `converter_id`.
pub fn mesh_cache_name(
    step_name: &str,
    step_bytes: &[u8],
    tolerance_m: f64,
    converter_id: &str,
) -> String {
    cache_name(
        step_name,
        &cache_key(step_bytes, tolerance_m, converter_id, "mesh"),
        "glb",
    )
}

/// Why a sandboxed scene cannot import.
const SANDBOX_REFUSAL: &str = "this STEP file has not been imported with this chord tolerance: scenes sent to the server never start the converter; run `pliant import STEP_FILE --tolerance …` in the served scene's folder (or load the scene once with `pliant run`)";

/// Makes sure `path`'s folder exists.
fn make_parent(path: &Path) -> Result<(), String> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create the cache folder {}: {e}", dir.display()))?;
    }
    Ok(())
}

/// The imported GLB of the STEP file `step` (read through `files`) at `tolerance_m`:
/// the cache entry's bytes and its name, converting first if it is missing or stale
/// (never in a sandbox). `converted` tells whether the converter ran.
pub struct CachedMesh {
    pub glb: Vec<u8>,
    pub cache: String,
    pub converted: bool,
}

/// See [`CachedMesh`].
pub fn cached_mesh(files: &FileAccess, step: &str, tolerance_m: f64) -> Result<CachedMesh, String> {
    let bytes = files.read(step)?;
    let converter = files.converter().converter()?;
    let cache = mesh_cache_name(step, &bytes, tolerance_m, converter.id());
    let sha = source_sha256(&bytes);
    let fresh =
        |glb: &[u8]| crate::glb_solids::glb_facts(glb).is_ok_and(|(f, _)| f.source_sha256 == sha);
    // a missing entry reads as an error; so does one that is not a file
    if let Ok(glb) = files.read(&cache) {
        if fresh(&glb) {
            return Ok(CachedMesh {
                glb,
                cache,
                converted: false,
            });
        }
    }
    if files.is_sandboxed() {
        return Err(SANDBOX_REFUSAL.to_string());
    }
    let step_path = files.resolve(step)?;
    let out = files.resolve(&cache)?;
    make_parent(&out)?;
    converter.convert_mesh(&step_path, &out, tolerance_m)?;
    let glb = files.read(&cache)?;
    if !fresh(&glb) {
        return Err(format!(
            "the converter wrote {} but it does not describe this STEP file",
            out.display()
        ));
    }
    Ok(CachedMesh {
        glb,
        cache,
        converted: true,
    })
}

/// The points of one curve of the STEP file `step` sampled within `tolerance_m` \[m\]
/// (metres), from the cache or by sampling it (never in a sandbox).
pub fn cached_curve(
    files: &FileAccess,
    step: &str,
    pick: &CurvePick,
    tolerance_m: f64,
) -> Result<Vec<DVec3>, String> {
    let bytes = files.read(step)?;
    let converter = files.converter().converter()?;
    let what = match pick {
        CurvePick::Name(n) => format!("curve name={n}"),
        CurvePick::Index(i) => format!("curve index={i}"),
    };
    let cache = cache_name(
        step,
        &cache_key(&bytes, tolerance_m, converter.id(), &what),
        "json",
    );
    if let Ok(json) = files.read(&cache) {
        return parse_curve(&json);
    }
    if files.is_sandboxed() {
        return Err(
            SANDBOX_REFUSAL.replace("STEP_FILE --tolerance …", "… or `pliant run` the scene")
        );
    }
    let step_path = files.resolve(step)?;
    let out: PathBuf = files.resolve(&cache)?;
    make_parent(&out)?;
    converter.sample_curve(&step_path, pick, tolerance_m, &out)?;
    parse_curve(&files.read(&cache)?)
}
