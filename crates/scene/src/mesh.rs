//! Triangle meshes for rigid parts: reading OBJ (`tobj`), STL (`stl_io`) and glTF/GLB
//! (`gltf`) files, generating primitives (box, cylinder, sphere), and checking a mesh
//! (non-empty, finite vertices, indices in range, not only degenerate triangles, at most
//! [`MAX_TRIANGLES`]). Errors are plain reasons; [`crate::parts`] attaches the field.

use crate::files::FileAccess;
use glam::{DMat4, DVec3};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::Path;

/// The most triangles one part may have.
pub const MAX_TRIANGLES: usize = 5_000_000;

/// Default number of segments around a cylinder.
pub const DEFAULT_CYLINDER_SEGMENTS: u32 = 32;
/// Default subdivision level of a sphere (an icosahedron subdivided this often: 20·4ⁿ
/// triangles; 3 → 1280).
pub const DEFAULT_SPHERE_SUBDIVISIONS: u32 = 3;

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Triangles as indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

/// Mesh file formats, chosen by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`.obj`).
    Obj,
    /// STL, ASCII or binary (`.stl`).
    Stl,
    /// glTF 2.0, JSON (`.gltf`) or binary (`.glb`).
    Gltf,
}

impl MeshFormat {
    /// The format's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Stl => "STL",
            MeshFormat::Gltf => "glTF",
        }
    }

    /// The format of a path, by its extension (case-insensitive).
    pub fn of(path: &Path) -> Result<MeshFormat, String> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("obj") => Ok(MeshFormat::Obj),
            Some("stl") => Ok(MeshFormat::Stl),
            Some("gltf") | Some("glb") => Ok(MeshFormat::Gltf),
            Some(other) => Err(format!(
                "unknown mesh format \".{other}\"; use .obj, .stl, .gltf or .glb"
            )),
            None => {
                Err("the file name has no extension; use .obj, .stl, .gltf or .glb".to_string())
            }
        }
    }
}

/// Reads the mesh file `name` through `files` (coordinates as stored in the file). In a
/// sandbox a reader's complaint is not passed on (it may quote the file).
pub fn read_mesh_file(files: &FileAccess, name: &str) -> Result<TriMesh, String> {
    let format = MeshFormat::of(Path::new(name))?;
    let bytes = files.read(name)?;
    let dir = files.beside(name);
    let result = match format {
        MeshFormat::Obj => read_obj(&bytes),
        MeshFormat::Stl => read_stl(&bytes),
        MeshFormat::Gltf => read_gltf(&bytes, &dir),
    };
    match result {
        Err(_) if files.is_sandboxed() => Err(format!(
            "is not a valid {} file (the reason is not shown to clients of the server; load the scene with `pliant run` to see it)",
            format.name()
        )),
        other => other,
    }
}

/// Runs a reader; a panic in it (a bug of the parsing library on a malformed file, such
/// as gltf-json 1.4's index panic on a POSITION accessor that does not exist) is
/// reported as a malformed file. Every public reader goes through here.
pub(crate) fn no_panic<T>(read: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(read))
        .unwrap_or_else(|_| Err("malformed file: the reader failed on it".to_string()))
}

/// Wavefront OBJ: all objects and groups, polygons triangulated; points, lines and
/// materials ignored.
pub fn read_obj(bytes: &[u8]) -> Result<TriMesh, String> {
    no_panic(|| read_obj_unguarded(bytes))
}

