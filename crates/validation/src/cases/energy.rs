//! `energy`: without damping the explicit integrator conserves the total energy
//! (kinetic + strain) of a freely vibrating cantilever: launched with a velocity field in
//! the shape of its static deflection line (tip speed ≈ 0.2 L·ω₁), it swings for 10 s and
//! the energy must stay within 1 % of its initial value.

use crate::harness::{build, clamp, hose1, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::{integrators::explicit, SimSettings, State};

const ELEMENTS: usize = 20;
const DURATION: f64 = 10.0;

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let settings = SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 0.0,
        damping_stiffness: Some(0.0),
        ..Default::default()
    };
    let model = build(
        straight_hose(ELEMENTS, len, &mat, sec, |_| DVec3::ZERO),
        settings,
    );
    let ei = mat.bending_modulus() * sec.second_moment();
    let omega1 = 1.875f64.powi(2) * (ei / (mat.density * sec.area() * len.powi(4))).sqrt();
    let tip_speed = 0.2 * len * omega1;
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    for i in 1..=ELEMENTS {
        let s = model.rest_x[i].x / len;
        // static deflection line of a tip-loaded cantilever, s²(3 − s)/2, and its slope
        state.v[i] = DVec3::new(0.0, tip_speed * s * s * (3.0 - s) / 2.0, 0.0);
        state.w[i] = DVec3::new(0.0, 0.0, tip_speed / len * 3.0 * s * (2.0 - s) / 2.0);
    }
    let total = |st: &State| st.kinetic_energy(&model) + st.strain_energy(&model);
    let e0 = total(&state);
    let steps = (DURATION / model.time_step).round() as u64;
    let mut worst: f64 = 0.0;
    for k in 0..steps {
        explicit::step(&model, &mut state);
        if k % 50 == 0 {
            worst = worst.max((total(&state) - e0).abs() / e0);
        }
    }
    let e_end = total(&state);
    vec![
        Check::with_error(
            "energy",
            "max |E(t)-E0|/E0 over 10 s",
            worst,
            0.0,
            worst,
            0.01,
        ),
        Check::relative("energy", "E(10 s) J", e_end, e0, 0.01),
    ]
}
