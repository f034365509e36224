//! Scenes are checked against resource limits before anything big is made, and scenes
//! sent by clients of `pliant serve` read files only inside their sandbox, with errors
//! that quote neither outside paths nor file contents (issue: hardening, items 2 and 4).

use pliant_scene::{load_scene_str_with, Limits, LoadOptions, SceneError};
use std::path::{Path, PathBuf};

const HEADER: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"
"#;

const HOSE: &str = r#"
[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 2000]
path = [{ line = { to = [300, 0, 2000] } }]
"#;

const UNIT_TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn folder(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("pliant-scene-limits-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("served/meshes")).expect("temp dir");
    std::fs::create_dir_all(dir.join("private")).expect("temp dir");
    dir
}

fn sandboxed() -> LoadOptions {
    LoadOptions {
        sandboxed: true,
        ..LoadOptions::default()
    }
}

fn load(
    dir: &Path,
    parts: &str,
    options: &LoadOptions,
) -> Result<pliant_scene::LoadedScene, SceneError> {
    let text = format!("{HEADER}{HOSE}{parts}");
    load_scene_str_with(&text, "client.toml", dir, options)
}

fn mesh_part(file: &str) -> String {
    format!("[[parts]]\nname = \"p\"\nmesh = \"{file}\"\n")
}

#[test]
fn client_scenes_read_only_inside_their_folder() {
    let dir = folder("sandbox");
    let served = dir.join("served");
    std::fs::write(served.join("meshes/tri.obj"), UNIT_TRIANGLE_OBJ).unwrap();
    let secret = dir.join("private/secret.obj");
    std::fs::write(&secret, UNIT_TRIANGLE_OBJ).unwrap();
    std::fs::write(
        dir.join("private/notes.stl"),
        "top secret line one\nline two\n",
    )
    .unwrap();

    // inside: fine
    let scene = load(&served, &mesh_part("meshes/tri.obj"), &sandboxed()).unwrap();
    assert_eq!(scene.parts[0].triangles, 1);
    // the source does not reveal the server's folders
    assert_eq!(scene.parts[0].source, "meshes/tri.obj");

    let outside_names = [
        secret.display().to_string(),
        "../private/secret.obj".to_string(),
        "meshes/../../private/secret.obj".to_string(),
    ];
    for name in &outside_names {
        let e = load(&served, &mesh_part(name), &sandboxed())
            .unwrap_err()
            .to_string();
        assert!(e.contains("parts[0].mesh"), "{e}");
        assert!(
            !e.contains(&dir.display().to_string()) || e.contains(&format!("\"{name}\"")),
            "{e}"
        );
        assert!(e.contains("not allowed"), "{name}: {e}");
    }
    // a missing file and a path through a file look the same
    let a = load(&served, &mesh_part("meshes/none.obj"), &sandboxed())
        .unwrap_err()
        .to_string();
    let b = load(&served, &mesh_part("meshes/tri.obj/x.obj"), &sandboxed())
        .unwrap_err()
        .to_string();
    assert_eq!(a.replace("none.obj", "X"), b.replace("tri.obj/x.obj", "X"));
    assert!(!a.contains(&served.display().to_string()), "{a}");

    #[cfg(unix)]
    {
        // a link inside the folder that leads outside is refused, one inside is fine
        std::os::unix::fs::symlink(&secret, served.join("meshes/out.obj")).unwrap();
        std::os::unix::fs::symlink(served.join("meshes/tri.obj"), served.join("in.obj")).unwrap();
        let e = load(&served, &mesh_part("meshes/out.obj"), &sandboxed())
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside the served scene's folder"), "{e}");
        assert!(load(&served, &mesh_part("in.obj"), &sandboxed()).is_ok());
        // a link to a non-mesh file: the parse error quotes nothing of it
        std::os::unix::fs::symlink(dir.join("private/notes.stl"), served.join("notes.stl"))
            .unwrap();
        let e = load(&served, &mesh_part("notes.stl"), &sandboxed())
            .unwrap_err()
            .to_string();
        assert!(!e.contains("secret") && !e.contains("line"), "{e}");
    }
    // a non-mesh file inside the folder: not quoted either
    std::fs::write(
        served.join("readme.stl"),
        "solid x\nthe password is swordfish\n",
    )
    .unwrap();
    let e = load(&served, &mesh_part("readme.stl"), &sandboxed())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("is not a valid STL file") && !e.contains("swordfish"),
        "{e}"
    );

    // the same scene from the user's own disk reads anywhere (`pliant run`)
    let local = load(
        &served,
        &mesh_part(&outside_names[1]),
        &LoadOptions::default(),
    )
    .unwrap();
    assert_eq!(local.parts[0].triangles, 1);
}

