//! A motion coordinate over time (a hinge's angle, a slide's distance) and its rate,
//! both analytic.
//!
//! - Keyframes: values at increasing times, held before the first and after the last.
//!   Between two keyframes either linearly (constant rate, the rate jumping at the
//!   keyframes) or by the quintic smooth-step s(τ) = 10τ³ − 15τ⁴ + 6τ⁵ (zero rate and
//!   acceleration at every keyframe: a door opened and stopped).
//! - Uniform acceleration from a start time: s = v₀ τ + ½ a τ², τ = t − t₀ ≥ 0 (0 before).

use serde::{Deserialize, Serialize};

/// A scalar coordinate over time (SI: radians or metres, seconds).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Profile {
    Keyframes {
        /// Strictly increasing times \[s\].
        times: Vec<f64>,
        /// The coordinate at each time.
        values: Vec<f64>,
        /// Quintic smooth-step between keyframes (else linear).
        smooth: bool,
    },
    UniformAcceleration {
        start_time: f64,
        /// Rate at the start time.
        initial_rate: f64,
        /// Constant second derivative after the start time.
        acceleration: f64,
    },
}

/// Quintic smooth-step and its derivative in τ ∈ [0, 1].
fn smooth_step(tau: f64) -> (f64, f64) {
    let t = tau.clamp(0.0, 1.0);
    (
        t * t * t * (10.0 + t * (-15.0 + 6.0 * t)),
        30.0 * t * t * (1.0 - t) * (1.0 - t),
    )
}

impl Profile {
    /// Why the profile cannot be used, if it cannot: keyframes that are empty, of
    /// unequal lengths, not finite or not increasing in time; rates not finite.
    pub fn check(&self) -> Result<(), String> {
        match self {
            Profile::Keyframes { times, values, .. } => {
                if times.is_empty() || times.len() != values.len() {
                    return Err(format!(
                        "keyframes need as many values as times, at least one ({} times, {} values)",
                        times.len(),
                        values.len()
                    ));
                }
                if let Some(v) = times.iter().chain(values).find(|v| !v.is_finite()) {
                    return Err(format!("keyframe value is not finite: {v}"));
                }
                if let Some(w) = times.windows(2).find(|w| w[1] <= w[0]) {
                    return Err(format!(
                        "keyframe times must increase ({} then {})",
                        w[0], w[1]
                    ));
                }
                Ok(())
            }
            Profile::UniformAcceleration {
                start_time,
                initial_rate,
                acceleration,
            } => {
                if [start_time, initial_rate, acceleration]
                    .iter()
                    .all(|v| v.is_finite())
                {
                    Ok(())
                } else {
                    Err("start time, rate and acceleration must be finite".into())
                }
            }
        }
    }

    /// The coordinate and its rate at time `t`.
    pub fn at(&self, t: f64) -> (f64, f64) {
        match self {
            Profile::Keyframes {
                times,
                values,
                smooth,
            } => {
                let n = times.len();
                if n == 0 {
                    return (0.0, 0.0);
                }
                if t <= times[0] {
                    return (values[0], 0.0);
                }
                if t >= times[n - 1] {
                    return (values[n - 1], 0.0);
                }
                let k = times.partition_point(|&s| s <= t).clamp(1, n - 1);
                let (t0, t1) = (times[k - 1], times[k]);
                let (v0, v1) = (values[k - 1], values[k]);
                let span = t1 - t0;
                let tau = (t - t0) / span;
                let (s, ds) = if *smooth {
                    smooth_step(tau)
                } else {
                    (tau, 1.0)
                };
                (v0 + (v1 - v0) * s, (v1 - v0) * ds / span)
            }
            Profile::UniformAcceleration {
                start_time,
                initial_rate,
                acceleration,
            } => {
                let tau = (t - start_time).max(0.0);
                if t < *start_time {
                    return (0.0, 0.0);
                }
                (
                    initial_rate * tau + 0.5 * acceleration * tau * tau,
                    initial_rate + acceleration * tau,
                )
            }
        }
    }

    /// A smooth ramp from `from` to `to` over `duration` starting at `start_time`.
    pub fn ramp(from: f64, to: f64, start_time: f64, duration: f64) -> Profile {
        Profile::Keyframes {
            times: vec![start_time, start_time + duration.max(1e-12)],
            values: vec![from, to],
            smooth: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rate is the derivative of the value (central differences).
    #[test]
    fn rates_are_the_derivatives() {
        let profiles = [
            Profile::Keyframes {
                times: vec![0.0, 1.0, 3.0],
                values: vec![0.0, 2.0, -1.0],
                smooth: true,
            },
            Profile::Keyframes {
                times: vec![0.0, 1.0, 3.0],
                values: vec![0.0, 2.0, -1.0],
                smooth: false,
            },
            Profile::UniformAcceleration {
                start_time: 0.5,
                initial_rate: 0.3,
                acceleration: 2.0,
            },
        ];
        for p in &profiles {
            p.check().unwrap();
            for t in [0.6, 1.5, 2.2] {
                let h = 1e-6;
                let numeric = (p.at(t + h).0 - p.at(t - h).0) / (2.0 * h);
                assert!((numeric - p.at(t).1).abs() < 1e-6, "{p:?} at {t}");
            }
        }
        let bad = Profile::Keyframes {
            times: vec![1.0, 1.0],
            values: vec![0.0, 1.0],
            smooth: false,
        };
        assert!(bad.check().is_err());
    }
}
