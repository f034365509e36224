//! Ordinary least squares of a straight line y = a + b x, with the slope's standard error
//! and its two-sided 95 % confidence interval from Student's t with n − 2 degrees of
//! freedom (the textbook result for independent errors of equal variance, e.g. Montgomery
//! & Runger, *Applied Statistics and Probability for Engineers*, §11.4):
//!
//! b = S_xy / S_xx, a = ȳ − b x̄, s² = Σ rᵢ² / (n − 2), se(b) = s / √S_xx,
//! CI = b ± t_{0.975, n−2} · se(b).

use crate::student_t;
use serde::Serialize;

/// A straight line fitted to points by least squares.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LineFit {
    /// Slope b.
    pub slope: f64,
    /// Intercept a.
    pub intercept: f64,
    /// Standard error of the slope, s / √S_xx.
    pub slope_std_error: f64,
    /// Two-sided 95 % confidence interval of the slope.
    pub slope_ci95: [f64; 2],
    /// Root mean square of the residuals, √(Σ rᵢ² / n).
    pub residual_rms: f64,
    /// Residual standard deviation s = √(Σ rᵢ² / (n − 2)).
    pub residual_std: f64,
    /// Coefficient of determination R².
    pub r_squared: f64,
    /// Number of points.
    pub points: usize,
}

/// Sums that a line (and a parabola, for the linearity test) fit needs, over any window,
/// from prefix sums. x and y are shifted and scaled first so that the sums stay well
/// conditioned whatever the units.
pub struct PrefixSums {
    x0: f64,
    xs: f64,
    ys: f64,
    /// Prefix sums of 1, u, u², u³, u⁴, v, u v, u² v, v² (u, v the scaled x, y).
    p: Vec<[f64; 9]>,
}

/// Sums of one window.
#[derive(Clone, Copy, Debug)]
struct Sums {
    n: f64,
    u: f64,
    uu: f64,
    uuu: f64,
    uuuu: f64,
    v: f64,
    uv: f64,
    uuv: f64,
    vv: f64,
}

impl PrefixSums {
    pub fn new(x: &[f64], y: &[f64]) -> Self {
        let x_min = x.iter().copied().fold(f64::INFINITY, f64::min);
        let x_max = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let x0 = 0.5 * (x_min + x_max);
        let xs = (0.5 * (x_max - x_min)).max(f64::MIN_POSITIVE);
        let ys = y
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        let mut p = Vec::with_capacity(x.len() + 1);
        let mut acc = [0.0; 9];
        p.push(acc);
        for (xi, yi) in x.iter().zip(y) {
            let u = (xi - x0) / xs;
            let v = yi / ys;
            let t = [
                1.0,
                u,
                u * u,
                u * u * u,
                u * u * u * u,
                v,
                u * v,
                u * u * v,
                v * v,
            ];
            for k in 0..9 {
                acc[k] += t[k];
            }
            p.push(acc);
        }
        Self { x0, xs, ys, p }
    }

    fn sums(&self, first: usize, last: usize) -> Sums {
        let a = &self.p[first];
        let b = &self.p[last + 1];
        let d = |k: usize| b[k] - a[k];
        Sums {
            n: d(0),
            u: d(1),
            uu: d(2),
            uuu: d(3),
            uuuu: d(4),
            v: d(5),
            uv: d(6),
            uuv: d(7),
            vv: d(8),
        }
    }

    /// Sum of squared residuals of the best line and of the best parabola through the
    /// points `first..=last`, in the units of y².
    pub fn ssr_line_and_parabola(&self, first: usize, last: usize) -> (f64, f64) {
        let s = self.sums(first, last);
        // centre u on the window's mean for conditioning
        let n = s.n;
        let mu = s.u / n;
        let m2 = s.uu - 2.0 * mu * s.u + n * mu * mu; // Σ (u−μ)²
        let m3 = s.uuu - 3.0 * mu * s.uu + 3.0 * mu * mu * s.u - n * mu.powi(3);
        let m4 = s.uuuu - 4.0 * mu * s.uuu + 6.0 * mu * mu * s.uu - 4.0 * mu.powi(3) * s.u
            + n * mu.powi(4);
        let vbar = s.v / n;
        let svv = s.vv - n * vbar * vbar; // Σ (v−v̄)²
        let c1 = s.uv - mu * s.v; // Σ (u−μ)(v)  = Σ (u−μ)(v−v̄)
        let c2raw = s.uuv - 2.0 * mu * s.uv + mu * mu * s.v; // Σ (u−μ)² v
        let c2 = c2raw - vbar * m2; // Σ (u−μ)² (v−v̄)
        let ssr_line = if m2 > 0.0 { svv - c1 * c1 / m2 } else { svv };
        // parabola: regress v−v̄ on w1 = (u−μ) and w2 = (u−μ)² − m2/n (centred)
        let w22 = m4 - m2 * m2 / n;
        let w12 = m3;
        let det = m2 * w22 - w12 * w12;
        let ssr_par = if det > 1e-14 * m2 * w22.max(f64::MIN_POSITIVE) {
            let b1 = (w22 * c1 - w12 * c2) / det;
            let b2 = (m2 * c2 - w12 * c1) / det;
            svv - b1 * c1 - b2 * c2
        } else {
            ssr_line
        };
        let scale = self.ys * self.ys;
        (
            ssr_line.max(0.0) * scale,
            ssr_par.max(0.0).min(ssr_line.max(0.0)) * scale,
        )
    }