#[test]
fn gltf_buffers_obey_the_sandbox() {
    let dir = folder("gltf");
    let served = dir.join("served");
    // 3 vertices (36 bytes) and 3 u16 indices (6 bytes) in an external buffer
    let mut bin = Vec::new();
    for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.join("private/buf.bin"), &bin).unwrap();
    std::fs::write(served.join("meshes/buf.bin"), &bin).unwrap();
    let gltf = |uri: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"uri":"{uri}","byteLength":42}}],
            "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
            "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
                         {{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}}],
            "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
            "nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}"#
        )
    };
    std::fs::write(served.join("meshes/good.gltf"), gltf("buf.bin")).unwrap();
    std::fs::write(
        served.join("meshes/bad.gltf"),
        gltf("../../private/buf.bin"),
    )
    .unwrap();
    let ok = load(&served, &mesh_part("meshes/good.gltf"), &sandboxed()).unwrap();
    assert_eq!(ok.parts[0].triangles, 1);
    let e = load(&served, &mesh_part("meshes/bad.gltf"), &sandboxed())
        .unwrap_err()
        .to_string();
    assert!(e.contains("parts[0].mesh") && !e.contains("private"), "{e}");
    // locally the same file reads its buffer outside
    assert!(load(
        &served,
        &mesh_part("meshes/bad.gltf"),
        &LoadOptions::default()
    )
    .is_ok());
}

#[test]
fn mesh_files_are_capped_and_must_be_regular() {
    let dir = folder("cap");
    let served = dir.join("served");
    std::fs::write(served.join("tri.obj"), UNIT_TRIANGLE_OBJ).unwrap();
    let small = LoadOptions {
        max_file_bytes: 10,
        ..LoadOptions::default()
    };
    let e = load(&served, &mesh_part("tri.obj"), &small)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("parts[0].mesh") && e.contains("bytes") && e.contains("--max-mesh-bytes"),
        "{e}"
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("/dev/zero", served.join("zero.stl")).unwrap();
        let e = load(&served, &mesh_part("zero.stl"), &LoadOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("not a regular file"), "{e}");
    }
}

#[test]
fn scenes_beyond_the_memory_limit_are_refused_before_they_are_built() {
    let dir = folder("memory");
    let served = dir.join("served");
    let limits = LoadOptions {
        limits: Limits::with_memory(200_000_000),
        ..LoadOptions::default()
    };
    // 10 hoses of 20 000 elements: ≈ 0.8 GB by the estimate; the 3rd breaks 200 MB
    let mut hoses = String::new();
    for h in 0..10 {
        hoses += &format!(
            "[[hoses]]\nname = \"h{h}\"\nmaterial = \"hose3\"\nstart = [0, {y}, 0]\npath = [{{ line = {{ to = [20000, {y}, 0] }} }}]\nelements = 20000\n",
            y = 100 * h
        );
    }
    let text = format!("{HEADER}{hoses}");
    let e = load_scene_str_with(&text, "big.toml", &served, &limits).unwrap_err();
    let shown = e.to_string();
    assert_eq!(e.field(), Some("hoses[2]"), "{shown}");
    assert!(
        shown.contains("60000 elements") && shown.contains("≈ 2"),
        "{shown}"
    );
    assert!(shown.contains("--max-memory"), "{shown}");
    // the same scene under the default limit loads, and its estimate is kept
    let scene = load_scene_str_with(&text, "big.toml", &served, &LoadOptions::default()).unwrap();
    assert_eq!(scene.estimate.elements, 200_000);

    // a sphere of 20·4⁸ triangles (≈ 0.5 GB) is refused from its subdivisions
    let e = load(
        &served,
        "[[parts]]\nname = \"s\"\nsphere = { radius = 10, subdivisions = 8 }\n",
        &limits,
    )
    .unwrap_err();
    assert_eq!(e.field(), Some("parts[0].sphere.subdivisions"), "{e}");
    assert!(
        e.to_string().contains("1310720 triangles") && e.to_string().contains("--max-memory"),
        "{e}"
    );
}
