//! `scale`: the static solver's default settings work from a millimetre silicone tube to
//! a steel pipe (issue 10 item 2: convergence tests relative to the problem's loads).
//!
//! Each rod is a cantilever of 40 elements under a dead tip load λ = PL²/EI = 2, solved
//! in one static solve with `StaticOptions::default()` — no tolerance tuned to the case.
//! The solve must report convergence, and the tip deflection must match the elastica
//! (w/L = 0.493457, Mattiasson 1981) to 0.1 %; the rods are slender enough (L/d ≥ 50)
//! that their extensibility shifts it by less than 1e-4.

use crate::harness::{build, clamp, dead_load, static_settings, straight_hose};
use crate::Check;
use glam::DVec3;
use pliant_core::integrators::StaticSolver;
use pliant_core::{Material, Section, State};

const ELEMENTS: usize = 40;
const LAMBDA: f64 = 2.0;
const EXACT_W: f64 = 0.493457;
const TOLERANCE: f64 = 1e-3;

/// A rod: name, material, section, length [m].
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
    for rod in rods() {
        if let Err(e) = check(&rod, &mut out) {
            out.push(Check::failed("scale", rod.name, &e));
        }
    }
    out
}

fn check(rod: &Rod, out: &mut Vec<Check>) -> Result<(), String> {
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
    let mut solver = StaticSolver::new(&model).map_err(|e| e.to_string())?;
    let report = solver
        .solve(&model, &mut state)
        .map_err(|e| e.to_string())?;
    eprintln!(
        "scale: {}: {} iterations, residual {:.2e} N of {:.2e} N allowed",
        rod.name, report.iterations, report.residual_force, report.force_limit
    );
    out.push(Check::with_error(
        "scale",
        &format!("{}: default static solve converged (1 = yes)", rod.name),
        f64::from(u8::from(report.converged)),
        1.0,
        f64::from(u8::from(!report.converged)),
        0.0,
    ));
    out.push(Check::relative(
        "scale",
        &format!("{}: tip w/L at lambda=2", rod.name),
        -state.x[ELEMENTS].y / rod.length,
        EXACT_W,
        TOLERANCE,
    ));
    Ok(())
}
