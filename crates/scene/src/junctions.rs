//! `[[junctions]]` (SPEC N1): hose ends joined into networks, checked against the hoses
//! they name. A welded branch point's ends must meet at one point; a junction body's
//! outlets may lie apart.

use crate::error::FieldError;
use crate::format::{HoseEndName, InertiaEntry, JunctionBodyEntry, JunctionEntry};
use crate::units::LengthUnit;
use crate::validate::{finite_vec, non_negative};
use glam::{DMat3, DVec3};
use pliant_core::rod::attached::check_inertia;
use pliant_core::{HoseEnd, HoseSpec, JunctionSpec, RigidPartSpec};

/// How far apart a welded branch point's ends may lie \[m\]: what a CAD export rounds to.
pub const WELD_TOLERANCE: f64 = 1e-5;

/// Checks and builds every junction.
pub fn build_junctions(
    entries: &[JunctionEntry],
    hoses: &[HoseSpec],
    parts: &[RigidPartSpec],
    unit: LengthUnit,
) -> Result<Vec<JunctionSpec>, FieldError> {
    let mut specs: Vec<JunctionSpec> = Vec::with_capacity(entries.len());
    // which junction each hose end already belongs to
    let mut taken: std::collections::HashMap<(usize, HoseEnd), usize> = Default::default();
    for (j, raw) in entries.iter().enumerate() {
        let at = |rest: &str| format!("junctions[{j}].{rest}");
        if raw.name.trim().is_empty() {
            return Err(FieldError::new(
                at("name"),
                "\"\"",
                "a junction name must not be empty",
            ));
        }
        if let Some(first) = entries[..j].iter().position(|e| e.name == raw.name) {
            return Err(FieldError::new(
                at("name"),
                format!("\"{}\"", raw.name),
                format!("duplicate junction name (also junctions[{first}].name)"),
            ));
        }
        if raw.ends.len() < 2 {
            return Err(FieldError::new(
                at("ends"),
                format!("{} end(s)", raw.ends.len()),
                "a junction joins at least two hose ends",
            ));
        }
        let mut ends = Vec::with_capacity(raw.ends.len());
        for (k, end) in raw.ends.iter().enumerate() {
            let field = at(&format!("ends[{k}].hose"));
            let Some(hose) = hoses.iter().position(|h| h.name == end.hose) else {
                return Err(FieldError::new(
                    field,
                    format!("\"{}\"", end.hose),
                    "no hose of this name",
                ));
            };
            let which = match end.end {
                HoseEndName::Start => HoseEnd::Start,
                HoseEndName::End => HoseEnd::End,
            };
            if let Some(&other) = taken.get(&(hose, which)) {
                let place = if other == j {
                    "this junction".to_string()
                } else {
                    format!("junctions[{other}] (\"{}\")", entries[other].name)
                };
                return Err(FieldError::new(
                    at(&format!("ends[{k}]")),
                    format!("{} {:?}", end.hose, which).to_lowercase(),
                    format!("this hose end is already joined at {place}"),
                ));
            }
            taken.insert((hose, which), j);
            ends.push((hose, which));
        }
        let point = |&(hose, end): &(usize, HoseEnd)| {
            let nodes = &hoses[hose].nodes;
            match end {
                HoseEnd::Start => nodes[0],
                HoseEnd::End => nodes[nodes.len() - 1],
            }
        };
        let body_mass = match &raw.body {
            Some(body) => non_negative(&at("body.mass_kg"), body.mass_kg, "kg")?,
            None => {
                let first = point(&ends[0]);
                for (k, end) in ends.iter().enumerate().skip(1) {
                    let gap = (point(end) - first).length();
                    if gap > WELD_TOLERANCE {
                        return Err(FieldError::new(
                            at(&format!("ends[{k}]")),
                            format!(
                                "{} {}",
                                gap / unit.to_metres(),
                                unit.symbol()
                            ),
                            format!(
                                "lies {:.3} mm from ends[0]: a welded branch point's ends must meet at one point (within {} mm); give `body` for a junction body whose outlets lie apart",
                                gap * 1e3,
                                WELD_TOLERANCE * 1e3
                            ),
                        ));
                    }
                }
                0.0
            }
        };
        let (body_centre, body_inertia) = match &raw.body {
            Some(body) => own_mass(body, body_mass, unit, &at)?,
            None => (None, None),
        };
        let shape = match raw.body.as_ref().and_then(|b| b.part.as_deref()) {
            Some(name) => Some(shape_part(name, parts, &specs, entries, &at)?),
            None => None,
        };
        specs.push(JunctionSpec {
            name: raw.name.clone(),
            ends,
            body_mass,
            body_centre,
            body_inertia,
            shape,
        });
    }
    Ok(specs)
}

