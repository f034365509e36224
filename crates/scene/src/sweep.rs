//! Building a scene's range-of-motion study (`[sweep]`, SPEC K2): the swept part and the
//! parts whose clearance is watched resolved by name, the clearance limit in metres.

use crate::error::FieldError;
use crate::fasteners::part_index;
use crate::format::SweepSection;
use crate::units::LengthUnit;
use crate::validate::non_negative;
use pliant_assembly::sweep::{CoordinateKind, SweepSettings};
use pliant_assembly::{Action, Timeline};
use pliant_core::spec::RigidPartSpec;

/// Checks and builds `[sweep]` against the built `parts` (the swept part must move);
/// a part the `timeline` moves is swept against its angle when the timeline only turns
/// it, its travel when it only shifts it, else time.
pub fn build_sweep(
    raw: Option<&SweepSection>,
    parts: &[RigidPartSpec],
    timeline: &Timeline,
    unit: LengthUnit,
) -> Result<Option<SweepSettings>, FieldError> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
    let part = part_index("sweep.part", Some(&raw.part), &names)?.unwrap_or_default();
    let moves = {
        let mut at = Some(part);
        let mut found = false;
        for _ in 0..=parts.len() {
            let Some(k) = at else { break };
            found |= parts[k].motion.is_some() || parts[k].movable;
            at = parts[k].parent;
        }
        found
    };
    if !moves {
        return Err(FieldError::new(
            "sweep.part",
            format!("\"{}\"", raw.part),
            "the part does not move: give it (or its parent) a `motion`, or move it in the timeline (`rotate_part`, `move_part`), to sweep",
        ));
    }
    let mut clearance_parts = Vec::new();
    for (k, name) in raw.clearance_to.iter().flatten().enumerate() {
        let field = format!("sweep.clearance_to[{k}]");
        clearance_parts.extend(part_index(&field, Some(name), &names)?);
    }
    let min_clearance = match raw.min_clearance {
        Some(m) => Some(non_negative("sweep.min_clearance", m, unit.symbol())? * unit.to_metres()),
        None => None,
    };
    let name = &parts[part].name;
    let (turned, shifted) = timeline
        .actions
        .iter()
        .fold((false, false), |(r, m), a| match a {
            Action::RotatePart { part, .. } if part == name => (true, m),
            Action::MovePart { part, .. } if part == name => (r, true),
            _ => (r, m),
        });
    let moved_by_inputs = parts[part].movable.then_some(match (turned, shifted) {
        (true, false) => CoordinateKind::Angle,
        (false, true) => CoordinateKind::Travel,
        _ => CoordinateKind::Time,
    });
    Ok(Some(SweepSettings {
        part,
        clearance_parts,
        min_clearance,
        moved_by_inputs,
    }))
}
