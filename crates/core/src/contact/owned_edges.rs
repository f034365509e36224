//! One owner per mesh edge: the beam-interior contact is a pair between the beam's
//! segment and a mesh *edge* (SPEC L4), and an edge that two triangles share would
//! otherwise be measured twice — by each of them, to the same distance — whenever a beam
//! lies across it, as a hose resting on a surface does. Each edge is measured only by the
//! triangle that owns it, made once when the environment is built.

use parry3d_f64::shape::TriMesh;

/// Every edge of a triangle (bit k: the edge from vertex k to vertex k + 1 mod 3).
pub(crate) const ALL_EDGES: u8 = 0b111;

/// For each triangle of `mesh`, the edges it owns (bit k: from vertex k to k + 1 mod 3).
/// An edge that several triangles share (the same two vertex indices, either way round)
/// is owned by the first of them in the mesh's order; an edge of one triangle (a border,
/// or a mesh whose vertices are not shared) by that triangle.
pub(crate) fn owned_edges(mesh: &TriMesh) -> Vec<u8> {
    let triangles = mesh.indices();
    // (lower vertex, higher vertex, triangle, edge): sorted, the first of each edge owns it
    let mut edges: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(3 * triangles.len());
    for (t, v) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (p, q) = (v[k], v[(k + 1) % 3]);
            edges.push((p.min(q), p.max(q), t as u32, k as u8));
        }
    }
    edges.sort_unstable();
    let mut owned = vec![0u8; triangles.len()];
    for (j, e) in edges.iter().enumerate() {
        if j == 0 || (edges[j - 1].0, edges[j - 1].1) != (e.0, e.1) {
            owned[e.2 as usize] |= 1 << e.3;
        }
    }
    owned
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A grid of `2·q²` triangles over the unit square.
    fn grid(q: usize) -> TriMesh {
        let mut vertices = Vec::new();
        for j in 0..=q {
            for i in 0..=q {
                vertices.push(DVec3::new(i as f64, j as f64, 0.0) / q as f64);
            }
        }
        let idx = |i: usize, j: usize| (j * (q + 1) + i) as u32;
        let mut triangles = Vec::new();
        for j in 0..q {
            for i in 0..q {
                triangles.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
                triangles.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
            }
        }
        TriMesh::new(vertices, triangles).unwrap()
    }

    /// Each edge of the grid is owned by exactly one triangle.
    #[test]
    fn each_edge_has_one_owner() {
        let q = 20;
        let owned = owned_edges(&grid(q));
        let count: u32 = owned.iter().map(|m| m.count_ones()).sum();
        // horizontal, vertical and diagonal edges of a q × q grid
        assert_eq!(count as usize, 2 * q * (q + 1) + q * q);
        // a quad's diagonal (edge 2 of its first triangle, edge 0 of its second) is
        // owned by the first
        for quad in owned.chunks(2) {
            assert_eq!(((quad[0] >> 2) & 1, quad[1] & 1), (1, 0));
        }
    }

    /// Triangles that share no vertex index own all their edges.
    #[test]
    fn unshared_vertices_own_every_edge() {
        let v = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let mesh = TriMesh::new(
            vec![
                v(0., 0.),
                v(1., 0.),
                v(1., 1.),
                v(0., 0.),
                v(1., 1.),
                v(0., 1.),
            ],
            vec![[0, 1, 2], [3, 4, 5]],
        )
        .unwrap();
        assert_eq!(owned_edges(&mesh), vec![ALL_EDGES, ALL_EDGES]);
    }
}
