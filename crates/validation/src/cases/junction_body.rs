//! `junction_body` and `junction_body_torsion`: a junction body with its own centre of
//! mass and inertia (SPEC N1; `[[junctions]] body = { mass_kg, centre_of_mass,
//! inertia_kg_m2 }`), written in a scene file as a user's would be. A hose `a` along x,
//! clamped at its start, carries at its end a rigid piece whose other outlet starts a
//! short hose `b` further along x; both outlets lie on the x axis.
//!
//! * `junction_body` (static, under every solver): under gravity −g ẑ the piece's centre
//!   of mass lies e beside the axis (at (x_c, e, 0)). Statics of the rest shape give the
//!   clamp's reaction moment exactly for small deflections: the torsion M_x = m g e (the
//!   hoses' nodes lie on the axis and add none) and the bending
//!   M_y = −g (m x_c + Σ m_i x_i) over the hoses' lumped masses. The hoses are stiff
//!   (EI = GJ = 10³ N·m²), so the rest shape moves the lever arms by second-order terms
//!   of the slopes (≲ 1e-4 rad): 1e-6 relative. (Lumped on the outlets, as a body
//!   without its own centre of mass is, the weight would give no torsion at all.)
//! * `junction_body_torsion` (dynamic, explicit and implicit): without gravity, hose `a`
//!   (GJ/L = 0.08 N·m) is a torsion spring for the piece, centred on the axis with its
//!   own moment of inertia I_x about it. Started twisting at a small rate, it turns at
//!   ω = √(k / I), k = GJ/L, I = I_x + Σ_a I_i (x_i/L)² + Σ_b I_i (the hoses' nodal
//!   polar inertias, hose `a`'s by Rayleigh's linear mode shape: 2e-3 of I_x): the period
//!   within 1 %. Lumped on the outlets (on the axis), the piece would have no inertia
//!   about it and the hoses' alone would set a far shorter period (a unit test here
//!   shows it missing by more than half).

use super::frames::network_with;
use crate::harness::{clamp, settle_to};
use crate::Check;
use glam::DVec3;
use pliant_core::integrators::{explicit, ImplicitOptions, ImplicitSolver};
use pliant_core::math::log_map;
use pliant_core::{Model, State};

const G: f64 = 9.81;
/// Hose `a`'s length and the outlets' gap \[m\].
const L: f64 = 0.5;
const GAP: f64 = 0.04;
const B_LENGTH: f64 = 0.1;

/// The two hoses and the body table (`body` TOML inline-table text).
fn scene(gravity: DVec3, stiffness: (f64, f64, f64), body: &str) -> Result<Model, String> {
    network_with(
        &[
            ("a", DVec3::ZERO, DVec3::new(L, 0.0, 0.0)),
            (
                "b",
                DVec3::new(L + GAP, 0.0, 0.0),
                DVec3::new(L + GAP + B_LENGTH, 0.0, 0.0),
            ),
        ],
        &format!(
            "\n[[junctions]]\nname = \"piece\"\nends = [{{ hose = \"a\", end = \"end\" }}, {{ hose = \"b\", end = \"start\" }}]\nbody = {body}\n"
        ),
        gravity,
        stiffness,
    )
}

