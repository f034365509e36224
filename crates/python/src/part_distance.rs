//! Distances from sampled hose points to a scene part, for a study's clearances
//! (`pliant.studies.geometry.Part`): the `clearance_*` column of a run is
//! min over its points of (distance to the part − the hose's outer radius).
//!
//! - Box, cylinder, sphere: the exact signed distance of the primitive (negative inside).
//!   In the part's frame, p = Rᵀ(x − x₀); a box of edges s has q_i = |p_i| − s_i/2, a
//!   cylinder of radius r and height h the rectangle q = (√(p_x² + p_y²) − r, |p_z| − h/2);
//!   d = |max(q, 0)| + min(max_i q_i, 0) (the rounded-box distance of Quilez, radius 0).
//!   A sphere of radius r: |p| − r.
//! - Meshes (triangles in world coordinates): the exact unsigned distance to the nearest
//!   triangle, found through the engine's own BVH ([`RigidEnvironment::closest_point`]);
//!   for a minimum over many points, each point's distance to the mesh's bounding box is
//!   a lower bound, so only points whose bound beats the best so far are measured.
//!
//! In Rust because numpy spent ≈ 12 ms per demo run here (31 000 points, six parts) on
//! temporaries, on a core the next run needs.

use glam::DVec3;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3};
use pliant_core::contact::RigidEnvironment;
use pliant_core::spec::RigidPartSpec;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// A part's shape, as `pliant.studies.geometry.Part` describes it.
enum Shape {
    /// Local → world rotation (rows), position, and the primitive.
    Primitive {
        rotation: [DVec3; 3],
        position: DVec3,
        kind: Primitive,
    },
    Mesh {
        env: RigidEnvironment,
        lo: DVec3,
        hi: DVec3,
    },
}

enum Primitive {
    Box(DVec3),
    Cylinder { radius: f64, height: f64 },
    Sphere(f64),
}

impl Shape {
    fn new(
        kind: &str,
        position: [f64; 3],
        rotation: [[f64; 3]; 3],
        size: &[f64],
        triangles: Option<PyReadonlyArray3<'_, f64>>,
    ) -> Result<Shape, String> {
        let need = |n: usize| {
            (size.len() == n && size.iter().all(|v| v.is_finite() && *v >= 0.0))
                .then_some(())
                .ok_or(format!("a {kind} needs {n} finite sizes ≥ 0, got {size:?}"))
        };
        let primitive = match kind {
            "box" => need(3).map(|_| Primitive::Box(DVec3::from_slice(size)))?,
            "cylinder" => need(2).map(|_| Primitive::Cylinder {
                radius: size[0],
                height: size[1],
            })?,
            "sphere" => need(1).map(|_| Primitive::Sphere(size[0]))?,
            "mesh" => return Shape::mesh(triangles.ok_or("a mesh needs its triangles")?),
            other => return Err(format!("no distance to a part of kind '{other}'")),
        };
        Ok(Shape::Primitive {
            rotation: rotation.map(DVec3::from_array),
            position: DVec3::from_array(position),
            kind: primitive,
        })
    }

    fn mesh(triangles: PyReadonlyArray3<'_, f64>) -> Result<Shape, String> {
        let t = triangles.as_array();
        if t.shape()[1] != 3 || t.shape()[2] != 3 || t.shape()[0] == 0 {
            return Err(format!(
                "triangles must be (F, 3, 3), F > 0, got {:?}",
                t.shape()
            ));
        }
        let vertices: Vec<DVec3> = t
            .outer_iter()
            .flat_map(|tri| {
                let v: Vec<DVec3> = (0..3)
                    .map(|k| DVec3::new(tri[[k, 0]], tri[[k, 1]], tri[[k, 2]]))
                    .collect();
                v
            })
            .collect();
        if !vertices.iter().all(|v| v.is_finite()) {
            return Err("triangles must be finite".into());
        }
        let (lo, hi) = vertices
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        let spec = RigidPartSpec {
            name: "part".into(),
            triangles: (0..vertices.len() as u32 / 3)
                .map(|f| [3 * f, 3 * f + 1, 3 * f + 2])
                .collect(),
            vertices,
            friction_static: 0.0,
            friction_sliding: 0.0,
            motion: None,
            parent: None,
            movable: false,
        };
        let env = RigidEnvironment::build(&[spec])?;
        Ok(Shape::Mesh { env, lo, hi })
    }

    /// Distance of `x` to the part's surface (signed for primitives); for a mesh, `None`
    /// if it is `limit` or more.
    fn distance(&self, x: DVec3, limit: f64) -> Option<f64> {
        match self {
            Shape::Primitive {
                rotation,
                position,
                kind,
            } => {
                let d = x - *position;
                // Rᵀ d: the rows of Rᵀ are R's columns
                let p = DVec3::new(
                    rotation[0].x * d.x + rotation[1].x * d.y + rotation[2].x * d.z,
                    rotation[0].y * d.x + rotation[1].y * d.y + rotation[2].y * d.z,
                    rotation[0].z * d.x + rotation[1].z * d.y + rotation[2].z * d.z,
                );
                Some(match kind {
                    Primitive::Sphere(r) => p.length() - r,
                    Primitive::Box(s) => rectangle_distance(&[
                        p.x.abs() - 0.5 * s.x,
                        p.y.abs() - 0.5 * s.y,
                        p.z.abs() - 0.5 * s.z,
                    ]),
                    Primitive::Cylinder { radius, height } => rectangle_distance(&[
                        (p.x * p.x + p.y * p.y).sqrt() - radius,
                        p.z.abs() - 0.5 * height,
                    ]),
                })
            }
            Shape::Mesh { env, lo, hi } => {
                // the nearest triangle lies within the box bound plus the box's diagonal
                let reach = limit.min(box_distance(x, *lo, *hi) + (*hi - *lo).length());
                env.closest_point(x, reach).map(|(_, _, d)| d)
            }
        }
    }

