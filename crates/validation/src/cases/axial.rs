//! `axial`: the bimodular axial law (SPEC M3). A clamped hose whose end is pulled out by
//! ΔL carries N = E_t A ΔL/L; pushed in (straight, below buckling) N = E_c A ΔL/L.
//! The push is 0.5 mm: N = 0.80 N, 0.6 × the clamped–clamped Euler load 4π²EI/L² ≈ 1.33 N
//! of hose 1 over 1 m. (It was 1 mm — 1.6 N, past the Euler load — until the static
//! solver learnt to see that the straight state is then unstable and buckled it.)

use crate::harness::{build, clamp, clamp_at, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::State;

const ELEMENTS: usize = 20;

fn end_force(delta: f64) -> Result<f64, String> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let model = build(
        straight_hose(ELEMENTS, len, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let q = state.q[ELEMENTS];
    clamp_at(&mut state, ELEMENTS, DVec3::new(len + delta, 0.0, 0.0), q);
    let scale = mat.e_tension * sec.area() * delta.abs() / len;
    settle_to(&model, &mut state, scale, len, 1e-9)?;
    // the support pulls the end by +N along x
    Ok(state.reaction_force[ELEMENTS].x)
}

pub fn run() -> Vec<Check> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let mut out = Vec::new();
    for (name, delta, e) in [
        ("stretch", 0.01 * len, mat.e_tension),
        ("compression", -0.0005 * len, mat.e_compression),
    ] {
        let exact = e * sec.area() * delta / len;
        match end_force(delta) {
            Ok(f) => out.push(Check::relative(
                "axial",
                &format!("{name} force N"),
                f,
                exact,
                0.001,
            )),
            Err(err) => out.push(Check::failed("axial", name, &err)),
        }
    }
    out
}
