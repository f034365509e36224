//! The stable time step of the explicit integrator (SPEC P4), computed from the model.
//!
//! Central differences are stable for Δt ≤ 2/ω_max (ω_max the highest natural frequency).
//! The thesis's bound (eq. 4.63) is the axial one, Δt ≤ l_min/c with c = √(E/ρ), which
//! equals 2/ω_max for the axial mode of a lumped chain; the dissertation's worked example
//! mixes N/mm² with g/mm³ and overstates it by √1000 — here everything is SI
//! (E = 12.36 MPa, ρ = 940 kg/m³ → c ≈ 115 m/s, Δt ≈ 0.87 ms for l = 100 mm).
//! Bending and rotation can be stiffer than the axial mode for short elements, so ω_max is
//! also estimated by power iteration on M⁻¹K (K by finite differences of the element
//! loads at the rest shape), and the smaller bound is used. Mass-proportional damping α
//! and stiffness-proportional damping β lower the limit to (2/ω)(√(1+ξ²) − ξ), with
//! ξ = α/2ω + βω/2 the highest mode's damping ratio (Belytschko, Liu & Moran §6.2).

use crate::math::exp_map;
use crate::model::ModelError;
use crate::rod::forces::internal_loads;
use crate::rod::inelastic::HistoryView;
use crate::rod::node_view::NodeView;
use crate::spec::SimSettings;
use crate::Model;
use glam::DVec3;
use serde::Serialize;

/// How the time step was chosen (all in seconds).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TimeStepReport {
    /// l_min / c, the axial (thesis) bound without safety factor.
    pub axial_bound: f64,
    /// 2 / ω_max from power iteration, without safety factor.
    pub eigen_bound: f64,
    /// The estimated highest natural frequency ω_max \[rad/s\].
    pub max_frequency: f64,
    /// The stiffness-proportional damping β used \[s\].
    pub damping_stiffness: f64,
    /// The undamped-safe critical step with damping reduction, before the safety factor.
    pub critical: f64,
    /// Safety factor applied.
    pub safety: f64,
    /// The step used.
    pub chosen: f64,
}

/// Largest damping ratio ξ of the highest mode taken as meant: a larger one shortens the
/// explicit step by about 2ξ and damps every mode of interest to a standstill.
pub const MAX_DAMPING_RATIO: f64 = 1e4;

/// Default stiffness-proportional damping: damping ratio 5 % at ω_max, fading as 1/ω
/// towards low modes (negligible on the hose's swinging modes).
const DEFAULT_HIGH_MODE_DAMPING_RATIO: f64 = 0.05;

pub fn stable_time_step(
    model: &Model,
    settings: &SimSettings,
) -> Result<TimeStepReport, ModelError> {
    let axial_bound = model
        .elements
        .iter()
        .map(|e| {
            let ea = e.axial_stiffness_tension.max(e.axial_stiffness_compression);
            e.rest_length / (ea / e.mass_per_length).sqrt() // l₀ / c, c = √(EA/ρA)
        })
        .fold(f64::INFINITY, f64::min)
        * model.mass_scaling.sqrt(); // c falls by √s with the inertia
    let omega = max_frequency(model);
    let eigen_bound = 2.0 / omega;
    // the default β of the unscaled model: a mass scaling s leaves the damping force
    // β K v as it was (ω_max of the unscaled model is √s ω)
    let beta = settings
        .damping_stiffness
        .unwrap_or(2.0 * DEFAULT_HIGH_MODE_DAMPING_RATIO / (omega * model.mass_scaling.sqrt()));
    // Rayleigh damping ratio of the highest mode: mass part α/2ω, stiffness part βω/2
    let xi = 0.5 * settings.damping_mass / omega + 0.5 * beta * omega;
    let undamped = axial_bound.min(eigen_bound);
    // (2/ω)(√(1+ξ²) − ξ) written as (2/ω)/(√(1+ξ²) + ξ): no overflow or cancellation
    let critical = undamped / (1.0f64.hypot(xi) + xi);
    if !(critical > 0.0 && critical.is_finite() && xi <= MAX_DAMPING_RATIO) {
        return Err(ModelError::Settings(format!(
            "no stable time step: the damping (simulation.damping_mass_per_s = {}, \
             simulation.damping_stiffness_s = {beta:e}) gives the highest mode a damping \
             ratio of {xi:.3e}; above {MAX_DAMPING_RATIO:e} it only makes the explicit step \
             that many times shorter (lower the damping)",
            settings.damping_mass
        )));
    }
    let safety = settings.time_step_safety;
    let chosen = match settings.time_step {
        Some(dt) if dt > critical => {
            return Err(ModelError::Settings(format!(
                "time step {dt:.3e} s exceeds the stable limit {critical:.3e} s of this model \
                 (shortest element / wave speed); leave time_step unset to choose it automatically"
            )))
        }
        Some(dt) => dt,
        None => safety * critical,
    };
    Ok(TimeStepReport {
        axial_bound,
        eigen_bound,
        max_frequency: omega,
        damping_stiffness: beta,
        critical,
        safety,
        chosen,
    })
}

