//! `relaxing_bar` and `relaxing_beam` (SPEC X2): a rubber hose whose moduli relax as a
//! two-term Prony series, E(t) = E₀ (1 − Σᵢ gᵢ (1 − e^{−t/τᵢ})), under every solver.
//!
//! * `relaxing_bar`: a 0.1 m hose clamped at one end, its other end pulled out by 1 %
//!   over 1 s (the drives' quintic smooth step) and held: the end force follows
//!   Boltzmann's hereditary integral N(t) = E₀A ε₀ ∫₀ᵗ R(t − s) p′(s) ds, R = E/E₀, p the
//!   smooth step — evaluated here by Gauss–Legendre quadrature, independently of the
//!   solvers' recursion.
//! * `relaxing_beam`: the same hose clamped at one end, its other end moved across by
//!   0.1 mm (δ/L = 10⁻³, the linear range) without turning and held (clamped–guided):
//!   the end force is 12 E₀I δ/L³ times the same integral (every modulus relaxes alike,
//!   so the correspondence principle carries the elastic solution over).
//!
//! Relaxation times 0.5 s and 5 s, weights 0.3 and 0.2; the force is compared during the
//! ramp, at its end and over the hold to 10 s. The ramp is slow enough for the hose's own
//! inertia to be negligible (ρA L⁴ p″/(12 E I T²) ≈ 2·10⁻⁴ of the beam's end force),
//! which the hereditary integral leaves out. The relaxing element is exact for strain
//! held or ramped linearly over a step ([`pliant_core::rod::relaxation`]), second order
//! for the smooth step: the implicit solver runs 10 ms steps, the static one 20 ms.

use crate::harness::{build, clamp, hose1, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::loads::{Drive, LoadCase};
use pliant_core::material::{relaxation_ratio, PronyTerm};
use pliant_core::{Material, SimSettings, Solver, SolverKind, SolverSettings, State};

const ELEMENTS: usize = 4;
const LENGTH: f64 = 0.1;
const RAMP: f64 = 1.0;
const TERMS: [PronyTerm; 2] = [
    PronyTerm {
        weight: 0.3,
        time: 0.5,
    },
    PronyTerm {
        weight: 0.2,
        time: 5.0,
    },
];
/// When the force is compared \[s\]: in the ramp, at its end, and during the hold.
const SAMPLES: [f64; 5] = [0.5, 1.0, 2.0, 5.0, 10.0];

/// ∫₀^min(t, RAMP) R(t − s) p′(s) ds for the quintic smooth step p over the ramp: the
/// hereditary integral of a unit strain (20-point Gauss–Legendre on the smooth
/// integrand, exact to round-off).
fn hereditary(t: f64) -> f64 {
    let m = t.min(RAMP);
    let (nodes, weights) = gauss_legendre_20();
    let mut sum = 0.0;
    for (x, w) in nodes.iter().zip(weights) {
        let s = 0.5 * m * (x + 1.0);
        let u = s / RAMP;
        let rate = 30.0 * u * u * (1.0 - u) * (1.0 - u) / RAMP;
        sum += w * 0.5 * m * relaxation_ratio(&TERMS, t - s) * rate;
    }
    sum
}

/// Nodes and weights of the 20-point Gauss–Legendre rule on [−1, 1] (Newton's method on
/// the Legendre polynomial's roots).
fn gauss_legendre_20() -> ([f64; 20], [f64; 20]) {
    const N: usize = 20;
    let (mut x, mut w) = ([0.0; N], [0.0; N]);
    for i in 0..N {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=N {
                let k = k as f64;
                (p0, p1) = (p1, ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k);
            }
            dp = N as f64 * (z * p1 - p0) / (z * z - 1.0);
            let dz = p1 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        x[i] = z;
        w[i] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
    (x, w)
}

fn rubber() -> Material {
    let mut m = hose1().0;
    m.relaxation = TERMS.to_vec();
    m
}

fn solver_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Explicit => "explicit",
        SolverKind::Implicit => "implicit",
        SolverKind::Static => "static",
    }
}

