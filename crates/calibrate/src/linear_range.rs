//! Finding the linear range of a test curve automatically.
//!
//! Method (documented in docs/calibration.md):
//!
//! 1. **Noise.** The scatter σ of the measurement is estimated from the curve itself:
//!    a line is fitted to every run of 5 consecutive points; on a locally straight curve
//!    each run's residual sum of squares is σ² χ²₃, whose median is 2.366 σ², so
//!    σ² = median(SSR₅) / 2.366. The median ignores the curved runs (toe, tail) as long
//!    as most of the curve is locally straight. σ is floored at 10⁻⁶ of the largest |y|
//!    (noise-free data).
//! 2. **Linearity of a window.** A window of m points is linear when (a) its line fit's
//!    residuals are noise, SSR/σ² ≤ (m − 2) + 3 √(2 (m − 2)) (χ² with m − 2 degrees of
//!    freedom, about 3 standard deviations), and (b) a parabola does not fit
//!    significantly better, (SSR_line − SSR_parabola)/σ² ≤ 9 (a 3σ test of curvature,
//!    which catches a toe region or a softening tail long before it shows in R²), and
//!    (c) its ends lie on its line: the mean residual of its first and of its last q
//!    points (q = 4, 8, 16, … up to a third of the window) stays within 3 σ/√q — a toe or
//!    a tail leaves the line at the window's ends first, where (a) and (b) are weakest —
//!    and (d) its slope is positive.
//! 3. **The window.** Among all windows of at least max(5, ⌈n/10⌉) points starting in the
//!    first half of the curve, the longest linear one is the linear range (ties: the
//!    earlier one). Every window is tested in O(1) from prefix sums.
//! 4. **The ends, as change points.** The tests pass a window a few points into a toe or
//!    a tail, where the departure still hides in the noise, and those points bias the
//!    slope by more than its standard error. So each end is then located as a change
//!    point: any smooth departure from a line starts as (x − x_e)², a kink as |x − x_e|,
//!    and the onset x_e (x_t for the toe) of least squares of the line plus that departure,
//!    fitted over the window and half as many points again beyond it, ends the range
//!    (see `refine_ends`).

use crate::least_squares::PrefixSums;
use serde::Serialize;

/// The linear range found in a curve: points `first..=last` (0-based data rows).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LinearRange {
    /// First data row of the range (0-based).
    pub first: usize,
    /// Last data row of the range (0-based, inclusive).
    pub last: usize,
    /// The estimated measurement scatter σ in y (the fit's y unit, SI).
    pub noise_std: f64,
    /// Smallest window length considered.
    pub min_points: usize,
}

/// Why no linear range was found.
#[derive(Clone, Debug, PartialEq)]
pub enum RangeError {
    TooFewPoints { points: usize, needed: usize },
    NoneLinear { min_points: usize, noise_std: f64 },
}

/// The end test's threshold in standard errors of the mean residual.
pub const END_Z: f64 = 2.0;

/// Fewest points a curve may have.
pub const MIN_CURVE_POINTS: usize = 6;

/// χ² acceptance for m − 2 degrees of freedom (about 3 σ).
fn chi2_limit(dof: f64) -> f64 {
    dof + 3.0 * (2.0 * dof).sqrt()
}

/// Estimates the scatter σ of `y` about a locally straight curve (step 1 above).
pub fn noise_std(sums: &PrefixSums, y: &[f64]) -> f64 {
    let n = y.len();
    let floor = 1e-6
        * y.iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()))
            .max(f64::MIN_POSITIVE);
    if n < 5 {
        return floor;
    }
    let mut ssr: Vec<f64> = (0..=n - 5)
        .map(|k| sums.ssr_line_and_parabola(k, k + 4).0)
        .collect();
    ssr.sort_by(f64::total_cmp);
    let median = if ssr.len() % 2 == 1 {
        ssr[ssr.len() / 2]
    } else {
        0.5 * (ssr[ssr.len() / 2 - 1] + ssr[ssr.len() / 2])
    };
    (median / 2.366).sqrt().max(floor)
}

