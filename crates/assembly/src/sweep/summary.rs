//! What a range-of-motion study found: its rows (`motion.csv`), the worst position of
//! each quantity named by the motion coordinate, and the clearance violations.

use super::coordinate::Coordinate;
use super::extremes::{ClosestApproach, MotionExtremes, RadiusAt};
use super::tracker::PER_HOSE;
use serde::Serialize;
use std::fmt;

/// A hose's smallest bend radius in a row \[m\].
pub const BEND_RADIUS: usize = 0;
/// A hose's largest ratio κ·r_min of a beam's curvature to its allowed one in a row.
pub const BEND_RATIO: usize = 1;
/// The minimum bend radius of the beam with that ratio \[m\] (0: not checked).
pub const BEND_LIMIT: usize = 2;
/// A hose's largest twist relative to the routed hose in a row [rad/m].
pub const TWIST: usize = 3;
/// A hose's largest axial force in a row \[N\].
pub const AXIAL_FORCE: usize = 4;

/// The rows of a sweep and what names them.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SweepSummary {
    pub coordinate: Option<Coordinate>,
    pub hose_names: Vec<String>,
    /// Per hose and beam, its minimum bend radius \[m\] (empty: not checked).
    pub allowed_radius: Vec<Vec<f64>>,
    /// The twist limit [rad/m].
    pub twist_limit: f64,
    /// (hose, part) pairs whose clearance is recorded, in row order.
    pub pairs: Vec<(usize, usize)>,
    pub part_names: Vec<String>,
    /// Smallest clearance allowed \[m\], if any.
    pub min_clearance: Option<f64>,
    /// Values per row: time, coordinate, five per hose, one per pair, the fixing
    /// force.
    pub stride: usize,
    /// The rows, flat (not in `report.json`: `motion.csv` holds them).
    #[serde(skip)]
    pub rows: Vec<f64>,
    /// Every hose's centre-line samples at the checked instants, for the swept
    /// envelopes (shared: a summary taken while the sweep goes on does not copy them).
    #[serde(skip)]
    pub swept: Option<std::sync::Arc<super::envelope::SweptHoses>>,
    /// The checked instant the hoses bent furthest past their minimum (the tightest,
    /// when no minimum is checked) and every part's pose then (the identity for a part
    /// that stands still): the envelope picture draws the parts there.
    #[serde(skip)]
    pub worst_bend_poses: Option<PosedInstant>,
}

/// Every part's pose at one instant.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PosedInstant {
    /// When \[s\].
    pub time: f64,
    /// How far past its minimum the worst bend was (κ·r_min; the curvature \[1/m\] when
    /// no minimum is checked): a later instant replaces this one only if it is worse.
    pub severity: f64,
    /// One per part.
    pub poses: Vec<pliant_core::kinematics::Pose>,
}

/// The worst value of one quantity over the sweep and where it was.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Worst {
    /// The quantity ("bend radius", "clearance", …) and whom it concerns.
    pub what: String,
    pub value: f64,
    pub time: f64,
    /// The motion coordinate there (SI).
    pub coordinate: f64,
}

/// A hose that came nearer to a part than the smallest clearance allowed, at its
/// nearest position.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClearanceViolation {
    pub hose: String,
    pub part: String,
    /// The clearance there and the smallest allowed \[m\].
    pub gap: f64,
    pub minimum: f64,
    /// When \[s\], the motion coordinate then (SI) and in words ("door angle 68°").
    pub time: f64,
    pub coordinate: f64,
    pub position: String,
}

impl fmt::Display for ClearanceViolation {
    /// "hose 'h' comes within 3.0 mm of part 'fan' (minimum 10.0 mm) at engine phase 212°
    /// (t = 1.23 s)".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "hose '{}' comes within {:.1} mm of part '{}' (minimum {:.1} mm) at {} (t = {:.2} s)",
            self.hose,
            1e3 * self.gap,
            self.part,
            1e3 * self.minimum,
            self.position,
            self.time
        )
    }
}

