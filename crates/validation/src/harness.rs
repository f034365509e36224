//! Shared set-up of the validation cases: straight hoses, clamping, relaxation.

use glam::{DQuat, DVec3};
use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::newton::Tolerance;
use pliant_core::relax::{relax, RelaxOptions, RelaxReport};
use pliant_core::SolverKind;
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};
use std::cell::Cell;

/// Material and section of a built-in library hose (SPEC M4), read from the library data
/// file so that every case uses the same values as scene files do.
pub fn library_hose(name: &str) -> (Material, Section) {
    let library = pliant_scene::Library::builtin().expect("the built-in material library parses");
    let entry = library
        .get(name)
        .unwrap_or_else(|| panic!("library hose {name} exists"));
    (entry.material.clone(), entry.section)
}

/// The validation hose: library hose 1 (d_i 10 mm, d_a 16 mm, bimodular E_t 11.583 MPa,
/// E_c 13.1363 MPa, ρ 940 kg/m³, ν 0.49), 1 m long in the cases — a slender hose
/// (L/d_a = 62.5) as in an engine bay.
pub fn hose1() -> (Material, Section) {
    library_hose("hose1")
}

/// Settings for static validation: no gravity, no mass damping (relaxation damps
/// kinetically); the default stiffness-proportional damping stays on, as in every run, to
/// keep the highest modes from feeding the kinetic-damping restarts.
pub fn static_settings() -> SimSettings {
    SimSettings {
        gravity: DVec3::ZERO,
        damping_mass: 0.0,
        damping_stiffness: None,
        ..Default::default()
    }
}

/// A hose of `n` elements along +x from the origin, rest nodes offset by `offset(x)`.
pub fn straight_hose(
    n: usize,
    length: f64,
    mat: &Material,
    sec: Section,
    offset: impl Fn(f64) -> DVec3,
) -> HoseSpec {
    let nodes = (0..=n)
        .map(|i| {
            let x = length * i as f64 / n as f64;
            DVec3::new(x, 0.0, 0.0) + offset(x)
        })
        .collect();
    HoseSpec {
        name: "hose".into(),
        material: mat.clone(),
        nodes,
        sections: vec![sec],
        normal_hint: Some(DVec3::Y),
    }
}

/// Builds a one-hose model; the specs here are the suite's own, so failure is a bug.
pub fn build(hose: HoseSpec, settings: SimSettings) -> Model {
    Model::build(&WorldSpec {
        hoses: vec![hose],
        rigid_parts: Vec::new(),
        settings,
    })
    .expect("validation model must build")
}

/// A dead force and moment on node `node`, acting at once.
pub fn dead_load(node: usize, force: DVec3, moment: DVec3) -> LoadCase {
    LoadCase::DeadLoad(pliant_core::loads::DeadLoad {
        node,
        force,
        moment,
        ramp: None,
    })
}

/// Holds node `i` where it is now.
pub fn clamp(state: &mut State, i: usize) {
    let case = LoadCase::Fix(Fix {
        node: i,
        position: state.x[i],
        orientation: state.q[i],
    });
    state.loads.add(case);
}

/// Holds node `i` at a given pose.
pub fn clamp_at(state: &mut State, i: usize, position: DVec3, orientation: DQuat) {
    state
        .loads
        .remove_on_node(i, |c| !matches!(c, LoadCase::DeadLoad(_)));
    state.x[i] = position;
    state.q[i] = orientation;
    state.loads.add(LoadCase::Fix(Fix {
        node: i,
        position,
        orientation,
    }));
}

thread_local! {
    /// The solver [`settle_to`] reaches rest with (the `solvers` case runs every case with
    /// a rest state under each).
    static SOLVER: Cell<SolverKind> = const { Cell::new(SolverKind::Explicit) };
}

/// Runs `f` with [`settle_to`] using `kind`.
pub fn with_solver<R>(kind: SolverKind, f: impl FnOnce() -> R) -> R {
    let before = SOLVER.with(|s| s.replace(kind));
    let out = f();
    SOLVER.with(|s| s.set(before));
    out
}