/// Whether the window's ends lie on its line: the mean residual of its first and of its
/// last q points, q = 4, 8, 16, … up to a third of the window, stays within 3 σ/√q (a
/// toe or a tail bends away from the line at the ends first, where a global test of the
/// whole window is weakest).
fn ends_straight(sums: &PrefixSums, first: usize, last: usize, sigma: f64) -> bool {
    let m = last - first + 1;
    let mut q = 4;
    while 3 * q <= m {
        let limit = END_Z * sigma * (q as f64).sqrt(); // |Σ r| ≤ z σ √q ⇔ |mean| ≤ z σ/√q
        if sums.residual_sum(first, last, first, first + q - 1).abs() > limit
            || sums.residual_sum(first, last, last + 1 - q, last).abs() > limit
        {
            return false;
        }
        q *= 2;
    }
    true
}

/// Least squares of y = α + β x + γ h(x) over `idx` (h the departure term) → SSR.
fn ssr_with_departure(x: &[f64], y: &[f64], lo: usize, hi: usize, h: impl Fn(f64) -> f64) -> f64 {
    // centred and scaled columns for conditioning
    let n = (hi - lo + 1) as f64;
    let xm = x[lo..=hi].iter().sum::<f64>() / n;
    let xs = x[lo..=hi]
        .iter()
        .fold(0.0_f64, |m, v| m.max((v - xm).abs()))
        .max(f64::MIN_POSITIVE);
    let hs: Vec<f64> = x[lo..=hi].iter().map(|&v| h(v)).collect();
    let hscale = hs
        .iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let mut a = [[0.0; 3]; 3];
    let mut r = [0.0; 3];
    for (k, i) in (lo..=hi).enumerate() {
        let row = [1.0, (x[i] - xm) / xs, hs[k] / hscale];
        for p in 0..3 {
            r[p] += row[p] * y[i];
            for q in 0..3 {
                a[p][q] += row[p] * row[q];
            }
        }
    }
    let Some(c) = solve3(a, r) else {
        return f64::INFINITY;
    };
    (lo..=hi)
        .enumerate()
        .map(|(k, i)| {
            let f = c[0] + c[1] * (x[i] - xm) / xs + c[2] * hs[k] / hscale;
            (y[i] - f).powi(2)
        })
        .sum()
}

/// Solves a 3 × 3 system by Gaussian elimination with partial pivoting.
fn solve3(mut a: [[f64; 3]; 3], mut r: [f64; 3]) -> Option<[f64; 3]> {
    for c in 0..3 {
        let p = (c..3).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() < 1e-12 * (a[0][0].abs() + 1.0) {
            return None;
        }
        a.swap(c, p);
        r.swap(c, p);
        for i in c + 1..3 {
            let f = a[i][c] / a[c][c];
            for j in c..3 {
                a[i][j] -= f * a[c][j];
            }
            r[i] -= f * r[c];
        }
    }
    let mut out = [0.0; 3];
    for c in (0..3).rev() {
        let s: f64 = (c + 1..3).map(|j| a[c][j] * out[j]).sum();
        out[c] = (r[c] - s) / a[c][c];
    }
    Some(out)
}

/// Step 4: locates where the curve leaves the line at each end, as a change point. Any
/// smooth departure from a straight line starts quadratically (a kink linearly), so
/// beyond the window's end the models y = α + β x − γ (x − x_e)₊ᵖ, p = 1 and 2, are
/// fitted for every candidate onset x_e
/// (the window's points and half as many again beyond it); the x_e of least squares is
/// the onset, and the range ends there when that is before the window's end. The toe
/// is located the same way with (x_t − x)₊ᵖ. The window found by the tests above lags
/// behind the onset by the points whose departure still hides in the noise; this
/// change point does not, which keeps the slope unbiased.
fn refine_ends(
    x: &[f64],
    y: &[f64],
    first: usize,
    last: usize,
    min_points: usize,
) -> (usize, usize) {
    let n = x.len();
    let m = last - first + 1;
    let stride = (n / 1000).max(1);
    let mut last_new = last;
    if last + 1 < n {
        let hi = (last + m / 2).min(n - 1);
        let mut best = (f64::INFINITY, last);
        let mut e = first + min_points - 1;
        while e <= last {
            let xe = x[e];
            for p in [1, 2] {
                let ssr = ssr_with_departure(x, y, first, hi, |v| (v - xe).max(0.0).powi(p));
                if ssr < best.0 {
                    best = (ssr, e);
                }
            }
            e += stride;
        }
        last_new = best.1;
    }
    let mut first_new = first;
    if first > 0 {
        let lo = first.saturating_sub(m / 2);
        let mut best = (f64::INFINITY, first);
        let mut t = first;
        while t + min_points <= last_new + 1 && t <= first + m / 2 {
            let xt = x[t];
            for p in [1, 2] {
                let ssr = ssr_with_departure(x, y, lo, last_new, |v| (xt - v).max(0.0).powi(p));
                if ssr < best.0 {
                    best = (ssr, t);
                }
            }
            t += stride;
        }
        first_new = best.1;
    }
    if last_new + 1 < first_new + min_points {
        return (first, last);
    }
    (first_new, last_new)
}