impl SweepSummary {
    /// The rows, each [time, coordinate, per hose (radius, bend ratio, its minimum radius,
    /// twist, force), per pair (clearance), fixing force].
    pub fn rows(&self) -> impl Iterator<Item = &[f64]> {
        self.rows.chunks_exact(self.stride.max(1))
    }

    /// Row `row`'s value `k` of hose `hose`: [`BEND_RADIUS`], [`BEND_RATIO`],
    /// [`BEND_LIMIT`], [`TWIST`] or [`AXIAL_FORCE`].
    pub fn hose_value(row: &[f64], hose: usize, k: usize) -> f64 {
        row[2 + PER_HOSE * hose + k]
    }

    /// Row `row`'s clearance of pair `pair` (index into `pairs`) \[m\].
    pub fn pair_value(&self, row: &[f64], pair: usize) -> f64 {
        row[2 + PER_HOSE * self.hose_names.len() + pair]
    }

    /// The row where `key` is least (the first such), if any row.
    fn least(&self, key: impl Fn(&[f64]) -> f64) -> Option<(&[f64], f64)> {
        let (i, v) = self.least_index(key)?;
        Some((self.rows().nth(i)?, v))
    }

    /// The index of the row where `key` is least (the first such) and that value.
    fn least_index(&self, key: impl Fn(&[f64]) -> f64) -> Option<(usize, f64)> {
        self.rows()
            .map(key)
            .enumerate()
            .filter(|(_, v)| !v.is_nan())
            .fold(None, |best, (i, v)| match best {
                Some((_, b)) if b <= v => best,
                _ => Some((i, v)),
            })
    }

    /// The rows [`Self::worst`] and [`Self::extremes`] name: per hose its worst bend, twist
    /// and axial force, per pair its smallest clearance, the largest fixing force — the
    /// rows a thinned series keeps ([`crate::series_cap`]).
    pub fn worst_rows(&self) -> Vec<usize> {
        let mut out = Vec::new();
        for h in 0..self.hose_names.len() {
            out.extend(self.least_index(|r| -Self::hose_value(r, h, BEND_RATIO)));
            out.extend(self.least_index(|r| Self::hose_value(r, h, BEND_RADIUS)));
            out.extend(self.least_index(|r| -Self::hose_value(r, h, TWIST)));
            out.extend(self.least_index(|r| -Self::hose_value(r, h, AXIAL_FORCE)));
        }
        for k in 0..self.pairs.len() {
            out.extend(self.least_index(|r| self.pair_value(r, k)));
        }
        out.extend(self.least_index(|r| -r[self.stride - 1]));
        let mut rows: Vec<usize> = out.into_iter().map(|(i, _)| i).collect();
        rows.sort_unstable();
        rows.dedup();
        rows
    }

    /// The motion coordinate at the recorded instant nearest to `time` (SI).
    pub fn coordinate_at(&self, time: f64) -> Option<f64> {
        self.least(|r| (r[0] - time).abs()).map(|(r, _)| r[1])
    }

    /// "door angle 68°" for the instant nearest to `time`.
    pub fn position_at(&self, time: f64) -> Option<String> {
        let c = self.coordinate.as_ref()?;
        Some(c.describe(self.coordinate_at(time)?))
    }

    /// Hose `h`'s worst bend over the sweep: where a minimum radius is checked, the
    /// row of the beam bent furthest past its own minimum (largest κ·r_min), else the
    /// row of the smallest radius; with that radius \[m\] and its minimum (0: none).
    pub fn worst_bend(&self, h: usize) -> Option<(&[f64], f64, f64)> {
        let checked = self
            .allowed_radius
            .get(h)
            .is_some_and(|a| a.iter().any(|&r| r > 0.0));
        if checked {
            self.least(|r| -Self::hose_value(r, h, BEND_RATIO))
                .map(|(r, ratio)| {
                    let limit = Self::hose_value(r, h, BEND_LIMIT);
                    (r, limit / -ratio, limit)
                })
        } else {
            self.least(|r| Self::hose_value(r, h, BEND_RADIUS))
                .map(|(r, radius)| (r, radius, 0.0))
        }
    }

