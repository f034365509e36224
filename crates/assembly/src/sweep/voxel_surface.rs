//! The surface of a voxel set: every face between an occupied voxel and an empty one, as
//! two triangles turned outwards, the corners shared. It is the boundary of the union of
//! the occupied cubes itself, so it encloses exactly their volume (count · h³) and
//! contains whatever they contain — the swept tube ([`super::voxels`]). Marching cubes
//! at the 0.5 level (the studies' smoother mesh) cuts the cubes' corners and loses that
//! guarantee; Surface Nets likewise. Where two voxels meet only along an edge, four faces
//! share it: the surface is closed (each edge taken once in each direction as often)
//! but not a 2-manifold there.

use super::voxels::VoxelGrid;
use std::collections::HashMap;

/// A triangle mesh \[m\].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    pub vertices: Vec<[f64; 3]>,
    /// Counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

/// The six face directions: the axis, the side (+1/−1).
const FACES: [(usize, i64); 6] = [(0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)];

/// The boundary of the union of `grid`'s occupied cubes.
pub fn voxel_surface(grid: &VoxelGrid) -> TriangleMesh {
    let mut mesh = TriangleMesh::default();
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let h = grid.h;
    for v in grid.voxels() {
        for (axis, side) in FACES {
            let mut n = v;
            n[axis] += side;
            if grid.contains(n) {
                continue;
            }
            // corners of the face on the side `side` of voxel v, in corner indices: the
            // corner c of the cube around v is at (c − ½)·h
            let (u, w) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut corner = |du: i64, dw: i64| {
                let mut c = v;
                c[axis] += (side + 1) / 2;
                c[u] += du;
                c[w] += dw;
                *index.entry(c).or_insert_with(|| {
                    mesh.vertices.push(c.map(|x| (x as f64 - 0.5) * h));
                    (mesh.vertices.len() - 1) as u32
                })
            };
            // (u, w, axis) is right-handed: counter-clockwise in (u, w) faces +axis
            let quad = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
            let [a, b, c, d] = if side > 0 {
                quad
            } else {
                [quad[0], quad[3], quad[2], quad[1]]
            };
            mesh.triangles.push([a, b, c]);
            mesh.triangles.push([a, c, d]);
        }
    }
    mesh
}

impl TriangleMesh {
    /// Whether every directed edge is matched by as many in the opposite direction: the
    /// surface is closed and consistently turned.
    pub fn is_closed(&self) -> bool {
        let mut count: HashMap<(u32, u32), i64> = HashMap::new();
        for t in &self.triangles {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                *count.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
            }
        }
        count.values().all(|&c| c == 0)
    }

    /// The enclosed volume \[m³\] (divergence theorem: Σ a · (b × c) / 6).
    pub fn volume(&self) -> f64 {
        let v = |i: u32| glam::DVec3::from_array(self.vertices[i as usize]);
        self.triangles
            .iter()
            .map(|t| v(t[0]).dot(v(t[1]).cross(v(t[2]))) / 6.0)
            .sum()
    }

    /// The smallest and largest corner of the vertices' bounding box \[m\].
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        self.vertices.iter().fold(
            ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
            |(lo, hi), p| {
                (
                    [0, 1, 2].map(|a| lo[a].min(p[a])),
                    [0, 1, 2].map(|a| hi[a].max(p[a])),
                )
            },
        )
    }

    /// Binary STL of the mesh (metres) into `out`.
    pub fn write_stl(&self, out: &mut impl std::io::Write) -> std::io::Result<()> {
        let vertex = |i: u32| {
            let p = self.vertices[i as usize];
            stl_io::Vertex::new([p[0] as f32, p[1] as f32, p[2] as f32])
        };
        let triangles: Vec<stl_io::Triangle> = self
            .triangles
            .iter()
            .map(|t| {
                let (a, b, c) = (
                    glam::DVec3::from_array(self.vertices[t[0] as usize]),
                    glam::DVec3::from_array(self.vertices[t[1] as usize]),
                    glam::DVec3::from_array(self.vertices[t[2] as usize]),
                );
                let n = (b - a).cross(c - a).normalize_or_zero();
                stl_io::Triangle {
                    normal: stl_io::Normal::new([n.x as f32, n.y as f32, n.z as f32]),
                    vertices: [vertex(t[0]), vertex(t[1]), vertex(t[2])],
                }
            })
            .collect();
        stl_io::write_stl(out, triangles.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::centreline_samples::sample_keys;

    #[test]
    fn the_surface_of_a_tube_is_closed_and_encloses_its_voxels() {
        let h = 0.002;
        let keys = sample_keys(&[0.0, 0.0, 0.0, 0.03, 0.01, 0.0], 1, 2, h).unwrap();
        let grid = VoxelGrid::of_samples(&keys, 0.004, h).unwrap();
        let mesh = voxel_surface(&grid);
        assert!(mesh.is_closed());
        let expected = grid.count() as f64 * h.powi(3);
        assert!(
            (mesh.volume() - expected).abs() < 1e-9 * expected,
            "{} {expected}",
            mesh.volume()
        );
        let mut stl = Vec::new();
        mesh.write_stl(&mut stl).unwrap();
        let read = stl_io::read_stl(&mut std::io::Cursor::new(stl)).unwrap();
        assert_eq!(read.faces.len(), mesh.triangles.len());
    }
}