/// Runs the hose with its end driven by `offset` over the ramp and returns
/// (time, end reaction force) at each of [`SAMPLES`].
fn end_forces(kind: SolverKind, offset: DVec3) -> Result<Vec<(f64, DVec3)>, String> {
    let (_, section) = hose1();
    let settings = SimSettings {
        solver: SolverSettings {
            kind,
            implicit_time_step: 0.01,
            static_input_step: 0.02,
            ..Default::default()
        },
        ..static_settings()
    };
    let model = build(
        straight_hose(ELEMENTS, LENGTH, &rubber(), section, |_| DVec3::ZERO),
        settings.clone(),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let end = ELEMENTS;
    let start = (state.x[end], state.q[end]);
    state.loads.add(LoadCase::Drive(Drive::new(
        end,
        start,
        &[start.0 + offset],
        DVec3::ZERO,
        0.0,
        RAMP,
    )));
    let mut solver = Solver::new(&model, settings.solver).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for t in SAMPLES {
        while state.time < t - 1e-9 {
            let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
            if !stats.converged {
                return Err(format!("step at t = {:.3} s did not converge", state.time));
            }
        }
        out.push((state.time, state.reaction_force[end]));
    }
    Ok(out)
}

/// The pulled bar under `kind`.
fn bar(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "relaxing_bar";
    let name = solver_name(kind);
    let strain = 0.01;
    let ea = rubber().e_tension * hose1().1.area();
    match end_forces(kind, DVec3::new(strain * LENGTH, 0.0, 0.0)) {
        Ok(samples) => samples
            .into_iter()
            .map(|(t, f)| {
                Check::relative(
                    CASE,
                    &format!("{name}: end force at {t:.2} s N"),
                    f.x,
                    ea * strain * hereditary(t),
                    1e-3,
                )
            })
            .collect(),
        Err(e) => vec![Check::failed(CASE, name, &e)],
    }
}

/// The clamped–guided beam under `kind`.
fn beam(kind: SolverKind) -> Vec<Check> {
    const CASE: &str = "relaxing_beam";
    let name = solver_name(kind);
    let delta = 1e-3 * LENGTH;
    let material = rubber();
    let ei = material.bending_modulus() * hose1().1.second_moment();
    let elastic = 12.0 * ei * delta / LENGTH.powi(3);
    match end_forces(kind, DVec3::new(0.0, delta, 0.0)) {
        Ok(samples) => samples
            .into_iter()
            .map(|(t, f)| {
                Check::relative(
                    CASE,
                    &format!("{name}: end force at {t:.2} s N"),
                    f.y,
                    elastic * hereditary(t),
                    1e-3,
                )
            })
            .collect(),
        Err(e) => vec![Check::failed(CASE, name, &e)],
    }
}

/// The pulled bar under every solver.
pub fn run_bar() -> Vec<Check> {
    [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ]
    .into_iter()
    .flat_map(bar)
    .collect()
}

/// The clamped–guided beam under every solver.
pub fn run_beam() -> Vec<Check> {
    [
        SolverKind::Explicit,
        SolverKind::Implicit,
        SolverKind::Static,
    ]
    .into_iter()
    .flat_map(beam)
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Long after the ramp (200 of the longest time) the integral is the long-term
    /// modulus ratio 1 − Σ gᵢ to round-off; at the
    /// ramp's end it lies between that and 1 (some relaxation during the ramp).
    #[test]
    fn the_hereditary_integral_of_a_long_hold_is_the_long_term_modulus() {
        let long = hereditary(1000.0);
        let want = 1.0 - TERMS.iter().map(|p| p.weight).sum::<f64>();
        assert!((long - want).abs() < 1e-12, "{long} vs {want}");
        // at the end of an infinitely fast ramp it is 1; at the end of this one, less
        let end = hereditary(RAMP);
        assert!(end < 1.0 && end > want, "{end}");
    }
}