/// Highest natural frequency ω_max of the linearised model at rest, by power iteration on
/// M⁻¹K with K·u from central differences of the internal loads (60 iterations;
/// the estimate converges from below, so it is padded by 2 %).
pub fn max_frequency(model: &Model) -> f64 {
    let n = model.node_count();
    let zero = vec![DVec3::ZERO; n];
    let mut u_x: Vec<DVec3> = (0..n).map(|i| pseudo_random_dir(i, 0)).collect();
    let mut u_r: Vec<DVec3> = (0..n).map(|i| pseudo_random_dir(i, 1)).collect();
    let (mut fp, mut mp, mut fm, mut mm) = (zero.clone(), zero.clone(), zero.clone(), zero.clone());
    let mut xp = model.rest_x.clone();
    let mut xm = model.rest_x.clone();
    let mut qp = model.rest_q.clone();
    let mut qm = model.rest_q.clone();
    let scale = model
        .elements
        .iter()
        .map(|e| e.rest_length)
        .fold(f64::INFINITY, f64::min)
        * 1e-6;
    for _ in 0..60 {
        let norm = (u_x
            .iter()
            .chain(&u_r)
            .map(|v| v.length_squared())
            .sum::<f64>())
        .sqrt();
        for v in u_x.iter_mut().chain(u_r.iter_mut()) {
            *v /= norm;
        }
        for i in 0..n {
            xp[i] = model.rest_x[i] + scale * u_x[i];
            xm[i] = model.rest_x[i] - scale * u_x[i];
            qp[i] = exp_map(scale * u_r[i]) * model.rest_q[i];
            qm[i] = exp_map(-scale * u_r[i]) * model.rest_q[i];
        }
        internal_loads(
            model,
            &NodeView {
                x: &xp,
                q: &qp,
                v: &zero,
                w: &zero,
                inelastic_history: HistoryView::NONE,
            },
            0.0,
            &mut fp,
            &mut mp,
        );
        internal_loads(
            model,
            &NodeView {
                x: &xm,
                q: &qm,
                v: &zero,
                w: &zero,
                inelastic_history: HistoryView::NONE,
            },
            0.0,
            &mut fm,
            &mut mm,
        );
        // u ← M⁻¹ K u, with K u = −(f(u·h) − f(−u·h)) / 2h; |M⁻¹ K u| → λ_max
        for i in 0..n {
            u_x[i] = -(fp[i] - fm[i]) / (2.0 * scale * model.mass[i]);
            u_r[i] = -(mp[i] - mm[i]) / (2.0 * scale * model.inertia[i]);
        }
    }
    // u had unit norm before the last product, so |M⁻¹ K u| is the eigenvalue estimate
    let lambda: f64 = u_x
        .iter()
        .chain(&u_r)
        .map(|v| v.length_squared())
        .sum::<f64>()
        .sqrt();
    1.02 * lambda.max(1e-300).sqrt()
}

/// A fixed pseudo-random unit-ish direction per node (deterministic).
fn pseudo_random_dir(i: usize, salt: u64) -> DVec3 {
    let mut h =
        (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ salt.wrapping_mul(0xD1B5_4A32_D192_ED03);
    let mut next = || {
        h ^= h >> 33;
        h = h.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
        h ^= h >> 33;
        (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    DVec3::new(next(), next(), next())
}
