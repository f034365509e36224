//! Centre curves of KBL segments: unclamped uniform B-splines, chained.
//!
//! A KBL `B_spline_curve` gives a degree p and n + 1 control points but no knot vector.
//! Read with the uniform knots t_i = i (i = 0 … n + p + 1) and the parameter domain
//! [p, n + 1] (the unclamped uniform B-spline, e.g. Piegl & Tiller, *The NURBS Book*,
//! 2nd ed., §2.2 and Alg. A2.2/A3.1 — de Boor's algorithm), the curves of the sample files end on
//! their segment's nodes and their arc length is the segment's `Virtual_length`.
//!
//! A segment's centre curve is one or more such splines in order; [`Chain`] joins them
//! under one parameter u ∈ [0, m] (m splines; spline k covers [k, k + 1]).

use glam::DVec3;

/// One unclamped uniform B-spline.
#[derive(Debug, Clone)]
pub struct BSpline {
    degree: usize,
    points: Vec<DVec3>,
}

impl BSpline {
    /// `None` unless degree ≥ 1 and there are more control points than the degree.
    pub fn new(degree: usize, points: Vec<DVec3>) -> Option<Self> {
        (degree >= 1 && points.len() > degree).then_some(BSpline { degree, points })
    }

    /// Parameter domain [p, n + 1].
    pub fn domain(&self) -> (f64, f64) {
        (self.degree as f64, self.points.len() as f64)
    }

    /// Point at parameter t (clamped to the domain), by de Boor's algorithm with knots
    /// t_i = i.
    pub fn point(&self, t: f64) -> DVec3 {
        de_boor(self.degree, &self.points, t, 0.0)
    }

    /// First derivative dC/dt. For uniform knots of spacing 1 the derivative is the
    /// B-spline of degree p − 1 with control points Q_i = P_{i+1} − P_i
    /// (p (P_{i+1} − P_i) / (t_{i+p+1} − t_{i+1}) with t_{i+p+1} − t_{i+1} = p) and knots
    /// shifted by one.
    pub fn derivative(&self, t: f64) -> DVec3 {
        let q: Vec<DVec3> = self.points.windows(2).map(|w| w[1] - w[0]).collect();
        if self.degree == 1 {
            // Degree 0: piecewise constant, Q_i on [i + 1, i + 2).
            let (a, b) = self.domain();
            let i = (t.clamp(a, b - 1e-12).floor() as usize)
                .saturating_sub(1)
                .min(q.len() - 1);
            return q[i];
        }
        de_boor(self.degree - 1, &q, t, 1.0)
    }
}

/// de Boor's algorithm for a B-spline of degree p with knots t_i = i + shift, evaluated
/// at t clamped to the domain [p + shift, n + 1 + shift].
fn de_boor(p: usize, ctrl: &[DVec3], t: f64, shift: f64) -> DVec3 {
    let n = ctrl.len() - 1;
    let knot = |i: usize| i as f64 + shift;
    let lo = knot(p);
    let hi = knot(n + 1);
    let t = t.clamp(lo, hi);
    // Span k with t in [t_k, t_{k+1}), p ≤ k ≤ n.
    let k = ((t - shift).floor() as usize).clamp(p, n);
    let mut d: Vec<DVec3> = (0..=p).map(|j| ctrl[j + k - p]).collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = j + k - p;
            let alpha = (t - knot(i)) / (knot(i + 1 + p - r) - knot(i));
            d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
        }
    }
    d[p]
}

/// Gauss–Legendre nodes and weights on [−1, 1], 8 points.
const GL8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_26),
];

/// Sub-intervals per unit of chain parameter for quadrature and tables.
const SUBDIV: usize = 32;

/// A chain of B-splines under one parameter u ∈ [0, m].
#[derive(Debug, Clone)]
pub struct Chain {
    splines: Vec<BSpline>,
}

impl Chain {
    /// `None` for an empty list.
    pub fn new(splines: Vec<BSpline>) -> Option<Self> {
        (!splines.is_empty()).then_some(Chain { splines })
    }

    /// A straight line from a to b (degree 1, two control points).
    pub fn line(a: DVec3, b: DVec3) -> Self {
        Chain {
            splines: vec![BSpline {
                degree: 1,
                points: vec![a, b],
            }],
        }
    }

    /// Parameter range [0, m].
    pub fn range(&self) -> (f64, f64) {
        (0.0, self.splines.len() as f64)
    }

    /// The spline and its own parameter for chain parameter u.
    fn local(&self, u: f64) -> (&BSpline, f64, f64) {
        let m = self.splines.len();
        let u = u.clamp(0.0, m as f64);
        let k = (u.floor() as usize).min(m - 1);
        let s = &self.splines[k];
        let (a, b) = s.domain();
        (s, a + (u - k as f64) * (b - a), b - a)
    }

    pub fn point(&self, u: f64) -> DVec3 {
        let (s, t, _) = self.local(u);
        s.point(t)
    }

    /// dC/du.
    pub fn derivative(&self, u: f64) -> DVec3 {
        let (s, t, scale) = self.local(u);
        s.derivative(t) * scale
    }

