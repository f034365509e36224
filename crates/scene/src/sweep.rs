//! Building a scene's range-of-motion study (`[sweep]`, SPEC K2): the swept part and the
//! parts whose clearance is watched resolved by name, the clearance limit in metres.

use crate::error::FieldError;
use crate::fasteners::part_index;
use crate::format::SweepSection;
use crate::units::LengthUnit;
use crate::validate::non_negative;
use pliant_assembly::sweep::SweepSettings;
use pliant_core::spec::RigidPartSpec;

/// Checks and builds `[sweep]` against the built `parts` (the swept part must move).
pub fn build_sweep(
    raw: Option<&SweepSection>,
    parts: &[RigidPartSpec],
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
            found |= parts[k].motion.is_some();
            at = parts[k].parent;
        }
        found
    };
    if !moves {
        return Err(FieldError::new(
            "sweep.part",
            format!("\"{}\"", raw.part),
            "the part does not move: give it (or its parent) a `motion` to sweep",
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
    Ok(Some(SweepSettings {
        part,
        clearance_parts,
        min_clearance,
    }))
}
