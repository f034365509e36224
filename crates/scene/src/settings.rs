//! Building the global settings: `[simulation]` into the core's [`SimSettings`] and
//! `[output]` into the record interval. These are SI and unaffected by `length_unit`.

use crate::error::FieldError;
use crate::format::{OutputSection, SimulationSection};
use crate::validate::{finite_vec, non_negative, positive, with_unit};
use pliant_core::SimSettings;

/// Smallest `simulation.time_step_safety` taken: the step is this fraction of the stable
/// step, so smaller factors multiply the steps (and the run time) beyond any use — 10⁻³
/// is already a thousand times the default's steps (1e-300 ran for ever,
/// 5e-324 gave a zero step).
pub const MIN_TIME_STEP_SAFETY: f64 = 1e-3;

/// Default interval between recorded states (s).
pub const DEFAULT_RECORD_INTERVAL: f64 = 0.01;

/// Checks `[simulation]`; omitted values take [`SimSettings::default`].
pub fn build_settings(raw: Option<&SimulationSection>) -> Result<SimSettings, FieldError> {
    let default = SimSettings::default();
    let Some(raw) = raw else { return Ok(default) };
    let gravity = match raw.gravity {
        Some(g) => crate::ranges::vec_at_most(
            "simulation.gravity",
            finite_vec("simulation.gravity", g, "m/s²")?,
            crate::ranges::MAX_GRAVITY,
            "m/s²",
            "gravity",
        )?,
        None => default.gravity,
    };
    let damping_mass = match raw.damping_mass_per_s {
        Some(a) => non_negative("simulation.damping_mass_per_s", a, "1/s")?,
        None => default.damping_mass,
    };
    let damping_stiffness = match raw.damping_stiffness_s {
        Some(b) => Some(non_negative("simulation.damping_stiffness_s", b, "s")?),
        None => default.damping_stiffness,
    };
    let time_step_safety = match raw.time_step_safety {
        Some(f) => {
            let f = positive("simulation.time_step_safety", f, "")?;
            if !(MIN_TIME_STEP_SAFETY..=1.0).contains(&f) {
                return Err(FieldError::new(
                    "simulation.time_step_safety",
                    with_unit(f, ""),
                    format!("must lie in [{MIN_TIME_STEP_SAFETY}, 1] (a fraction of the stable time step)"),
                ));
            }
            f
        }
        None => default.time_step_safety,
    };
    let time_step = match raw.time_step_s {
        Some(dt) => Some(positive("simulation.time_step_s", dt, "s")?),
        None => default.time_step,
    };
    let mut solver = default.solver;
    if let Some(name) = &raw.solver {
        solver.kind = name.parse().map_err(|reason: String| {
            FieldError::new("simulation.solver", name.clone(), &reason)
        })?;
    }
    for (field, value, target) in [
        (
            "simulation.implicit_time_step_s",
            raw.implicit_time_step_s,
            &mut solver.implicit_time_step,
        ),
        (
            "simulation.static_input_step_s",
            raw.static_input_step_s,
            &mut solver.static_input_step,
        ),
    ] {
        if let Some(v) = value {
            let v = positive(field, v, "s")?;
            if v > 1.0 {
                return Err(FieldError::new(
                    field,
                    with_unit(v, "s"),
                    "must lie in (0, 1] s",
                ));
            }
            *target = v;
        }
    }
    if let Some(n) = raw.static_max_iterations {
        let most = pliant_core::model::MAX_STATIC_ITERATIONS;
        if n == 0 || n > most as u64 {
            return Err(FieldError::new(
                "simulation.static_max_iterations",
                n.to_string(),
                format!("must lie in 1 … {most}"),
            ));
        }
        solver.static_max_iterations = n as usize;
    }
    if let Some(n) = raw.static_relaxation_budget {
        solver.static_relaxation_budget = n;
    }
    let mass_scaling = match raw.mass_scaling {
        Some(s) => {
            let most = pliant_core::model::MAX_MASS_SCALING;
            if !(1.0..=most).contains(&s) {
                return Err(FieldError::new(
                    "simulation.mass_scaling",
                    with_unit(s, ""),
                    format!("must lie in 1 … {most} (the inertia's multiple of the mass)"),
                ));
            }
            s
        }
        None => default.mass_scaling,
    };
    let hose_contact = match &raw.hose_contact {
        Some(name) => name.parse().map_err(|reason: String| {
            FieldError::new("simulation.hose_contact", name.clone(), &reason)
        })?,
        None => default.hose_contact,
    };
    Ok(SimSettings {
        gravity,
        damping_mass,
        damping_stiffness,
        time_step_safety,
        time_step,
        solver,
        threads: default.threads,
        hose_contact,
        max_contact_pairs: default.max_contact_pairs,
        mass_scaling,
    })
}

/// Checks `[output]` and returns the record interval (s).
pub fn build_record_interval(raw: Option<&OutputSection>) -> Result<f64, FieldError> {
    match raw.and_then(|o| o.record_interval_s) {
        Some(dt) => non_negative("output.record_interval_s", dt, "s"),
        None => Ok(DEFAULT_RECORD_INTERVAL),
    }
}

#[cfg(test)]
mod tests {
    use super::build_settings;
    use crate::format::SimulationSection;
    use pliant_core::contact::HoseContactRule;

    #[test]
    fn hose_contact_and_static_iterations_reach_the_settings() {
        let raw = SimulationSection {
            hose_contact: Some("apart_at_rest".into()),
            static_max_iterations: Some(5000),
            static_relaxation_budget: Some(0),
            ..Default::default()
        };
        let s = build_settings(Some(&raw)).unwrap();
        assert_eq!(s.hose_contact, HoseContactRule::ApartAtRest);
        assert_eq!(s.solver.static_max_iterations, 5000);
        assert_eq!(s.solver.static_relaxation_budget, 0);
        let default = build_settings(None).unwrap();
        assert_eq!(default.hose_contact, HoseContactRule::All);
        assert_eq!(default.solver.static_max_iterations, 60);
        assert_eq!(default.solver.static_relaxation_budget, 10_000_000);
    }
}
