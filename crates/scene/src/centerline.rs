//! Centre lines (SPEC M1): a composite curve of straight lines, circular arcs through
//! three points and uniform Catmull-Rom splines, measured by arc length and discretised
//! into nodes at equal arc-length spacing. Pure geometry in any consistent length unit.

use glam::DVec3;
use std::f64::consts::PI;

/// Most elements one hose may have; more is refused rather than allocated.
pub const MAX_ELEMENTS: usize = 100_000;

/// Relative tolerance below which two points count as the same point.
const COINCIDENT_TOL: f64 = 1e-12;
/// Below this sine of the angle between the chords an arc's points count as collinear.
const COLLINEAR_TOL: f64 = 1e-9;
/// Sub-intervals per spline span for the arc-length table.
const SPLINE_SUBDIVISIONS: usize = 16;
/// 8-point Gauss–Legendre abscissae on [−1, 1] (positive half).
const GL_X: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// 8-point Gauss–Legendre weights matching [`GL_X`].
const GL_W: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// One segment of a centre line; each starts where the previous one ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Segment {
    /// Straight line to `to`.
    Line { to: DVec3 },
    /// Circular arc from the current point through `via` to `to`.
    Arc { via: DVec3, to: DVec3 },
    /// Uniform Catmull-Rom spline from the current point through `through` to `to`.
    /// Its start tangent continues the previous segment (if any); its end tangent is the
    /// last chord.
    Spline { through: Vec<DVec3>, to: DVec3 },
}

/// Why a centre line cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveError {
    /// Index of the offending segment.
    pub segment: usize,
    /// The offending part of the segment relative to it, e.g. `arc.via` or `line.to`.
    pub part: String,
    /// What is wrong.
    pub reason: String,
}

/// How the element count is requested.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Resolution {
    /// Exactly this many elements (raised if arcs need more).
    Elements(usize),
    /// Elements of about this length (rounded up to a whole number of elements).
    ElementLength(f64),
}

/// Outcome of [`element_count`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ElementCount {
    /// Count from the request alone.
    pub requested: usize,
    /// Count actually used (≥ `requested`).
    pub count: usize,
    /// Whether arcs forced more elements than requested.
    pub raised_for_arcs: bool,
}

/// A cubic Hermite span with its cumulative arc-length table.
#[derive(Clone, Debug)]
struct Hermite {
    p0: DVec3,
    p1: DVec3,
    m0: DVec3,
    m1: DVec3,
    /// Arc length from t = 0 to t = k / SPLINE_SUBDIVISIONS, k = 0..=SPLINE_SUBDIVISIONS.
    table: Vec<f64>,
}

/// A piece of the curve with exact or tabulated arc length.
#[derive(Clone, Debug)]
enum Piece {
    Line {
        a: DVec3,
        b: DVec3,
        length: f64,
    },
    Arc {
        center: DVec3,
        radius: f64,
        e1: DVec3,
        e2: DVec3,
        sweep: f64,
    },
    Spline(Hermite),
}

/// A composite centre line parametrised by arc length.
#[derive(Clone, Debug)]
pub struct Centerline {
    start: DVec3,
    end: DVec3,
    pieces: Vec<Piece>,
    /// Arc length at the start of each piece, plus the total at the end.
    offsets: Vec<f64>,
}

impl Hermite {
    fn point(&self, t: f64) -> DVec3 {
        let (t2, t3) = (t * t, t * t * t);
        self.p0 * (2.0 * t3 - 3.0 * t2 + 1.0)
            + self.m0 * (t3 - 2.0 * t2 + t)
            + self.p1 * (-2.0 * t3 + 3.0 * t2)
            + self.m1 * (t3 - t2)
    }

    fn derivative(&self, t: f64) -> DVec3 {
        let t2 = t * t;
        self.p0 * (6.0 * t2 - 6.0 * t)
            + self.m0 * (3.0 * t2 - 4.0 * t + 1.0)
            + self.p1 * (-6.0 * t2 + 6.0 * t)
            + self.m1 * (3.0 * t2 - 2.0 * t)
    }

