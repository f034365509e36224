//! Nonlinear least squares for the inelastic laws: min Σ (yᵢ − f(xᵢ; p))² by the
//! Levenberg–Marquardt method (Marquardt 1963, SIAM J. Appl. Math. 11; the damping
//! scaled by the diagonal of JᵀJ, as in Moré 1978, *Lecture Notes in Math.* 630), with
//! a central-difference Jacobian, and each parameter's standard error and 95 % interval
//! from the asymptotic covariance s² (JᵀJ)⁻¹ at the minimum, s² = Σ rᵢ² / (n − p), and
//! Student's t with n − p degrees of freedom (Seber & Wild, *Nonlinear Regression*,
//! 1989, §2.2 and §5.1).
//!
//! A parameter that must stay positive is fitted as its logarithm; its interval is then
//! exp(ln p ± t·se) (asymmetric, never below zero; Seber & Wild §5.2 on reparameterisation).
//! A parameter the data cannot fix (JᵀJ singular along it, or an interval spanning more
//! than a factor [`MAX_INTERVAL_RATIO`], or a linear one's interval holding zero) is
//! reported as not identified: callers turn that into an error, never a silent value.

use crate::student_t;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// How a parameter is searched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Positive, fitted as its logarithm.
    Log,
    /// Any real value (e.g. a hardening modulus that may be zero), kept ≥ 0 if `non_negative`.
    Linear { non_negative: bool },
}

/// One parameter to fit: its name for messages, the start value and how it is searched.
#[derive(Clone, Copy, Debug)]
pub struct Parameter {
    pub name: &'static str,
    pub start: f64,
    pub scale: Scale,
}

/// A parameter's fitted value with its uncertainty.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Estimate {
    pub name: String,
    pub value: f64,
    /// Standard error (of ln p for a [`Scale::Log`] parameter, of p otherwise).
    pub std_error: f64,
    /// 95 % confidence interval of p (infinite bounds when not identified).
    pub ci95: [f64; 2],
    /// Whether the data fix the parameter (module doc).
    pub identified: bool,
}

/// A finished fit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NonlinearFit {
    pub estimates: Vec<Estimate>,
    /// Sum of squared residuals, and the residual standard deviation √(SSR / (n − p)).
    pub ssr: f64,
    pub residual_std: f64,
    /// Bayesian information criterion n ln(SSR / n) + p ln n (Schwarz 1978).
    pub bic: f64,
    pub iterations: usize,
    /// Data points and parameters.
    pub points: usize,
}

/// An interval wider than this ratio (upper/lower bound) leaves a positive parameter
/// not identified.
pub const MAX_INTERVAL_RATIO: f64 = 100.0;

const MAX_ITERATIONS: usize = 500;

/// The parameter's value from its search variable u: e^u, or u × `typical` (a linear
/// parameter is searched in units of its start's magnitude, so that every column of the
/// Jacobian has a like scale).
fn to_value(scale: Scale, typical: f64, u: f64) -> f64 {
    match scale {
        Scale::Log => u.exp(),
        Scale::Linear { .. } => u * typical,
    }
}

fn ssr_of<F>(model: &F, y: &[f64], p: &[f64]) -> Option<f64>
where
    F: Fn(&[f64]) -> Option<Vec<f64>>,
{
    let f = model(p)?;
    let s: f64 = f.iter().zip(y).map(|(f, y)| (y - f) * (y - f)).sum();
    s.is_finite().then_some(s)
}

