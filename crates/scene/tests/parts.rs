//! Rigid parts: meshes from OBJ, STL, glTF and GLB, and primitives, posed and converted
//! to metres; every kind of broken part gives an error naming the field and the reason.

use glam::DVec3;
use pliant_core::RigidPartSpec;
use pliant_scene::{
    load_scene_file, load_scene_json_str_in, load_scene_str, load_scene_str_in, LoadedScene,
    SceneError, MAX_TRIANGLES,
};
use pliant_testkit::bad_inputs::{check_refusals, Refusal};
use pliant_testkit::scenes::RAISED_HOSE3_300;
use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------
// Mesh files written by the tests: a cube [0, s]³, 12 triangles, outward.

/// Corners of the cube [0, s]³ (index bits: x, y, z).
fn cube_vertices(s: f64) -> Vec<[f64; 3]> {
    (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { 0.0 } else { s },
                if i & 2 == 0 { 0.0 } else { s },
                if i & 4 == 0 { 0.0 } else { s },
            ]
        })
        .collect()
}

/// The cube's 12 triangles, counter-clockwise seen from outside (0-based).
fn cube_triangles() -> Vec<[u32; 3]> {
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect()
}

fn obj_text(s: f64) -> String {
    let mut t = String::from("# unit cube\no cube\n");
    for v in cube_vertices(s) {
        t += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in cube_triangles() {
        t += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    t
}

fn stl_ascii_text(s: f64) -> String {
    let v = cube_vertices(s);
    let mut t = String::from("solid cube\n");
    for f in cube_triangles() {
        t += "  facet normal 0 0 0\n    outer loop\n";
        for i in f {
            let p = v[i as usize];
            t += &format!("      vertex {} {} {}\n", p[0], p[1], p[2]);
        }
        t += "    endloop\n  endfacet\n";
    }
    t + "endsolid cube\n"
}

/// Binary STL; `header` fills the 80-byte header (e.g. `solid …`, as some exporters do).
fn stl_binary(s: f64, header: &[u8]) -> Vec<u8> {
    let v = cube_vertices(s);
    let mut b = vec![0u8; 80];
    b[..header.len()].copy_from_slice(header);
    let tris = cube_triangles();
    b.extend((tris.len() as u32).to_le_bytes());
    for f in tris {
        b.extend([0u8; 12]);
        for i in f {
            for c in v[i as usize] {
                b.extend((c as f32).to_le_bytes());
            }
        }
        b.extend([0u8; 2]);
    }
    b
}

/// The cube's glTF buffer: 8 × VEC3 f32 positions, then 36 u16 indices.
fn gltf_buffer(s: f64, indices: &[u32]) -> Vec<u8> {
    let mut b = Vec::new();
    for v in cube_vertices(s) {
        for c in v {
            b.extend((c as f32).to_le_bytes());
        }
    }
    for &i in indices {
        b.extend((i as u16).to_le_bytes());
    }
    b
}

fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in data.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// glTF JSON for the cube; `uri` is the buffer's URI (`None` for the GLB binary chunk);
/// `translation` is the node's; `s` the cube's edge (for POSITION's required min/max).
fn gltf_json(
    s: f64,
    buffer_len: usize,
    index_count: usize,
    uri: Option<&str>,
    translation: [f64; 3],
) -> String {
    let uri = uri.map_or(String::new(), |u| format!(", \"uri\": \"{u}\""));
    format!(
        r#"{{
  "asset": {{ "version": "2.0" }},
  "scene": 0,
  "scenes": [{{ "nodes": [0] }}],
  "nodes": [{{ "mesh": 0, "translation": [{}, {}, {}] }}],
  "meshes": [{{ "primitives": [{{ "attributes": {{ "POSITION": 0 }}, "indices": 1 }}] }}],
  "buffers": [{{ "byteLength": {buffer_len}{uri} }}],
  "bufferViews": [
    {{ "buffer": 0, "byteOffset": 0, "byteLength": 96 }},
    {{ "buffer": 0, "byteOffset": 96, "byteLength": {} }}
  ],
  "accessors": [
    {{ "bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0], "max": [{s}, {s}, {s}] }},
    {{ "bufferView": 1, "componentType": 5123, "count": {index_count}, "type": "SCALAR" }}
  ]
}}"#,
        translation[0],
        translation[1],
        translation[2],
        2 * index_count
    )
}

fn cube_indices() -> Vec<u32> {
    cube_triangles().into_iter().flatten().collect()
}

/// A `.gltf` with the buffer embedded as a data URI.
fn gltf_text(s: f64, indices: &[u32], translation: [f64; 3]) -> String {
    let buf = gltf_buffer(s, indices);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&buf));
    gltf_json(s, buf.len(), indices.len(), Some(&uri), translation)
}