fn read_obj_unguarded(bytes: &[u8]) -> Result<TriMesh, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::BufReader::new(bytes);
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::GenericFailure)
    })
    .map_err(|e| match e {
        tobj::LoadError::FaceVertexOutOfBounds => {
            "index out of range: a face refers to a vertex that does not exist".to_string()
        }
        other => format!("cannot parse as OBJ: {other}"),
    })?;
    let mut mesh = TriMesh::default();
    for model in models {
        let m = model.mesh;
        let base = index_base(mesh.vertices.len())?;
        let first = mesh.vertices.len();
        mesh.vertices.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2])),
        );
        let count = mesh.vertices.len() - first;
        for (k, t) in m.indices.chunks_exact(3).enumerate() {
            check_triangle_count(mesh.triangles.len() + 1)?;
            let mut tri = [0u32; 3];
            for (j, &i) in t.iter().enumerate() {
                if i as usize >= count {
                    return Err(format!(
                        "index out of range: triangle {} refers to vertex {i} of an object with {count} vertices",
                        mesh.triangles.len() + k
                    ));
                }
                tri[j] = base + i;
            }
            mesh.triangles.push(tri);
        }
    }
    Ok(mesh)
}

/// STL, ASCII or binary. A binary file whose 80-byte header happens to start with
/// `solid ` (as some CAD exporters write) is recognised by its size.
pub fn read_stl(bytes: &[u8]) -> Result<TriMesh, String> {
    no_panic(|| read_stl_unguarded(bytes))
}

fn read_stl_unguarded(bytes: &[u8]) -> Result<TriMesh, String> {
    let binary_count = (bytes.len() >= 84)
        .then(|| u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize);
    let looks_ascii = bytes.starts_with(b"solid ");
    let mut data = bytes.to_vec();
    if let Some(n) = binary_count {
        let exact_binary = n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len());
        if !looks_ascii || exact_binary {
            if n > MAX_TRIANGLES {
                return Err(too_many(n));
            }
            if exact_binary {
                // The header carries no data; blank it so the reader cannot take the file
                // for ASCII.
                data[..80].fill(0);
            }
        }
    }
    let mut cursor = std::io::Cursor::new(data);
    let stl = stl_io::read_stl(&mut cursor).map_err(|e| format!("cannot parse as STL: {e}"))?;
    check_triangle_count(stl.faces.len())?;
    let vertices = stl
        .vertices
        .iter()
        .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
        .collect::<Vec<_>>();
    index_base(vertices.len())?;
    let triangles = stl
        .faces
        .iter()
        .map(|f| f.vertices.map(|i| i as u32))
        .collect();
    Ok(TriMesh {
        vertices,
        triangles,
    })
}

/// glTF 2.0 (`.gltf` with embedded `data:` or external buffers, or `.glb`): every
/// triangle primitive (triangles, strips, fans) of every mesh instance of the default
/// scene (else the first scene; else every mesh once), with its node transforms applied.
/// Points and lines are ignored.
pub fn read_gltf(bytes: &[u8], dir: &FileAccess) -> Result<TriMesh, String> {
    no_panic(|| read_gltf_unguarded(bytes, dir))
}

fn read_gltf_unguarded(bytes: &[u8], dir: &FileAccess) -> Result<TriMesh, String> {
    let gltf = gltf::Gltf::from_slice(bytes).map_err(|e| format!("cannot parse as glTF: {e}"))?;
    let doc = &gltf.document;
    let mut buffers: Vec<Vec<u8>> = Vec::new();
    for buffer in doc.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                format!(
                    "buffer {} refers to the binary chunk, but the file has none",
                    buffer.index()
                )
            })?,
            gltf::buffer::Source::Uri(uri) => read_uri(uri, dir)
                .map_err(|e| format!("buffer {} (\"{uri}\"): {e}", buffer.index()))?,
        };
        if data.len() < buffer.length() {
            return Err(format!(
                "buffer {} is {} bytes long, but the file declares {}",
                buffer.index(),
                data.len(),
                buffer.length()
            ));
        }
        buffers.push(data);
    }
    let mut mesh = TriMesh::default();
    let scene = doc.default_scene().or_else(|| doc.scenes().next());
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                gltf_node(&node, DMat4::IDENTITY, &buffers, &mut mesh, 0)?;
            }
        }
        None => {
            for m in doc.meshes() {
                gltf_mesh(&m, DMat4::IDENTITY, &buffers, &mut mesh)?;
            }
        }
    }
    Ok(mesh)
}

