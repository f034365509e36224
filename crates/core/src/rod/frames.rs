//! Material frames of a hose's nodes in its rest shape (SPEC M1): the local x axis is the
//! tangent, the cross-section axes are carried along by parallel transport so that the
//! rest shape has no spurious twist.

use crate::math::rotation_between;
use glam::{DQuat, DVec3};

/// Unit tangent at each node: the chord direction at the ends, the normalised mean of the
/// two adjacent chord directions inside.
pub fn node_tangents(nodes: &[DVec3]) -> Vec<DVec3> {
    let n = nodes.len();
    (0..n)
        .map(|i| {
            let back = if i > 0 {
                (nodes[i] - nodes[i - 1]).normalize()
            } else {
                DVec3::ZERO
            };
            let fwd = if i + 1 < n {
                (nodes[i + 1] - nodes[i]).normalize()
            } else {
                DVec3::ZERO
            };
            let t = back + fwd;
            if t.length_squared() > 1e-24 {
                t.normalize()
            } else {
                // a full reversal: fall back on the incoming chord
                back
            }
        })
        .collect()
}

/// Unit tangents of the curve through `nodes`: [`node_tangents`] inside, and at each end
/// the end chord turned back by half the turn to the next chord — exact on a circular
/// arc, second order on any smooth curve, where the end chord is first order off.
pub fn curve_tangents(nodes: &[DVec3]) -> Vec<DVec3> {
    let mut t = node_tangents(nodes);
    let n = nodes.len();
    if n >= 3 {
        let chord = |i: usize| (nodes[i + 1] - nodes[i]).normalize();
        let half_back =
            |from: DVec3, to: DVec3| DQuat::IDENTITY.slerp(rotation_between(from, to), 0.5);
        t[0] = (half_back(chord(1), chord(0)) * chord(0)).normalize();
        t[n - 1] = (half_back(chord(n - 3), chord(n - 2)) * chord(n - 2)).normalize();
    }
    t
}

/// Node frames (local → global) by parallel transport along the tangents. The first
/// frame's local y axis is `normal_hint` projected normal to the tangent when given and
/// not parallel to it; otherwise the shortest rotation of the global x axis onto the
/// first tangent fixes it.
pub fn node_frames(nodes: &[DVec3], normal_hint: Option<DVec3>) -> Vec<DQuat> {
    frames_along(&node_tangents(nodes), normal_hint)
}

/// [`node_frames`] along [`curve_tangents`]: frames whose ends follow the curve, as a
/// hose whose rest shape is another needs (its end elements' bend is then the curve's,
/// not half of it).
pub fn curve_frames(nodes: &[DVec3], normal_hint: Option<DVec3>) -> Vec<DQuat> {
    frames_along(&curve_tangents(nodes), normal_hint)
}

/// Frames by parallel transport along `tangents` (see [`node_frames`]).
fn frames_along(tangents: &[DVec3], normal_hint: Option<DVec3>) -> Vec<DQuat> {
    let mut frames = Vec::with_capacity(tangents.len());
    let t0 = tangents[0];
    let mut q = rotation_between(DVec3::X, t0);
    if let Some(hint) = normal_hint {
        let y = hint - t0 * hint.dot(t0);
        if y.length_squared() > 1e-12 * hint.length_squared().max(1e-300) {
            let y = y.normalize();
            let z = t0.cross(y);
            q = DQuat::from_mat3(&glam::DMat3::from_cols(t0, y, z)).normalize();
        }
    }
    frames.push(q);
    for i in 1..tangents.len() {
        q = (rotation_between(tangents[i - 1], tangents[i]) * q).normalize();
        frames.push(q);
    }
    frames
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On nodes of a circular arc, the curve's tangents at the ends are exact, where the
    /// end chords are half an element's turn off.
    #[test]
    fn curve_tangents_are_exact_on_an_arc() {
        let (r, step) = (0.3, 0.1);
        let nodes: Vec<DVec3> = (0..=6)
            .map(|i| {
                let a = i as f64 * step;
                DVec3::new(r * a.sin(), r * (1.0 - a.cos()), 0.0)
            })
            .collect();
        let exact = |a: f64| DVec3::new(a.cos(), a.sin(), 0.0);
        let t = curve_tangents(&nodes);
        assert!((t[0] - exact(0.0)).length() < 1e-12, "{}", t[0]);
        assert!((t[6] - exact(0.6)).length() < 1e-12, "{}", t[6]);
        let chord_end = node_tangents(&nodes)[0];
        assert!((chord_end.angle_between(exact(0.0)) - 0.5 * step).abs() < 1e-12);
    }

    #[test]
    fn frames_follow_tangent_of_an_arc() {
        let nodes: Vec<DVec3> = (0..=8)
            .map(|i| {
                let a = i as f64 * std::f64::consts::FRAC_PI_2 / 8.0;
                DVec3::new(a.sin(), 1.0 - a.cos(), 0.0)
            })
            .collect();
        let frames = node_frames(&nodes, Some(DVec3::Z));
        let tangents = node_tangents(&nodes);
        for (q, t) in frames.iter().zip(&tangents) {
            assert!((*q * DVec3::X - *t).length() < 1e-12);
            // planar curve: the binormal stays the global y? no — local y stays z (hint)
            assert!((*q * DVec3::Y - DVec3::Z).length() < 1e-12);
        }
    }
}