    /// Per hose its worst bend over the sweep ([`Self::worst_bend`]), per pair its smallest
    /// clearance, and the largest fixing force, each with where it was.
    pub fn worst(&self) -> Vec<Worst> {
        let mut out = Vec::new();
        let mut push = |what: String, found: Option<(&[f64], f64)>, sign: f64| {
            if let Some((r, v)) = found {
                out.push(Worst {
                    what,
                    value: sign * v,
                    time: r[0],
                    coordinate: r[1],
                });
            }
        };
        for (h, name) in self.hose_names.iter().enumerate() {
            push(
                format!("hose '{name}': bend radius"),
                self.worst_bend(h).map(|(r, radius, _)| (r, radius)),
                1.0,
            );
            push(
                format!("hose '{name}': twist"),
                self.least(|r| -Self::hose_value(r, h, TWIST)),
                -1.0,
            );
            push(
                format!("hose '{name}': axial force"),
                self.least(|r| -Self::hose_value(r, h, AXIAL_FORCE)),
                -1.0,
            );
        }
        for (k, &(h, p)) in self.pairs.iter().enumerate() {
            push(
                format!(
                    "hose '{}' to part '{}': clearance",
                    self.hose_names[h], self.part_names[p]
                ),
                self.least(|r| self.pair_value(r, k)),
                1.0,
            );
        }
        push(
            "fixing force".into(),
            self.least(|r| -r[self.stride - 1]),
            -1.0,
        );
        out
    }

    /// Each hose and part that came nearer than the smallest clearance allowed, at its
    /// nearest position.
    pub fn clearance_violations(&self) -> Vec<ClearanceViolation> {
        let (Some(limit), Some(c)) = (self.min_clearance, &self.coordinate) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (k, &(h, p)) in self.pairs.iter().enumerate() {
            if let Some((r, gap)) = self.least(|r| self.pair_value(r, k)) {
                if gap < limit {
                    out.push(ClearanceViolation {
                        hose: self.hose_names[h].clone(),
                        part: self.part_names[p].clone(),
                        gap,
                        minimum: limit,
                        time: r[0],
                        coordinate: r[1],
                        position: c.describe(r[1]),
                    });
                }
            }
        }
        out
    }

    /// Over the motion, each hose's worst bend ([`Self::worst_bend`]) and the smallest
    /// clearance, with where they were; `None` without a coordinate or rows.
    pub fn extremes(&self) -> Option<MotionExtremes> {
        let c = self.coordinate.as_ref()?;
        let (from, to) = self
            .rows()
            .map(|r| r[1])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        if !from.is_finite() {
            return None;
        }
        let mut bend_radii = Vec::new();
        for (h, name) in self.hose_names.iter().enumerate() {
            if let Some((r, radius, allowed)) = self.worst_bend(h) {
                if radius.is_finite() {
                    bend_radii.push(RadiusAt {
                        hose: name.clone(),
                        radius,
                        allowed,
                        coordinate: r[1],
                    });
                }
            }
        }
        let clearance = (0..self.pairs.len())
            .filter_map(|k| {
                self.least(|r| self.pair_value(r, k))
                    .map(|(r, g)| (r, g, k))
            })
            .fold(None, |best: Option<(&[f64], f64, usize)>, x| match best {
                Some(b) if b.1 <= x.1 => Some(b),
                _ => Some(x),
            })
            .map(|(r, gap, k)| {
                let (h, p) = self.pairs[k];
                ClosestApproach {
                    hose: self.hose_names[h].clone(),
                    part: self.part_names[p].clone(),
                    gap,
                    coordinate: r[1],
                }
            });
        Some(MotionExtremes {
            coordinate: c.clone(),
            from,
            to,
            bend_radii,
            clearance,
        })
    }

