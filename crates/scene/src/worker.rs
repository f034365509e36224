//! Building the worker (SPEC E1–E2): `[worker]` onto the assembly layer's
//! [`WorkerSettings`] — the population parsed by `pliant-worker`, the position converted
//! from the file's length unit, the vertical taken against gravity (+z without
//! gravity); each error names its field.

use crate::error::FieldError;
use crate::format::{WorkerPosition, WorkerSection};
use crate::units::LengthUnit;
use crate::validate::{finite, finite_vec, non_zero_vec};
use glam::DVec3;
use pliant_assembly::worker::{Stance, WorkerSettings};
use pliant_worker::{Coupling, Placement, Population, ScoreOptions, Sex, WorkerError};

fn field_error(field: &str, e: WorkerError) -> FieldError {
    match e {
        WorkerError::Field { value, reason, .. } => FieldError::new(field, value, reason),
        e => FieldError::new(field, "", e.to_string()),
    }
}

/// Checks `[worker]` (`None` when absent); `gravity` the scene's \[m/s²\], `interval`
/// its record interval \[s\] (the posed instants).
pub fn build_worker(
    raw: Option<&WorkerSection>,
    unit: LengthUnit,
    gravity: DVec3,
    interval: f64,
) -> Result<Option<WorkerSettings>, FieldError> {
    let Some(raw) = raw else { return Ok(None) };
    let words = raw.population.split_whitespace().count();
    let population = match (words, raw.percentile) {
        (2, None) => Population::parse("worker.population", &raw.population)
            .map_err(|e| field_error("worker.population", e))?,
        (2, Some(p)) => {
            return Err(FieldError::new(
                "worker.percentile",
                p.to_string(),
                format!(
                    "worker.population \"{}\" already names the percentile",
                    raw.population
                ),
            ))
        }
        (_, p) => {
            let sex = Sex::parse("worker.population", &raw.population)
                .map_err(|e| field_error("worker.population", e))?;
            Population::new(sex, p.unwrap_or(50.0))
                .map_err(|e| field_error("worker.percentile", e))?
        }
    };
    if let Some(p) = &raw.posture {
        if !p.trim().eq_ignore_ascii_case("standing") {
            return Err(FieldError::new(
                "worker.posture",
                format!("\"{p}\""),
                "only \"standing\" is modelled (feet on the floor, knees straight)",
            ));
        }
    }
    let coupling = match &raw.coupling {
        Some(c) => Coupling::parse(c).ok_or_else(|| {
            FieldError::new(
                "worker.coupling",
                format!("\"{c}\""),
                "expected \"good\", \"fair\", \"poor\" or \"unacceptable\"",
            )
        })?,
        None => Coupling::default(),
    };
    let up = gravity.try_normalize().map(|g| -g).unwrap_or(DVec3::Z);
    let facing = match raw.facing {
        Some(f) => non_zero_vec("worker.facing", f, "")?,
        None => DVec3::X,
    };
    let to_m = unit.to_metres();
    let stance = match &raw.position {
        None | Some(WorkerPosition::Auto(_)) => {
            let floor = finite("worker.floor", raw.floor.unwrap_or(0.0), unit.symbol())? * to_m;
            WorkerSettings::auto_stance(facing, up, floor)
                .map_err(|e| field_error("worker.facing", e))?
        }
        Some(WorkerPosition::At(p)) => {
            let p = finite_vec("worker.position", *p, unit.symbol())? * to_m;
            Stance::At(Placement::new(p, facing, up).map_err(|e| field_error("worker.facing", e))?)
        }
    };
    Ok(Some(WorkerSettings {
        population,
        stance,
        interval,
        decide: raw.decide.unwrap_or(true),
        steps: raw.steps.unwrap_or(false),
        scores: ScoreOptions {
            static_or_repeated: false,
            coupling,
        },
    }))
}
