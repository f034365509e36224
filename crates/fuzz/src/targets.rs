//! The fuzz targets: each takes raw bytes and checks the properties its reader promises.
//! `Err` is a broken property; a panic is a find as well.

use crate::seeds;
use pliant_assembly::WorkcellOptions;
use pliant_scene::mesh::{check_mesh, read_gltf, read_obj, read_stl, TriMesh};
use pliant_scene::{FileAccess, Limits, LoadOptions, LoadedScene};
use pliant_server::ClientMessage;

/// What is fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    SceneToml,
    SceneJson,
    Obj,
    Stl,
    Gltf,
    Protocol,
    SessionLog,
    CalibrationSpec,
    CalibrationCsv,
    Kbl,
    Study,
}

impl Target {
    pub const ALL: [Target; 11] = [
        Target::SceneToml,
        Target::SceneJson,
        Target::Obj,
        Target::Stl,
        Target::Gltf,
        Target::Protocol,
        Target::SessionLog,
        Target::CalibrationSpec,
        Target::CalibrationCsv,
        Target::Kbl,
        Target::Study,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Target::SceneToml => "scene-toml",
            Target::SceneJson => "scene-json",
            Target::Obj => "obj",
            Target::Stl => "stl",
            Target::Gltf => "gltf",
            Target::Protocol => "protocol",
            Target::SessionLog => "session-log",
            Target::CalibrationSpec => "calibration-spec",
            Target::CalibrationCsv => "calibration-csv",
            Target::Kbl => "kbl",
            Target::Study => "study",
        }
    }

    /// The target named `name`.
    pub fn named(name: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == name)
    }

    /// The seeds its inputs are made from.
    pub fn seeds(self) -> Vec<Vec<u8>> {
        match self {
            Target::SceneToml => seeds::SCENES
                .iter()
                .map(|s| s.as_bytes().to_vec())
                .collect(),
            Target::SceneJson => seeds::scenes_json()
                .into_iter()
                .map(String::into_bytes)
                .collect(),
            Target::Obj => seeds::obj(),
            Target::Stl => seeds::stl(),
            Target::Gltf => seeds::gltf(),
            Target::Protocol => seeds::MESSAGES
                .iter()
                .map(|s| s.as_bytes().to_vec())
                .collect(),
            Target::SessionLog => seeds::session_logs(),
            Target::CalibrationSpec => vec![seeds::CALIBRATION_SPEC.as_bytes().to_vec()],
            Target::CalibrationCsv => seeds::CALIBRATION_CURVES
                .iter()
                .map(|(_, c)| c.as_bytes().to_vec())
                .collect(),
            Target::Kbl => seeds::KBL.iter().map(|k| k.as_bytes().to_vec()).collect(),
            Target::Study => crate::study::seeds(),
        }
    }

    /// Runs the target on one input.
    pub fn run(self, input: &[u8]) -> Result<(), String> {
        match self {
            Target::SceneToml => scene(input, false),
            Target::SceneJson => scene(input, true),
            Target::Obj => mesh(read_obj(input)),
            Target::Stl => mesh(read_stl(input)),
            Target::Gltf => mesh(read_gltf(input, &FileAccess::sandbox(&empty_dir()))),
            Target::Protocol => protocol(input),
            Target::SessionLog => crate::readers::session_log(input),
            Target::CalibrationSpec => crate::readers::calibration_spec(input),
            Target::CalibrationCsv => crate::readers::calibration_csv(input),
            Target::Kbl => crate::readers::kbl(input),
            Target::Study => crate::study::study(input),
        }
    }
}

/// Limits that keep one input cheap (a scene within them loads and builds in
/// milliseconds) while still reaching every check.
fn fuzz_options() -> LoadOptions {
    LoadOptions {
        limits: Limits {
            max_memory_bytes: 200_000_000,
            max_elements: 2_000,
            max_triangles: 100_000,
            max_steps: 1_000_000,
            raise_with: "the fuzz target's limits",
        },
        max_file_bytes: 1 << 20,
        sandboxed: true,
        ..pliant_runs::load_options()
    }
}

