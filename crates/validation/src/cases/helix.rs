//! `helix`: a cantilever under a dead end moment m oblique to its axis winds into an
//! exact helix — a twisted 3-D shape (Kirchhoff rod, no force anywhere so no stretch).
//!
//! With no force the internal moment is m everywhere; m = EI d₁ × d₁′ + GJ τ d₁ gives
//! d₁′ = (m/EI) × d₁: the tangent turns about m̂ at the rate k = |m|/EI, and the material
//! frame's angular rate is ω = k m̂ + c d₁ with c = (m·d₁)(1/GJ − 1/EI), constant since
//! m·d₁ is. So R(s) = Rot(m̂, k s)·Rot(x̂, c s)·R₀ and, with x̂ = a m̂ + b û,
//! x(L) = a L m̂ + b [sin(kL)/k û + (1 − cos kL)/k (m̂ × û)].

use crate::harness::{
    build, clamp, dead_load, hose1, settle_to, static_settings, straight_hose, with_solver,
};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::{SolverKind, State};
use std::f64::consts::PI;

const ELEMENTS: usize = 40;
const L: f64 = 1.0;
/// Angle between the moment and the hose axis, and the turn k L of the tangent about it.
const MOMENT_ANGLE: f64 = PI / 3.0;
const TURN: f64 = 1.5 * PI;
/// 0.1 % of L on the tip position, 1e-3 rad on the end orientation (SPEC S4).
const TOLERANCE: f64 = 1e-3;
const STEPS: usize = 8;

/// A moment fixed in space is not conservative under finite 3-D rotations (Ziegler's
/// "axial" moment): a cantilever under it has no stable rest the explicit dynamic
/// relaxation could damp down to, while the equilibrium itself exists. The case is
/// therefore solved by the Newton solvers, static and implicit (damped to rest), each
/// checked against the exact helix.
pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    for kind in [SolverKind::Static, SolverKind::Implicit] {
        match with_solver(kind, || helix(kind)) {
            Ok(checks) => out.extend(checks),
            Err(e) => out.push(Check::failed("helix", &format!("[{kind}]"), &e)),
        }
    }
    out
}

fn helix(kind: SolverKind) -> Result<Vec<Check>, String> {
    let (mat, sec) = hose1();
    let mut model = build(
        straight_hose(ELEMENTS, L, &mat, sec, |_| DVec3::ZERO),
        static_settings(),
    );
    // the case tests the element; the helix stays clear of itself anyway
    model.hose_contact.active = false;
    let ei = model.elements[0].bending_stiffness[0];
    let gj = model.elements[0].torsion_stiffness;
    let axis = DVec3::new(MOMENT_ANGLE.cos(), MOMENT_ANGLE.sin(), 0.0);
    let k = TURN / L;
    let moment = axis * (k * ei);

    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let mut id = None;
    for step in 1..=STEPS {
        if let Some(old) = id {
            state.loads.remove(old);
        }
        id = Some(state.loads.add(dead_load(
            ELEMENTS,
            DVec3::ZERO,
            moment * (step as f64 / STEPS as f64),
        )));
        settle_to(&model, &mut state, moment.length() / L, L, 1e-8)?;
    }

    let (a, b) = (MOMENT_ANGLE.cos(), MOMENT_ANGLE.sin());
    let across = (DVec3::X - axis * a) / b;
    let tip = axis * (a * L)
        + (across * (TURN.sin() / k) + axis.cross(across) * ((1.0 - TURN.cos()) / k)) * b;
    let c = moment.length() * a * (1.0 / gj - 1.0 / ei);
    let end_frame = DQuat::from_axis_angle(axis, TURN)
        * DQuat::from_axis_angle(DVec3::X, c * L)
        * model.rest_q[ELEMENTS];
    let computed = state.x[ELEMENTS] - state.x[0];
    let mut out: Vec<Check> = ["x", "y", "z"]
        .iter()
        .enumerate()
        .map(|(i, name)| {
            Check::scaled(
                "helix",
                &format!("tip {name}/L [{kind}]"),
                computed[i] / L,
                tip[i] / L,
                1.0,
                TOLERANCE,
            )
        })
        .collect();
    let turn_error = (state.q[ELEMENTS] * end_frame.conjugate()).normalize();
    out.push(Check::scaled(
        "helix",
        &format!("end orientation error (rad) [{kind}]"),
        2.0 * turn_error.xyz().length().atan2(turn_error.w.abs()),
        0.0,
        1.0,
        TOLERANCE,
    ));
    Ok(out)
}
