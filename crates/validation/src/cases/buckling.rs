//! `buckling`: Euler critical loads, clamped–free P_cr = π²EI/4L² and clamped–clamped
//! P_cr = 4π²EI/L², measured with the Southwell plot (Southwell 1932): a column with an
//! imperfection in the shape of its first buckling mode, loaded to P < P_cr, deflects by
//! δ = δ₀ (P/P_cr)/(1 − P/P_cr), so δ/P against δ is a straight line of slope 1/P_cr.
//! The clamped–free column carries a dead end load; the clamped–clamped one is shortened
//! by moving its clamped end, and P is the measured support force.

use crate::harness::{build, clamp, clamp_at, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::loads::{DeadLoad, LoadCase};
use pliant_core::{SimSettings, State};
use std::f64::consts::PI;

const ELEMENTS: usize = 40;
const LOAD_FRACTIONS: [f64; 5] = [0.2, 0.35, 0.5, 0.65, 0.8];
const IMPERFECTION: f64 = 1e-3; // δ₀ / L

/// Least-squares slope of y over x.
fn slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let sxy: f64 = points.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = points.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

fn clamped_free(p_exact: f64) -> Result<f64, String> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let d0 = IMPERFECTION * len;
    let shape = move |x: f64| DVec3::new(0.0, d0 * (1.0 - (PI * x / (2.0 * len)).cos()), 0.0);
    // viscous relaxation, critically damped for the softest state (P = 0.8 P_cr): the
    // lateral mode is too soft for kinetic damping to converge in reasonable time
    let ei = mat.bending_modulus() * sec.second_moment();
    let omega1 = 3.516 * (ei / (mat.density * sec.area() * len.powi(4))).sqrt();
    let softest = omega1 * (1.0 - LOAD_FRACTIONS[LOAD_FRACTIONS.len() - 1]).sqrt();
    let settings = SimSettings {
        damping_mass: 2.0 * softest,
        ..static_settings()
    };
    let model = build(straight_hose(ELEMENTS, len, &mat, sec, shape), settings);
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let rest_tip = model.rest_x[ELEMENTS].y;
    let mut points = Vec::new();
    let mut id = None;
    for f in LOAD_FRACTIONS {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        let p = f * p_exact;
        let load = DeadLoad {
            node: ELEMENTS,
            force: DVec3::new(-p, 0.0, 0.0),
            moment: DVec3::ZERO,
            ramp: None,
        };
        id = Some(state.loads.add(LoadCase::DeadLoad(load)));
        settle_to(&model, &mut state, p_exact, len, 1e-8)?;
        let delta = state.x[ELEMENTS].y - rest_tip;
        points.push((delta, delta / p));
    }
    Ok(1.0 / slope(&points))
}

fn clamped_clamped(p_exact: f64) -> Result<f64, String> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let d0 = IMPERFECTION * len;
    let shape = move |x: f64| DVec3::new(0.0, 0.5 * d0 * (1.0 - (2.0 * PI * x / len).cos()), 0.0);
    let model = build(
        straight_hose(ELEMENTS, len, &mat, sec, shape),
        static_settings(),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let mid = ELEMENTS / 2;
    let rest_mid = model.rest_x[mid].y;
    let ea = mat.e_compression * sec.area();
    let mut points = Vec::new();
    for f in LOAD_FRACTIONS {
        // shorten so that the axial force is about f·P_cr; P itself is measured
        let shortening = f * p_exact * len / ea;
        let (x, q) = (
            model.rest_x[ELEMENTS] - DVec3::new(shortening, 0.0, 0.0),
            model.rest_q[ELEMENTS],
        );
        clamp_at(&mut state, ELEMENTS, x, q);
        settle_to(&model, &mut state, p_exact, len, 1e-8)?;
        let p = -state.reaction_force[ELEMENTS].x; // support pushes the end towards −x
        let delta = state.x[mid].y - rest_mid;
        points.push((delta, delta / p));
    }
    Ok(1.0 / slope(&points))
}

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let ei = mat.bending_modulus() * sec.second_moment();
    let len = 1.0;
    let mut out = Vec::new();
    let cf = PI * PI * ei / (4.0 * len * len);
    match clamped_free(cf) {
        Ok(p) => out.push(Check::relative(
            "buckling",
            "clamped-free P_cr N",
            p,
            cf,
            0.001,
        )),
        Err(e) => out.push(Check::failed("buckling", "clamped-free", &e)),
    }
    let cc = 4.0 * PI * PI * ei / (len * len);
    match clamped_clamped(cc) {
        Ok(p) => out.push(Check::relative(
            "buckling",
            "clamped-clamped P_cr N",
            p,
            cc,
            0.001,
        )),
        Err(e) => out.push(Check::failed("buckling", "clamped-clamped", &e)),
    }
    out
}