    /// `motion.csv`: one row per checked instant (SI, angles in degrees as the scene
    /// writes them): time, the coordinate, per hose its smallest bend radius, the largest
    /// ratio of a beam's minimum radius to its radius (above 1 breaks it; empty when not
    /// checked), its largest twist and axial force, per hose and part
    /// the clearance, the largest fixing force.
    pub fn csv(&self) -> String {
        let Some(c) = &self.coordinate else {
            return String::new();
        };
        let clean = |s: &str| s.replace([',', '\n', '"'], ";");
        let mut head = vec!["time_s".to_string(), c.column()];
        for name in &self.hose_names {
            let n = clean(name);
            head.extend([
                format!("{n}: min_bend_radius_m"),
                format!("{n}: bend_radius_ratio"),
                format!("{n}: max_twist_deg_m"),
                format!("{n}: max_axial_force_n"),
            ]);
        }
        for &(h, p) in &self.pairs {
            head.push(format!(
                "clearance_m {} to {}",
                clean(&self.hose_names[h]),
                clean(&self.part_names[p])
            ));
        }
        head.push("max_fixing_force_n".into());
        let mut out = head.join(",");
        out.push('\n');
        let factor = c.kind.unit().1;
        for r in self.rows() {
            let mut cells = vec![format!("{:.6}", r[0]), format!("{:.6}", r[1] * factor)];
            for h in 0..self.hose_names.len() {
                cells.push(format!("{:.6e}", Self::hose_value(r, h, BEND_RADIUS)));
                cells.push(if Self::hose_value(r, h, BEND_LIMIT) > 0.0 {
                    format!("{:.6e}", Self::hose_value(r, h, BEND_RATIO))
                } else {
                    String::new()
                });
                cells.push(format!(
                    "{:.6e}",
                    Self::hose_value(r, h, TWIST).to_degrees()
                ));
                cells.push(format!("{:.6e}", Self::hose_value(r, h, AXIAL_FORCE)));
            }
            for k in 0..self.pairs.len() {
                cells.push(format!("{:.6e}", self.pair_value(r, k)));
            }
            cells.push(format!("{:.6e}", r[self.stride - 1]));
            out.push_str(&cells.join(","));
            out.push('\n');
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::CoordinateKind;

    /// One hose, two beams: the first may bend to 0.1 m, the second (a protected
    /// stretch) only to 0.3 m. Row 1 bends the first beam to 0.2 m (ratio 0.5), row 2
    /// the second to 0.25 m (ratio 1.2) while the first is at 0.5 m.
    fn two_rows() -> SweepSummary {
        let row = |t: f64, angle: f64, radius: f64, ratio: f64, limit: f64| {
            vec![t, angle, radius, ratio, limit, 0.0, 0.0, 1.0]
        };
        SweepSummary {
            coordinate: Some(Coordinate {
                part: 0,
                part_name: "door".into(),
                kind: CoordinateKind::Angle,
            }),
            hose_names: vec!["h".into()],
            allowed_radius: vec![vec![0.1, 0.3]],
            stride: 2 + PER_HOSE + 1,
            rows: [row(0.0, 0.1, 0.2, 0.5, 0.1), row(1.0, 0.2, 0.25, 1.2, 0.3)].concat(),
            ..Default::default()
        }
    }

    #[test]
    fn the_worst_bend_is_the_one_furthest_past_its_own_minimum_not_the_tightest() {
        let s = two_rows();
        let (row, radius, limit) = s.worst_bend(0).unwrap();
        assert_eq!(row[0], 1.0);
        assert!(
            (radius - 0.25).abs() < 1e-15 && limit == 0.3,
            "{radius} {limit}"
        );
        let line = s.extremes().unwrap().to_string();
        assert!(line.contains("bend radius 250 mm < 300 mm at"), "{line}");
        let csv = s.csv();
        let cells: Vec<&str> = csv.lines().nth(2).unwrap().split(',').collect();
        assert_eq!(cells[3], "1.200000e0", "{csv}");
    }

    #[test]
    fn the_rows_a_thinned_sweep_keeps_are_its_worst() {
        let s = two_rows();
        // row 0: the smallest radius and the largest fixing force (the first of equals);
        // row 1: the largest bend ratio
        assert_eq!(s.worst_rows(), vec![0, 1]);
    }

    #[test]
    fn an_unchecked_hose_reports_its_smallest_radius() {
        let mut s = two_rows();
        s.allowed_radius = vec![Vec::new()];
        let (row, radius, limit) = s.worst_bend(0).unwrap();
        assert_eq!((row[0], radius, limit), (0.0, 0.2, 0.0));
    }
}