/// Adds a node's meshes and those of its children.
fn gltf_node(
    node: &gltf::Node,
    parent: DMat4,
    buffers: &[Vec<u8>],
    mesh: &mut TriMesh,
    depth: usize,
) -> Result<(), String> {
    if depth > 64 {
        return Err("the node hierarchy is deeper than 64 levels (a cycle?)".to_string());
    }
    let m = node.transform().matrix().map(|c| c.map(f64::from));
    let transform = parent * DMat4::from_cols_array_2d(&m);
    if let Some(m) = node.mesh() {
        gltf_mesh(&m, transform, buffers, mesh)?;
    }
    for child in node.children() {
        gltf_node(&child, transform, buffers, mesh, depth + 1)?;
    }
    Ok(())
}

/// Adds one glTF mesh's triangle primitives, transformed.
pub(crate) fn gltf_mesh(
    m: &gltf::Mesh,
    transform: DMat4,
    buffers: &[Vec<u8>],
    mesh: &mut TriMesh,
) -> Result<(), String> {
    use gltf::accessor::{DataType, Dimensions};
    use gltf::mesh::Mode;
    for p in m.primitives() {
        let what = || format!("mesh {} primitive {}", m.index(), p.index());
        if !matches!(
            p.mode(),
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            continue;
        }
        let positions = p
            .get(&gltf::Semantic::Positions)
            .ok_or_else(|| format!("{} has no POSITION attribute", what()))?;
        if positions.dimensions() != Dimensions::Vec3
            || positions.data_type() != DataType::F32
            || positions.normalized()
        {
            return Err(format!(
                "{}: POSITION must be VEC3 of 32-bit floats",
                what()
            ));
        }
        if let Some(ind) = p.indices() {
            if ind.dimensions() != Dimensions::Scalar
                || !matches!(
                    ind.data_type(),
                    DataType::U8 | DataType::U16 | DataType::U32
                )
            {
                return Err(format!(
                    "{}: indices must be SCALAR unsigned integers",
                    what()
                ));
            }
            if ind.count() == 0 {
                continue;
            }
        }
        if positions.count() == 0 {
            return Err(format!("{} has no vertices", what()));
        }
        let reader = p.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
        let local: Vec<DVec3> = reader
            .read_positions()
            .ok_or_else(|| format!("{}: POSITION data lies outside its buffer", what()))?
            .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
            .collect();
        if local.len() != positions.count() {
            return Err(format!("{}: POSITION data lies outside its buffer", what()));
        }
        let order: Vec<u32> = match reader.read_indices() {
            Some(ind) => ind.into_u32().collect(),
            None => (0..local.len() as u32).collect(),
        };
        let count = local.len();
        if let Some((k, &i)) = order.iter().enumerate().find(|(_, &i)| i as usize >= count) {
            return Err(format!(
                "index out of range: {} index {k} refers to vertex {i}, but the primitive has {count} vertices",
                what()
            ));
        }
        let base = index_base(mesh.vertices.len())?;
        index_base(mesh.vertices.len() + count)?;
        mesh.vertices
            .extend(local.iter().map(|v| transform.transform_point3(*v)));
        let tris: Vec<[u32; 3]> = match p.mode() {
            Mode::Triangles => order.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
            Mode::TriangleStrip => (0..order.len().saturating_sub(2))
                .map(|k| {
                    if k % 2 == 0 {
                        [order[k], order[k + 1], order[k + 2]]
                    } else {
                        [order[k + 1], order[k], order[k + 2]]
                    }
                })
                .collect(),
            _ => (1..order.len().saturating_sub(1))
                .map(|k| [order[0], order[k], order[k + 1]])
                .collect(),
        };
        check_triangle_count(mesh.triangles.len() + tris.len())?;
        mesh.triangles
            .extend(tris.into_iter().map(|t| t.map(|i| base + i)));
    }
    Ok(())
}

