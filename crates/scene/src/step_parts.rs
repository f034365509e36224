//! Rigid parts from a STEP assembly (`[[parts]] step = "bay.step"`): every solid of the
//! file becomes a part named `NAME/solid path` (the file's product and instance names),
//! placed as in the assembly and then by the entry's `position` and `rotation`. The
//! meshes come from the STEP cache ([`crate::step_cache`]); solids the converter could
//! not read are warnings that reach the user, never silently dropped.

use crate::budget::Budget;
use crate::error::FieldError;
use crate::files::FileAccess;
use crate::format::PartEntry;
use crate::glb_solids::{glb_facts, read_glb_solids};
use crate::mesh::{bounds, check_mesh};
use crate::parts::{friction, pose, BuiltParts, DEFAULT_FRICTION_SLIDING, DEFAULT_FRICTION_STATIC};
use crate::scene::PartInfo;
use crate::step_cache::{cached_mesh, DEFAULT_CHORD_TOLERANCE};
use crate::units::LengthUnit;
use crate::validate::positive;
use pliant_core::RigidPartSpec;

/// Builds `parts[index]`, a STEP part, into `built` (one part per solid).
pub fn build_step_part(
    index: usize,
    raw: &PartEntry,
    unit: LengthUnit,
    files: &FileAccess,
    budget: &mut Budget,
    built: &mut BuiltParts,
) -> Result<(), FieldError> {
    let at = |rest: &str| format!("parts[{index}].{rest}");
    let Some(file) = raw.step.as_deref() else {
        return Err(FieldError::about(at("step"), "missing"));
    };
    if raw.mesh_unit.is_some() {
        return Err(FieldError::about(
            at("mesh_unit"),
            "not allowed with `step`: a STEP file carries its own length unit",
        ));
    }
    let field = at("step");
    let err = |reason: String| FieldError::new(field.clone(), format!("\"{file}\""), reason);
    if file.trim().is_empty() {
        return Err(err("must name a STEP file".to_string()));
    }
    let tolerance = match raw.chord_tolerance {
        Some(t) => positive(&at("chord_tolerance"), t, unit.symbol())? * unit.to_metres(),
        None => DEFAULT_CHORD_TOLERANCE,
    };
    let (position, rotation) = pose(index, raw, unit)?;
    let (friction_static, friction_sliding) = friction(
        &at("friction"),
        raw.friction.as_ref(),
        (DEFAULT_FRICTION_STATIC, DEFAULT_FRICTION_SLIDING),
    )?;

    let cached = cached_mesh(files, file, tolerance).map_err(err)?;
    let (facts, triangles) = glb_facts(&cached.glb).map_err(err)?;
    // counted before any geometry is built
    budget.add_triangles(&field, triangles)?;
    let solids = read_glb_solids(&cached.glb).map_err(err)?;
    if solids.is_empty() {
        return Err(err("the STEP file holds no solid".to_string()));
    }
    let source = files.shown(file);
    for s in &facts.skipped {
        built.warnings.push(format!(
            "parts[{index}] (\"{}\", {source}): skipped {s}",
            raw.name
        ));
    }
    for solid in solids {
        let name = format!("{}/{}", raw.name, solid.name);
        let checked = match check_mesh(solid.mesh) {
            Ok(c) => c,
            Err(reason) => {
                built.warnings.push(format!(
                    "parts[{index}] (\"{}\", {source}): skipped solid \"{}\": {reason}",
                    raw.name, solid.name
                ));
                continue;
            }
        };
        let vertices: Vec<_> = checked
            .mesh
            .vertices
            .iter()
            .map(|v| position + rotation * *v)
            .collect();
        if vertices.iter().any(|v| !v.is_finite()) {
            return Err(FieldError::about(
                format!("parts[{index}]"),
                "coordinates overflow after placing the part",
            ));
        }
        built.infos.push(PartInfo {
            name: name.clone(),
            source: format!("{source} (solid \"{}\", {})", solid.name, cached.cache),
            triangles: checked.mesh.triangles.len(),
            dropped_degenerate: checked.dropped_degenerate,
            bounds: bounds(&vertices),
        });
        built.specs.push(RigidPartSpec {
            name,
            vertices,
            triangles: checked.mesh.triangles,
            friction_static,
            friction_sliding,
            motion: None,
            parent: None,
            movable: false,
        });
    }
    Ok(())
}
