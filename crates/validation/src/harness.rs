//! Shared set-up of the validation cases: straight hoses, clamping, relaxation.

use glam::{DQuat, DVec3};
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::relax::{relax, RelaxOptions, RelaxReport};
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

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

/// Relaxes to equilibrium with out-of-balance loads below `rel` times the force scale
/// `force` (and `force·length` for moments). Kinetic damping is used unless the model
/// has viscous mass damping of its own. Divergence or no convergence is an error.
pub fn relax_to(
    model: &Model,
    state: &mut State,
    force: f64,
    length: f64,
    rel: f64,
) -> Result<RelaxReport, String> {
    let kinetic_damping = model.damping_mass == 0.0;
    let opts = RelaxOptions {
        force_tolerance: rel * force,
        moment_tolerance: rel * force * length,
        max_steps: 1_500_000,
        kinetic_damping,
    };
    let report = relax(model, state, &opts).map_err(|d| d.to_string())?;
    if report.converged {
        Ok(report)
    } else {
        Err(format!(
            "relaxation did not converge in {} steps (residual {:.3e} N)",
            report.steps, report.residual_force
        ))
    }
}