/// Reads a glTF buffer URI: a `data:…;base64,…` URI, or a path relative to the glTF
/// file, through the scene's file access (sandbox and size cap).
fn read_uri(uri: &str, dir: &FileAccess) -> Result<Vec<u8>, String> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or("only base64 data URIs are supported")?;
        return decode_base64(payload);
    }
    if uri.contains("://") {
        return Err("only relative file paths and data: URIs are supported".to_string());
    }
    dir.read(&percent_decode(uri)?)
}

/// Decodes `%XX` escapes in a URI path.
fn percent_decode(s: &str) -> Result<String, String> {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = s
                .get(i + 1..i + 3)
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("bad escape in URI \"{s}\""))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("URI \"{s}\" is not UTF-8"))
}

/// Decodes standard base64 (padding optional, whitespace not allowed).
pub fn decode_base64(s: &str) -> Result<Vec<u8>, String> {
    let value = |c: u8| -> Result<u32, String> {
        Ok(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return Err(format!("invalid base64 character {:?}", c as char)),
        } as u32)
    };
    let s = s.trim_end_matches('=').as_bytes();
    if s.len() % 4 == 1 {
        return Err("invalid base64 length".to_string());
    }
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    for chunk in s.chunks(4) {
        let mut acc = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            acc |= value(c)? << (18 - 6 * k);
        }
        let bytes = acc.to_be_bytes();
        out.extend_from_slice(&bytes[1..chunk.len()]);
    }
    Ok(out)
}

/// Index of the next vertex as a `u32`, or an error if the mesh has too many vertices.
fn index_base(len: usize) -> Result<u32, String> {
    u32::try_from(len).map_err(|_| format!("more than {} vertices", u32::MAX))
}

fn too_many(n: usize) -> String {
    format!("{n} triangles; at most {MAX_TRIANGLES} are supported per part")
}

/// Fails if `n` exceeds [`MAX_TRIANGLES`].
pub fn check_triangle_count(n: usize) -> Result<(), String> {
    if n > MAX_TRIANGLES {
        Err(too_many(n))
    } else {
        Ok(())
    }
}

/// The result of [`check_mesh`].
#[derive(Clone, Debug, PartialEq)]
pub struct Checked {
    /// The mesh without degenerate triangles.
    pub mesh: TriMesh,
    /// How many degenerate (zero-area or repeated-index) triangles were dropped.
    pub dropped_degenerate: usize,
}

/// Checks a mesh: at least one triangle, at most [`MAX_TRIANGLES`], every vertex finite,
/// every index in range, at least one non-degenerate triangle. Degenerate triangles
/// (repeated indices, or area ≤ 1e-12 × the squared bounding-box diagonal) are dropped.
pub fn check_mesh(mesh: TriMesh) -> Result<Checked, String> {
    if mesh.triangles.is_empty() {
        return Err("empty mesh: it contains no triangles".to_string());
    }
    check_triangle_count(mesh.triangles.len())?;
    if let Some((k, v)) = mesh
        .vertices
        .iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
    {
        return Err(format!(
            "vertex {k} has a non-finite coordinate {}",
            crate::units::fmt_vec(v.to_array())
        ));
    }
    let n = mesh.vertices.len();
    for (k, t) in mesh.triangles.iter().enumerate() {
        if let Some(&i) = t.iter().find(|&&i| i as usize >= n) {
            return Err(format!(
                "index out of range: triangle {k} refers to vertex {i}, but the mesh has {n} vertices"
            ));
        }
    }
    let (lo, hi) = bounds(&mesh.vertices);
    let diag2 = (hi - lo).length_squared();
    let total = mesh.triangles.len();
    let TriMesh {
        vertices,
        triangles,
    } = mesh;
    let kept: Vec<[u32; 3]> = triangles
        .into_iter()
        .filter(|t| {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            t[0] != t[1]
                && t[1] != t[2]
                && t[0] != t[2]
                && (b - a).cross(c - a).length() > 1e-12 * diag2
        })
        .collect();
    if kept.is_empty() {
        return Err(format!(
            "degenerate mesh: all {total} triangles have zero area"
        ));
    }
    Ok(Checked {
        dropped_degenerate: total - kept.len(),
        mesh: TriMesh {
            vertices,
            triangles: kept,
        },
    })
}