    /// Arc length between parameters a and b by 8-point Gauss–Legendre.
    fn length_between(&self, a: f64, b: f64) -> f64 {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        GL_X.iter()
            .zip(GL_W)
            .map(|(x, w)| {
                w * (self.derivative(mid - half * x).length()
                    + self.derivative(mid + half * x).length())
            })
            .sum::<f64>()
            * half
    }

    fn new(p0: DVec3, p1: DVec3, m0: DVec3, m1: DVec3) -> Self {
        let mut h = Hermite {
            p0,
            p1,
            m0,
            m1,
            table: vec![0.0],
        };
        let step = 1.0 / SPLINE_SUBDIVISIONS as f64;
        let mut acc = 0.0;
        for k in 0..SPLINE_SUBDIVISIONS {
            acc += h.length_between(k as f64 * step, (k + 1) as f64 * step);
            h.table.push(acc);
        }
        h
    }

    fn length(&self) -> f64 {
        self.table[SPLINE_SUBDIVISIONS]
    }

    /// Parameter t at arc length s from the span's start (safeguarded Newton).
    fn parameter_at(&self, s: f64) -> f64 {
        let k = self
            .table
            .partition_point(|&v| v <= s)
            .clamp(1, SPLINE_SUBDIVISIONS)
            - 1;
        let step = 1.0 / SPLINE_SUBDIVISIONS as f64;
        let (mut lo, mut hi) = (k as f64 * step, (k + 1) as f64 * step);
        let (s_lo, s_hi) = (self.table[k], self.table[k + 1]);
        let base = lo;
        let mut t = if s_hi > s_lo {
            lo + (hi - lo) * (s - s_lo) / (s_hi - s_lo)
        } else {
            lo
        };
        for _ in 0..60 {
            let f = s_lo + self.length_between(base, t) - s;
            if f.abs() <= 1e-15 * (1.0 + s.abs()) {
                break;
            }
            if f > 0.0 {
                hi = t;
            } else {
                lo = t;
            }
            let d = self.derivative(t).length();
            let newton = if d > 0.0 { t - f / d } else { f64::NAN };
            t = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if hi - lo <= 1e-16 {
                break;
            }
        }
        t
    }
}

impl Piece {
    fn length(&self) -> f64 {
        match self {
            Piece::Line { length, .. } => *length,
            Piece::Arc { radius, sweep, .. } => radius * sweep,
            Piece::Spline(h) => h.length(),
        }
    }

    /// Point at arc length s ∈ [0, length] from the piece's start.
    fn point_at(&self, s: f64) -> DVec3 {
        match self {
            Piece::Line { a, b, length } => a.lerp(*b, s / length),
            Piece::Arc {
                center,
                radius,
                e1,
                e2,
                ..
            } => {
                let phi = s / radius;
                *center + (*e1 * phi.cos() + *e2 * phi.sin()) * *radius
            }
            Piece::Spline(h) => h.point(h.parameter_at(s)),
        }
    }

    /// Unit tangent at the piece's end.
    fn end_tangent(&self) -> DVec3 {
        match self {
            Piece::Line { a, b, .. } => (*b - *a).normalize(),
            Piece::Arc { e1, e2, sweep, .. } => *e2 * sweep.cos() - *e1 * sweep.sin(),
            Piece::Spline(h) => h.derivative(1.0).normalize_or_zero(),
        }
    }
}

/// Circle through three points: centre, radius, in-plane basis (e1 towards `a`) and the
/// angle swept from `a` through `b` to `c`. `None` if the points are collinear.
fn circle_through(a: DVec3, b: DVec3, c: DVec3) -> Option<(DVec3, f64, DVec3, DVec3, f64)> {
    let (u, v) = (b - a, c - a);
    let w = u.cross(v);
    let w2 = w.length_squared();
    if w.length() <= COLLINEAR_TOL * u.length() * v.length() || w2 == 0.0 {
        return None;
    }
    let center =
        a + (w.cross(u) * v.length_squared() + v.cross(w) * u.length_squared()) / (2.0 * w2);
    let radius = (a - center).length();
    let n = w / w2.sqrt();
    let e1 = (a - center) / radius;
    let e2 = n.cross(e1);
    let rc = c - center;
    let mut sweep = rc.dot(e2).atan2(rc.dot(e1));
    if sweep <= 0.0 {
        sweep += 2.0 * PI;
    }
    Some((center, radius, e1, e2, sweep))
}