/// A `.glb`: JSON chunk and binary chunk.
fn glb(s: f64) -> Vec<u8> {
    let mut buf = gltf_buffer(s, &cube_indices());
    let mut json = gltf_json(s, buf.len(), 36, None, [0.0; 3]).into_bytes();
    json.resize(json.len().next_multiple_of(4), b' ');
    buf.resize(buf.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + buf.len();
    let mut b = Vec::new();
    b.extend(b"glTF");
    b.extend(2u32.to_le_bytes());
    b.extend((total as u32).to_le_bytes());
    b.extend((json.len() as u32).to_le_bytes());
    b.extend(b"JSON");
    b.extend(&json);
    b.extend((buf.len() as u32).to_le_bytes());
    b.extend(b"BIN\0");
    b.extend(&buf);
    b
}

/// A fresh directory for one test's files.
fn temp_dir(name: &str) -> PathBuf {
    pliant_testkit::files::scratch_dir("scene-parts", name)
}

// ---------------------------------------------------------------------------------------
// Scenes.

fn scene_with(parts: &str) -> String {
    format!("{RAISED_HOSE3_300}\n{parts}")
}

fn load_in(dir: &Path, parts: &str) -> Result<LoadedScene, SceneError> {
    load_scene_str_in(&scene_with(parts), "scene.toml", dir)
}

/// Signed volume by the divergence theorem.
fn volume(p: &RigidPartSpec) -> f64 {
    p.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| p.vertices[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

fn bounds(p: &RigidPartSpec) -> (DVec3, DVec3) {
    p.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    )
}

/// Every edge used exactly once in each direction.
fn closed_and_oriented(p: &RigidPartSpec) -> bool {
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    for t in &p.triangles {
        for k in 0..3 {
            *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

fn assert_close(a: DVec3, b: DVec3, tol: f64) {
    assert!((a - b).abs().max_element() <= tol, "{a} vs {b}");
}

// ---------------------------------------------------------------------------------------
// Loading each format.

/// A cube of 100 mm, rotated 90° about z, moved to x = 1 m: x ∈ [0.9, 1], y, z ∈ [0, 0.1].
/// Files that store 32-bit floats (STL, glTF) carry 0.1 to within 1.5e-9, so bounds are
/// checked to 1e-8 m and the volume to 1e-6 relative; exact values (100 mm) to 1e-12.
fn check_posed_cube(p: &RigidPartSpec) {
    assert_eq!(p.triangles.len(), 12);
    let (lo, hi) = bounds(p);
    assert_close(lo, DVec3::new(0.9, 0.0, 0.0), 1e-8);
    assert_close(hi, DVec3::new(1.0, 0.1, 0.1), 1e-8);
    assert!((volume(p) - 1e-3).abs() < 1e-9, "volume {}", volume(p));
    assert!(closed_and_oriented(p));
}

#[test]
fn each_format_loads_a_cube_with_pose_and_unit() {
    let dir = temp_dir("formats");
    std::fs::write(dir.join("cube.obj"), obj_text(100.0)).unwrap();
    std::fs::write(dir.join("cube.stl"), stl_ascii_text(100.0)).unwrap();
    std::fs::write(dir.join("cube_bin.STL"), stl_binary(100.0, b"binary cube")).unwrap();
    std::fs::write(
        dir.join("cube_solid.stl"),
        stl_binary(100.0, b"solid exported by CAD"),
    )
    .unwrap();
    std::fs::write(
        dir.join("cube.gltf"),
        gltf_text(100.0, &cube_indices(), [0.0; 3]),
    )
    .unwrap();
    std::fs::write(dir.join("cube.glb"), glb(100.0)).unwrap();
    let pose = "position = [1000, 0, 0]\nrotation = { axis = [0, 0, 1], angle_deg = 90 }";
    for file in [
        "cube.obj",
        "cube.stl",
        "cube_bin.STL",
        "cube_solid.stl",
        "cube.gltf",
        "cube.glb",
    ] {
        let parts =
            format!("[[parts]]\nname = \"c\"\nmesh = \"{file}\"\nmesh_unit = \"mm\"\n{pose}\n");
        let scene = load_in(&dir, &parts).unwrap_or_else(|e| panic!("{file}: {e}"));
        let p = &scene.world.rigid_parts[0];
        check_posed_cube(p);
        assert_eq!(scene.parts[0].triangles, 12);
        assert_eq!(scene.parts[0].dropped_degenerate, 0);
        assert_eq!(scene.parts[0].source, dir.join(file).display().to_string());
        assert_eq!((p.friction_static, p.friction_sliding), (0.5, 0.4));
    }
}

#[test]
fn mesh_unit_defaults_to_the_scene_unit_but_metres_for_gltf() {
    let dir = temp_dir("units");
    std::fs::write(dir.join("cube.obj"), obj_text(100.0)).unwrap();
    std::fs::write(dir.join("cube_m.glb"), glb(0.1)).unwrap();
    std::fs::write(dir.join("cube_m.obj"), obj_text(0.1)).unwrap();
    let pose = "position = [1000, 0, 0]\nrotation = { axis = [0, 0, 1], angle_deg = 90 }";
    // OBJ in the scene's mm; GLB in metres by default; OBJ in metres when told.
    for (file, unit) in [
        ("cube.obj", ""),
        ("cube_m.glb", ""),
        ("cube_m.obj", "mesh_unit = \"m\""),
    ] {
        let parts = format!("[[parts]]\nname = \"c\"\nmesh = \"{file}\"\n{unit}\n{pose}\n");
        let scene = load_in(&dir, &parts).unwrap_or_else(|e| panic!("{file}: {e}"));
        check_posed_cube(&scene.world.rigid_parts[0]);
    }
    // A metre scene with a millimetre OBJ.
    let text = scene_with(
        "[[parts]]\nname = \"c\"\nmesh = \"cube.obj\"\nmesh_unit = \"mm\"\nposition = [1, 0, 0]\nrotation = { axis = [0, 0, 1], angle_deg = 90 }\n",
    )
    .replace("length_unit = \"mm\"", "length_unit = \"m\"")
    .replace("2000", "2")
    .replace("300, 0", "0.3, 0");
    let scene = load_scene_str_in(&text, "m.toml", &dir).unwrap_or_else(|e| panic!("{e}"));
    check_posed_cube(&scene.world.rigid_parts[0]);
}

#[test]
fn gltf_node_transforms_are_applied() {
    let dir = temp_dir("nodes");
    std::fs::write(
        dir.join("moved.gltf"),
        gltf_text(1.0, &cube_indices(), [2.0, 0.0, 0.0]),
    )
    .unwrap();
    let scene = load_in(&dir, "[[parts]]\nname = \"c\"\nmesh = \"moved.gltf\"\n").unwrap();
    let (lo, hi) = bounds(&scene.world.rigid_parts[0]);
    assert_close(lo, DVec3::new(2.0, 0.0, 0.0), 1e-12);
    assert_close(hi, DVec3::new(3.0, 1.0, 1.0), 1e-12);
}

#[test]
fn gltf_with_an_external_buffer_loads() {
    let dir = temp_dir("external");
    let buf = gltf_buffer(1.0, &cube_indices());
    std::fs::write(dir.join("cube data.bin"), &buf).unwrap();
    std::fs::write(
        dir.join("ext.gltf"),
        gltf_json(1.0, buf.len(), 36, Some("cube%20data.bin"), [0.0; 3]),
    )
    .unwrap();
    let scene = load_in(&dir, "[[parts]]\nname = \"c\"\nmesh = \"ext.gltf\"\n")
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((volume(&scene.world.rigid_parts[0]) - 1.0).abs() < 1e-12);
}

#[test]
fn degenerate_triangles_are_dropped_and_counted() {
    let dir = temp_dir("degenerate");
    let text = obj_text(100.0) + "f 1 2 2\nf 1 2 4\n"; // a repeated index; a real triangle
    std::fs::write(dir.join("extra.obj"), text).unwrap();
    let scene = load_in(&dir, "[[parts]]\nname = \"c\"\nmesh = \"extra.obj\"\n").unwrap();
    assert_eq!(scene.parts[0].dropped_degenerate, 1);
    assert_eq!(scene.world.rigid_parts[0].triangles.len(), 13);
}

#[test]
fn relative_paths_resolve_against_the_scene_file() {
    let dir = temp_dir("relative");
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    std::fs::write(dir.join("meshes/cube.obj"), obj_text(100.0)).unwrap();
    let path = dir.join("scene.toml");
    let text = scene_with("[[parts]]\nname = \"c\"\nmesh = \"meshes/cube.obj\"\n");
    std::fs::write(&path, &text).unwrap();
    // From the file, from text whose origin names the file, and as JSON.
    let a = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let b = load_scene_str(&text, &path.display().to_string()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.world, b.world);
    let value: toml::Value = toml::from_str(&text).unwrap();
    let json = serde_json::to_string(&value).unwrap();
    let c = load_scene_json_str_in(&json, "scene.json", &dir).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(a.world, c.world);
    // An origin that is not a file: the current directory (the crate's, under cargo test).
    let err = load_scene_str(&text, "inline text").unwrap_err();
    assert_eq!(err.field(), Some("parts[0].mesh"), "{err}");
    let text =
        scene_with("[[parts]]\nname = \"c\"\nmesh = \"../../examples/meshes/engine_block.obj\"\n");
    load_scene_str(&text, "inline text").unwrap_or_else(|e| panic!("{e}"));
    // An absolute path works from anywhere.
    let abs = dir
        .join("meshes/cube.obj")
        .display()
        .to_string()
        .replace('\\', "/");
    let text = scene_with(&format!("[[parts]]\nname = \"c\"\nmesh = \"{abs}\"\n"));
    load_scene_str(&text, "inline text").unwrap_or_else(|e| panic!("{e}"));
}

// ---------------------------------------------------------------------------------------
// Primitives.

#[test]
fn primitives_are_closed_with_the_right_bounds_and_volume() {
    let scene = load_scene_str(
        &scene_with(
            r#"
[[parts]]
name = "box"
box = { size = [600, 50, 400] }
position = [100, 200, 300]
friction = { static = 0.3, sliding = 0.3 }

[[parts]]
name = "box turned"
box = { size = [600, 50, 400] }
rotation = { axis = [0, 0, 1], angle_deg = 90 }

[[parts]]
name = "cyl"
cylinder = { radius = 50, height = 200 }
position = [0, 0, 1000]
rotation = { axis = [1, 0, 0], angle_deg = 90 }

[[parts]]
name = "cyl 6"
cylinder = { radius = 50, height = 200, segments = 6 }

[[parts]]
name = "ball"
sphere = { radius = 100 }
position = [-500, 0, 0]

[[parts]]
name = "ball 0"
sphere = { radius = 100, subdivisions = 0 }
"#,
        ),
        "prims.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let parts = &scene.world.rigid_parts;
    for p in parts {
        assert!(closed_and_oriented(p), "{}", p.name);
    }
    // Box: exact volume and bounds.
    let (lo, hi) = bounds(&parts[0]);
    assert_close(lo, DVec3::new(-0.2, 0.175, 0.1), 1e-12);
    assert_close(hi, DVec3::new(0.4, 0.225, 0.5), 1e-12);
    assert!((volume(&parts[0]) - 0.6 * 0.05 * 0.4).abs() < 1e-15);
    assert_eq!(
        (parts[0].friction_static, parts[0].friction_sliding),
        (0.3, 0.3)
    );
    let (lo, hi) = bounds(&parts[1]);
    assert_close(lo, DVec3::new(-0.025, -0.3, -0.2), 1e-12);
    assert_close(hi, DVec3::new(0.025, 0.3, 0.2), 1e-12);
    // Cylinder along z, turned to lie along −y: length 0.2 in y, radius 0.05 in x and z
    // (32 segments: a vertex at angle 0 and π/2, so the bounds are exact).
    let (lo, hi) = bounds(&parts[2]);
    assert_close(lo, DVec3::new(-0.05, -0.1, 0.95), 1e-12);
    assert_close(hi, DVec3::new(0.05, 0.1, 1.05), 1e-12);
    assert_eq!(parts[2].triangles.len(), 128);
    // Volume: the inscribed 32-gon prism, n/2 r² sin(2π/n) h, exact to rounding; it lies
    // 0.64 % below π r² h.
    let prism = |n: f64| n / 2.0 * 0.05f64.powi(2) * (2.0 * PI / n).sin() * 0.2;
    assert!((volume(&parts[2]) - prism(32.0)).abs() < 1e-15);
    let cyl = PI * 0.05f64.powi(2) * 0.2;
    assert!((cyl - volume(&parts[2])) / cyl < 0.0065);
    assert!((volume(&parts[3]) - prism(6.0)).abs() < 1e-15);
    assert_eq!(parts[3].triangles.len(), 24);
    // Sphere: default 3 subdivisions = 1280 triangles, every vertex on the radius, volume
    // within 1.5 % below 4/3 π r³; bounds exact (icosphere vertices include no poles, so
    // within the radius).
    let ball = &parts[4];
    assert_eq!(ball.triangles.len(), 1280);
    let c = DVec3::new(-0.5, 0.0, 0.0);
    assert!(ball
        .vertices
        .iter()
        .all(|v| ((*v - c).length() - 0.1).abs() < 1e-12));
    let exact = 4.0 / 3.0 * PI * 0.1f64.powi(3);
    let v = volume(ball);
    assert!(v < exact && (exact - v) / exact < 0.015, "{v} vs {exact}");
    let (lo, hi) = bounds(ball);
    assert!(lo.cmpge(c - 0.1 - 1e-12).all() && hi.cmple(c + 0.1 + 1e-12).all());
    assert!((hi - lo).min_element() > 0.19);
    assert_eq!(parts[5].triangles.len(), 20);
    // Facts for reports.
    assert_eq!(scene.parts.len(), 6);
    assert_eq!(scene.parts[4].source, "sphere");
    assert_eq!(scene.parts[4].bounds, bounds(ball));
}

#[test]
fn no_parts_is_fine() {
    let scene = load_scene_str(&scene_with(""), "none.toml").unwrap();
    assert!(scene.world.rigid_parts.is_empty());
    assert!(scene.parts.is_empty());
}

#[test]
fn engine_bay_example_has_its_parts() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/engine_bay.toml");
    let scene = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let names: Vec<&str> = scene
        .world
        .rigid_parts
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(
        names,
        [
            "floor",
            "radiator",
            "engine block",
            "fan hub",
            "expansion tank cap",
            "heat shield"
        ]
    );
    let block = &scene.world.rigid_parts[2];
    assert_eq!(block.triangles.len(), 24);
    let (lo, hi) = bounds(block);
    assert_close(lo, DVec3::new(-0.15, -0.2, 0.1), 1e-12);
    assert_close(hi, DVec3::new(0.35, 0.2, 0.6), 1e-12);
    // Crankcase 0.5·0.4·0.35 plus head 0.4·0.3·0.15.
    assert!((volume(block) - (0.07 + 0.018)).abs() < 1e-12);
    // No hose node starts inside a part's bounding box (the hoses lie free).
    for hose in &scene.world.hoses {
        for n in &hose.nodes {
            for p in &scene.world.rigid_parts {
                let (lo, hi) = bounds(p);
                let r = 0.0175;
                let inside = (n.cmpgt(lo - r) & n.cmplt(hi + r)).all();
                assert!(!inside, "hose {} node {n} touches {}", hose.name, p.name);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Errors.

/// One broken part: the `[[parts]]` text, the field the error must name, pieces of the
/// message.
struct Case {
    what: &'static str,
    parts: String,
    field: &'static str,
    message: &'static [&'static str],
}

fn case(
    what: &'static str,
    parts: &str,
    field: &'static str,
    message: &'static [&'static str],
) -> Case {
    Case {
        what,
        parts: parts.to_string(),
        field,
        message,
    }
}

/// Writes the broken mesh files the cases refer to.
fn write_broken_meshes(dir: &Path) {
    std::fs::write(dir.join("cube.obj"), obj_text(1.0)).unwrap();
    std::fs::write(dir.join("empty.obj"), "# nothing\nv 0 0 0\nv 1 0 0\n").unwrap();
    std::fs::write(dir.join("empty.stl"), "solid empty\nendsolid empty\n").unwrap();
    std::fs::write(
        dir.join("nan.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("inf.stl"),
        stl_ascii_text(1.0).replacen("vertex 0 0 0", "vertex 0 0 inf", 1),
    )
    .unwrap();
    // Binary STL carries NaN through to the check.
    let mut nan = stl_binary(1.0, b"binary");
    nan[84 + 12..84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
    std::fs::write(dir.join("nan.stl"), nan).unwrap();
    std::fs::write(
        dir.join("range.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    )
    .unwrap();
    let mut bad = cube_indices();
    bad[5] = 8;
    std::fs::write(dir.join("range.gltf"), gltf_text(1.0, &bad, [0.0; 3])).unwrap();
    std::fs::write(
        dir.join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n",
    )
    .unwrap();
    // A binary STL that declares more triangles than allowed (the data is never read).
    let mut huge = vec![0u8; 80];
    huge.extend(((MAX_TRIANGLES + 1) as u32).to_le_bytes());
    std::fs::write(dir.join("huge.stl"), huge).unwrap();
    std::fs::write(dir.join("garbage.stl"), "solid x\n facet nonsense\n").unwrap();
    std::fs::write(dir.join("garbage.glb"), b"glTF\x02\x00\x00\x00garbage").unwrap();
    std::fs::write(dir.join("garbage.gltf"), "{ not json").unwrap();
    std::fs::write(dir.join("garbage.obj"), "v 0 0 zero\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("part.step"), "ISO-10303-21;").unwrap();
    std::fs::create_dir_all(dir.join("folder.obj")).unwrap();
}

fn cases() -> Vec<Case> {
    let p = |body: &str| format!("[[parts]]\nname = \"a\"\n{body}\n");
    let two = |first: &str, second: &str| {
        format!("[[parts]]\nname = \"a\"\n{first}\n[[parts]]\nname = \"b\"\n{second}\n")
    };
    vec![
        case(
            "missing file",
            &p("mesh = \"nope.stl\""),
            "parts[0].mesh",
            &["= \"nope.stl\": cannot read", "nope.stl", "No such file"],
        ),
        case(
            "directory instead of file",
            &p("mesh = \"folder.obj\""),
            "parts[0].mesh",
            &["= \"folder.obj\": is not a regular file"],
        ),
        case(
            "unknown extension",
            &p("mesh = \"part.step\""),
            "parts[0].mesh",
            &["unknown mesh format \".step\"", ".obj, .stl, .gltf or .glb"],
        ),
        case(
            "no extension",
            &p("mesh = \"cube\""),
            "parts[0].mesh",
            &["no extension"],
        ),
        case(
            "empty mesh path",
            &p("mesh = \"\""),
            "parts[0].mesh",
            &["must name a mesh file"],
        ),
        case(
            "empty OBJ",
            &p("mesh = \"empty.obj\""),
            "parts[0].mesh",
            &["= \"empty.obj\": empty mesh: it contains no triangles"],
        ),
        case(
            "empty STL",
            &p("mesh = \"empty.stl\""),
            "parts[0].mesh",
            &["empty mesh"],
        ),
        case(
            "NaN vertex",
            &p("mesh = \"nan.obj\""),
            "parts[0].mesh",
            &["vertex 2 has a non-finite coordinate [0, nan, 0]"],
        ),
        case(
            "NaN vertex in binary STL",
            &p("mesh = \"nan.stl\""),
            "parts[0].mesh",
            &["vertex 0 has a non-finite coordinate [nan, 0, 0]"],
        ),
        case(
            "inf vertex in ASCII STL",
            &p("mesh = \"inf.stl\""),
            "parts[0].mesh",
            &["cannot parse as STL", "finite", "inf"],
        ),
        case(
            "OBJ index out of range",
            &p("mesh = \"range.obj\""),
            "parts[0].mesh",
            &["index out of range"],
        ),
        case(
            "glTF index out of range",
            &p("mesh = \"range.gltf\""),
            "parts[0].mesh",
            &["index out of range", "refers to vertex 8", "8 vertices"],
        ),
        case(
            "degenerate only",
            &p("mesh = \"flat.obj\""),
            "parts[0].mesh",
            &["degenerate mesh: all 2 triangles have zero area"],
        ),
        case(
            "too many triangles in a file",
            &p("mesh = \"huge.stl\""),
            "parts[0].mesh",
            &["5000001 triangles; at most 5000000"],
        ),
        case(
            "too many triangles in a sphere",
            &p("sphere = { radius = 1, subdivisions = 9 }"),
            "parts[0].sphere.subdivisions",
            &["= 9: gives 5242880 triangles; at most 5000000"],
        ),
        case(
            "absurd sphere subdivisions",
            &p("sphere = { radius = 1, subdivisions = 100 }"),
            "parts[0].sphere.subdivisions",
            &["at most 5000000"],
        ),
        case(
            "too many cylinder segments",
            &p("cylinder = { radius = 1, height = 1, segments = 2000000 }"),
            "parts[0].cylinder.segments",
            &["8000000 triangles"],
        ),
        case(
            "unparsable STL",
            &p("mesh = \"garbage.stl\""),
            "parts[0].mesh",
            &["cannot parse as STL"],
        ),
        case(
            "unparsable GLB",
            &p("mesh = \"garbage.glb\""),
            "parts[0].mesh",
            &["cannot parse as glTF"],
        ),
        case(
            "unparsable glTF",
            &p("mesh = \"garbage.gltf\""),
            "parts[0].mesh",
            &["cannot parse as glTF"],
        ),
        case(
            "unparsable OBJ",
            &p("mesh = \"garbage.obj\""),
            "parts[0].mesh",
            &["cannot parse as OBJ"],
        ),
        case(
            "zero box edge",
            &p("box = { size = [1, 0, 1] }"),
            "parts[0].box.size[1]",
            &["= 0 mm: must be greater than 0"],
        ),
        case(
            "negative box edge",
            &p("box = { size = [-1, 1, 1] }"),
            "parts[0].box.size[0]",
            &["= -1 mm: must be greater than 0"],
        ),
        case(
            "nan box edge",
            &p("box = { size = [1, 1, nan] }"),
            "parts[0].box.size[2]",
            &["must be a finite number"],
        ),
        case(
            "negative cylinder radius",
            &p("cylinder = { radius = -5, height = 10 }"),
            "parts[0].cylinder.radius",
            &["= -5 mm: must be greater than 0"],
        ),
        case(
            "zero cylinder height",
            &p("cylinder = { radius = 5, height = 0 }"),
            "parts[0].cylinder.height",
            &["= 0 mm: must be greater than 0"],
        ),
        case(
            "two-sided cylinder",
            &p("cylinder = { radius = 5, height = 1, segments = 2 }"),
            "parts[0].cylinder.segments",
            &["= 2: must be at least 3"],
        ),
        case(
            "zero sphere radius",
            &p("sphere = { radius = 0 }"),
            "parts[0].sphere.radius",
            &["= 0 mm: must be greater than 0"],
        ),
        case(
            "duplicate names",
            &two("box = { size = [1, 1, 1] }", "box = { size = [1, 1, 1] }")
                .replace("name = \"b\"", "name = \"a\""),
            "parts[1].name",
            &["= \"a\": duplicate part name (also parts[0].name)"],
        ),
        case(
            "empty name",
            &p("box = { size = [1, 1, 1] }").replace("name = \"a\"", "name = \" \""),
            "parts[0].name",
            &["must not be empty"],
        ),
        case(
            "no shape",
            &p("position = [0, 0, 0]"),
            "parts[0]",
            &["needs exactly one of `mesh`, `step`, `box`, `cylinder`, `sphere`"],
        ),
        case(
            "two shapes",
            &two(
                "box = { size = [1, 1, 1] }",
                "mesh = \"cube.obj\"\nsphere = { radius = 1 }",
            ),
            "parts[1]",
            &["exactly one of", "not `mesh` and `sphere`"],
        ),
        case(
            "mesh unit on a primitive",
            &p("box = { size = [1, 1, 1] }\nmesh_unit = \"m\""),
            "parts[0].mesh_unit",
            &["only allowed with `mesh`"],
        ),
        case(
            "negative static friction",
            &p("box = { size = [1, 1, 1] }\nfriction = { static = -0.1, sliding = 0 }"),
            "parts[0].friction.static",
            &["= -0.1: must not be negative"],
        ),
        case(
            "negative sliding friction",
            &p("box = { size = [1, 1, 1] }\nfriction = { static = 0.5, sliding = -1 }"),
            "parts[0].friction.sliding",
            &["must not be negative"],
        ),
        case(
            "sliding above static",
            &p("box = { size = [1, 1, 1] }\nfriction = { static = 0.3, sliding = 0.4 }"),
            "parts[0].friction.sliding",
            &["= 0.4: must not exceed static (0.3)"],
        ),
        case(
            "friction incomplete",
            &p("box = { size = [1, 1, 1] }\nfriction = { static = 0.3 }"),
            "parts[0].friction.sliding",
            &["missing field `sliding`"],
        ),
        case(
            "nan position",
            &p("box = { size = [1, 1, 1] }\nposition = [0, nan, 0]"),
            "parts[0].position[1]",
            &["= nan mm: must be a finite number"],
        ),
        case(
            "zero rotation axis",
            &p("box = { size = [1, 1, 1] }\nrotation = { axis = [0, 0, 0], angle_deg = 5 }"),
            "parts[0].rotation.axis",
            &["must not be the zero vector"],
        ),
        case(
            "unknown part field",
            &p("box = { size = [1, 1, 1] }\ncolour = \"red\""),
            "parts[0].colour",
            &["unknown field `colour`"],
        ),
        case(
            "unknown box field",
            &p("box = { sise = [1, 1, 1] }"),
            "parts[0].box.sise",
            &["unknown field `sise`"],
        ),
        case(
            "unknown mesh unit",
            &p("mesh = \"cube.obj\"\nmesh_unit = \"cm\""),
            "parts[0].mesh_unit",
            &["unknown variant `cm`"],
        ),
        case(
            "missing name",
            "[[parts]]\nbox = { size = [1, 1, 1] }\n",
            "parts[0].name",
            &["missing field `name`"],
        ),
    ]
}

#[test]
fn every_broken_part_is_named_and_explained() {
    let dir = temp_dir("errors");
    write_broken_meshes(&dir);
    let cases = cases();
    check_refusals(
        cases.iter().map(|c| {
            let expected = Refusal {
                what: c.what,
                field: Some(c.field),
                message: c.message,
            };
            (scene_with(&c.parts), expected)
        }),
        "scene.toml",
        |text| load_scene_str_in(text, "scene.toml", &dir),
        |e| e.field(),
    );
    assert!(cases.len() >= 30);
}

#[test]
fn a_broken_part_loads_nothing() {
    let dir = temp_dir("nothing");
    write_broken_meshes(&dir);
    let text = scene_with("[[parts]]\nname = \"ok\"\nmesh = \"cube.obj\"\n[[parts]]\nname = \"bad\"\nmesh = \"nan.obj\"\n");
    let err = load_scene_str_in(&text, "scene.toml", &dir).unwrap_err();
    assert_eq!(err.field(), Some("parts[1].mesh"));
}