    /// Unit tangent at u (zero if the derivative vanishes).
    pub fn tangent(&self, u: f64) -> DVec3 {
        self.derivative(u).normalize_or_zero()
    }

    /// Knot spans of spline k (its speed is smooth only within a span).
    fn spans(&self, k: usize) -> usize {
        let s = &self.splines[k];
        s.points.len() - s.degree
    }

    /// Quadrature pieces from u0 to u1 (either order): the interval cut at every knot of
    /// every spline, each knot span split into max(1, ⌈32 / spans⌉) equal parts (a spline
    /// of one span — the KBL sample curves — gets 32 parts per unit of u; a degree-1 curve
    /// through many points one part per straight piece, on which 8-point Gauss–Legendre is
    /// exact).
    fn pieces(&self, u0: f64, u1: f64) -> Vec<(f64, f64)> {
        let (a, b) = if u0 <= u1 { (u0, u1) } else { (u1, u0) };
        let mut cuts = vec![a];
        let (_, m) = self.range();
        let first = (a.floor().max(0.0) as usize).min(self.splines.len() - 1);
        for k in first..self.splines.len() {
            if k as f64 >= b {
                break;
            }
            let spans = self.spans(k);
            let parts = spans * SUBDIV.div_ceil(spans).max(1);
            for j in 1..=parts {
                let u = (k as f64 + j as f64 / parts as f64).min(m);
                if u > a && u < b {
                    cuts.push(u);
                }
            }
        }
        cuts.push(b);
        let mut out: Vec<(f64, f64)> = cuts
            .windows(2)
            .filter(|w| w[1] > w[0])
            .map(|w| (w[0], w[1]))
            .collect();
        if out.is_empty() {
            out.push((a, b));
        }
        if u1 < u0 {
            out.reverse();
            for p in &mut out {
                *p = (p.1, p.0);
            }
        }
        out
    }

    /// 8-point Gauss–Legendre over one piece (either order; positive).
    fn piece_length(&self, a: f64, b: f64) -> f64 {
        let h = b - a;
        GL8.iter()
            .map(|(x, w)| w * self.derivative(a + (x + 1.0) * 0.5 * h).length())
            .sum::<f64>()
            * 0.5
            * h.abs()
    }

    /// Arc length between u0 and u1 (u1 < u0 gives the same positive length):
    /// 8-point Gauss–Legendre on each piece of `Chain::pieces`.
    pub fn arc_length(&self, u0: f64, u1: f64) -> f64 {
        self.pieces(u0, u1)
            .into_iter()
            .map(|(a, b)| self.piece_length(a, b))
            .sum()
    }

    /// The parameter of the curve point closest to `p`, and its distance: a scan at 256
    /// samples per spline, then golden-section search around the best sample.
    pub fn closest(&self, p: DVec3) -> (f64, f64) {
        let (_, m) = self.range();
        let n = 256 * self.splines.len();
        let d = |u: f64| self.point(u).distance_squared(p);
        let best = (0..=n)
            .map(|i| m * i as f64 / n as f64)
            .fold((0.0, f64::INFINITY), |acc, u| {
                let v = d(u);
                if v < acc.1 {
                    (u, v)
                } else {
                    acc
                }
            });
        let step = m / n as f64;
        let (mut a, mut b) = ((best.0 - step).max(0.0), (best.0 + step).min(m));
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - g * (b - a);
        let mut e = a + g * (b - a);
        for _ in 0..80 {
            if d(c) < d(e) {
                b = e;
            } else {
                a = c;
            }
            c = b - g * (b - a);
            e = a + g * (b - a);
        }
        let u = 0.5 * (a + b);
        (u, d(u).sqrt())
    }

    /// Cumulative arc-length table from u0 to u1 (either order): pairs (u, s), one entry
    /// per piece of `Chain::pieces`.
    fn table(&self, u0: f64, u1: f64) -> Vec<(f64, f64)> {
        let pieces = self.pieces(u0, u1);
        let mut out = Vec::with_capacity(pieces.len() + 1);
        let mut s = 0.0;
        out.push((u0, 0.0));
        for (a, b) in pieces {
            s += self.piece_length(a, b);
            out.push((b, s));
        }
        out
    }

    /// Parameter at arc length `s` from u0 towards u1 (Newton on the arc length, started
    /// from the table).
    fn param_at(&self, table: &[(f64, f64)], s: f64) -> f64 {
        let i = table
            .partition_point(|&(_, si)| si < s)
            .clamp(1, table.len() - 1);
        let (ua, sa) = table[i - 1];
        let (ub, sb) = table[i];
        let mut u = if sb > sa {
            ua + (ub - ua) * (s - sa) / (sb - sa)
        } else {
            ua
        };
        let dir = (ub - ua).signum();
        for _ in 0..4 {
            let err = self.arc_length(ua, u) + sa - s;
            let speed = self.derivative(u).length();
            if speed < 1e-15 {
                break;
            }
            u -= dir * err / speed;
            u = if ua <= ub {
                u.clamp(ua, ub)
            } else {
                u.clamp(ub, ua)
            };
        }
        u
    }