/// Fits `model` (parameter values → one prediction per data point, `None` where the
/// parameters are outside the law's domain) to `y`, starting from `parameters`. `None`
/// when no prediction at the start is finite or there are not more points than parameters.
pub fn fit<F>(model: F, y: &[f64], parameters: &[Parameter]) -> Option<NonlinearFit>
where
    F: Fn(&[f64]) -> Option<Vec<f64>>,
{
    let (n, m) = (y.len(), parameters.len());
    if n <= m || m == 0 {
        return None;
    }
    // a linear parameter's unit: its start's magnitude
    let typical: Vec<f64> = parameters
        .iter()
        .map(|p| match p.scale {
            Scale::Log => 1.0,
            Scale::Linear { .. } if p.start != 0.0 => p.start.abs(),
            Scale::Linear { .. } => 1.0,
        })
        .collect();
    let values = |u: &[f64]| -> Vec<f64> {
        parameters
            .iter()
            .zip(u)
            .zip(&typical)
            .map(|((p, u), t)| to_value(p.scale, *t, *u))
            .collect()
    };
    let clamp = |u: &mut [f64]| {
        for (p, u) in parameters.iter().zip(u.iter_mut()) {
            if let Scale::Linear { non_negative: true } = p.scale {
                *u = u.max(0.0);
            }
        }
    };
    let mut u: Vec<f64> = parameters
        .iter()
        .zip(&typical)
        .map(|(p, t)| match p.scale {
            Scale::Log => p.start.ln(),
            Scale::Linear { .. } => p.start / t,
        })
        .collect();
    if u.iter().any(|u| !u.is_finite()) {
        return None;
    }
    let predict = |u: &[f64]| model(&values(u));
    let mut cost = ssr_of(&model, y, &values(&u))?;
    let jacobian = |u: &[f64]| -> Option<DMatrix<f64>> {
        let mut j = DMatrix::zeros(n, m);
        for k in 0..m {
            let h = 1e-6 * u[k].abs().max(1e-3);
            let mut up = u.to_vec();
            let mut down = u.to_vec();
            up[k] += h;
            down[k] -= h;
            if let Scale::Linear { non_negative: true } = parameters[k].scale {
                down[k] = down[k].max(0.0);
            }
            let (fp, fm) = (predict(&up)?, predict(&down)?);
            let width = up[k] - down[k];
            for i in 0..n {
                j[(i, k)] = (fp[i] - fm[i]) / width;
            }
        }
        j.iter().all(|v| v.is_finite()).then_some(j)
    };
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut j = jacobian(&u)?;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let f = predict(&u)?;
        let r = DVector::from_iterator(n, y.iter().zip(&f).map(|(y, f)| y - f));
        let jtj = j.transpose() * &j;
        let g = j.transpose() * r;
        let mut improved = false;
        while lambda < 1e20 {
            let mut a = jtj.clone();
            for k in 0..m {
                a[(k, k)] += lambda * jtj[(k, k)].max(1e-300);
            }
            let Some(step) = a.cholesky().map(|c| c.solve(&g)) else {
                lambda *= 10.0;
                continue;
            };
            let mut trial: Vec<f64> = u.iter().zip(step.iter()).map(|(u, d)| u + d).collect();
            clamp(&mut trial);
            match ssr_of(&model, y, &values(&trial)) {
                Some(c) if c <= cost => {
                    let small = trial
                        .iter()
                        .zip(&u)
                        .all(|(t, u)| (t - u).abs() <= 1e-13 * u.abs().max(1.0));
                    let gain = cost - c;
                    u = trial;
                    lambda = (lambda / 3.0).max(1e-12);
                    improved = !(small || gain <= 1e-15 * cost);
                    cost = c;
                    break;
                }
                _ => lambda *= 4.0,
            }
        }
        if !improved {
            break;
        }
        j = jacobian(&u)?;
    }
    let j = jacobian(&u)?;
    let dof = (n - m) as f64;
    let s2 = cost / dof;
    let jtj = j.transpose() * &j;
    let svd = jtj.clone().svd(true, true);
    let s_max = svd.singular_values.max();
    let inverse = svd
        .clone()
        .pseudo_inverse(s_max * 1e-13)
        .unwrap_or_else(|_| DMatrix::from_element(m, m, f64::INFINITY));
    let singular = |k: usize| -> bool {
        // the parameter moves along a near-null direction of JᵀJ
        svd.singular_values.iter().enumerate().any(|(i, s)| {
            *s <= s_max * 1e-13 && svd.v_t.as_ref().is_some_and(|v| v[(i, k)].abs() > 1e-3)
        })
    };
    let t = student_t::quantile(0.975, dof);
    let v = values(&u);
    let estimates = parameters
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let se = (s2 * inverse[(k, k)]).max(0.0).sqrt();
            let se = if singular(k) || !se.is_finite() {
                f64::INFINITY
            } else {
                se
            };
            let (ci95, identified) = match p.scale {
                Scale::Log => {
                    let ci = [(u[k] - t * se).exp(), (u[k] + t * se).exp()];
                    (ci, se.is_finite() && ci[1] <= MAX_INTERVAL_RATIO * ci[0])
                }
                Scale::Linear { .. } => {
                    let se = se * typical[k];
                    let ci = [v[k] - t * se, v[k] + t * se];
                    (ci, se.is_finite())
                }
            };
            let se = match p.scale {
                Scale::Log => se,
                Scale::Linear { .. } => se * typical[k],
            };
            Estimate {
                name: p.name.to_string(),
                value: v[k],
                std_error: se,
                ci95: if se.is_finite() {
                    ci95
                } else {
                    [f64::NEG_INFINITY, f64::INFINITY]
                },
                identified,
            }
        })
        .collect();
    let nf = n as f64;
    Some(NonlinearFit {
        estimates,
        ssr: cost,
        residual_std: s2.sqrt(),
        bic: nf * (cost / nf).max(f64::MIN_POSITIVE).ln() + m as f64 * nf.ln(),
        iterations,
        points: n,
    })
}

