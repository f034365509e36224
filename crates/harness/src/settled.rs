//! The settled route of a harness: what Pliant computed, handed to the exporters
//! (`export.rs` for KBL, `step.rs` for STEP).
//!
//! For each segment, by its KBL id, the centre line as a polyline of points in metres:
//! the first point at the segment's start node, the last at its end node (the route
//! Pliant settled, e.g. a hose's node positions). Kept in id order, so every export of
//! the same route writes the same file.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::geometry::SegmentCurve;
use crate::model::Harness;

/// Points closer than this \[m\] to the point before them are dropped (10⁻⁹ m: below the
/// 10⁻⁶ mm the files are written with, such points would coincide).
pub const DUPLICATE_M: f64 = 1e-9;

/// Each segment's settled centre line, by KBL segment id.
#[derive(Debug, Clone, Default)]
pub struct SettledHarness {
    segments: BTreeMap<String, Vec<DVec3>>,
}

impl SettledHarness {
    pub fn new() -> Self {
        Self::default()
    }

    /// Set the centre line of segment `kbl_id` (points in metres, start node to end node).
    pub fn insert(&mut self, kbl_id: impl Into<String>, points: Vec<DVec3>) {
        self.segments.insert(kbl_id.into(), points);
    }

    pub fn get(&self, kbl_id: &str) -> Option<&[DVec3]> {
        self.segments.get(kbl_id).map(Vec::as_slice)
    }

    /// (KBL id, points) in id order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &[DVec3])> {
        self.segments
            .iter()
            .map(|(k, v)| (k.as_str(), v.as_slice()))
    }

    pub fn len(&self) -> usize {
        self.segments.len()
    }

    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// The harness as imported, each segment's (trimmed) centre curve sampled about every
    /// `spacing` metres (at least 2 points): the "route" before Pliant moved anything.
    pub fn from_harness(h: &Harness, spacing: f64) -> Self {
        let mut out = Self::new();
        for s in &h.segments {
            let c = SegmentCurve::of(h, s);
            let count = if spacing > 0.0 && spacing.is_finite() {
                ((c.length / spacing).ceil() as usize + 1).max(2)
            } else {
                2
            };
            out.insert(s.kbl_id.clone(), c.sample(count));
        }
        out
    }

    /// Check every polyline: at least two points, all finite. `Err((kbl_id, reason))`.
    pub fn check(&self) -> Result<(), (String, String)> {
        for (id, pts) in self.iter() {
            if let Some(i) = pts.iter().position(|p| !p.is_finite()) {
                return Err((id.to_string(), format!("point {i} is not finite")));
            }
            if clean(pts).len() < 2 {
                return Err((
                    id.to_string(),
                    format!(
                        "needs at least two distinct points, has {} ({} distinct)",
                        pts.len(),
                        clean(pts).len()
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The polyline without points that repeat the one before them (within [`DUPLICATE_M`]).
pub fn clean(points: &[DVec3]) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = Vec::with_capacity(points.len());
    for &p in points {
        if out.last().is_none_or(|q| q.distance(p) > DUPLICATE_M) {
            out.push(p);
        }
    }
    out
}

/// Length of a polyline \[m\].
pub fn polyline_length(points: &[DVec3]) -> f64 {
    points.windows(2).map(|w| w[0].distance(w[1])).sum()
}

/// Distance from `p` to the nearest point of the polyline \[m\].
pub fn distance_to_polyline(points: &[DVec3], p: DVec3) -> f64 {
    match points {
        [] => f64::INFINITY,
        [q] => q.distance(p),
        _ => points
            .windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                let l2 = d.length_squared();
                let t = if l2 > 0.0 {
                    ((p - w[0]).dot(d) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (w[0] + d * t).distance(p)
            })
            .fold(f64::INFINITY, f64::min),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polyline_helpers() {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::X, DVec3::new(1.0, 1.0, 0.0)];
        assert_eq!(clean(&p).len(), 3);
        assert!((polyline_length(&p) - 2.0).abs() < 1e-15);
        assert!((distance_to_polyline(&p, DVec3::new(0.5, -0.25, 0.0)) - 0.25).abs() < 1e-15);
        assert!((distance_to_polyline(&p, DVec3::new(2.0, 0.5, 0.0)) - 1.0).abs() < 1e-15);
    }

    #[test]
    fn check_names_the_bad_segment() {
        let mut s = SettledHarness::new();
        s.insert("Segment_1", vec![DVec3::ZERO, DVec3::X]);
        assert!(s.check().is_ok());
        s.insert("Segment_2", vec![DVec3::ZERO, DVec3::ZERO]);
        let (id, why) = s.check().unwrap_err();
        assert_eq!(id, "Segment_2");
        assert!(why.contains("two distinct"), "{why}");
        s.insert(
            "Segment_2",
            vec![DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)],
        );
        assert!(s.check().unwrap_err().1.contains("not finite"));
    }
}