    /// Sum of the residuals of the points `p..=q` about the best line through
    /// `first..=last` (which contains them), in the units of y.
    pub fn residual_sum(&self, first: usize, last: usize, p: usize, q: usize) -> f64 {
        let s = self.sums(first, last);
        let mu = s.u / s.n;
        let m2 = s.uu - s.n * mu * mu;
        let beta = if m2 > 0.0 {
            (s.uv - mu * s.v) / m2
        } else {
            0.0
        };
        let vbar = s.v / s.n;
        let t = self.sums(p, q);
        (t.v - t.n * vbar - beta * (t.u - t.n * mu)) * self.ys
    }

    /// The slope of the best line through `first..=last`, in the units of y per x.
    pub fn slope(&self, first: usize, last: usize) -> f64 {
        let s = self.sums(first, last);
        let mu = s.u / s.n;
        let m2 = s.uu - s.n * mu * mu;
        let c1 = s.uv - mu * s.v;
        if m2 > 0.0 {
            c1 / m2 * self.ys / self.xs
        } else {
            0.0
        }
    }

    /// The x offset the sums were taken about (for tests).
    #[allow(dead_code)]
    pub fn x_offset(&self) -> f64 {
        self.x0
    }
}

/// Fits a line to `x`, `y` (at least 3 points, not all x equal) and returns it with its
/// statistics; two passes over the data with centred sums, so it is exact to rounding.
pub fn fit_line(x: &[f64], y: &[f64]) -> Option<LineFit> {
    let n = x.len();
    if n < 3 || y.len() != n {
        return None;
    }
    let nf = n as f64;
    let xm = x.iter().sum::<f64>() / nf;
    let ym = y.iter().sum::<f64>() / nf;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (xi, yi) in x.iter().zip(y) {
        let (dx, dy) = (xi - xm, yi - ym);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if !(sxx > 0.0) {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = ym - slope * xm;
    let ssr: f64 = x
        .iter()
        .zip(y)
        .map(|(xi, yi)| (yi - intercept - slope * xi).powi(2))
        .sum();
    let dof = nf - 2.0;
    let residual_std = (ssr / dof).sqrt();
    let se = residual_std / sxx.sqrt();
    let t = student_t::quantile(0.975, dof);
    Some(LineFit {
        slope,
        intercept,
        slope_std_error: se,
        slope_ci95: [slope - t * se, slope + t * se],
        residual_rms: (ssr / nf).sqrt(),
        residual_std,
        r_squared: if syy > 0.0 { 1.0 - ssr / syy } else { 1.0 },
        points: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_line_is_recovered() {
        let x: Vec<f64> = (0..10).map(|i| i as f64 * 0.1).collect();
        let y: Vec<f64> = x.iter().map(|x| 3.0 + 2.0 * x).collect();
        let f = fit_line(&x, &y).unwrap();
        assert!((f.slope - 2.0).abs() < 1e-12);
        assert!((f.intercept - 3.0).abs() < 1e-12);
        assert!(f.residual_rms < 1e-12);
        let p = PrefixSums::new(&x, &y);
        let (l, q) = p.ssr_line_and_parabola(2, 8);
        assert!(l < 1e-10 && q < 1e-10, "{l} {q}");
        assert!((p.slope(0, 9) - 2.0).abs() < 1e-10);
    }

    #[test]
    fn prefix_sums_agree_with_direct_fit() {
        let x: Vec<f64> = (0..50).map(|i| 1e-3 * i as f64).collect();
        let y: Vec<f64> = x
            .iter()
            .enumerate()
            .map(|(i, x)| 5e6 * x + 1e3 * ((i * 7919 % 13) as f64 - 6.0) + 1e9 * x * x)
            .collect();
        let p = PrefixSums::new(&x, &y);
        let f = fit_line(&x[5..40], &y[5..40]).unwrap();
        let (l, q) = p.ssr_line_and_parabola(5, 39);
        let ssr = f.residual_rms.powi(2) * 35.0;
        assert!((l - ssr).abs() < 1e-6 * ssr, "{l} vs {ssr}");
        assert!(q < l);
        assert!((p.slope(5, 39) - f.slope).abs() < 1e-8 * f.slope.abs());
    }

    #[test]
    fn parabola_ssr_is_zero_for_a_parabola() {
        let x: Vec<f64> = (0..20).map(|i| i as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| 1.0 + 0.5 * x - 0.02 * x * x).collect();
        let p = PrefixSums::new(&x, &y);
        let (l, q) = p.ssr_line_and_parabola(0, 19);
        assert!(l > 1e-3);
        assert!(q < 1e-9 * l, "{q}");
    }
}