/// The static case: the clamp's reaction moment against statics of the rest shape.
pub fn run_static() -> Vec<Check> {
    let (mass, e, x_c) = (0.2, 0.05, L + 0.5 * GAP);
    let body = format!(
        "{{ mass_kg = {mass}, centre_of_mass = [{x_c}, {e}, 0], inertia_kg_m2 = [2e-4, 3e-4, 3e-4] }}"
    );
    let model = match scene(DVec3::new(0.0, 0.0, -G), (1e6, 1e3, 1e3), &body) {
        Ok(m) => m,
        Err(e) => return vec![Check::failed("junction_body", "scene", &e)],
    };
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let weight = G * (mass + model.mass.iter().sum::<f64>());
    if let Err(why) = settle_to(&model, &mut state, weight, L, 3e-8) {
        return vec![Check::failed("junction_body", "rest", &why)];
    }
    let torsion = mass * G * e;
    let lever: f64 = (0..model.node_count())
        .map(|i| model.mass[i] * model.rest_x[i].x)
        .sum::<f64>()
        + mass * x_c;
    let bending = -G * lever;
    let r = state.reaction_moment[0];
    vec![
        Check::relative(
            "junction_body",
            "clamp torsion moment / m g e (centre of mass e beside the axis)",
            r.x / torsion,
            1.0,
            1e-6,
        ),
        Check::relative(
            "junction_body",
            "clamp bending moment / −g (m x_c + Σ m_i x_i)",
            r.y / bending,
            1.0,
            1e-6,
        ),
    ]
}

/// Which solver runs the free torsional oscillation.
#[derive(Clone, Copy)]
enum Dynamic {
    Explicit,
    Implicit,
}

/// The body's own moment of inertia about the axis \[kg·m²\] and its mass \[kg\].
const I_X: f64 = 2e-4;
const BODY_MASS: f64 = 0.05;
/// The torsion spring GJ \[N·m²\].
const GJ: f64 = 0.04;
/// The centre of mass's distance beside the axis in the offset variant \[m\].
const OFFSET: f64 = 0.05;

/// A torsion scene: the body's centre of mass `e` beside the axis (0: on it), the
/// hoses' bending stiffness EI; `lumped`: the body's mass lumped on its outlets instead.
fn torsion_scene(e: f64, ei: f64, lumped: bool) -> Result<Model, String> {
    let body = if lumped {
        format!("{{ mass_kg = {BODY_MASS} }}")
    } else {
        format!(
            "{{ mass_kg = {BODY_MASS}, centre_of_mass = [{}, {e}, 0], inertia_kg_m2 = [{I_X}, 3e-4, 3e-4] }}",
            L + 0.5 * GAP
        )
    };
    // EA/EI as a solid rod's, A/I = 16/d² (a given section's rotary inertia ρI follows
    // the ratio)
    scene(DVec3::ZERO, (ei * 4e4, ei, GJ), &body)
}

/// 2π√(I/k) with k = GJ/L and I = I_x + m e² (parallel axes) with the hoses' share
/// (module doc).
fn expected_period(model: &Model, e: f64) -> f64 {
    let k = GJ / L;
    let a = model.hoses[0]
        .nodes()
        .map(|i| model.inertia[i] * (model.rest_x[i].x / L).powi(2))
        .sum::<f64>();
    let b = model.hoses[1]
        .nodes()
        .map(|i| model.inertia[i])
        .sum::<f64>();
    2.0 * std::f64::consts::PI * ((I_X + BODY_MASS * e * e + a + b) / k).sqrt()
}

/// The torsion case: the period of the free oscillation, the body's centre of mass on
/// the axis (the hoses soft in bending, EI = 0.05 N·m²) under each dynamic solver, and
/// beside it (stiff in bending, EI = 500 N·m², so that the axis stays put: the hose's
/// lateral spring 3EI/L³ holds the body at ω_lat ≈ 490 rad/s against ω ≈ 16 rad/s)
/// under the implicit solver.
pub fn run_torsion() -> Vec<Check> {
    let mut out = Vec::new();
    const BOTH: &[(Dynamic, &str)] = &[
        (Dynamic::Explicit, "explicit"),
        (Dynamic::Implicit, "implicit"),
    ];
    // explicitly, the stiff hose would take 10⁴ times the steps (Δt ∝ 1/√EI)
    const IMPLICIT: &[(Dynamic, &str)] = &[(Dynamic::Implicit, "implicit")];
    for (e, ei, what, solvers) in [
        (
            0.0,
            0.05,
            "period, centre of mass on the axis / 2π√(I_x/k)",
            BOTH,
        ),
        (
            OFFSET,
            500.0,
            "period, centre of mass e beside the axis / 2π√((I_x + m e²)/k)",
            IMPLICIT,
        ),
    ] {
        let model = match torsion_scene(e, ei, false) {
            Ok(m) => m,
            Err(why) => {
                out.push(Check::failed("junction_body_torsion", "scene", &why));
                continue;
            }
        };
        let period = expected_period(&model, e);
        for &(solver, name) in solvers {
            let what = format!("{what} [{name}]");
            match measured_period(&model, solver, period) {
                Ok(t) => out.push(Check::relative(
                    "junction_body_torsion",
                    &what,
                    t,
                    period,
                    0.01,
                )),
                Err(why) => out.push(Check::failed("junction_body_torsion", &what, &why)),
            }
        }
    }
    out
}