/// The index of the part named `name` that a junction body takes as its shape, checked:
/// it exists, stands still on its own (no motion, no parent, not moved by the
/// timeline), carries no other part and is no earlier junction's shape (`done`).
fn shape_part(
    name: &str,
    parts: &[RigidPartSpec],
    done: &[JunctionSpec],
    entries: &[JunctionEntry],
    at: &dyn Fn(&str) -> String,
) -> Result<usize, FieldError> {
    let field = at("body.part");
    let value = format!("\"{name}\"");
    let refuse = |reason: String| Err(FieldError::new(&field, &value, reason));
    let Some(k) = parts.iter().position(|p| p.name == name) else {
        return refuse("no part of this name in [[parts]]".into());
    };
    let part = &parts[k];
    if part.motion.is_some() {
        return refuse(
            "the part has a `motion`; a junction body's shape moves with the body only".into(),
        );
    }
    if part.parent.is_some() {
        return refuse(
            "the part has a `parent`; a junction body's shape moves with the body only".into(),
        );
    }
    if part.movable {
        return refuse(
            "the timeline moves the part; a junction body's shape moves with the body only".into(),
        );
    }
    if let Some(child) = parts.iter().find(|p| p.parent == Some(k)) {
        return refuse(format!(
            "part \"{}\" has it as its `parent`; a junction body's shape carries no parts",
            child.name
        ));
    }
    if let Some(other) = done.iter().position(|s| s.shape == Some(k)) {
        return refuse(format!(
            "the part is already the shape of junctions[{other}] (\"{}\")",
            entries[other].name
        ));
    }
    Ok(k)
}

/// A body's own centre of mass \[m\] and inertia tensor, checked (`at` names a field of
/// this junction).
fn own_mass(
    body: &JunctionBodyEntry,
    mass: f64,
    unit: LengthUnit,
    at: &dyn Fn(&str) -> String,
) -> Result<(Option<DVec3>, Option<DMat3>), FieldError> {
    let centre = match body.centre_of_mass {
        Some(c) => {
            Some(finite_vec(&at("body.centre_of_mass"), c, unit.symbol())? * unit.to_metres())
        }
        None => None,
    };
    let inertia = match body.inertia_kg_m2 {
        Some(entry) => {
            let field = at("body.inertia_kg_m2");
            let j = match entry {
                InertiaEntry::Principal(d) => DMat3::from_diagonal(DVec3::from_array(d)),
                // rows as written; a symmetric tensor is its own transpose
                InertiaEntry::Tensor(rows) => DMat3::from_cols_array_2d(&rows).transpose(),
            };
            check_inertia(j).map_err(|reason| {
                FieldError::new(
                    &field,
                    format!("{:?}", j.transpose().to_cols_array_2d()),
                    format!("the inertia tensor about the centre of mass {reason}"),
                )
            })?;
            Some(j)
        }
        None => None,
    };
    if (centre.is_some() || inertia.is_some()) && !(mass > 0.0) {
        return Err(FieldError::new(
            at("body.mass_kg"),
            format!("{mass} kg"),
            "a body with its own centre of mass or inertia needs a mass > 0 kg",
        ));
    }
    Ok((centre, inertia))
}
