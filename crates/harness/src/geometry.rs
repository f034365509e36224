//! A segment's centre line: its B-spline chain, trimmed to the part between its nodes.
//!
//! Most KBL centre curves start on the start node and end on the end node. Segments made
//! by splitting a longer one ("Split" in their `Id`) may keep the whole original curve,
//! which runs past their nodes; those are trimmed to the parameter interval between the
//! curve points closest to the start and end nodes.

use glam::DVec3;

use crate::bspline::{BSpline, Chain};
use crate::model::{Harness, Segment};

/// Distance \[m\] within which a curve end counts as lying on its node (10⁻³ mm).
pub const END_TOLERANCE_M: f64 = 1e-6;

/// The centre line of one segment.
#[derive(Debug, Clone)]
pub struct SegmentCurve {
    pub chain: Chain,
    /// Chain parameter at the start node and at the end node (u_end < u_start when the
    /// curve runs from the end node to the start node).
    pub u_start: f64,
    pub u_end: f64,
    /// Whether the chain was cut short of its own ends.
    pub trimmed: bool,
    /// Whether the segment had no centre curve (a straight line is used).
    pub straight_fallback: bool,
    /// Distance \[m\] of the trimmed curve's first and last point from the nodes.
    pub start_error: f64,
    pub end_error: f64,
    /// Arc length \[m\] between u_start and u_end.
    pub length: f64,
}

impl SegmentCurve {
    /// Build, orient and trim the centre line of `seg`.
    pub fn of(h: &Harness, seg: &Segment) -> SegmentCurve {
        let a = h.nodes[seg.start_node].position;
        let b = h.nodes[seg.end_node].position;
        let splines: Vec<BSpline> = seg
            .curves
            .iter()
            .filter_map(|c| BSpline::new(c.degree, c.control_points.clone()))
            .collect();
        let Some(chain) = Chain::new(splines) else {
            let chain = Chain::line(a, b);
            return SegmentCurve {
                length: a.distance(b),
                chain,
                u_start: 0.0,
                u_end: 1.0,
                trimmed: false,
                straight_fallback: true,
                start_error: 0.0,
                end_error: 0.0,
            };
        };
        let (lo, hi) = chain.range();
        let (p_lo, p_hi) = (chain.point(lo), chain.point(hi));
        let (u_start, u_end, trimmed) =
            if p_lo.distance(a) <= END_TOLERANCE_M && p_hi.distance(b) <= END_TOLERANCE_M {
                (lo, hi, false)
            } else if p_lo.distance(b) <= END_TOLERANCE_M && p_hi.distance(a) <= END_TOLERANCE_M {
                (hi, lo, false)
            } else {
                let (us, _) = chain.closest(a);
                let (ue, _) = chain.closest(b);
                (
                    us,
                    ue,
                    !(us.min(ue) <= lo + 1e-12 && us.max(ue) >= hi - 1e-12),
                )
            };
        let length = chain.arc_length(u_start, u_end);
        SegmentCurve {
            start_error: chain.point(u_start).distance(a),
            end_error: chain.point(u_end).distance(b),
            chain,
            u_start,
            u_end,
            trimmed,
            straight_fallback: false,
            length,
        }
    }

    /// `count` ≥ 2 points at equal arc-length spacing from the start node to the end node.
    pub fn sample(&self, count: usize) -> Vec<DVec3> {
        self.chain.sample(self.u_start, self.u_end, count)
    }

    /// Point and unit tangent (pointing from start to end node) at the arc-length fraction f.
    pub fn at_fraction(&self, f: f64) -> (DVec3, DVec3) {
        let u = self.chain.param_at_fraction(self.u_start, self.u_end, f);
        let mut t = self.chain.tangent(u);
        if self.u_end < self.u_start {
            t = -t;
        }
        (self.chain.point(u), t)
    }
}
