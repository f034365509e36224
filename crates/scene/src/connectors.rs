//! Building connectors (`[[connectors]]`): the counterpart's mouth, axis and travel in
//! metres, the mating force curve, latch and retention checked, as the assembly layer's
//! [`Mating`].

use crate::error::FieldError;
use crate::fasteners::{d_outer_at, hose_end, part_index, MIN_STUB_LENGTH};
use crate::format::ConnectorEntry;
use crate::scene::SceneConnector;
use crate::units::LengthUnit;
use crate::validate::{finite_vec, non_negative, non_zero_vec, positive, with_unit};
use pliant_assembly::stub::{Mating, StubSpec, MAX_MATING_POINTS};
use pliant_core::HoseSpec;

/// Checks and builds `connectors[index]`.
pub fn build_connector(
    index: usize,
    raw: &ConnectorEntry,
    hoses: &[HoseSpec],
    unit: LengthUnit,
    parts: &[&str],
) -> Result<SceneConnector, FieldError> {
    let at = |rest: &str| format!("connectors[{index}].{rest}");
    let part = part_index(&at("part"), raw.part.as_ref(), parts)?;
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let origin = finite_vec(&at("origin"), raw.origin, u)? * scale;
    let axis = non_zero_vec(&at("axis"), raw.axis, "")?;
    let travel = positive(&at("travel"), raw.travel, u)? * scale;
    if travel < MIN_STUB_LENGTH {
        return Err(FieldError::new(
            at("travel"),
            with_unit(raw.travel, u),
            "a connector's travel must be at least 1 mm",
        ));
    }
    let hose_end = hose_end(at, raw.hose.as_ref(), raw.end, hoses, "into the connector")?;
    let hose = &hoses[hose_end.hose];
    let size = match raw.size {
        Some(s) => positive(&at("size"), s, u)? * scale,
        None => 2.0 * d_outer_at(hose, hose_end.node(hose.nodes.len())),
    };
    if raw.mating_force.is_empty() || raw.mating_force.len() > MAX_MATING_POINTS {
        return Err(FieldError::new(
            at("mating_force"),
            format!("{} points", raw.mating_force.len()),
            format!("needs 1 to {MAX_MATING_POINTS} points [travel, force_n]"),
        ));
    }
    let mut curve = Vec::with_capacity(raw.mating_force.len());
    for (k, &[s, f]) in raw.mating_force.iter().enumerate() {
        let field = at(&format!("mating_force[{k}]"));
        let s = non_negative(&field, s, u)? * scale;
        let f = non_negative(&field, f, "N")?;
        if s > travel {
            return Err(FieldError::about(
                field,
                "travel beyond the connector's `travel`",
            ));
        }
        if curve.last().is_some_and(|&(prev, _)| s <= prev) {
            return Err(FieldError::about(
                field,
                "the points' travel must increase from one point to the next",
            ));
        }
        curve.push((s, f));
    }
    let latch_at = match raw.latch_at {
        Some(l) => positive(&at("latch_at"), l, u)? * scale,
        None => travel,
    };
    if latch_at > travel {
        return Err(FieldError::new(
            at("latch_at"),
            with_unit(raw.latch_at.unwrap_or_default(), u),
            "must not lie beyond the connector's `travel`",
        ));
    }
    let retention = non_negative(&at("retention_force_n"), raw.retention_force_n, "N")?;
    let counterpart = StubSpec::new(origin, axis, travel, size, 0.0, 0.0)
        .map_err(|e| FieldError::about(format!("connectors[{index}]"), e.to_string()))?;
    let mating = Mating::new(counterpart, &curve, latch_at, retention)
        .map_err(|e| FieldError::about(format!("connectors[{index}]"), e.to_string()))?;
    Ok(SceneConnector {
        name: raw.name.clone(),
        mating,
        hose_end,
        part,
    })
}