    /// Points at equal arc-length spacing from u0 to u1 (either order), `count` ≥ 2 points,
    /// the first at u0 and the last at u1.
    pub fn sample(&self, u0: f64, u1: f64, count: usize) -> Vec<DVec3> {
        let count = count.max(2);
        let table = self.table(u0, u1);
        let total = table.last().map_or(0.0, |t| t.1);
        (0..count)
            .map(|i| {
                if i == 0 {
                    self.point(u0)
                } else if i == count - 1 {
                    self.point(u1)
                } else {
                    self.point(self.param_at(&table, total * i as f64 / (count - 1) as f64))
                }
            })
            .collect()
    }

    /// Parameter at the fraction f ∈ [0, 1] of the arc length from u0 to u1.
    pub fn param_at_fraction(&self, u0: f64, u1: f64, f: f64) -> f64 {
        let table = self.table(u0, u1);
        let total = table.last().map_or(0.0, |t| t.1);
        self.param_at(&table, total * f.clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_uniform_spline_is_the_polyline_between_midpoints() {
        // Degree 1, knots 0..3, domain [1, 2]: from P0 (at t=1) to P1 (t=2)? With knots
        // t_i = i, the degree-1 basis N_i peaks at t_{i+1}: C(1) = P0, C(2) = P1.
        let s = BSpline::new(1, vec![DVec3::ZERO, DVec3::X]).unwrap();
        assert!((s.point(1.0) - DVec3::ZERO).length() < 1e-15);
        assert!((s.point(2.0) - DVec3::X).length() < 1e-15);
        assert!((s.point(1.5) - DVec3::X * 0.5).length() < 1e-15);
    }

    #[test]
    fn degree_one_interpolates_every_control_point() {
        // Knots t_i = i, domain [1, n + 1]: C(i + 1) = P_i, so a degree-1 curve is the
        // polyline through its control points, first and last included (the KBL export
        // relies on this).
        let p: Vec<DVec3> = (0..9)
            .map(|i| DVec3::new(i as f64, (i as f64).sin(), 0.1 * (i * i) as f64))
            .collect();
        let s = BSpline::new(1, p.clone()).unwrap();
        assert_eq!(s.domain(), (1.0, 9.0));
        for (i, q) in p.iter().enumerate() {
            assert!((s.point(i as f64 + 1.0) - *q).length() < 1e-14, "P{i}");
        }
        // Arc length: exactly the polyline's (one quadrature piece per straight piece).
        let c = Chain::new(vec![s]).unwrap();
        let poly: f64 = p.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!((c.arc_length(0.0, 1.0) - poly).abs() < 1e-12 * poly);
        // Equal arc-length samples lie on the polyline, evenly spaced along it.
        let pts = c.sample(0.0, 1.0, 17);
        assert!((pts[0] - p[0]).length() < 1e-14 && (pts[16] - p[8]).length() < 1e-14);
        let back = c.sample(1.0, 0.0, 5);
        assert!((back[0] - p[8]).length() < 1e-14 && (back[4] - p[0]).length() < 1e-14);
        let u = c.param_at_fraction(0.0, 1.0, 0.5);
        assert!((c.arc_length(0.0, u) - 0.5 * poly).abs() < 1e-9 * poly);
    }

    #[test]
    fn quadratic_uniform_spline_starts_at_midpoint() {
        // Uniform quadratic: C starts at (P0 + P1)/2 and ends at (P1 + P2)/2.
        let p = vec![
            DVec3::ZERO,
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ];
        let s = BSpline::new(2, p.clone()).unwrap();
        let (a, b) = s.domain();
        assert!((s.point(a) - (p[0] + p[1]) * 0.5).length() < 1e-14);
        assert!((s.point(b) - (p[1] + p[2]) * 0.5).length() < 1e-14);
        // Derivative at the start: P1 − P0.
        assert!((s.derivative(a) - (p[1] - p[0])).length() < 1e-12);
    }

    #[test]
    fn derivative_matches_finite_difference() {
        let p: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(i as f64, (i * i) as f64 * 0.1, (i as f64).sin()))
            .collect();
        let s = BSpline::new(4, p).unwrap();
        for t in [4.1, 5.0, 5.5, 6.9] {
            let h = 1e-6;
            let fd = (s.point(t + h) - s.point(t - h)) / (2.0 * h);
            assert!((fd - s.derivative(t)).length() < 1e-6, "t = {t}");
        }
    }

    #[test]
    fn line_length_sampling_and_closest() {
        let c = Chain::line(DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0));
        assert!((c.arc_length(0.0, 1.0) - 5.0).abs() < 1e-12);
        let pts = c.sample(0.0, 1.0, 6);
        assert!((pts[1] - DVec3::new(0.6, 0.8, 0.0)).length() < 1e-9);
        let (u, d) = c.closest(DVec3::new(3.0, 4.0, 1.0));
        assert!((u - 1.0).abs() < 1e-9 && (d - 1.0).abs() < 1e-9);
        let pts = c.sample(1.0, 0.0, 2);
        assert!((pts[0] - DVec3::new(3.0, 4.0, 0.0)).length() < 1e-12);
    }
}