/// A folder with nothing in it: glTF buffers named by a fuzzed file find nothing.
fn empty_dir() -> std::path::PathBuf {
    let dir = std::env::temp_dir().join("pliant-fuzz-empty");
    let _ = std::fs::create_dir_all(&dir);
    dir
}

/// The scene loader: never panics; a scene it accepts is finite and in SI, and either
/// builds a workcell with a finite positive time step or is refused with a message.
fn scene(input: &[u8], json: bool) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let dir = seeds::examples_dir();
    let loaded = if json {
        pliant_scene::load_scene_json_str_with(&text, "fuzz.json", &dir, &fuzz_options())
    } else {
        pliant_scene::load_scene_str_with(&text, "fuzz.toml", &dir, &fuzz_options())
    };
    let scene = match loaded {
        Ok(s) => s,
        Err(e) => return non_empty(&e.to_string()),
    };
    accepted_scene_is_sound(&scene)?;
    match scene.workcell(WorkcellOptions::default()) {
        Ok(cell) => {
            let dt = cell.time_step();
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(format!("accepted scene gives the time step {dt}"));
            }
            Ok(())
        }
        Err(e) => non_empty(&e.to_string()),
    }
}

fn non_empty(message: &str) -> Result<(), String> {
    if message.trim().is_empty() {
        Err("an error without a message".to_string())
    } else {
        Ok(())
    }
}

fn accepted_scene_is_sound(scene: &LoadedScene) -> Result<(), String> {
    for h in &scene.world.hoses {
        if h.nodes.len() < 2 || h.nodes.iter().any(|p| !p.is_finite()) {
            return Err(format!("hose '{}' has non-finite or too few nodes", h.name));
        }
    }
    for p in &scene.world.rigid_parts {
        mesh_is_sound(&p.vertices, &p.triangles).map_err(|e| format!("part '{}': {e}", p.name))?;
    }
    // 0 is documented: record every step
    if !(scene.record_interval >= 0.0 && scene.record_interval.is_finite()) {
        return Err(format!("record interval {}", scene.record_interval));
    }
    Ok(())
}

fn mesh_is_sound(vertices: &[glam::DVec3], triangles: &[[u32; 3]]) -> Result<(), String> {
    if vertices.iter().any(|v| !v.is_finite()) {
        return Err("a non-finite vertex".to_string());
    }
    if triangles
        .iter()
        .flatten()
        .any(|&i| i as usize >= vertices.len())
    {
        return Err("an index out of range".to_string());
    }
    Ok(())
}

/// A mesh reader: never panics; what the check passes is finite with indices in range.
fn mesh(read: Result<TriMesh, String>) -> Result<(), String> {
    let Ok(mesh) = read else {
        return Ok(());
    };
    if let Ok(checked) = check_mesh(mesh) {
        mesh_is_sound(&checked.mesh.vertices, &checked.mesh.triangles)?;
        if checked.mesh.triangles.is_empty() {
            return Err("the check passed a mesh without triangles".to_string());
        }
    }
    Ok(())
}

/// The protocol parser: never panics; a message it accepts survives a round trip.
fn protocol(input: &[u8]) -> Result<(), String> {
    let Ok(text) = std::str::from_utf8(input) else {
        return Ok(());
    };
    let Ok(message) = serde_json::from_str::<ClientMessage>(text) else {
        return Ok(());
    };
    let again = serde_json::to_string(&message).map_err(|e| e.to_string())?;
    let back: ClientMessage = serde_json::from_str(&again).map_err(|e| format!("{again}: {e}"))?;
    // floats compare bit-exactly except NaN (never accepted from JSON)
    if back != message {
        return Err(format!("round trip changed {message:?} into {back:?}"));
    }
    Ok(())
}
