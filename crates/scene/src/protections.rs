//! A hose's `protections`: what covers which stretch of a harness segment (tape,
//! corrugated tube, sleeve), addressed by arc length as `spans` are. They say what is
//! where, for drawing and reports; the stiffness, diameter and mass of a protected stretch
//! are its span's section.

use serde::Serialize;

use crate::error::FieldError;
use crate::format::{HoseEntry, ProtectionKindName};
use crate::hoses::stretch;
use crate::units::LengthUnit;
use crate::validate::with_unit;

/// A protection over the stretch `from..to` of a hose (arc length along its centre line,
/// m).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ProtectionSpan {
    pub kind: ProtectionKindName,
    pub from: f64,
    pub to: f64,
}

/// Checks hose `index`'s protections against its `length` \[m\]: each within the hose,
/// none overlapping another of its kind.
pub fn build_protections(
    index: usize,
    raw: &HoseEntry,
    unit: LengthUnit,
    length: f64,
) -> Result<Vec<ProtectionSpan>, FieldError> {
    let u = unit.symbol();
    let mut out: Vec<ProtectionSpan> = Vec::with_capacity(raw.protections.len());
    for (k, p) in raw.protections.iter().enumerate() {
        let field = format!("hoses[{index}].protections[{k}]");
        let (from, to) = stretch(&format!("{field}."), p.from, p.to, unit, length)?;
        if let Some(j) = out
            .iter()
            .position(|q| q.kind == p.kind && from < q.to && q.from < to)
        {
            let q = &raw.protections[j];
            return Err(FieldError::new(
                field,
                format!("{}..{}", with_unit(p.from, u), with_unit(p.to, u)),
                format!(
                    "overlaps protections[{j}] ({}..{}), of the same kind \"{}\": one protection of a kind per stretch",
                    with_unit(q.from, u),
                    with_unit(q.to, u),
                    p.kind.key()
                ),
            ));
        }
        out.push(ProtectionSpan {
            kind: p.kind,
            from,
            to,
        });
    }
    Ok(out)
}
