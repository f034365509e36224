//! `plastic_section` and `springback` (SPEC X1): a yielding metal tube.
//!
//! * `plastic_section`: the fibre section's moment–curvature and torque–twist curves of an
//!   elastic–perfectly plastic tube (8 × 1 mm) and solid rod (8 mm), loaded monotonically,
//!   against the closed forms ([`pliant_core::rod::plastic_moment`]): past first yield
//!   (the elastic–plastic transition) and deep in the plastic range (→ M_p, T_p).
//! * `springback`: a 100 mm line of that tube, clamped at one end, its other end held
//!   on the arc of radius R = 50 mm (the curvature a mandrel imposes: uniform moment) in
//!   40 static steps, then released: the reaction moment is M(1/R) and the line springs
//!   back to 1/R_after = 1/R − M/EI of the closed form with linear hardening (H = 1 % of
//!   E) — and keeps that set.

use crate::harness::{build, clamp, static_settings, straight_hose};
use crate::Check;
use glam::{DQuat, DVec3};
use pliant_core::autodiff::V3;
use pliant_core::integrators::StaticSolver;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::material::YieldLaw;
use pliant_core::newton::Tolerance;
use pliant_core::rod::fibre_law::FibreLaw;
use pliant_core::rod::fibre_section::FibreSection;
use pliant_core::rod::plastic_moment;
use pliant_core::{Material, Section, State};

const E: f64 = 200e9;
const G: f64 = 200e9 / 2.6;
const SY: f64 = 250e6;
const D_OUTER: f64 = 0.008;
const D_INNER: f64 = 0.006;

/// The moment–curvature and torque–twist curves against the closed forms.
pub fn run_section() -> Vec<Check> {
    let law = FibreLaw {
        e: E,
        g: G,
        h: 0.0,
        yield_stress: SY,
    };
    let mut checks = Vec::new();
    for (name, di) in [("tube", D_INNER), ("solid", 0.0)] {
        let section = FibreSection::tube(di, D_OUTER, law);
        let history = vec![0.0; section.history_len()];
        let (ri, ro) = (0.5 * di, 0.5 * D_OUTER);
        let ke = SY / (E * ro);
        for factor in [1.5, 3.0, 20.0] {
            // bending about an axis between two fibres' directions (the worst case)
            let k = factor * ke;
            let (c, s) = (0.3_f64.cos(), 0.3_f64.sin());
            let m = section.moments(V3::new(0.0, k * c, k * s), &history);
            let computed = (m.y * m.y + m.z * m.z).sqrt();
            let exact = plastic_moment::bending_moment(ri, ro, E, SY, k);
            checks.push(Check::relative(
                "plastic_section",
                &format!("{name} M at {factor} κ_e N*m"),
                computed,
                exact,
                0.005,
            ));
        }
        let twist_e = SY / 3f64.sqrt() / (G * ro);
        for factor in [1.5, 20.0] {
            let t = factor * twist_e;
            let m = section.moments(V3::new(t, 0.0, 0.0), &history);
            let exact = plastic_moment::torque(ri, ro, G, SY, t);
            checks.push(Check::relative(
                "plastic_section",
                &format!("{name} T at {factor} θ'_e N*m"),
                m.x,
                exact,
                0.005,
            ));
        }
    }
    checks
}

const LENGTH: f64 = 0.1;
const ELEMENTS: usize = 20;
const HARDENING: f64 = 2e9;

/// Bending to the mandrel's curvature and releasing.
pub fn run_springback() -> Vec<Check> {
    let fail = |why: String| vec![Check::failed("springback", "bend and release", &why)];
    let mut material = Material::isotropic(E, 0.3, 7850.0);
    material.plasticity = Some(YieldLaw {
        yield_stress: SY,
        hardening_modulus: HARDENING,
    });
    let section = Section::new(D_INNER, D_OUTER);
    let hose = straight_hose(ELEMENTS, LENGTH, &material, section, |_| DVec3::ZERO);
    let model = build(hose, static_settings());
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    let tip = state.loads.add(LoadCase::Fix(Fix {
        node: ELEMENTS,
        position: model.rest_x[ELEMENTS],
        orientation: model.rest_q[ELEMENTS],
    }));
    let Ok(mut solver) = StaticSolver::new(&model) else {
        return fail("the static solver needs a chain".into());
    };
    // pure bending carries no shear: the element forces (the relative test's force
    // scale) are round-off, so the force residual gets a floor of 1 µN against ~2 kN of
    // shear scale (M/l of one element)
    solver.options.tolerance = Tolerance {
        force: 1e-6,
        ..Tolerance::default()
    };
    let kappa = 1.0 / 0.05;
    let steps = 40;
    for k in 1..=steps {
        let phi = kappa * k as f64 / steps as f64 * LENGTH;
        let r = LENGTH / phi;
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(tip) {
            f.position = DVec3::new(r * phi.sin(), r * (1.0 - phi.cos()), 0.0);
            f.orientation = DQuat::from_rotation_z(phi) * model.rest_q[ELEMENTS];
        }
        match solver.solve(&model, &mut state) {
            Ok(report) if report.converged => {}
            other => return fail(format!("bending step {k}: {other:?}")),
        }
    }
    let moment = state.reaction_moment[ELEMENTS].z.abs();
    state.loads.remove(tip);
    match solver.solve(&model, &mut state) {
        Ok(report) if report.converged => {}
        other => return fail(format!("release: {other:?}")),
    }
    let turned = state.q[ELEMENTS] * model.rest_q[ELEMENTS].conjugate();
    let (axis, angle) = turned.to_axis_angle();
    let after = angle * axis.z.signum() / LENGTH;
    let (ri, ro) = (0.5 * D_INNER, 0.5 * D_OUTER);
    let exact = plastic_moment::hardening_bending_moment(ri, ro, E, SY, HARDENING, kappa);
    let ei = E * section.second_moment();
    vec![
        Check::relative("springback", "moment at 1/R N*m", moment, exact, 0.005),
        Check::relative(
            "springback",
            "springback 1/R − 1/R_after 1/m",
            kappa - after,
            exact / ei,
            0.005,
        ),
        Check::relative(
            "springback",
            "curvature kept 1/R_after 1/m",
            after,
            kappa - exact / ei,
            1e-3,
        ),
    ]
}