/// Finds the linear range of the curve `x`, `y` (x increasing).
pub fn find(x: &[f64], y: &[f64]) -> Result<LinearRange, RangeError> {
    let n = x.len();
    if n < MIN_CURVE_POINTS {
        return Err(RangeError::TooFewPoints {
            points: n,
            needed: MIN_CURVE_POINTS,
        });
    }
    let sums = PrefixSums::new(x, y);
    let sigma = noise_std(&sums, y);
    let var = sigma * sigma;
    let min_points = 5.max(n.div_ceil(10));
    // long curves: every window would cost O(n²) tests; stride starts and ends so that
    // about 2000 × 1000 windows are tested
    let stride = (n / 2000).max(1);
    let mut best: Option<(usize, usize)> = None;
    let mut start = 0;
    while start + min_points <= n && start <= n / 2 {
        let longest_possible = n - start;
        if let Some((f, l)) = best {
            if longest_possible < l - f + 1 {
                break;
            }
        }
        let mut last = n - 1;
        loop {
            let m = last - start + 1;
            if m < min_points {
                break;
            }
            if let Some((f, l)) = best {
                if m <= l - f + 1 {
                    break;
                }
            }
            let (ssr_line, ssr_par) = sums.ssr_line_and_parabola(start, last);
            let dof = (m - 2) as f64;
            if ssr_line / var <= chi2_limit(dof)
                && (ssr_line - ssr_par) / var <= 9.0
                && ends_straight(&sums, start, last, sigma)
                && sums.slope(start, last) > 0.0
            {
                best = Some((start, last));
                break;
            }
            if last < stride {
                break;
            }
            last -= stride;
        }
        start += stride;
    }
    match best {
        Some((first, last)) => {
            let (first, last) = refine_ends(x, y, first, last, min_points);
            Ok(LinearRange {
                first,
                last,
                noise_std: sigma,
                min_points,
            })
        }
        None => Err(RangeError::NoneLinear {
            min_points,
            noise_std: sigma,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_line_is_linear_throughout() {
        let x: Vec<f64> = (0..40).map(|i| i as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| 2.0 * x + 1.0).collect();
        let r = find(&x, &y).unwrap();
        assert_eq!((r.first, r.last), (0, 39));
    }

    #[test]
    fn a_kink_ends_the_range_at_the_kink() {
        // slope 1 up to x = 30, then slope 0.3 (noise-free)
        let x: Vec<f64> = (0..50).map(|i| i as f64).collect();
        let y: Vec<f64> = x
            .iter()
            .map(|&x| {
                if x <= 30.0 {
                    x
                } else {
                    30.0 + 0.3 * (x - 30.0)
                }
            })
            .collect();
        let r = find(&x, &y).unwrap();
        assert_eq!(r.first, 0);
        assert!((30..=31).contains(&r.last), "{r:?}");
    }

    #[test]
    fn too_few_points_and_no_linear_range_are_errors() {
        assert!(matches!(
            find(&[0.0, 1.0, 2.0], &[0.0, 1.0, 2.0]),
            Err(RangeError::TooFewPoints { .. })
        ));
        // a falling curve has no range of positive slope
        let x: Vec<f64> = (0..20).map(|i| i as f64).collect();
        let y: Vec<f64> = x.iter().map(|x| -x).collect();
        assert!(matches!(find(&x, &y), Err(RangeError::NoneLinear { .. })));
    }
}