impl NonlinearFit {
    /// The fitted values, in the parameters' order.
    pub fn values(&self) -> Vec<f64> {
        self.estimates.iter().map(|e| e.value).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An exponential decay y = a e^{−x/b} + c is recovered exactly from exact data, and
    /// with noise its interval holds the truth.
    #[test]
    fn recovers_a_decay() {
        let x: Vec<f64> = (0..60).map(|i| i as f64 * 0.1).collect();
        let truth = [2.0, 1.3, 0.5];
        let law = |p: &[f64]| -> Option<Vec<f64>> {
            Some(x.iter().map(|x| p[0] * (-x / p[1]).exp() + p[2]).collect())
        };
        let y = law(&truth).unwrap();
        let params = [
            Parameter {
                name: "a",
                start: 1.0,
                scale: Scale::Log,
            },
            Parameter {
                name: "b",
                start: 0.3,
                scale: Scale::Log,
            },
            Parameter {
                name: "c",
                start: 0.0,
                scale: Scale::Linear {
                    non_negative: false,
                },
            },
        ];
        let f = fit(law, &y, &params).unwrap();
        for (e, t) in f.estimates.iter().zip(truth) {
            assert!((e.value - t).abs() < 1e-9 * t, "{e:?}");
        }
        let mut rng = crate::synthetic::Rng::new(7);
        let noisy: Vec<f64> = y.iter().map(|y| y + 0.01 * rng.normal()).collect();
        let f = fit(law, &noisy, &params).unwrap();
        for (e, t) in f.estimates.iter().zip(truth) {
            assert!(
                e.identified && e.ci95[0] <= t && t <= e.ci95[1],
                "{e:?} vs {t}"
            );
        }
    }

    /// A parameter the model does not depend on is reported as not identified.
    #[test]
    fn flags_a_parameter_the_data_cannot_fix() {
        let x: Vec<f64> = (0..20).map(|i| i as f64).collect();
        let law = |p: &[f64]| -> Option<Vec<f64>> {
            Some(x.iter().map(|x| p[0] * x + 0.0 * p[1]).collect())
        };
        let y: Vec<f64> = x.iter().map(|x| 3.0 * x + 0.01 * (x * 7.0).sin()).collect();
        let params = [
            Parameter {
                name: "a",
                start: 1.0,
                scale: Scale::Log,
            },
            Parameter {
                name: "b",
                start: 1.0,
                scale: Scale::Log,
            },
        ];
        let f = fit(law, &y, &params).unwrap();
        assert!(f.estimates[0].identified);
        assert!(!f.estimates[1].identified, "{:?}", f.estimates[1]);
    }
}