/// Brings `state` to rest under its load cases with the current solver (explicit by
/// default, see [`with_solver`]): out-of-balance force below `rel · force` and moment
/// below `rel · force · length` on every free node.
///
/// * explicit — dynamic relaxation of the explicit step (kinetic damping when the model
///   has no mass damping; [`pliant_core::relax`]);
/// * static — one Newton solve ([`pliant_core::integrators::StaticSolver`]);
/// * implicit — HHT-α steps of 50 ms with the most numerical damping (α = −⅓), each
///   started from rest, until the residual is met ("implicit, damped to rest").
pub fn settle_to(
    model: &Model,
    state: &mut State,
    force: f64,
    length: f64,
    rel: f64,
) -> Result<RelaxReport, String> {
    let (force_tolerance, moment_tolerance) = (rel * force, rel * force * length);
    let report = match SOLVER.with(|s| s.get()) {
        SolverKind::Explicit => {
            let opts = RelaxOptions {
                force_tolerance,
                moment_tolerance,
                max_steps: 1_500_000,
                kinetic_damping: model.damping_mass == 0.0,
            };
            relax(model, state, &opts).map_err(|d| d.to_string())?
        }
        SolverKind::Static => {
            let mut solver = StaticSolver::new(model).map_err(|e| e.to_string())?;
            solver.options.tolerance = Tolerance::absolute(force_tolerance, moment_tolerance);
            solver.options.max_iterations = 200;
            let r = solver.solve(model, state).map_err(|e| e.to_string())?;
            RelaxReport {
                steps: r.iterations as u64,
                residual_force: r.residual_force,
                residual_moment: r.residual_moment,
                converged: r.converged,
            }
        }
        SolverKind::Implicit => {
            let newton = Tolerance::absolute(1e-3 * force_tolerance, 1e-3 * moment_tolerance);
            implicit_to_rest(model, state, newton, force_tolerance, moment_tolerance)?
        }
    };
    if report.converged {
        Ok(report)
    } else {
        Err(format!(
            "{} solver did not reach rest in {} steps (residual {:.3e} N)",
            SOLVER.with(|s| s.get()),
            report.steps,
            report.residual_force
        ))
    }
}

/// Implicit steps, each from rest: after every step the velocities (and accelerations)
/// are zeroed — kinetic damping at its strongest, a pseudo-transient continuation of the
/// static problem with the implicit step's mass term as regularisation — until the static
/// residual is met (`force_tolerance`, `moment_tolerance`). Each step's Newton solve
/// converges to `newton`. (Zeroing only at kinetic-energy peaks lets the large-step
/// scheme's spurious velocity after a sudden load, e.g. the torsion case's 0.5 rad jump
/// in one element, spin the hose into an equilibrium whole turns away.)
pub fn implicit_to_rest(
    model: &Model,
    state: &mut State,
    newton: Tolerance,
    force_tolerance: f64,
    moment_tolerance: f64,
) -> Result<RelaxReport, String> {
    let options = ImplicitOptions {
        time_step: 0.05,
        alpha: -1.0 / 3.0,
        tolerance: newton,
        max_halvings: 10,
        ..Default::default()
    };
    let mut solver = ImplicitSolver::new(model, options).map_err(|e| e.to_string())?;
    let mut report = RelaxReport {
        steps: 0,
        residual_force: f64::INFINITY,
        residual_moment: f64::INFINITY,
        converged: false,
    };
    let size = model
        .rest_x
        .iter()
        .fold(1.0_f64, |m, x| m.max(x.abs().max_element()));
    while report.steps < 20_000 {
        let before = (state.x.clone(), state.q.clone());
        solver.step(model, state).map_err(|e| e.to_string())?;
        report.steps += 1;
        let (f, m) = pliant_core::integrators::free_node_residual(state);
        report.residual_force = f;
        report.residual_moment = m;
        // at rest: residual met, or a whole step moved and turned no node beyond
        // round-off (the residual left is the round-off of stiff — rigid-factor — elements)
        let moved = state
            .x
            .iter()
            .zip(&before.0)
            .fold(0.0_f64, |m, (a, b)| m.max((*a - *b).length()));
        let turned = state.q.iter().zip(&before.1).fold(0.0_f64, |m, (a, b)| {
            m.max(pliant_core::math::log_map(*a * b.conjugate()).length())
        });
        if (f <= force_tolerance && m <= moment_tolerance)
            || (moved <= 1e-14 * size && turned <= 1e-14)
        {
            report.converged = true;
            break;
        }
        state.v.fill(DVec3::ZERO);
        state.w.fill(DVec3::ZERO);
        state.implicit.restart_at_rest();
    }
    Ok(report)
}
