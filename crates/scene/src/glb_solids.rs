//! The meshes of an imported STEP assembly, as the STEP converter writes them
//! (`crates/python/python/pliant/cad/step_mesh.py`): a binary glTF with one named node
//! per solid occurrence, vertices in world coordinates in metres, and the conversion's
//! facts (source hash, tolerance, skipped solids) in the asset's `extras.pliant`.

use crate::files::FileAccess;
use crate::mesh::{check_triangle_count, gltf_mesh, no_panic, TriMesh};
use glam::DMat4;
use serde::Deserialize;

/// What the converter recorded about one conversion (`asset.extras.pliant`).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
pub struct ImportFacts {
    /// SHA-256 of the STEP file's bytes (hex).
    #[serde(default)]
    pub source_sha256: String,
    /// Chord tolerance of the tessellation \[m\].
    #[serde(default)]
    pub tolerance_m: f64,
    /// The converter's version.
    #[serde(default)]
    pub converter: String,
    /// The length units the STEP file declares (e.g. `INCH`, `millimetre`).
    #[serde(default)]
    pub file_units: Vec<String>,
    /// Solid occurrences kept.
    #[serde(default)]
    pub solids: usize,
    /// Distinct solid shapes (instances of one part share its shape).
    #[serde(default)]
    pub distinct_solids: usize,
    /// Triangles of all solids.
    #[serde(default)]
    pub triangles: usize,
    /// Solids (or faces of solids) left out, each with the reason.
    #[serde(default)]
    pub skipped: Vec<String>,
    /// Seconds the conversion took (reading and tessellating, without start-up).
    #[serde(default)]
    pub seconds: f64,
}

/// One solid occurrence: its name in the assembly and its triangles [m, world].
#[derive(Clone, Debug, PartialEq)]
pub struct NamedMesh {
    pub name: String,
    pub mesh: TriMesh,
}

/// The JSON chunk of a GLB (the file's structure, no geometry).
fn json_chunk(bytes: &[u8]) -> Result<&[u8], String> {
    let word = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    if word(0) != Some(0x4654_6C67) {
        return Err("not a binary glTF (GLB) file".to_string());
    }
    let len = word(12).ok_or("the GLB file is truncated")?;
    if word(16) != Some(0x4E4F_534A) {
        return Err("the GLB file's first chunk is not JSON".to_string());
    }
    bytes
        .get(20..20usize.saturating_add(len))
        .ok_or_else(|| "the GLB file is truncated".to_string())
}

/// The conversion facts and the triangle count of an imported GLB, read from its JSON
/// alone (so that the scene's budget is checked before any geometry is built).
pub fn glb_facts(bytes: &[u8]) -> Result<(ImportFacts, u64), String> {
    #[derive(Deserialize)]
    struct Accessor {
        count: u64,
        #[serde(rename = "type")]
        kind: String,
    }
    #[derive(Deserialize, Default)]
    struct Extras {
        #[serde(default)]
        pliant: Option<ImportFacts>,
    }
    #[derive(Deserialize)]
    struct Asset {
        #[serde(default)]
        extras: Option<Extras>,
    }
    #[derive(Deserialize)]
    struct Doc {
        asset: Asset,
        #[serde(default)]
        accessors: Vec<Accessor>,
    }
    let doc: Doc = serde_json::from_slice(json_chunk(bytes)?)
        .map_err(|e| format!("the GLB file's JSON is not readable: {e}"))?;
    let facts = doc
        .asset
        .extras
        .and_then(|e| e.pliant)
        .ok_or("the GLB file was not written by Pliant's STEP importer (no extras.pliant)")?;
    let triangles = doc
        .accessors
        .iter()
        .filter(|a| a.kind == "SCALAR")
        .map(|a| a.count / 3)
        .sum();
    Ok((facts, triangles))
}

/// Every named solid of an imported GLB (each top-level node with its subtree).
pub fn read_glb_solids(bytes: &[u8]) -> Result<Vec<NamedMesh>, String> {
    no_panic(|| read_unguarded(bytes))
}

fn read_unguarded(bytes: &[u8]) -> Result<Vec<NamedMesh>, String> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| format!("cannot parse as glTF: {e}"))?;
    let blob = gltf
        .blob
        .clone()
        .ok_or("the GLB file has no binary chunk")?;
    let buffers = vec![blob];
    let doc = &gltf.document;
    let scene = doc
        .default_scene()
        .or_else(|| doc.scenes().next())
        .ok_or("the GLB file has no scene")?;
    let mut out = Vec::new();
    for node in scene.nodes() {
        let Some(m) = node.mesh() else { continue };
        let name = node
            .name()
            .map(str::to_string)
            .unwrap_or_else(|| format!("node {}", node.index()));
        let mut mesh = TriMesh::default();
        let matrix = node.transform().matrix().map(|c| c.map(f64::from));
        gltf_mesh(&m, DMat4::from_cols_array_2d(&matrix), &buffers, &mut mesh)?;
        check_triangle_count(mesh.triangles.len())?;
        out.push(NamedMesh { name, mesh });
    }
    Ok(out)
}

/// Reads an imported GLB through the scene's file access: facts, triangle count.
pub fn read_glb_file_facts(
    files: &FileAccess,
    name: &str,
) -> Result<(Vec<u8>, ImportFacts, u64), String> {
    let bytes = files.read(name)?;
    let (facts, triangles) = glb_facts(&bytes)?;
    Ok((bytes, facts, triangles))
}
