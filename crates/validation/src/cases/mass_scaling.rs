//! `mass_scaling`: a mass scaling s changes the dynamics exactly as scaling the inertia
//! should and the statics not at all. A cantilever (hose 1, 1 m, 20 elements) with
//! s = 100:
//!
//! * its sag under its own weight, settled by the explicit solver with mass damping,
//!   equals the static solver's (which has no inertia) and the unscaled explicit run's;
//! * its stable step is √s = 10 times the unscaled one (the highest frequency estimate
//!   and the axial bound both fall by √s, exactly);
//! * its first bending period, swinging freely, is √s times the closed form
//!   2π / (1.8751² √(EI / μL⁴)) of the Euler–Bernoulli cantilever.

use crate::harness::{build, clamp, hose1, settle_to, straight_hose, with_solver};
use crate::Check;
use glam::DVec3;
use pliant_core::{integrators::explicit, Model, SimSettings, SolverKind, State};

const ELEMENTS: usize = 20;
const LENGTH: f64 = 1.0;
const SCALING: f64 = 100.0;
/// β₁L of the first cantilever mode (cos βL cosh βL = −1).
const BETA1_L: f64 = 1.875_104_068_711_961;

fn model(scaling: f64, gravity: DVec3, damping_mass: f64) -> Model {
    let (mat, sec) = hose1();
    build(
        straight_hose(ELEMENTS, LENGTH, &mat, sec, |_| DVec3::ZERO),
        SimSettings {
            gravity,
            damping_mass,
            mass_scaling: scaling,
            ..Default::default()
        },
    )
}

/// Tip deflection (−y) of the cantilever sagging under gravity −g ŷ, settled by `solver`.
fn sag(scaling: f64, solver: SolverKind) -> Result<f64, String> {
    let model = model(scaling, DVec3::new(0.0, -9.81, 0.0), 20.0);
    let weight: f64 = model.mass.iter().sum::<f64>() * model.gravity.length();
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    with_solver(solver, || {
        settle_to(&model, &mut state, weight, LENGTH, 1e-7)
    })?;
    Ok(-state.x[ELEMENTS].y)
}

/// Period of the tip's free swing: launched in the shape of the static deflection line,
/// no mass damping, timed between the first and the fourth upward zero crossing.
fn period(model: &Model) -> Result<f64, String> {
    let mut state = State::at_rest(model);
    clamp(&mut state, 0);
    for i in 1..=ELEMENTS {
        let s = model.rest_x[i].x / LENGTH;
        state.v[i] = DVec3::new(0.0, 1e-3 * s * s * (3.0 - s) / 2.0, 0.0);
        state.w[i] = DVec3::new(0.0, 0.0, 1e-3 / LENGTH * 3.0 * s * (2.0 - s) / 2.0);
    }
    let mut crossings = Vec::new();
    let mut before = state.x[ELEMENTS].y;
    let mut t = 0.0;
    while crossings.len() < 4 {
        explicit::step(model, &mut state);
        t += model.time_step;
        let now = state.x[ELEMENTS].y;
        if before < 0.0 && now >= 0.0 {
            // linear interpolation of the crossing within the step
            crossings.push(t - model.time_step * now / (now - before));
        }
        before = now;
        if t > 1e4 {
            return Err("the tip did not swing through zero in 10⁴ s".into());
        }
    }
    Ok((crossings[3] - crossings[0]) / 3.0)
}

pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    let reference = sag(1.0, SolverKind::Static);
    for (what, got) in [
        (
            "tip sag, explicit, s = 100 / static",
            sag(SCALING, SolverKind::Explicit),
        ),
        (
            "tip sag, explicit, s = 1 / static",
            sag(1.0, SolverKind::Explicit),
        ),
        (
            "tip sag, static, s = 100 / static, s = 1",
            sag(SCALING, SolverKind::Static),
        ),
    ] {
        match (&got, &reference) {
            (Ok(got), Ok(exact)) => {
                out.push(Check::relative("mass_scaling", what, *got, *exact, 1e-5))
            }
            (Err(why), _) | (_, Err(why)) => out.push(Check::failed("mass_scaling", what, why)),
        }
    }
    let plain = model(1.0, DVec3::ZERO, 0.0);
    let scaled = model(SCALING, DVec3::ZERO, 0.0);
    let (a, b) = (&plain.time_step_report, &scaled.time_step_report);
    out.push(Check::relative(
        "mass_scaling",
        "highest-frequency bound, s = 100 / s = 1",
        b.eigen_bound / a.eigen_bound,
        SCALING.sqrt(),
        1e-9,
    ));
    out.push(Check::relative(
        "mass_scaling",
        "axial bound, s = 100 / s = 1",
        b.axial_bound / a.axial_bound,
        SCALING.sqrt(),
        1e-12,
    ));
    let (mat, sec) = hose1();
    let ei = mat.bending_modulus() * sec.second_moment();
    let mu = mat.density * sec.area();
    let omega1 = BETA1_L.powi(2) * (ei / (mu * LENGTH.powi(4))).sqrt();
    let exact = 2.0 * std::f64::consts::PI / omega1 * SCALING.sqrt();
    let what = "first bending period, s = 100 / √s 2π/ω₁";
    match period(&scaled) {
        Ok(t) => out.push(Check::relative("mass_scaling", what, t, exact, 0.01)),
        Err(why) => out.push(Check::failed("mass_scaling", what, &why)),
    }
    out
}
