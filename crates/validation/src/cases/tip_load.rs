//! `tip_load`: cantilever under a dead tip load normal to its axis (large-deflection
//! elastica). Exact tip deflections for λ = PL²/EI from the elliptic-integral solution
//! (Bisshopp & Drucker 1945; Mattiasson 1981, table 1).

use crate::harness::{build, clamp, dead_load, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::State;

/// (λ, w/L, −u/L), Mattiasson 1981.
pub const EXACT: [(f64, f64, f64); 4] = [
    (1.0, 0.301721, 0.056433),
    (2.0, 0.493457, 0.160642),
    (5.0, 0.713792, 0.387628),
    (10.0, 0.810609, 0.554996),
];

const ELEMENTS: usize = 40;
const TOLERANCE: f64 = 0.001;

/// Tip position (w/L, −u/L) of an `n`-element cantilever of length 1 m under λ.
pub fn tip_deflection(n: usize, lambda: f64) -> Result<(f64, f64), String> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let model = build(
        straight_hose(n, len, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    let ei = mat.bending_modulus() * sec.second_moment();
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    // load in increments so relaxation follows the equilibrium path
    let mut id = None;
    let p_full = lambda * ei / (len * len);
    for k in 1..=4 {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        let p = p_full * k as f64 / 4.0;
        id = Some(
            state
                .loads
                .add(dead_load(n, DVec3::new(0.0, -p, 0.0), DVec3::ZERO)),
        );
        settle_to(&model, &mut state, p_full, len, 1e-9)?;
    }
    let tip = state.x[n];
    Ok((-tip.y / len, (len - tip.x) / len))
}

pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    for (lambda, w, u) in EXACT {
        match tip_deflection(ELEMENTS, lambda) {
            Ok((cw, cu)) => {
                out.push(Check::relative(
                    "tip_load",
                    &format!("w/L at lambda={lambda}"),
                    cw,
                    w,
                    TOLERANCE,
                ));
                out.push(Check::relative(
                    "tip_load",
                    &format!("-u/L at lambda={lambda}"),
                    cu,
                    u,
                    TOLERANCE,
                ));
            }
            Err(e) => out.push(Check::failed("tip_load", &format!("lambda={lambda}"), &e)),
        }
    }
    out
}
