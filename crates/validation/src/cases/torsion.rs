//! `torsion`: a clamped hose whose end is turned by φ about its axis needs the end torque
//! G J φ / L, with G = E_b / (2(1 + ν)) (SPEC M2, M3).

use crate::harness::{build, clamp, clamp_at, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::State;

const ELEMENTS: usize = 20;

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let phi = 0.5;
    let gj = mat.shear_modulus() * sec.polar_moment();
    let exact = gj * phi / len;
    let model = build(
        straight_hose(ELEMENTS, len, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let (x, q) = (state.x[ELEMENTS], state.q[ELEMENTS]);
    clamp_at(
        &mut state,
        ELEMENTS,
        x,
        DQuat::from_axis_angle(DVec3::X, phi) * q,
    );
    match settle_to(&model, &mut state, exact / len, len, 1e-10) {
        Ok(_) => vec![Check::relative(
            "torsion",
            "end torque N*m",
            state.reaction_moment[ELEMENTS].x,
            exact,
            0.001,
        )],
        Err(e) => vec![Check::failed("torsion", "end torque", &e)],
    }
}
