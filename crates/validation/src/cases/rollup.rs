//! `rollup`: a cantilever under an end moment bends into an exact circular arc of
//! curvature M/EI. M = 2πEI/L closes a full circle (tip back at the root); M = πEI/L
//! makes a half circle with the tip at w = 2L/π, u = −L. Self contact is off here.

use crate::harness::{build, clamp, hose1, settle_to, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::loads::{DeadLoad, LoadCase};
use pliant_core::State;
use std::f64::consts::PI;

const ELEMENTS: usize = 40;

fn tip_under_moment(fraction_of_turn: f64) -> Result<DVec3, String> {
    let (mat, sec) = hose1();
    let len = 1.0;
    let mut model = build(
        straight_hose(ELEMENTS, len, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    let ei = mat.bending_modulus() * sec.second_moment();
    let m_full = fraction_of_turn * 2.0 * PI * ei / len;
    // the full circle brings the tip back onto the root: switch self contact off, this
    // case tests the element, not contact (which would rightly stop the tip short)
    model.hose_contact.active = false;
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let mut id = None;
    let steps = 8;
    for k in 1..=steps {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        let m = m_full * k as f64 / steps as f64;
        let load = DeadLoad {
            node: ELEMENTS,
            force: DVec3::ZERO,
            moment: DVec3::new(0.0, 0.0, m),
            ramp: None,
        };
        id = Some(state.loads.add(LoadCase::DeadLoad(load)));
        settle_to(&model, &mut state, m_full / len, len, 1e-8)?;
    }
    Ok(state.x[ELEMENTS] - state.x[0])
}

pub fn run() -> Vec<Check> {
    let len = 1.0;
    let mut out = Vec::new();
    match tip_under_moment(1.0) {
        Ok(d) => out.push(Check::scaled(
            "rollup",
            "tip-root distance / L at M=2*pi*EI/L",
            d.length(),
            0.0,
            len,
            0.001,
        )),
        Err(e) => out.push(Check::failed("rollup", "full circle", &e)),
    }
    match tip_under_moment(0.5) {
        Ok(d) => {
            out.push(Check::relative(
                "rollup",
                "tip w/L at M=pi*EI/L",
                d.y / len,
                2.0 / PI,
                0.001,
            ));
            out.push(Check::scaled(
                "rollup",
                "tip x/L at M=pi*EI/L (error of L)",
                d.x / len,
                0.0,
                1.0,
                0.001,
            ));
        }
        Err(e) => out.push(Check::failed("rollup", "half circle", &e)),
    }
    out
}