/// Component-wise minimum and maximum of points (zero for none).
pub fn bounds(points: &[DVec3]) -> (DVec3, DVec3) {
    if points.is_empty() {
        return (DVec3::ZERO, DVec3::ZERO);
    }
    points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Signed volume enclosed by a closed mesh (divergence theorem); positive when its
/// triangles are oriented counter-clockwise seen from outside.
pub fn signed_volume(mesh: &TriMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// An axis-aligned box of edge lengths `size`, centred at the origin; 12 triangles,
/// outward.
pub fn box_mesh(size: DVec3) -> TriMesh {
    let h = size / 2.0;
    let vertices = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            )
        })
        .collect();
    // Faces as quads (counter-clockwise from outside), split into two triangles each.
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    TriMesh {
        vertices,
        triangles,
    }
}

/// Triangles of a closed cylinder with `segments` sides.
pub fn cylinder_triangles(segments: u32) -> usize {
    4 * segments as usize
}

/// A closed cylinder (a prism with `segments` ≥ 3 sides inscribed in the circle) of
/// `radius` and `height` along z, centred at the origin; outward.
pub fn cylinder_mesh(radius: f64, height: f64, segments: u32) -> TriMesh {
    let n = segments.max(3);
    let h = height / 2.0;
    let mut vertices = Vec::with_capacity(2 * n as usize + 2);
    for k in 0..n {
        let a = 2.0 * PI * k as f64 / n as f64;
        let (s, c) = a.sin_cos();
        vertices.push(DVec3::new(radius * c, radius * s, -h));
        vertices.push(DVec3::new(radius * c, radius * s, h));
    }
    let bottom = 2 * n;
    let top = 2 * n + 1;
    vertices.push(DVec3::new(0.0, 0.0, -h));
    vertices.push(DVec3::new(0.0, 0.0, h));
    let mut triangles = Vec::with_capacity(cylinder_triangles(n));
    for k in 0..n {
        let (b0, t0) = (2 * k, 2 * k + 1);
        let (b1, t1) = (2 * ((k + 1) % n), 2 * ((k + 1) % n) + 1);
        triangles.push([b0, b1, t1]);
        triangles.push([b0, t1, t0]);
        triangles.push([bottom, b1, b0]);
        triangles.push([top, t0, t1]);
    }
    TriMesh {
        vertices,
        triangles,
    }
}

/// Triangles of a sphere of `subdivisions` (20·4ⁿ), or `None` if absurdly many.
pub fn sphere_triangles(subdivisions: u32) -> Option<usize> {
    4usize
        .checked_pow(subdivisions)
        .and_then(|p| p.checked_mul(20))
}

