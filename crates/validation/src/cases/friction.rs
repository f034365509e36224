//! `friction_newton`: Coulomb friction under the Newton solvers, on the incline
//! of `contact_incline` (μ_s = 0.5, μ_k = 0.4, a 0.5 m hose lying down the slope):
//! * static, tan φ = 0.8 μ_s: an equilibrium exists; the hose sticks (creep along the
//!   slope below 10 µm, the elastic give of the friction spring) and the parts carry its
//!   weight (the total contact force balances gravity within 0.1 %);
//! * static, tan φ = 1.2 μ_s: no equilibrium exists; the solver must say so (the input
//!   step does not converge) and must not hold the hose in place;
//! * implicit, tan φ = 0.8 μ_s: sticks over 0.5 s (creep below 10 µm);
//! * implicit, tan φ = 1.2 μ_s: slides with g (sin φ − μ_k cos φ) — distance in 0.3 s
//!   within 2 % of ½ a t², at the implicit solver's default 10 ms step.
//!
//! Stress cases, implicit (10 ms steps, 0.5 s) at tan φ = 0.8 μ_k, where every node
//! starts slipping towards a friction anchor that the balance sticks at — anchors 2 mm
//! up-slope, and 2 mm down-slope, of where the hose lies: every step converges by Newton
//! (no explicit fallback), no node's friction is outside its cone (|f_t| ≤ μ_s f_n, to
//! round-off) and the hose comes to rest (every node slower than 1 mm/s at the end).
//!
//! The same under the static solver (three 10 ms input steps): the hose lying in balance
//! with its anchors then moved 2 mm up- or down-slope, and a hose released 1 mm above the
//! slope — every node slipping when Newton starts. Each step converges; the balance is
//! the incremental problem's from the anchors: every node within the friction spring's
//! reach of its anchor (the hose moved by the anchor shift, to 10 µm), no friction outside
//! its cone, the weight carried (0.1 %).

use super::contact::{incline_plane, world, G};
use crate::Check;
use glam::DVec3;
use pliant_core::contact::friction::FrictionMemory;
use pliant_core::integrators::{Solver, SolverSettings};
use pliant_core::{SolverKind, State};

const CASE: &str = "friction_newton";
const MU: (f64, f64) = (0.5, 0.4);
/// The node the displacements are read at (the hose's middle).
const MIDDLE: usize = 10;

/// How the hose starts: where its friction anchors are, down the slope from its nodes
/// \[m\], and how high above the slope it is released (vertically) \[m\].
#[derive(Clone, Copy)]
struct Start {
    anchor_shift: f64,
    lift: f64,
}

const LYING: Start = Start {
    anchor_shift: 0.0,
    lift: 0.0,
};

/// What a run on an incline of angle φ gave.
struct Run {
    /// Displacement of the middle node along the slope, downwards \[m\].
    slid: f64,
    /// Whether every step converged.
    converged: bool,
    /// Steps taken by the explicit fallback pieces (implicit).
    fallback: usize,
    /// |Σ contact force + Σ m g| / |Σ m g| at the end.
    imbalance: f64,
    /// Largest |f_t| / (μ_s f_n) of a touching node at the end (Coulomb: ≤ 1).
    cone: f64,
    /// Largest node speed at the end \[m/s\].
    speed: f64,
}