/// Sets the hoses twisting about x at rate `rate` at the body (linearly along hose `a`,
/// rigidly with the body along hose `b`), runs three expected periods with `solver` and
/// returns the period from the zero crossings of the body's twist.
fn measured_period(model: &Model, solver: Dynamic, expected: f64) -> Result<f64, String> {
    let mut state = State::at_rest(model);
    clamp(&mut state, 0);
    let rate = 0.01 * 2.0 * std::f64::consts::PI / expected;
    for i in model.hoses[0].nodes() {
        state.w[i] = DVec3::new(rate * model.rest_x[i].x / L, 0.0, 0.0);
    }
    for i in model.hoses[1].nodes() {
        state.w[i] = DVec3::new(rate, 0.0, 0.0);
    }
    for body in state.bodies.iter_mut() {
        body.angular_velocity = DVec3::new(rate, 0.0, 0.0);
        // turning about the axis, the centre of mass beside it moves
        let arm = DVec3::new(0.0, body.centre.y, body.centre.z);
        body.velocity = body.angular_velocity.cross(arm);
    }
    let master = model.junctions[0].nodes[0];
    let twist = |state: &State| log_map(state.q[master] * model.rest_q[master].conjugate()).x;
    let mut implicit = match solver {
        Dynamic::Explicit => None,
        Dynamic::Implicit => Some(
            ImplicitSolver::new(
                model,
                ImplicitOptions {
                    time_step: expected / 400.0,
                    ..Default::default()
                },
            )
            .map_err(|e| e.to_string())?,
        ),
    };
    let mut crossings = Vec::new();
    let mut before = (state.time, twist(&state));
    while state.time < 3.2 * expected {
        match implicit.as_mut() {
            None => explicit::step(model, &mut state),
            Some(s) => {
                s.step(model, &mut state).map_err(|e| e.to_string())?;
            }
        }
        let now = (state.time, twist(&state));
        if !now.1.is_finite() {
            return Err(format!("the twist is {} at t = {} s", now.1, now.0));
        }
        if before.1 != 0.0 && now.1 * before.1 <= 0.0 && now.1 != before.1 {
            crossings.push(before.0 + (now.0 - before.0) * before.1 / (before.1 - now.1));
        }
        before = now;
    }
    if crossings.len() < 4 {
        return Err(format!(
            "{} zero crossings of the twist in {:.3} s",
            crossings.len(),
            state.time
        ));
    }
    // half a period between consecutive crossings
    let n = crossings.len();
    Ok(2.0 * (crossings[n - 1] - crossings[0]) / (n - 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The torsion case tells the body's own inertia from the old lumping: with the
    /// mass lumped on its outlets (on the axis) the measured period misses 2π√(I/k) by
    /// far more than the case's 1 %.
    #[test]
    fn lumped_inertia_would_fail_the_torsion_case() {
        let model = torsion_scene(0.0, 0.05, false).unwrap();
        let lumped = torsion_scene(0.0, 0.05, true).unwrap();
        let period = expected_period(&model, 0.0);
        let t = measured_period(&lumped, Dynamic::Explicit, period).unwrap();
        eprintln!("lumped: period {t} s against {period} s");
        assert!((t - period).abs() / period > 0.5, "{t} vs {period}");
    }
}