/// A sphere of `radius` centred at the origin: an icosahedron subdivided `subdivisions`
/// times, every vertex on the sphere; outward.
pub fn sphere_mesh(radius: f64, subdivisions: u32) -> TriMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut vertices: Vec<DVec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|p| DVec3::from_array(*p).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut mid = |a: u32, b: u32, vertices: &mut Vec<DVec3>| -> u32 {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let m = ((vertices[a as usize] + vertices[b as usize]) / 2.0).normalize();
                vertices.push(m);
                (vertices.len() - 1) as u32
            })
        };
        let mut next = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let ab = mid(a, b, &mut vertices);
            let bc = mid(b, c, &mut vertices);
            let ca = mid(c, a, &mut vertices);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    for v in &mut vertices {
        *v *= radius;
    }
    TriMesh {
        vertices,
        triangles,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every edge is used exactly twice, once in each direction: closed and consistently
    /// oriented.
    fn closed_and_oriented(m: &TriMesh) -> bool {
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a, b)).or_default() += 1;
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    #[test]
    fn box_is_closed_with_the_right_volume() {
        let m = box_mesh(DVec3::new(2.0, 3.0, 4.0));
        assert_eq!(m.triangles.len(), 12);
        assert!(closed_and_oriented(&m));
        assert!((signed_volume(&m) - 24.0).abs() < 1e-12);
        assert_eq!(
            bounds(&m.vertices),
            (DVec3::new(-1.0, -1.5, -2.0), DVec3::new(1.0, 1.5, 2.0))
        );
    }

    #[test]
    fn cylinder_is_closed_with_the_prism_volume() {
        for n in [3, 7, 32, 200] {
            let m = cylinder_mesh(0.5, 2.0, n);
            assert_eq!(m.triangles.len(), cylinder_triangles(n));
            assert!(closed_and_oriented(&m), "n = {n}");
            // Exact: the inscribed n-gon prism, n/2 · r² · sin(2π/n) · h.
            let prism = n as f64 / 2.0 * 0.25 * (2.0 * PI / n as f64).sin() * 2.0;
            assert!((signed_volume(&m) - prism).abs() < 1e-12, "n = {n}");
        }
        // Against the true cylinder π r² h: relative deficit 1 − sin(2π/n)/(2π/n) ≈ 0.64 %
        // at 32 segments.
        let v = signed_volume(&cylinder_mesh(0.5, 2.0, 32));
        let exact = PI * 0.25 * 2.0;
        assert!((exact - v) / exact < 0.0065 && v < exact);
    }

    #[test]
    fn sphere_is_closed_on_its_radius() {
        for s in 0..=4 {
            let m = sphere_mesh(2.0, s);
            assert_eq!(Some(m.triangles.len()), sphere_triangles(s));
            assert!(closed_and_oriented(&m), "s = {s}");
            assert!(m.vertices.iter().all(|v| (v.length() - 2.0).abs() < 1e-12));
        }
        // Three subdivisions: 1280 triangles, volume within 1.5 % below 4/3 π r³.
        let v = signed_volume(&sphere_mesh(2.0, 3));
        let exact = 4.0 / 3.0 * PI * 8.0;
        assert!(v < exact && (exact - v) / exact < 0.015, "{v} vs {exact}");
        assert_eq!(sphere_triangles(40), None);
    }

    #[test]
    fn gltf_position_accessor_out_of_range_is_an_error_not_a_panic() {
        // found by the fuzzer (crates/fuzz): gltf-json indexes the accessor unchecked
        let doc = br#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}"#;
        let e = read_gltf(doc, &FileAccess::local(Path::new("."))).unwrap_err();
        assert!(!e.is_empty());
    }

    #[test]
    fn base64_round_trips() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGVsbG8").unwrap(), b"hello");
        assert_eq!(decode_base64("AAEC/w==").unwrap(), [0, 1, 2, 255]);
        assert!(decode_base64("a$==").is_err());
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
    }

    #[test]
    fn obj_ignores_materials_and_triangulates_polygons() {
        let text = "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\nl 1 3\n";
        let m = read_obj(text.as_bytes()).unwrap();
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.triangles.len(), 2);
        // Negative (relative) indices.
        let m = read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n").unwrap();
        assert_eq!(m.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn checks_drop_degenerate_triangles() {
        let mut m = box_mesh(DVec3::ONE);
        m.triangles.push([0, 0, 1]);
        m.triangles.push([0, 1, 1]);
        let c = check_mesh(m).unwrap();
        assert_eq!(c.dropped_degenerate, 2);
        assert_eq!(c.mesh.triangles.len(), 12);
    }
}
