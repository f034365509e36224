//! A triangle mesh as binary glTF 2.0 (`.glb`, Khronos glTF 2.0 specification §4.4):
//! one mesh of one indexed triangle primitive, positions as f32 metres, written with the
//! `gltf` crate's JSON types and GLB container.

use super::voxel_surface::TriangleMesh;
use gltf::json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use std::borrow::Cow;

/// Writes `mesh`, named `name`, as a GLB file to `out`.
pub fn write_glb(
    mesh: &TriangleMesh,
    name: &str,
    out: &mut impl std::io::Write,
) -> std::io::Result<()> {
    let invalid = |e: String| std::io::Error::new(std::io::ErrorKind::InvalidData, e);
    let positions: Vec<[f32; 3]> = mesh.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
    let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
    for p in &positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    // the binary chunk: positions, then indices (both 4-byte aligned)
    let mut bin: Vec<u8> = Vec::with_capacity(12 * positions.len() + 12 * mesh.triangles.len());
    for c in positions.iter().flatten() {
        bin.extend_from_slice(&c.to_le_bytes());
    }
    let position_bytes = bin.len();
    for i in mesh.triangles.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let index_bytes = bin.len() - position_bytes;

    let mut root = json::Root::default();
    let buffer = root.push(json::Buffer {
        byte_length: USize64::from(bin.len()),
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        uri: None,
    });
    let view = |root: &mut json::Root, offset: usize, length: usize, target| {
        root.push(json::buffer::View {
            buffer,
            byte_length: USize64::from(length),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            extensions: Default::default(),
            extras: Default::default(),
            name: None,
            target: Some(Valid(target)),
        })
    };
    let position_view = view(
        &mut root,
        0,
        position_bytes,
        json::buffer::Target::ArrayBuffer,
    );
    let index_view = view(
        &mut root,
        position_bytes,
        index_bytes,
        json::buffer::Target::ElementArrayBuffer,
    );
    let accessor = |root: &mut json::Root,
                    view,
                    count,
                    component,
                    type_,
                    bounds: Option<([f32; 3], [f32; 3])>| {
        let (min, max) = match bounds {
            Some(([a, b, c], [d, e, f])) => (
                Some(json::Value::from(vec![a, b, c])),
                Some(json::Value::from(vec![d, e, f])),
            ),
            None => (None, None),
        };
        root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: Some(USize64(0)),
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: Default::default(),
            extras: Default::default(),
            type_: Valid(type_),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    };
    let vertices = accessor(
        &mut root,
        position_view,
        positions.len(),
        json::accessor::ComponentType::F32,
        json::accessor::Type::Vec3,
        (!positions.is_empty()).then_some((lo, hi)),
    );
    let indices = accessor(
        &mut root,
        index_view,
        3 * mesh.triangles.len(),
        json::accessor::ComponentType::U32,
        json::accessor::Type::Scalar,
        None,
    );
    let primitive = json::mesh::Primitive {
        attributes: [(Valid(json::mesh::Semantic::Positions), vertices)].into(),
        extensions: Default::default(),
        extras: Default::default(),
        indices: Some(indices),
        material: None,
        mode: Valid(json::mesh::Mode::Triangles),
        targets: None,
    };
    let mesh_index = root.push(json::Mesh {
        extensions: Default::default(),
        extras: Default::default(),
        name: Some(name.to_string()),
        primitives: vec![primitive],
        weights: None,
    });
    let node = root.push(json::Node {
        mesh: Some(mesh_index),
        name: Some(name.to_string()),
        ..Default::default()
    });
    let scene = root.push(json::Scene {
        extensions: Default::default(),
        extras: Default::default(),
        name: None,
        nodes: vec![node],
    });
    root.scene = Some(scene);
    let text = json::serialize::to_vec(&root).map_err(|e| invalid(e.to_string()))?;
    let length = 12 + 8 + text.len().next_multiple_of(4) + 8 + bin.len().next_multiple_of(4);
    let glb = gltf::binary::Glb {
        header: gltf::binary::Header {
            magic: *b"glTF",
            version: 2,
            length: u32::try_from(length)
                .map_err(|_| invalid(format!("{length} bytes: beyond the GLB limit of 4 GiB")))?,
        },
        json: Cow::Owned(text),
        bin: Some(Cow::Owned(bin)),
    };
    glb.to_writer(out).map_err(|e| invalid(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::voxel_surface::voxel_surface;
    use crate::sweep::voxels::VoxelGrid;

    /// A GLB read back by the `gltf` crate's own reader holds the mesh's vertices (as
    /// f32) and triangles, and its header's length is the file's.
    #[test]
    fn a_voxel_surface_reads_back_from_its_glb() {
        let h = 0.004;
        let frames = [0.0, 0.0, 0.0, 0.05, 0.02, 0.0];
        let samples = crate::sweep::centreline_samples::sample_keys(&frames, 1, 2, h).unwrap();
        let grid = VoxelGrid::of_samples(&samples, 0.006, h).unwrap();
        let mesh = voxel_surface(&grid);
        assert!(mesh.triangles.len() > 100);
        let mut bytes = Vec::new();
        write_glb(&mesh, "envelope", &mut bytes).unwrap();
        assert_eq!(
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
            bytes.len()
        );
        let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
        let blob = gltf.blob.clone().expect("a binary chunk");
        let read = gltf.meshes().next().expect("a mesh");
        assert_eq!(read.name(), Some("envelope"));
        let primitive = read.primitives().next().unwrap();
        let reader = primitive.reader(|_| Some(&blob));
        let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        let want: Vec<[f32; 3]> = mesh.vertices.iter().map(|v| v.map(|c| c as f32)).collect();
        assert_eq!(positions, want);
        let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
        let want: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
        assert_eq!(indices, want);
    }
}
