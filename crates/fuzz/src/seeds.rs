//! The seed inputs each target's mutations start from.

/// The example scenes (TOML), as shipped.
pub const SCENES: &[&str] = &[
    include_str!("../../../examples/engine_bay.toml"),
    include_str!("../../../examples/demo.toml"),
    include_str!("../../../examples/thesis_1.toml"),
    include_str!("../../../examples/thesis_2.toml"),
    include_str!("../../../examples/thesis_3.toml"),
    include_str!("../../../examples/thesis_4.toml"),
];

/// The folder the example scenes' meshes are in (the scene targets' sandbox).
pub fn examples_dir() -> std::path::PathBuf {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples")).to_path_buf()
}

/// The example scenes as JSON (same structure).
pub fn scenes_json() -> Vec<String> {
    SCENES
        .iter()
        .map(|t| {
            let value: toml::Value = toml::from_str(t).expect("example scenes parse");
            serde_json::to_string_pretty(&value).expect("TOML values are JSON")
        })
        .collect()
}

/// OBJ seeds: the demo's engine block and a quad with a normal and a texture line.
pub fn obj() -> Vec<Vec<u8>> {
    vec![
        include_bytes!("../../../examples/meshes/engine_block.obj").to_vec(),
        b"o q\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\n"
            .to_vec(),
    ]
}

/// A unit tetrahedron's corners and faces.
const TET: ([[f32; 3]; 4], [[usize; 3]; 4]) = (
    [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ],
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
);

/// STL seeds: the tetrahedron in ASCII and in binary.
pub fn stl() -> Vec<Vec<u8>> {
    let (v, f) = TET;
    let mut ascii = String::from("solid tet\n");
    let mut binary = vec![0u8; 80];
    binary.extend_from_slice(&(f.len() as u32).to_le_bytes());
    for t in f {
        ascii += "facet normal 0 0 0\nouter loop\n";
        binary.extend_from_slice(&[0u8; 12]);
        for i in t {
            ascii += &format!("vertex {} {} {}\n", v[i][0], v[i][1], v[i][2]);
            for c in v[i] {
                binary.extend_from_slice(&c.to_le_bytes());
            }
        }
        ascii += "endloop\nendfacet\n";
        binary.extend_from_slice(&[0u8; 2]);
    }
    ascii += "endsolid tet\n";
    vec![ascii.into_bytes(), binary]
}

/// glTF seeds: the tetrahedron with its buffer as a data URI, with and without a node
/// transform.
pub fn gltf() -> Vec<Vec<u8>> {
    let (v, f) = TET;
    let mut bin = Vec::new();
    for p in v {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for t in f {
        for i in t {
            bin.extend_from_slice(&(i as u16).to_le_bytes());
        }
    }
    let data = base64(&bin);
    let doc = |node: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"uri":"data:application/octet-stream;base64,{data}","byteLength":{len}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":24}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,1]}},{{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"nodes":[{node}],"scenes":[{{"nodes":[0]}}],"scene":0}}"#,
            len = bin.len()
        )
        .into_bytes()
    };
    vec![
        doc(r#"{"mesh":0}"#),
        doc(r#"{"mesh":0,"translation":[1,2,3],"scale":[2,2,2]}"#),
    ]
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..=c.len() {
            s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
        }
    }
    s
}

/// Protocol seeds: one message of every kind (docs/protocol.md).
pub const MESSAGES: &[&str] = &[
    r#"{"type":"hello","version":1}"#,
    r#"{"type":"grab","hand_id":0,"position":[0.1,0.2,0.3]}"#,
    r#"{"type":"move","hand_id":0,"position":[0.1,0.2,0.3],"orientation":[0,0,0,1]}"#,
    r#"{"type":"release","hand_id":0}"#,
    r#"{"type":"pause"}"#,
    r#"{"type":"resume"}"#,
    r#"{"type":"step","n":10}"#,
    r#"{"type":"reset"}"#,
    r#"{"type":"set_ergonomics","posture":"sitting","population":"men","duty":"continuous","moments_decide":true}"#,
    r#"{"type":"load_scene","text":"format = \"pliant-scene\"\nversion = 1\n","format":"toml","name":"a.toml"}"#,
    r#"{"type":"report"}"#,
    r#"{"type":"scene_source"}"#,
];

/// A calibration spec and its curves (`examples/calibration`).
pub const CALIBRATION_SPEC: &str = include_str!("../../../examples/calibration/hose.toml");

/// The curves the calibration spec names, by file name, in its order.
pub const CALIBRATION_CURVES: &[(&str, &str)] = &[
    (
        "tension.csv",
        include_str!("../../../examples/calibration/tension.csv"),
    ),
    (
        "compression.csv",
        include_str!("../../../examples/calibration/compression.csv"),
    ),
    (
        "bending.csv",
        include_str!("../../../examples/calibration/bending.csv"),
    ),
    (
        "torsion.csv",
        include_str!("../../../examples/calibration/torsion.csv"),
    ),
];

/// A KBL sample file of `data/harness` (see its README) and the hand-written VEC file of
/// the harness tests.
pub const KBL: &[&str] = &[
    include_str!("../../../data/harness/kblxml_2.3sr-1_000971228_ltgs_batterie_plus_170718.kbl"),
    include_str!("../../harness/tests/data/y_harness_3d.vec"),
];

/// Session logs: one of every kind of line, sealed (version 2) and unsealed (version 1).
pub fn session_logs() -> Vec<Vec<u8>> {
    use pliant_assembly::timeline::NodeRef;
    use pliant_assembly::workcell::log::{header_line, line_text, LogHeader, LogLine};
    use pliant_assembly::workcell::StampedInput;
    use pliant_assembly::{Input, WorkcellOptions};
    let header = LogHeader::new(
        "demo",
        "demo.toml",
        "scene.toml",
        ".",
        WorkcellOptions::default(),
        2.5e-4,
    );
    let inputs = [
        Input::Grab {
            grip: Default::default(),
            hand: 3,
            at: glam::DVec3::new(-0.17, -0.6, 0.25),
        },
        Input::Fix {
            node: NodeRef { hose: 0, node: 1 },
        },
        Input::Reset,
        Input::Rollback,
    ];
    let mut sealed = header_line(&header);
    for (k, input) in inputs.iter().enumerate() {
        sealed.push_str(&line_text(&LogLine::Input(StampedInput {
            tick: 40 * k as u64,
            input: input.clone(),
        })));
        sealed.push_str(&line_text(&LogLine::Mark {
            tick: 40 * k as u64 + 20,
        }));
    }
    let unsealed: String = sealed
        .lines()
        .map(|l| match l.rfind(",\"crc32\"") {
            Some(at) => format!("{}}}\n", &l[..at]),
            None => format!("{l}\n"),
        })
        .collect::<String>()
        .replacen("\"version\":2", "\"version\":1", 1);
    vec![sealed.into_bytes(), unsealed.into_bytes()]
}