fn incline(
    phi: f64,
    kind: SolverKind,
    step: f64,
    seconds: f64,
    start: Start,
) -> Result<Run, String> {
    let r = crate::harness::hose1().1.outer_radius();
    let (plane, down, normal) = incline_plane(phi, MU);
    let model = world(
        |s| -down * (0.5 * s - 0.25) + normal * r + DVec3::Z * start.lift,
        vec![plane],
        DVec3::new(0.0, 0.0, -G),
        0.0,
    );
    let settings = SolverSettings {
        kind,
        implicit_time_step: step,
        static_input_step: step,
        ..Default::default()
    };
    let mut solver = Solver::new(&model, settings).map_err(|e| e.to_string())?;
    let mut state = State::at_rest(&model);
    if kind == SolverKind::Static && start.anchor_shift != 0.0 {
        // the static stress cases start from the hose lying in balance (one static step
        // with the anchors where it lies), its anchors then moved
        let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
        if !stats.converged {
            return Err("the hose did not settle on the slope".into());
        }
    }
    let anchors: Vec<DVec3> = state
        .x
        .iter()
        .map(|x| *x + down * start.anchor_shift)
        .collect();
    state.friction = FrictionMemory::new(&anchors);
    let begin = state.x[MIDDLE];
    let mut converged = true;
    let mut fallback = 0;
    for _ in 0..(seconds / step).round() as usize {
        let stats = solver.step(&model, &mut state).map_err(|e| e.to_string())?;
        converged &= stats.converged;
        fallback += stats.explicit_fallback;
    }
    let weight: DVec3 = model.mass.iter().map(|m| m * model.gravity).sum();
    let carried: DVec3 = state.contact_force.iter().copied().sum();
    let cone = state
        .contact_force
        .iter()
        .filter(|f| f.dot(normal) > 0.0)
        .map(|f| {
            let f_n = f.dot(normal);
            (*f - normal * f_n).length() / (MU.0 * f_n)
        })
        .fold(0.0, f64::max);
    Ok(Run {
        slid: (state.x[MIDDLE] - begin).dot(down),
        converged,
        fallback,
        imbalance: (carried + weight).length() / weight.length(),
        cone,
        speed: state.v.iter().map(|v| v.length()).fold(0.0, f64::max),
    })
}

pub fn run() -> Vec<Check> {
    let stick = (0.8 * MU.0).atan();
    let slide = (1.2 * MU.0).atan();
    let mut out = Vec::new();
    match incline(stick, SolverKind::Static, 0.01, 0.1, LYING) {
        Ok(run) if run.converged => {
            out.push(Check::with_error(
                CASE,
                "static, tan(phi)=0.8 mu_s: creep m (abs)",
                run.slid,
                0.0,
                run.slid.abs(),
                1e-5,
            ));
            out.push(Check::with_error(
                CASE,
                "static, tan(phi)=0.8 mu_s: |contact force + weight| / weight",
                run.imbalance,
                0.0,
                run.imbalance,
                1e-3,
            ));
        }
        Ok(_) => out.push(Check::failed(CASE, "static stick", "did not converge")),
        Err(e) => out.push(Check::failed(CASE, "static stick", &e)),
    }
    match incline(slide, SolverKind::Static, 0.01, 0.01, LYING) {
        Ok(run) => {
            // no equilibrium: the step must not converge (pass = 0 error), and the hose
            // must not be held where it was (it slides by more than the stick creep)
            let honest = if run.converged { 1.0 } else { 0.0 };
            out.push(Check::with_error(
                CASE,
                "static, tan(phi)=1.2 mu_s: step reported converged (no equilibrium exists)",
                honest,
                0.0,
                honest,
                0.0,
            ));
            out.push(Check::with_error(
                CASE,
                "static, tan(phi)=1.2 mu_s: slid beyond 1 mm (1 = yes)",
                if run.slid > 1e-3 { 1.0 } else { 0.0 },
                1.0,
                if run.slid > 1e-3 { 0.0 } else { 1.0 },
                0.0,
            ));
        }
        Err(e) => out.push(Check::failed(CASE, "static slide", &e)),
    }
    match incline(stick, SolverKind::Implicit, 0.01, 0.5, LYING) {
        Ok(run) => out.push(Check::with_error(
            CASE,
            "implicit, tan(phi)=0.8 mu_s: creep over 0.5 s m (abs)",
            run.slid,
            0.0,
            run.slid.abs(),
            1e-5,
        )),
        Err(e) => out.push(Check::failed(CASE, "implicit stick", &e)),
    }
    let t = 0.3;
    match incline(slide, SolverKind::Implicit, 0.01, t, LYING) {
        Ok(run) => {
            let a = G * (slide.sin() - MU.1 * slide.cos());
            out.push(Check::relative(
                CASE,
                "implicit, tan(phi)=1.2 mu_s: distance in 0.3 s m",
                run.slid,
                0.5 * a * t * t,
                0.02,
            ));
        }
        Err(e) => out.push(Check::failed(CASE, "implicit slide", &e)),
    }
    out.extend(back_to_the_apex());
    out.extend(static_from_slip());
    out
}

