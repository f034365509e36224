//! The fit shared by the tests past yield (`plastic_bending`, `plastic_torsion`,
//! `plastic_cantilever`, `plastic_three_point_bending`): a law of three parameters — an
//! elastic modulus, a yield stress and the hardening modulus H — whose loading curve
//! y_mono(x) is given in closed form, fitted by nonlinear least squares to the whole
//! load–unload curve, the unloading branch by Masing's rule ([`crate::load_unload`]).
//!
//! A curve that never yields (the fitted first yield beyond the largest x, or the elastic
//! line y = k x explaining the curve as well: ΔBIC below [`crate::law_fit::BIC_MARGIN`])
//! is an error, never a yield stress; so is a parameter the curve does not identify.

use crate::error::CalibError;
use crate::law_fit::{self, LawFit, TwoColumns};
use crate::load_unload;
use crate::mechanics::{Geometry, TestKind};
use crate::nonlinear_least_squares::{NonlinearFit, Parameter, Scale};

/// A load–unload curve and the law to fit to it.
pub struct YieldCurve<'a, M> {
    /// The file, for messages.
    pub file: &'a str,
    /// The controlled quantity (rising to `x[peak]`, then falling) and the response, SI.
    pub x: &'a [f64],
    pub y: &'a [f64],
    pub peak: usize,
    /// The parameters' names: modulus, yield stress, hardening modulus.
    pub names: [&'static str; 3],
    /// Start values of the modulus and the yield stress (the latter tried at 0.5, 0.8
    /// and 1 times this), and of H.
    pub start: [f64; 3],
    /// y_mono(p, x) on loading; a non-finite value marks parameters the law cannot take.
    pub mono: M,
}

/// The fitted law.
pub struct YieldFit {
    pub fit: NonlinearFit,
    /// The law's values at the curve's points.
    pub fitted: Vec<f64>,
}

/// How a law fit is shown: its formula, the axes' labels and their factors from SI.
pub struct Shown {
    pub formula: String,
    pub x_label: &'static str,
    pub y_label: &'static str,
    pub y_scale: f64,
}

impl YieldFit {
    /// The finished [`LawFit`] of a `kind` test on the curve `c` with its `checks` (the
    /// remark on a curve recorded negative added).
    pub fn finish(
        self,
        (kind, csv_name, geometry): (TestKind, &str, Geometry),
        shown: Shown,
        mut checks: Vec<String>,
        c: TwoColumns,
    ) -> LawFit {
        if c.flipped {
            checks
                .push("the curve was recorded with negative signs: magnitudes were fitted".into());
        }
        LawFit {
            kind,
            csv: csv_name.to_string(),
            geometry,
            fit: self.fit,
            formula: shown.formula,
            x_label: shown.x_label.into(),
            y_label: shown.y_label.into(),
            x_scale: 1.0,
            y_scale: shown.y_scale,
            checks,
            x: c.x,
            y: c.y,
            fitted: self.fitted,
            lines: c.lines,
        }
    }
}

impl<M: Fn([f64; 3], f64) -> f64> YieldCurve<'_, M> {
    /// The law's value at `x` for `p`, on loading or (`unloading`) by Masing's rule.
    pub fn value(&self, p: [f64; 3], x: f64, unloading: bool) -> f64 {
        load_unload::masing(|x| (self.mono)(p, x), self.x[self.peak], x, unloading)
    }

    /// The law's values along the curve for `p`, or `None` when one is not finite.
    pub fn values(&self, p: &[f64]) -> Option<Vec<f64>> {
        let p = [p[0], p[1], p[2]];
        let x_max = self.x[self.peak];
        let at_peak = (self.mono)(p, x_max);
        // Masing's branch with the peak's value evaluated once
        let v: Vec<f64> = self
            .x
            .iter()
            .enumerate()
            .map(|(i, x)| {
                if i > self.peak {
                    at_peak - 2.0 * (self.mono)(p, 0.5 * (x_max - x))
                } else {
                    (self.mono)(p, *x)
                }
            })
            .collect();
        v.iter().all(|v| v.is_finite()).then_some(v)
    }

    /// Fits the law; `first_yield(p)` is the x where the outermost fibre yields, and
    /// `never_yields(k)` the message when the elastic line y = k x is as good.
    pub fn fit(
        &self,
        first_yield: impl Fn([f64; 3]) -> f64,
        never_yields: impl Fn(f64) -> String,
        why_not_identified: &str,
    ) -> Result<YieldFit, CalibError> {
        let [modulus, yield_stress, hardening] = self.names;
        let starts: Vec<Vec<Parameter>> = [0.5, 0.8, 1.0]
            .iter()
            .map(|f| {
                vec![
                    Parameter {
                        name: modulus,
                        start: self.start[0],
                        scale: Scale::Log,
                    },
                    Parameter {
                        name: yield_stress,
                        start: f * self.start[1],
                        scale: Scale::Log,
                    },
                    Parameter {
                        name: hardening,
                        start: self.start[2],
                        scale: Scale::Linear { non_negative: true },
                    },
                ]
            })
            .collect();
        let model = |p: &[f64]| self.values(p);
        let fit = law_fit::best_of(&model, self.y, &starts).ok_or_else(|| {
            CalibError::file(
                self.file,
                "the yield law could not be evaluated along this curve",
            )
        })?;
        let v = fit.values();
        let p = [v[0], v[1], v[2]];
        let (bic_elastic, k_line) = law_fit::elastic_line_bic(self.x, self.y);
        let bic_plastic = law_fit::bic(fit.ssr, self.x.len() as f64, 3, self.y);
        if first_yield(p) >= self.x[self.peak] || bic_plastic > bic_elastic - law_fit::BIC_MARGIN {
            return Err(CalibError::file(self.file, never_yields(k_line)));
        }
        law_fit::require_identified(&fit, self.file, why_not_identified)?;
        let fitted = self.values(&v).unwrap_or_default();
        Ok(YieldFit { fit, fitted })
    }

    /// The x where the unloading branch of `p` crosses y = 0 (the permanent set), by
    /// bisection on [−x_max, x_max].
    pub fn set(&self, p: [f64; 3]) -> f64 {
        let x_max = self.x[self.peak];
        let (mut lo, mut hi) = (-x_max, x_max);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.value(p, mid, true) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Where the measured unloading branch crosses y = 0 (linear interpolation), or
    /// `None` when it stops before.
    pub fn measured_set(&self) -> Option<f64> {
        let (x, y) = (self.x, self.y);
        (self.peak + 1..x.len()).find(|&i| y[i] <= 0.0).map(|i| {
            let (x0, x1, y0, y1) = (x[i - 1], x[i], y[i - 1], y[i]);
            x0 + (x1 - x0) * y0 / (y0 - y1)
        })
    }

    /// The check comparing the measured set with `predicted`, in the curve's symbols
    /// (`y` "M" in `y_unit`, `x` "κ" in `x_unit`).
    pub fn measured_set_check(
        &self,
        predicted: f64,
        (y, y_unit, x, x_unit): (&str, &str, &str, &str),
    ) -> String {
        match self.measured_set() {
            Some(k) => format!(
                "springback measured: the curve crosses {y} = 0 at {x} = {k:.6} {x_unit} ({:+.2} % of the predicted set)",
                100.0 * (k - predicted) / predicted.abs().max(f64::MIN_POSITIVE)
            ),
            None => format!(
                "springback measured: the unloading stops at {y} = {:.5} {y_unit}, before {y} = 0",
                self.y[self.y.len() - 1]
            ),
        }
    }
}
