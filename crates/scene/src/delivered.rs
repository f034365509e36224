//! A hose's delivered shape (SPEC X2, pre-deformation): the stress-free shape of a hose
//! delivered as straight stock, coiled or folded, discretised with the routed hose's
//! node count at equal arc length over the routed hose's length.

use crate::centerline::Centerline;
use crate::error::FieldError;
use crate::format::DeliveredEntry;
use crate::hoses::segment;
use crate::units::LengthUnit;
use crate::validate::with_unit;
use crate::validate::{non_negative, positive};
use glam::DVec3;

/// Largest turn of the delivered shape over one element \[rad\]: 22.5°, the routed
/// centre line's rule (≥ 4 elements per quarter circle).
const MAX_TURN_PER_ELEMENT: f64 = std::f64::consts::PI / 8.0;

/// The nodes (m) of the delivered shape `entry` of a hose `length` long (m) with
/// `elements` elements; `field` names `hoses[i].delivered` in errors.
pub fn delivered_nodes(
    field: &str,
    entry: &DeliveredEntry,
    unit: LengthUnit,
    length: f64,
    elements: usize,
) -> Result<Vec<DVec3>, FieldError> {
    let u = unit.symbol();
    let scale = unit.to_metres();
    let at = |i: usize| i as f64 / elements as f64;
    let in_unit = |metres: f64| with_unit((metres / scale * 1e3).round() / 1e3, u);
    let nodes: Vec<DVec3> = match entry {
        DeliveredEntry::Named(_) => (0..=elements)
            .map(|i| DVec3::X * (length * at(i)))
            .collect(),
        DeliveredEntry::Coil { coil } => {
            let radius = positive(&format!("{field}.coil.radius"), coil.radius, u)? * scale;
            let pitch = non_negative(&format!("{field}.coil.pitch"), coil.pitch, u)? * scale;
            // the helix (R cos t, R sin t, c t), c = pitch/2π, has arc length √(R² + c²) t
            let rise = pitch / std::f64::consts::TAU;
            let turn = length / radius.hypot(rise);
            (0..=elements)
                .map(|i| {
                    let t = turn * at(i);
                    DVec3::new(radius * t.cos(), radius * t.sin(), rise * t)
                })
                .collect()
        }
        DeliveredEntry::Path { path } => {
            let segments = path
                .iter()
                .enumerate()
                .map(|(k, s)| segment(&format!("{field}.path[{k}]"), s, unit))
                .collect::<Result<Vec<_>, _>>()?;
            let curve = Centerline::new(DVec3::ZERO, &segments)
                .map_err(|e| FieldError::about(format!("{field}.path[{}]", e.segment), e.reason))?;
            let delivered = curve.length();
            if (delivered - length).abs() > 0.01 * length {
                return Err(FieldError::new(
                    format!("{field}.path"),
                    format!("a centre line of {}", in_unit(delivered)),
                    format!(
                        "the delivered hose is the routed one, {} long: the lengths must \
                         agree within 1 %",
                        in_unit(length)
                    ),
                ));
            }
            let stretch = length / delivered;
            curve
                .discretise(elements)
                .into_iter()
                .map(|p| p * stretch)
                .collect()
        }
    };
    if let Some((k, turn)) = sharpest_turn(&nodes) {
        if turn > MAX_TURN_PER_ELEMENT {
            return Err(FieldError::about(
                field.to_string(),
                format!(
                    "turns by {:.1}° between elements {} and {}: at most {:.1}° per element \
                     (give the hose more elements)",
                    turn.to_degrees(),
                    k,
                    k + 1,
                    MAX_TURN_PER_ELEMENT.to_degrees()
                ),
            ));
        }
    }
    Ok(nodes)
}

/// The largest angle between consecutive chords of `nodes` and the element before it.
fn sharpest_turn(nodes: &[DVec3]) -> Option<(usize, f64)> {
    nodes
        .windows(3)
        .enumerate()
        .map(|(k, w)| (k, (w[1] - w[0]).angle_between(w[2] - w[1])))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::CoilEntry;

    /// A coil's nodes lie on its helix at equal arc length: every chord is the helix's
    /// chord over the same parameter step, and the polyline is as long as the hose to
    /// the chords' (κ l)²/24.
    #[test]
    fn a_coil_is_the_helix_at_equal_arc_length() {
        let entry = DeliveredEntry::Coil {
            coil: CoilEntry {
                radius: 100.0,
                pitch: 30.0,
            },
        };
        let (length, n) = (1.0, 64);
        let nodes = delivered_nodes("d", &entry, LengthUnit::Millimetre, length, n).unwrap();
        assert_eq!(nodes.len(), n + 1);
        let chords: Vec<f64> = nodes.windows(2).map(|w| (w[1] - w[0]).length()).collect();
        for c in &chords {
            assert!((c - chords[0]).abs() < 1e-12, "{c} vs {}", chords[0]);
        }
        for p in &nodes {
            assert!((p.x.hypot(p.y) - 0.1).abs() < 1e-12);
        }
        let (r, rise) = (0.1, 0.03 / std::f64::consts::TAU);
        let kappa = r / (r * r + rise * rise);
        let l = length / n as f64;
        let total: f64 = chords.iter().sum();
        let want = length * (1.0 - (kappa * l).powi(2) / 24.0);
        assert!((total - want).abs() < 1e-6 * length, "{total} vs {want}");
    }

    /// A path whose length is 2 % off the hose's is refused with both lengths; a coil too
    /// tight for the elements names the turn.
    #[test]
    fn bad_shapes_are_refused() {
        let tight = DeliveredEntry::Coil {
            coil: CoilEntry {
                radius: 10.0,
                pitch: 0.0,
            },
        };
        let err = delivered_nodes(
            "hoses[0].delivered",
            &tight,
            LengthUnit::Millimetre,
            1.0,
            10,
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("hoses[0].delivered") && err.contains("per element"),
            "{err}"
        );
    }
}
