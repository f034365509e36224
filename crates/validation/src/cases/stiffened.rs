//! `stiffened`: a cantilever whose outer quarter is a stiffened (rigid) section (SPEC M6)
//! under a small dead tip load P (λ = PL²/EI = 0.01, linear range). Linear beam theory
//! gives the exact tip deflection of a flexible length a carrying a rigid arm b:
//! the flexible part ends with shear P and moment P·b, so
//! w(a) = P a³/3EI + P b a²/2EI, θ(a) = P a²/2EI + P b a/EI, and the tip lies at
//! w = w(a) + b·θ(a). The stiffened span must also stay undeformed (its node distances
//! unchanged) and move the model's tip within 0.5 % of w.

use crate::harness::{build, clamp, dead_load, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::rod::stiffened::StiffenedSpan;
use pliant_core::State;

const ELEMENTS: usize = 40;
const RIGID_FROM: usize = 30;

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let model = build(
        straight_hose(ELEMENTS, len, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    let model = match model.with_stiffened_spans(&[StiffenedSpan {
        hose: 0,
        first: RIGID_FROM,
        last: ELEMENTS,
    }]) {
        Ok(m) => m,
        Err(e) => return vec![Check::failed("stiffened", "span", &e.to_string())],
    };
    let ei = mat.bending_modulus() * sec.second_moment();
    let p = 0.01 * ei / (len * len);
    let (a, b) = (
        len * RIGID_FROM as f64 / ELEMENTS as f64,
        len * (ELEMENTS - RIGID_FROM) as f64 / ELEMENTS as f64,
    );
    let w_a = p * a.powi(3) / (3.0 * ei) + p * b * a * a / (2.0 * ei);
    let theta_a = p * a * a / (2.0 * ei) + p * b * a / ei;
    let exact = w_a + b * theta_a;
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    state
        .loads
        .add(dead_load(ELEMENTS, DVec3::new(0.0, -p, 0.0), DVec3::ZERO));
    if let Err(e) = settle_to(&model, &mut state, p, len, 1e-6) {
        return vec![Check::failed("stiffened", "relaxation", &e)];
    }
    let tip = -state.x[ELEMENTS].y;
    let stretch = (RIGID_FROM..ELEMENTS)
        .map(|i| ((state.x[i + 1] - state.x[i]).length() - len / ELEMENTS as f64).abs())
        .fold(0.0, f64::max);
    vec![
        Check::relative(
            "stiffened",
            "tip deflection with rigid outer quarter m",
            tip,
            exact,
            0.005,
        ),
        Check::with_error(
            "stiffened",
            "change of node spacing in the rigid span m (abs)",
            stretch,
            0.0,
            stretch,
            1e-12,
        ),
    ]
}