impl Centerline {
    /// Builds the composite curve starting at `start`.
    pub fn new(start: DVec3, segments: &[Segment]) -> Result<Self, CurveError> {
        if segments.is_empty() {
            return Err(CurveError {
                segment: 0,
                part: String::new(),
                reason: "a hose needs at least one segment".into(),
            });
        }
        let scale = segments
            .iter()
            .flat_map(|s| match s {
                Segment::Line { to } => vec![*to],
                Segment::Arc { via, to } => vec![*via, *to],
                Segment::Spline { through, to } => through.iter().copied().chain([*to]).collect(),
            })
            .fold(start.length(), |m, p| m.max(p.length()));
        let same = |p: DVec3, q: DVec3| (p - q).length() <= COINCIDENT_TOL * scale;
        let err = |segment: usize, part: &str, reason: &str| CurveError {
            segment,
            part: part.into(),
            reason: reason.into(),
        };

        let mut pieces: Vec<Piece> = Vec::with_capacity(segments.len());
        let mut current = start;
        for (i, seg) in segments.iter().enumerate() {
            match seg {
                Segment::Line { to } => {
                    if same(current, *to) {
                        return Err(err(
                            i,
                            "line.to",
                            "segment has zero length (end equals its start point)",
                        ));
                    }
                    pieces.push(Piece::Line {
                        a: current,
                        b: *to,
                        length: (*to - current).length(),
                    });
                    current = *to;
                }
                Segment::Arc { via, to } => {
                    if same(current, *to) {
                        return Err(err(i, "arc.to", "end point equals the arc's start point (use two arcs for a full circle)"));
                    }
                    if same(current, *via) {
                        return Err(err(i, "arc.via", "coincides with the arc's start point"));
                    }
                    if same(*via, *to) {
                        return Err(err(i, "arc.via", "coincides with the arc's end point"));
                    }
                    let (center, radius, e1, e2, sweep) = circle_through(current, *via, *to)
                        .ok_or_else(|| {
                            err(
                                i,
                                "arc",
                                "start, via and to are collinear: no circle passes through them",
                            )
                        })?;
                    pieces.push(Piece::Arc {
                        center,
                        radius,
                        e1,
                        e2,
                        sweep,
                    });
                    current = *to;
                }
                Segment::Spline { through, to } => {
                    let pts: Vec<DVec3> = std::iter::once(current)
                        .chain(through.iter().copied())
                        .chain([*to])
                        .collect();
                    for k in 1..pts.len() {
                        if same(pts[k - 1], pts[k]) {
                            let part = if k == pts.len() - 1 {
                                "spline.to".to_string()
                            } else {
                                format!("spline.through[{}]", k - 1)
                            };
                            return Err(CurveError {
                                segment: i,
                                part,
                                reason: "coincides with the previous point of the spline".into(),
                            });
                        }
                    }
                    let incoming = pieces.last().map(Piece::end_tangent);
                    let last = pts.len() - 1;
                    let tangent = |k: usize| -> DVec3 {
                        if k == 0 {
                            match incoming {
                                Some(d) if d != DVec3::ZERO => d * (pts[1] - pts[0]).length(),
                                _ => pts[1] - pts[0],
                            }
                        } else if k == last {
                            pts[last] - pts[last - 1]
                        } else {
                            (pts[k + 1] - pts[k - 1]) * 0.5
                        }
                    };
                    for k in 0..last {
                        pieces.push(Piece::Spline(Hermite::new(
                            pts[k],
                            pts[k + 1],
                            tangent(k),
                            tangent(k + 1),
                        )));
                    }
                    current = *to;
                }
            }
        }
        let mut offsets = Vec::with_capacity(pieces.len() + 1);
        let mut acc = 0.0;
        offsets.push(0.0);
        for p in &pieces {
            acc += p.length();
            offsets.push(acc);
        }
        Ok(Centerline {
            start,
            end: current,
            pieces,
            offsets,
        })
    }