/// The stress cases: every node starts slipping towards an anchor the balance sticks at.
fn back_to_the_apex() -> Vec<Check> {
    let phi = (0.8 * MU.1).atan();
    let offset = 0.002;
    let mut out = Vec::new();
    for (name, shift) in [("up-slope", -offset), ("down-slope", offset)] {
        let label =
            |what: &str| format!("implicit, tan(phi)=0.8 mu_k, anchors 2 mm {name}: {what}");
        let start = Start {
            anchor_shift: shift,
            lift: 0.0,
        };
        match incline(phi, SolverKind::Implicit, 0.01, 0.5, start) {
            Ok(run) => {
                let fell_back = run.fallback as f64;
                out.push(Check::with_error(
                    CASE,
                    &label("explicit fallback steps"),
                    fell_back,
                    0.0,
                    fell_back + if run.converged { 0.0 } else { 1.0 },
                    0.0,
                ));
                out.push(coulomb(&label("largest |f_t| / (mu_s f_n)"), run.cone));
                out.push(Check::with_error(
                    CASE,
                    &label("largest node speed at 0.5 s m/s"),
                    run.speed,
                    0.0,
                    run.speed,
                    1e-3,
                ));
            }
            Err(e) => out.push(Check::failed(CASE, &label("ran"), &e)),
        }
    }
    out
}

/// Coulomb's law at a balance: no node's friction beyond μ_s f_n (round-off allowed).
fn coulomb(quantity: &str, cone: f64) -> Check {
    let beyond = (cone - 1.0).max(0.0);
    Check::with_error(CASE, quantity, cone, 1.0, beyond, 1e-9)
}

/// The stress cases under the static solver (three 10 ms input steps) at tan φ = 0.8 μ_k:
/// the hose lying in balance on the slope with its anchors then moved 2 mm up- or
/// down-slope, and a hose released 1 mm (vertically) above the slope with its anchors
/// where it is released (it first touches the slope in slip) — every node in slip when
/// Newton starts. A static step is the
/// incremental problem from the anchors: the friction springs hold the slope's pull
/// tan φ f_n < μ_k f_n only near their anchors, so the balance has every node sticking
/// within the spring's reach μ_s f_n / k_t (below 10 µm, the creep bound of the stick
/// check) of its anchor — the hose moved by the anchor shift — with its friction inside
/// the cone and the parts carrying its weight (0.1 %).
fn static_from_slip() -> Vec<Check> {
    let phi = (0.8 * MU.1).atan();
    let starts = [
        (
            "anchors 2 mm up-slope",
            Start {
                anchor_shift: -0.002,
                lift: 0.0,
            },
        ),
        (
            "anchors 2 mm down-slope",
            Start {
                anchor_shift: 0.002,
                lift: 0.0,
            },
        ),
        (
            "released 1 mm above",
            Start {
                anchor_shift: 0.0,
                lift: 0.001,
            },
        ),
    ];
    let mut out = Vec::new();
    for (name, start) in starts {
        let label = |what: &str| format!("static, tan(phi)=0.8 mu_k, {name}: {what}");
        match incline(phi, SolverKind::Static, 0.01, 0.03, start) {
            Ok(run) if run.converged => {
                out.push(Check::with_error(
                    CASE,
                    &label("distance from the anchor along the slope m (abs)"),
                    run.slid,
                    start.anchor_shift,
                    (run.slid - start.anchor_shift).abs(),
                    1e-5,
                ));
                out.push(coulomb(&label("largest |f_t| / (mu_s f_n)"), run.cone));
                out.push(Check::with_error(
                    CASE,
                    &label("|contact force + weight| / weight"),
                    run.imbalance,
                    0.0,
                    run.imbalance,
                    1e-3,
                ));
            }
            Ok(_) => out.push(Check::failed(CASE, &label("converged"), "did not converge")),
            Err(e) => out.push(Check::failed(CASE, &label("ran"), &e)),
        }
    }
    out
}
