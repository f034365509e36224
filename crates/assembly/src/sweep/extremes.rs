//! The extremes of a range-of-motion study, for the verdict and the report: over the
//! motion, each hose's worst bend and the smallest clearance, each with the
//! motion coordinate where it was.

use super::coordinate::Coordinate;
use serde::Serialize;
use std::fmt;

/// A hose's worst bend over the motion — the beam furthest past its own minimum radius —
/// its radius and that minimum \[m\], at `coordinate` (SI).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RadiusAt {
    pub hose: String,
    pub radius: f64,
    pub allowed: f64,
    pub coordinate: f64,
}

/// The smallest clearance between a hose and a part over the motion \[m\], at
/// `coordinate` (SI).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ClosestApproach {
    pub hose: String,
    pub part: String,
    pub gap: f64,
    pub coordinate: f64,
}

/// Over the motion of `coordinate`'s part, from `from` to `to` (SI): each hose's worst
/// bend and the smallest clearance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MotionExtremes {
    pub coordinate: Coordinate,
    pub from: f64,
    pub to: f64,
    pub bend_radii: Vec<RadiusAt>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clearance: Option<ClosestApproach>,
}

impl fmt::Display for MotionExtremes {
    /// "over the motion of part 'door' (angle 0° … 70°): hose 'h' bend radius 80 mm ≥ 60 mm
    /// at door angle 70°; smallest clearance 12.0 mm, hose 'h' to part 'pillar', at door
    /// angle 35°".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = &self.coordinate;
        let (unit, factor) = c.kind.unit();
        let unit = if unit == "deg" { "°" } else { unit };
        write!(
            f,
            "over the motion of part '{}' ({} {:.0}{} … {:.0}{}): ",
            c.part_name,
            c.kind.name(),
            self.from * factor,
            if unit == "°" { "°" } else { "" },
            self.to * factor,
            unit,
        )?;
        let mut separator = "";
        for r in &self.bend_radii {
            let relation = if r.radius < r.allowed { "<" } else { "≥" };
            write!(
                f,
                "{separator}hose '{}' bend radius {:.0} mm {relation} {:.0} mm at {}",
                r.hose,
                1e3 * r.radius,
                1e3 * r.allowed,
                c.describe(r.coordinate)
            )?;
            separator = "; ";
        }
        if let Some(a) = &self.clearance {
            write!(
                f,
                "{separator}smallest clearance {:.1} mm, hose '{}' to part '{}', at {}",
                1e3 * a.gap,
                a.hose,
                a.part,
                c.describe(a.coordinate)
            )?;
        }
        Ok(())
    }
}