    /// min over points of (distance − offset); +∞ for no points.
    fn clearance(&self, points: &[DVec3], offsets: &[f64]) -> f64 {
        let Shape::Mesh { lo, hi, .. } = self else {
            return points
                .iter()
                .zip(offsets)
                .filter_map(|(&x, &o)| self.distance(x, f64::INFINITY).map(|d| d - o))
                .fold(f64::INFINITY, f64::min);
        };
        let bound = |i: usize| box_distance(points[i], *lo, *hi) - offsets[i];
        // the point nearest the box first, then only those whose bound beats the best
        let Some(first) = (0..points.len()).min_by(|&i, &j| bound(i).total_cmp(&bound(j))) else {
            return f64::INFINITY;
        };
        let mut best = self
            .distance(points[first], f64::INFINITY)
            .map_or(f64::INFINITY, |d| d - offsets[first]);
        for (i, (&x, &o)) in points.iter().zip(offsets).enumerate() {
            if bound(i) < best {
                if let Some(d) = self.distance(x, best + o) {
                    best = best.min(d - o);
                }
            }
        }
        best
    }
}

/// |max(q, 0)| + min(max_i q_i, 0): the signed distance to a box (or rectangle) whose
/// half-extents were subtracted from the point's absolute coordinates to give q.
fn rectangle_distance(q: &[f64]) -> f64 {
    let outside = q.iter().map(|v| v.max(0.0).powi(2)).sum::<f64>().sqrt();
    let inside = q.iter().copied().fold(f64::NEG_INFINITY, f64::max).min(0.0);
    outside + inside
}

/// Distance from `x` to the box [lo, hi] (0 inside).
fn box_distance(x: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    (lo - x).max(x - hi).max(DVec3::ZERO).length()
}

/// The part's shape and the points (K, 3), from the Python arguments (ValueError if bad).
fn shape_and_points(
    points: &PyReadonlyArray2<'_, f64>,
    kind: &str,
    position: [f64; 3],
    rotation: [[f64; 3]; 3],
    size: &[f64],
    triangles: Option<PyReadonlyArray3<'_, f64>>,
) -> PyResult<(Shape, Vec<DVec3>)> {
    let shape =
        Shape::new(kind, position, rotation, size, triangles).map_err(PyValueError::new_err)?;
    Ok((shape, points_of(points)?))
}

fn points_of(points: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<DVec3>> {
    let p = points.as_array();
    if p.shape()[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "points must be (K, 3), got {:?}",
            p.shape()
        )));
    }
    Ok(p.outer_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// `part_distances(points, kind, position, rotation, size, triangles)`: the distance of
/// each point (K, 3) \[m\] to a part's surface (module doc). `kind` is "box", "cylinder",
/// "sphere" (with `size`: edges; radius and height; radius) or "mesh" (with `triangles`
/// (F, 3, 3) in world coordinates). Raises ValueError for anything else.
#[pyfunction]
#[pyo3(signature = (points, kind, position, rotation, size, triangles=None))]
pub fn part_distances<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    kind: &str,
    position: [f64; 3],
    rotation: [[f64; 3]; 3],
    size: Vec<f64>,
    triangles: Option<PyReadonlyArray3<'py, f64>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (shape, points) = shape_and_points(&points, kind, position, rotation, &size, triangles)?;
    let d: Vec<f64> = points
        .into_iter()
        .map(|x| shape.distance(x, f64::INFINITY).unwrap_or(f64::NAN))
        .collect();
    Ok(d.into_pyarray(py))
}

/// `part_clearance(points, offsets, kind, position, rotation, size, triangles)`: min over
/// the points (K, 3) of (distance to the part − offset) \[m\], exactly, as
/// `part_distances(...) - offsets` would give; +∞ for no points.
#[pyfunction]
#[pyo3(signature = (points, offsets, kind, position, rotation, size, triangles=None))]
#[allow(clippy::too_many_arguments)]
pub fn part_clearance(
    points: PyReadonlyArray2<'_, f64>,
    offsets: PyReadonlyArray1<'_, f64>,
    kind: &str,
    position: [f64; 3],
    rotation: [[f64; 3]; 3],
    size: Vec<f64>,
    triangles: Option<PyReadonlyArray3<'_, f64>>,
) -> PyResult<f64> {
    let (shape, points) = shape_and_points(&points, kind, position, rotation, &size, triangles)?;
    let offsets = offsets.as_slice()?;
    if offsets.len() != points.len() {
        return Err(PyValueError::new_err(format!(
            "{} offsets for {} points",
            offsets.len(),
            points.len()
        )));
    }
    Ok(shape.clearance(&points, offsets))
}