    /// Total arc length.
    pub fn length(&self) -> f64 {
        self.offsets.last().copied().unwrap_or(0.0)
    }

    /// Smallest radius among the arcs, if there are arcs.
    pub fn min_arc_radius(&self) -> Option<f64> {
        self.pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Arc { radius, .. } => Some(*radius),
                _ => None,
            })
            .reduce(f64::min)
    }

    /// Point at arc length `s` (clamped to the curve).
    pub fn point_at(&self, s: f64) -> DVec3 {
        let s = s.clamp(0.0, self.length());
        let i = self
            .offsets
            .partition_point(|&o| o <= s)
            .clamp(1, self.pieces.len())
            - 1;
        match self.pieces.get(i) {
            Some(piece) => piece.point_at((s - self.offsets[i]).min(piece.length())),
            None => self.start,
        }
    }

    /// `n + 1` nodes at equal arc-length spacing, first and last exactly at the ends.
    pub fn discretise(&self, n: usize) -> Vec<DVec3> {
        let n = n.max(1);
        let total = self.length();
        let mut nodes: Vec<DVec3> = (0..=n)
            .map(|i| self.point_at(total * i as f64 / n as f64))
            .collect();
        nodes[0] = self.start;
        nodes[n] = self.end;
        nodes
    }
}

