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
use pliant_worker::{Coupling, Placement, Population, ScoreOptions, Seat, Sex, WorkerError};

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
    let sitting = match raw
        .posture
        .as_deref()
        .map(|p| p.trim().to_ascii_lowercase())
    {
        None => false,
        Some(p) if p == "standing" => false,
        Some(p) if p == "sitting" => true,
        Some(_) => {
            return Err(FieldError::new(
                "worker.posture",
                format!("\"{}\"", raw.posture.as_deref().unwrap_or_default()),
                "expected \"standing\" or \"sitting\"",
            ))
        }
    };
    let steps = raw.steps.unwrap_or(false);
    let to_m = unit.to_metres();
    let seat =
        match (sitting, raw.seat_height) {
            (false, None) => None,
            (false, Some(h)) => {
                return Err(FieldError::new(
                    "worker.seat_height",
                    h.to_string(),
                    "a seat height needs worker.posture = \"sitting\"",
                ))
            }
            (true, _) if steps => return Err(FieldError::new(
                "worker.steps",
                "true",
                "a seated worker does not step (worker.posture = \"sitting\"): a target out of \
                 reach from the seat is out of reach",
            )),
            (true, height) => {
                let body = pliant_worker::body(population)
                    .map_err(|e| field_error("worker.population", e))?;
                Some(match height {
                    None => Seat::for_body(&body),
                    Some(h) => {
                        let h = finite("worker.seat_height", h, unit.symbol())?;
                        Seat::new(&body, h * to_m, "worker.seat_height")
                            .map_err(|e| field_error("worker.seat_height", e))?
                    }
                })
            }
        };
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
        seat,
        interval,
        decide: raw.decide.unwrap_or(true),
        steps,
        scores: ScoreOptions {
            static_or_repeated: false,
            coupling,
        },
    }))
}
