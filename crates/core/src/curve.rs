//! Uniform Catmull-Rom splines through points (Catmull & Rom 1974), sampled into a dense
//! polyline — used to move a hand smoothly through waypoints.

use glam::DVec3;

/// Samples the Catmull-Rom spline through `points` (end tangents: the end chords) with
/// `per_segment` samples per span; the result starts and ends at the first and last point.
pub fn catmull_rom(points: &[DVec3], per_segment: usize) -> Vec<DVec3> {
    if points.len() < 3 || per_segment < 2 {
        return points.to_vec();
    }
    let n = points.len();
    let mut out = Vec::with_capacity((n - 1) * per_segment + 1);
    for i in 0..n - 1 {
        let (p1, p2) = (points[i], points[i + 1]);
        let p0 = if i > 0 { points[i - 1] } else { p1 - (p2 - p1) };
        let p3 = if i + 2 < n {
            points[i + 2]
        } else {
            p2 + (p2 - p1)
        };
        for k in 0..per_segment {
            let t = k as f64 / per_segment as f64;
            let (t2, t3) = (t * t, t * t * t);
            out.push(
                0.5 * ((2.0 * p1)
                    + (p2 - p0) * t
                    + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
                    + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3),
            );
        }
    }
    out.push(points[n - 1]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_every_point_and_keeps_straight_lines_straight() {
        let pts = [
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.5),
            DVec3::new(3.0, 0.0, 0.0),
        ];
        let c = catmull_rom(&pts, 8);
        for (i, p) in pts.iter().enumerate() {
            assert!((c[i * 8] - *p).length() < 1e-15);
        }
        let line = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        for p in catmull_rom(&line, 5) {
            assert!(p.y.abs() < 1e-15 && p.z.abs() < 1e-15);
        }
    }
}