/// Number of elements for a curve of `length`: the request, raised so that the spacing
/// along every arc is at most R·π/8 (≥ 4 elements per quarter circle), and at least 1.
/// `None` if that would exceed [`MAX_ELEMENTS`].
pub fn element_count(
    length: f64,
    resolution: Resolution,
    min_arc_radius: Option<f64>,
) -> Option<ElementCount> {
    // Round away tiny floating-point excess so that 500 / 25 gives 20, not 21.
    let whole = |x: f64| (x * (1.0 - 1e-12)).ceil().max(1.0);
    let requested = match resolution {
        Resolution::Elements(n) => n.max(1) as f64,
        Resolution::ElementLength(l) => whole(length / l),
    };
    let for_arcs = min_arc_radius.map_or(1.0, |r| whole(length / (r * PI / 8.0)));
    let count = requested.max(for_arcs);
    if count.is_nan() || count > MAX_ELEMENTS as f64 {
        return None;
    }
    Some(ElementCount {
        requested: requested as usize,
        count: count as usize,
        raised_for_arcs: for_arcs > requested,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    fn polyline_length(nodes: &[DVec3]) -> f64 {
        nodes.windows(2).map(|w| (w[1] - w[0]).length()).sum()
    }

    #[test]
    fn straight_line_gives_exact_nodes() {
        let c = Centerline::new(
            DVec3::ZERO,
            &[Segment::Line {
                to: v(0.5, 0.0, 0.0),
            }],
        )
        .unwrap();
        assert_eq!(c.length(), 0.5);
        let nodes = c.discretise(20);
        assert_eq!(nodes.len(), 21);
        for (i, p) in nodes.iter().enumerate() {
            let expected = v(0.025 * i as f64, 0.0, 0.0);
            assert!(
                (*p - expected).length() <= 1e-16,
                "node {i}: {p} vs {expected}"
            );
        }
    }

    #[test]
    fn line_through_several_segments_is_evenly_spaced() {
        let segs = [
            Segment::Line {
                to: v(0.3, 0.0, 0.0),
            },
            Segment::Line {
                to: v(0.3, 0.4, 0.0),
            },
        ];
        let c = Centerline::new(DVec3::ZERO, &segs).unwrap();
        assert!((c.length() - 0.7).abs() < 1e-15);
        let nodes = c.discretise(7);
        assert!((nodes[3] - v(0.3, 0.0, 0.0)).length() < 1e-15);
        assert!((nodes[5] - v(0.3, 0.2, 0.0)).length() < 1e-15);
    }

    #[test]
    fn arc_nodes_lie_on_the_circle() {
        // Three-quarter circle of radius 0.2 about (0, 0.2, 0.1) in a tilted plane.
        let center = v(0.0, 0.2, 0.1);
        let r = 0.2;
        let (e1, e2) = (v(0.0, -1.0, 0.0), v(0.6, 0.0, 0.8));
        let at = |phi: f64| center + (e1 * phi.cos() + e2 * phi.sin()) * r;
        let segs = [Segment::Arc {
            via: at(1.0),
            to: at(1.5 * PI),
        }];
        let c = Centerline::new(at(0.0), &segs).unwrap();
        assert!((c.length() - r * 1.5 * PI).abs() <= 1e-12 * c.length());
        assert!((c.min_arc_radius().unwrap() - r).abs() < 1e-12);
        let nodes = c.discretise(37);
        for p in &nodes {
            let d = (*p - center).length();
            assert!((d - r).abs() <= 1e-9 * r, "off the circle by {}", d - r);
            assert!(
                (*p - center).dot(e1.cross(e2)).abs() <= 1e-12,
                "off the plane"
            );
        }
        // Equal arc-length spacing means equal chords.
        let chord = (nodes[1] - nodes[0]).length();
        for w in nodes.windows(2) {
            assert!(((w[1] - w[0]).length() - chord).abs() < 1e-12);
        }
    }

    #[test]
    fn arc_sweeps_through_via() {
        // Start (1,0), via (0,1), end (0,-1): the long way round, 270°.
        let segs = [Segment::Arc {
            via: v(0.0, 1.0, 0.0),
            to: v(0.0, -1.0, 0.0),
        }];
        let c = Centerline::new(v(1.0, 0.0, 0.0), &segs).unwrap();
        assert!((c.length() - 1.5 * PI).abs() < 1e-12);
        assert!((c.point_at(0.5 * PI) - v(0.0, 1.0, 0.0)).length() < 1e-12);
    }

    #[test]
    fn polyline_length_converges_to_curve_length() {
        let segs = [
            Segment::Line {
                to: v(0.3, 0.0, 0.0),
            },
            Segment::Arc {
                via: v(0.4, 0.05, 0.0),
                to: v(0.45, 0.15, 0.0),
            },
            Segment::Spline {
                through: vec![v(0.5, 0.25, 0.0)],
                to: v(0.5, 0.4, 0.1),
            },
        ];
        let c = Centerline::new(DVec3::ZERO, &segs).unwrap();
        let total = c.length();
        let mut last_err = f64::INFINITY;
        for n in [10, 40, 160, 640, 2560] {
            let err = total - polyline_length(&c.discretise(n));
            assert!(err >= -1e-12, "a polyline is never longer than its curve");
            eprintln!("n = {n}: error {err}");
            assert!(
                err < last_err / 3.5,
                "n = {n}: error {err} did not shrink enough from {last_err}"
            );
            last_err = err;
        }
        assert!(last_err < 2e-6 * total, "final error {last_err}");
    }

    #[test]
    fn spline_arc_length_is_accurate() {
        // A spline through points on a straight line is that straight line.
        let segs = [Segment::Spline {
            through: vec![v(0.1, 0.0, 0.0), v(0.2, 0.0, 0.0)],
            to: v(0.3, 0.0, 0.0),
        }];
        let c = Centerline::new(DVec3::ZERO, &segs).unwrap();
        assert!((c.length() - 0.3).abs() < 1e-14);
        let nodes = c.discretise(6);
        for (i, p) in nodes.iter().enumerate() {
            assert!((*p - v(0.05 * i as f64, 0.0, 0.0)).length() < 1e-12);
        }
    }

    #[test]
    fn curved_spline_length_matches_a_fine_polyline() {
        let segs = [Segment::Spline {
            through: vec![v(0.1, 0.08, 0.0), v(0.2, -0.03, 0.05), v(0.3, 0.05, 0.0)],
            to: v(0.4, 0.0, 0.1),
        }];
        let c = Centerline::new(DVec3::ZERO, &segs).unwrap();
        // A smooth curve: the polyline error falls as h², so Richardson extrapolation of
        // two fine polylines estimates the true length independently of the quadrature.
        let (p1, p2) = (
            polyline_length(&c.discretise(10_000)),
            polyline_length(&c.discretise(20_000)),
        );
        let extrapolated = (4.0 * p2 - p1) / 3.0;
        assert!(
            (c.length() - extrapolated).abs() <= 1e-10 * c.length(),
            "{} vs {extrapolated}",
            c.length()
        );
        // Equal arc-length spacing: chords equal to first order.
        let nodes = c.discretise(400);
        let h = c.length() / 400.0;
        for w in nodes.windows(2) {
            assert!(((w[1] - w[0]).length() - h).abs() < 1e-3 * h);
        }
    }

    #[test]
    fn spline_continues_the_previous_tangent() {
        let segs = [
            Segment::Line {
                to: v(1.0, 0.0, 0.0),
            },
            Segment::Spline {
                through: vec![],
                to: v(2.0, 1.0, 0.0),
            },
        ];
        let c = Centerline::new(DVec3::ZERO, &segs).unwrap();
        let d = c.point_at(1.0 + 1e-6) - c.point_at(1.0);
        assert!(d.normalize().dot(DVec3::X) > 1.0 - 1e-6);
    }

    #[test]
    fn collinear_arc_is_rejected() {
        let segs = [Segment::Arc {
            via: v(1.0, 0.0, 0.0),
            to: v(2.0, 0.0, 0.0),
        }];
        let e = Centerline::new(DVec3::ZERO, &segs).unwrap_err();
        assert_eq!(e.part, "arc");
        assert!(e.reason.contains("collinear"));
    }

    #[test]
    fn zero_length_segment_is_rejected() {
        let segs = [
            Segment::Line {
                to: v(1.0, 0.0, 0.0),
            },
            Segment::Line {
                to: v(1.0, 0.0, 0.0),
            },
        ];
        let e = Centerline::new(DVec3::ZERO, &segs).unwrap_err();
        assert_eq!((e.segment, e.part.as_str()), (1, "line.to"));
        assert!(e.reason.contains("zero length"));
    }

    #[test]
    fn coincident_points_are_rejected() {
        let arc = [Segment::Arc {
            via: v(0.0, 0.0, 0.0),
            to: v(1.0, 1.0, 0.0),
        }];
        assert_eq!(
            Centerline::new(DVec3::ZERO, &arc).unwrap_err().part,
            "arc.via"
        );
        let spline = [Segment::Spline {
            through: vec![v(1.0, 0.0, 0.0), v(1.0, 0.0, 0.0)],
            to: v(2.0, 0.0, 0.0),
        }];
        let e = Centerline::new(DVec3::ZERO, &spline).unwrap_err();
        assert_eq!(e.part, "spline.through[1]");
        assert!(e.reason.contains("coincides"));
    }

    #[test]
    fn element_count_rules() {
        let ec = element_count(0.5, Resolution::ElementLength(0.025), None).unwrap();
        assert_eq!(
            (ec.requested, ec.count, ec.raised_for_arcs),
            (20, 20, false)
        );
        let ec = element_count(0.5, Resolution::ElementLength(0.03), None).unwrap();
        assert_eq!(ec.count, 17);
        let ec = element_count(0.5, Resolution::Elements(0), None).unwrap();
        assert_eq!(ec.count, 1);
        // A quarter circle of radius 0.1 alone, requested with 1 element: raised to 4.
        let ec = element_count(0.1 * PI / 2.0, Resolution::Elements(1), Some(0.1)).unwrap();
        assert_eq!((ec.count, ec.raised_for_arcs), (4, true));
        assert!(element_count(1.0, Resolution::ElementLength(1e-9), None).is_none());
    }
}
