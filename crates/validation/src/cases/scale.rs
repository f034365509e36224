//! `scale`: the solvers' default settings work from a millimetre silicone tube to a steel
//! pipe (convergence tests relative to the problem's loads).
//!
//! Each rod is a cantilever of 40 elements under a dead tip load λ = PL²/EI = 2, applied
//! at once; the tip deflection must match the elastica (w/L = 0.493457: the
//! elliptic-integral solution of Bisshopp & Drucker 1945, tabulated by Mattiasson 1981,
//! as in `tip_load`) to 0.1 %; the rods are
//! slender enough (L/d ≥ 50) that their extensibility shifts it by less than 1e-4.
//!
//! * static: one static solve with `StaticOptions::default()` — no tolerance tuned to the
//!   case; the solve must report convergence;
//! * implicit: HHT-α steps of 50 ms, each from rest ([`implicit_to_rest`]), every Newton
//!   solve with the default tolerance (`Tolerance::default()`, 1e-8 of the load scale) —
//!   every step must converge, until the static residual is below 1e-7 P (and 1e-7 P·L)
//!   (27 steps for the steel pipe, 63 for the silicone tube, 2449 for the EPDM hose);
//! * explicit: dynamic relaxation with kinetic damping ([`settle_to`]) to the same
//!   residual, at each rod's own stable step (3·10⁴–8·10⁴ steps; the whole case takes
//!   about 2 s in release).

use crate::harness::{
    build, clamp, dead_load, implicit_to_rest, settle_to, static_settings, straight_hose,
    with_solver,
};
use crate::Check;
use glam::DVec3;
use pliant_core::integrators::StaticSolver;
use pliant_core::newton::Tolerance;
use pliant_core::{Material, Model, Section, SolverKind, State};

const ELEMENTS: usize = 40;
const LAMBDA: f64 = 2.0;
const EXACT_W: f64 = 0.493457;
const TOLERANCE: f64 = 1e-3;
/// Static residual at which the dynamic solvers are at rest, over P (and P·L).
const REST: f64 = 1e-7;

/// A rod: name, material, section, length \[m\].
struct Rod {
    name: &'static str,
    material: Material,
    section: Section,
    length: f64,
}

fn rods() -> [Rod; 3] {
    [
        Rod {
            name: "silicone micro-tube 0.5/1 mm, 50 mm, E 1 MPa",
            material: Material::isotropic(1e6, 0.49, 1100.0),
            section: Section::new(0.5e-3, 1.0e-3),
            length: 0.05,
        },
        Rod {
            name: "EPDM hose 10/16 mm, 1 m, E 12 MPa",
            material: Material::isotropic(12e6, 0.49, 940.0),
            section: Section::new(0.010, 0.016),
            length: 1.0,
        },
        Rod {
            name: "steel pipe 10/12 mm, 2 m, E 210 GPa",
            material: Material::isotropic(210e9, 0.3, 7850.0),
            section: Section::new(0.010, 0.012),
            length: 2.0,
        },
    ]
}

pub fn run() -> Vec<Check> {
    let mut out = Vec::new();
    for kind in [
        SolverKind::Static,
        SolverKind::Implicit,
        SolverKind::Explicit,
    ] {
        for rod in rods() {
            if let Err(e) = check(&rod, kind, &mut out) {
                out.push(Check::failed(
                    "scale",
                    &format!("{} [{kind}]", rod.name),
                    &e,
                ));
            }
        }
    }
    out
}

/// The rod clamped at x = 0 with the tip load λ EI/L² on (and P).
fn cantilever(rod: &Rod) -> (Model, State, f64) {
    let model = build(
        straight_hose(ELEMENTS, rod.length, &rod.material, rod.section, |_| {
            DVec3::ZERO
        }),
        static_settings(),
    );
    let ei = model.elements[0].bending_stiffness[0];
    let p = LAMBDA * ei / (rod.length * rod.length);
    let mut state = State::at_rest(&model);
    clamp(&mut state, 0);
    state
        .loads
        .add(dead_load(ELEMENTS, DVec3::new(0.0, -p, 0.0), DVec3::ZERO));
    (model, state, p)
}

fn check(rod: &Rod, kind: SolverKind, out: &mut Vec<Check>) -> Result<(), String> {
    let (model, mut state, p) = cantilever(rod);
    let converged = match kind {
        SolverKind::Static => {
            let mut solver = StaticSolver::new(&model).map_err(|e| e.to_string())?;
            let report = solver
                .solve(&model, &mut state)
                .map_err(|e| e.to_string())?;
            eprintln!(
                "scale: {}: {} iterations, residual {:.2e} N of {:.2e} N allowed",
                rod.name, report.iterations, report.residual_force, report.force_limit
            );
            report.converged
        }
        SolverKind::Implicit => {
            let (f, m) = (REST * p, REST * p * rod.length);
            // a step that does not converge is an error (the check fails)
            let report = implicit_to_rest(&model, &mut state, Tolerance::default(), f, m)?;
            eprintln!(
                "scale: {} [implicit]: {} steps to rest, residual {:.2e} N",
                rod.name, report.steps, report.residual_force
            );
            report.converged
        }
        SolverKind::Explicit => {
            let report = with_solver(kind, || settle_to(&model, &mut state, p, rod.length, REST))?;
            eprintln!(
                "scale: {} [explicit]: {} steps to rest, residual {:.2e} N",
                rod.name, report.steps, report.residual_force
            );
            report.converged
        }
    };
    let (label, what) = match kind {
        SolverKind::Static => ("", "default static solve converged"),
        SolverKind::Implicit => (" [implicit]", "default implicit steps converged, at rest"),
        SolverKind::Explicit => (" [explicit]", "at rest"),
    };
    out.push(Check::with_error(
        "scale",
        &format!("{}: {what} (1 = yes){label}", rod.name),
        f64::from(u8::from(converged)),
        1.0,
        f64::from(u8::from(!converged)),
        0.0,
    ));
    out.push(Check::relative(
        "scale",
        &format!("{}: tip w/L at lambda=2{label}", rod.name),
        -state.x[ELEMENTS].y / rod.length,
        EXACT_W,
        TOLERANCE,
    ));
    Ok(())
}
