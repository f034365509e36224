//! Building rigid parts (SPEC §5, L4): a mesh file or a primitive, posed, converted to
//! metres, checked, as a core [`RigidPartSpec`] in world coordinates.

use crate::budget::Budget;
use crate::error::FieldError;
use crate::files::FileAccess;
use crate::format::{FrictionEntry, PartEntry};
use crate::mesh::{
    bounds, box_mesh, check_mesh, check_triangle_count, cylinder_mesh, cylinder_triangles,
    read_mesh_file, sphere_mesh, sphere_triangles, MeshFormat, TriMesh, DEFAULT_CYLINDER_SEGMENTS,
    DEFAULT_SPHERE_SUBDIVISIONS, MAX_TRIANGLES,
};
use crate::scene::PartInfo;
use crate::units::LengthUnit;
use crate::validate::{finite, finite_vec, non_negative, non_zero_vec, positive, with_unit};
use glam::{DQuat, DVec3};
use pliant_core::RigidPartSpec;
use std::path::Path;

/// Default static friction coefficient of a hose on a part. Assumption: the dissertation
/// gives none; 0.5 is typical of rubber on painted or lacquered metal and hard plastics.
pub const DEFAULT_FRICTION_STATIC: f64 = 0.5;
/// Default sliding friction coefficient (assumption, see [`DEFAULT_FRICTION_STATIC`]).
pub const DEFAULT_FRICTION_SLIDING: f64 = 0.4;

/// The shape kinds of a part, as written.
const KINDS: &str = "`mesh`, `step`, `box`, `cylinder`, `sphere`";

/// Every part of a scene, built: the core's parts, their facts, and warnings for the
/// user (e.g. solids of a STEP assembly that could not be read).
#[derive(Clone, Debug, Default)]
pub struct BuiltParts {
    pub specs: Vec<RigidPartSpec>,
    pub infos: Vec<PartInfo>,
    pub warnings: Vec<String>,
}

/// Checks and builds every part; `files` resolves and reads mesh files. A STEP part
/// gives one part per solid ([`crate::step_parts`]).
pub fn build_parts(
    raw: &[PartEntry],
    unit: LengthUnit,
    files: &FileAccess,
    budget: &mut Budget,
) -> Result<BuiltParts, FieldError> {
    for (i, p) in raw.iter().enumerate() {
        if p.name.trim().is_empty() {
            return Err(FieldError::new(
                format!("parts[{i}].name"),
                format!("\"{}\"", p.name),
                "a part name must not be empty",
            ));
        }
        if let Some(first) = raw[..i].iter().position(|q| q.name == p.name) {
            return Err(FieldError::new(
                format!("parts[{i}].name"),
                format!("\"{}\"", p.name),
                format!("duplicate part name (also parts[{first}].name)"),
            ));
        }
    }
    let mut built = BuiltParts::default();
    // per entry, the parts it gave
    let mut gave = Vec::with_capacity(raw.len());
    for (i, p) in raw.iter().enumerate() {
        let only_step = p.step.is_some()
            && p.mesh.is_none()
            && p.box_.is_none()
            && p.cylinder.is_none()
            && p.sphere.is_none();
        let first_new = built.specs.len();
        if only_step {
            crate::step_parts::build_step_part(i, p, unit, files, budget, &mut built)?;
        } else {
            let (spec, info) = build_part(i, p, unit, files, budget)?;
            built.specs.push(spec);
            built.infos.push(info);
        }
        for spec in &built.specs[first_new..] {
            if let Some(other) = built.specs[..first_new]
                .iter()
                .position(|q| q.name == spec.name)
            {
                return Err(FieldError::new(
                    format!("parts[{i}].name"),
                    format!("\"{}\"", p.name),
                    format!(
                        "gives the part \"{}\", which an earlier part already is (part {other}); rename one",
                        spec.name
                    ),
                ));
            }
        }
        gave.push(first_new..built.specs.len());
    }
    place_motions(raw, unit, files, &gave, &mut built)?;
    Ok(built)
}

/// Gives each entry's parts their `motion` and `parent` ([`crate::part_motion`]): a
/// parent is named by its entry's `name` (a STEP entry's first solid stands for it).
fn place_motions(
    raw: &[PartEntry],
    unit: LengthUnit,
    files: &FileAccess,
    gave: &[std::ops::Range<usize>],
    built: &mut BuiltParts,
) -> Result<(), FieldError> {
    for (i, p) in raw.iter().enumerate() {
        let at = |rest: &str| format!("parts[{i}].motion.{rest}");
        let motion = match &p.motion {
            Some(m) => Some(crate::part_motion::build_motion(m, &at, unit, files)?),
            None => None,
        };
        let parent = match &p.parent {
            None => None,
            Some(name) => {
                let Some(j) = raw.iter().position(|q| &q.name == name) else {
                    let names: Vec<&str> = raw.iter().map(|q| q.name.as_str()).collect();
                    return Err(FieldError::new(
                        format!("parts[{i}].parent"),
                        format!("\"{name}\""),
                        format!("names no part; parts are: {}", names.join(", ")),
                    ));
                };
                if j == i {
                    return Err(FieldError::new(
                        format!("parts[{i}].parent"),
                        format!("\"{name}\""),
                        "a part cannot be its own parent",
                    ));
                }
                Some(gave[j].start)
            }
        };
        let movable = p.movable.unwrap_or(false);
        if movable && motion.is_some() {
            return Err(FieldError::new(
                format!("parts[{i}].movable"),
                "true",
                "a part with a `motion` cannot be moved by inputs as well",
            ));
        }
        for k in gave[i].clone() {
            built.specs[k].motion = motion.clone();
            built.specs[k].parent = parent;
            built.specs[k].movable = movable;
        }
    }
    // a cycle of parents: named at the first part in it
    let parts: Vec<_> = built
        .specs
        .iter()
        .map(|s| (s.motion.clone(), s.parent))
        .collect();
    let (motions, parents) = parts.into_iter().unzip();
    if let Err(e) = pliant_core::kinematics::PartKinematics::new(motions, parents) {
        let part = e
            .split_once(':')
            .and_then(|(h, _)| h.strip_prefix("part ")?.parse::<usize>().ok())
            .and_then(|k| gave.iter().position(|r| r.contains(&k)))
            .unwrap_or(0);
        return Err(FieldError::about(format!("parts[{part}].parent"), e));
    }
    Ok(())
}

/// The pose of `parts[index]`: position \[m\] and rotation.
pub(crate) fn pose(
    index: usize,
    raw: &PartEntry,
    unit: LengthUnit,
) -> Result<(DVec3, DQuat), FieldError> {
    let at = |rest: &str| format!("parts[{index}].{rest}");
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let position = match raw.position {
        Some(p) => finite_vec(&at("position"), p, u)? * scale,
        None => DVec3::ZERO,
    };
    let rotation = match &raw.rotation {
        Some(r) => {
            let axis = non_zero_vec(&at("rotation.axis"), r.axis, "")?;
            let angle = finite(&at("rotation.angle_deg"), r.angle_deg, "°")?;
            DQuat::from_axis_angle(axis.normalize(), angle.to_radians())
        }
        None => DQuat::IDENTITY,
    };
    Ok((position, rotation))
}

/// Checks and builds `parts[index]`.
pub fn build_part(
    index: usize,
    raw: &PartEntry,
    unit: LengthUnit,
    files: &FileAccess,
    budget: &mut Budget,
) -> Result<(RigidPartSpec, PartInfo), FieldError> {
    let at = |rest: &str| format!("parts[{index}].{rest}");
    let (u, scale) = (unit.symbol(), unit.to_metres());

    let given: Vec<&str> = [
        ("mesh", raw.mesh.is_some()),
        ("step", raw.step.is_some()),
        ("box", raw.box_.is_some()),
        ("cylinder", raw.cylinder.is_some()),
        ("sphere", raw.sphere.is_some()),
    ]
    .iter()
    .filter(|(_, g)| *g)
    .map(|(n, _)| *n)
    .collect();
    match given.len() {
        0 => {
            return Err(FieldError::about(
                format!("parts[{index}]"),
                format!("a part needs exactly one of {KINDS}"),
            ))
        }
        1 => {}
        _ => {
            return Err(FieldError::about(
                format!("parts[{index}]"),
                format!(
                    "give exactly one of {KINDS}, not {}",
                    given
                        .iter()
                        .map(|g| format!("`{g}`"))
                        .collect::<Vec<_>>()
                        .join(" and ")
                ),
            ))
        }
    }
    if raw.mesh_unit.is_some() && raw.mesh.is_none() {
        return Err(FieldError::about(
            at("mesh_unit"),
            "only allowed with `mesh` (primitive sizes are in the scene's length_unit)",
        ));
    }

    if raw.chord_tolerance.is_some() {
        return Err(FieldError::about(
            at("chord_tolerance"),
            "only allowed with `step` (the tessellation tolerance of a STEP file)",
        ));
    }
    let (position, rotation) = pose(index, raw, unit)?;
    let (friction_static, friction_sliding) = friction(
        &at("friction"),
        raw.friction.as_ref(),
        (DEFAULT_FRICTION_STATIC, DEFAULT_FRICTION_SLIDING),
    )?;

    // The local mesh in metres, its source, and how many degenerate triangles went.
    let (local, source, dropped) = if let Some(file) = &raw.mesh {
        let field = at("mesh");
        let err = |reason: String| FieldError::new(field.clone(), format!("\"{file}\""), reason);
        if file.trim().is_empty() {
            return Err(err("must name a mesh file".to_string()));
        }
        let format = MeshFormat::of(Path::new(file)).map_err(err)?;
        let mesh_unit = raw.mesh_unit.unwrap_or(match format {
            MeshFormat::Gltf => LengthUnit::Metre,
            MeshFormat::Obj | MeshFormat::Stl => unit,
        });
        let mesh = read_mesh_file(files, file).map_err(err)?;
        let checked = check_mesh(mesh).map_err(err)?;
        budget.add_triangles(&field, checked.mesh.triangles.len() as u64)?;
        let s = mesh_unit.to_metres();
        let mut mesh = checked.mesh;
        for v in &mut mesh.vertices {
            *v *= s;
        }
        (mesh, files.shown(file), checked.dropped_degenerate)
    } else if let Some(b) = &raw.box_ {
        let mut size = DVec3::ZERO;
        for k in 0..3 {
            size[k] = positive(&at(&format!("box.size[{k}]")), b.size[k], u)? * scale;
        }
        let mesh = box_mesh(size);
        budget.add_triangles(&at("box"), mesh.triangles.len() as u64)?;
        (mesh, "box".to_string(), 0)
    } else if let Some(c) = &raw.cylinder {
        let radius = positive(&at("cylinder.radius"), c.radius, u)? * scale;
        let height = positive(&at("cylinder.height"), c.height, u)? * scale;
        let segments = c.segments.unwrap_or(DEFAULT_CYLINDER_SEGMENTS);
        if segments < 3 {
            return Err(FieldError::new(
                at("cylinder.segments"),
                segments.to_string(),
                "must be at least 3",
            ));
        }
        check_triangle_count(cylinder_triangles(segments)).map_err(|r| {
            FieldError::new(
                at("cylinder.segments"),
                segments.to_string(),
                format!("gives {r}"),
            )
        })?;
        budget.add_triangles(
            &at("cylinder.segments"),
            cylinder_triangles(segments) as u64,
        )?;
        (
            cylinder_mesh(radius, height, segments),
            "cylinder".to_string(),
            0,
        )
    } else if let Some(s) = &raw.sphere {
        let radius = positive(&at("sphere.radius"), s.radius, u)? * scale;
        let subdivisions = s.subdivisions.unwrap_or(DEFAULT_SPHERE_SUBDIVISIONS);
        let count = sphere_triangles(subdivisions).unwrap_or(usize::MAX);
        if count > MAX_TRIANGLES {
            let n = if count == usize::MAX {
                "more than 2^64 triangles".to_string()
            } else {
                format!("{count} triangles")
            };
            return Err(FieldError::new(
                at("sphere.subdivisions"),
                subdivisions.to_string(),
                format!("gives {n}; at most {MAX_TRIANGLES} are supported per part"),
            ));
        }
        budget.add_triangles(&at("sphere.subdivisions"), count as u64)?;
        (sphere_mesh(radius, subdivisions), "sphere".to_string(), 0)
    } else {
        unreachable!("exactly one shape kind was checked above")
    };

    let TriMesh {
        vertices,
        triangles,
    } = local;
    let vertices: Vec<DVec3> = vertices
        .into_iter()
        .map(|v| position + rotation * v)
        .collect();
    if vertices.iter().any(|v| !v.is_finite()) {
        return Err(FieldError::about(
            format!("parts[{index}]"),
            "coordinates overflow after scaling and placing the part",
        ));
    }
    let info = PartInfo {
        name: raw.name.clone(),
        source,
        triangles: triangles.len(),
        dropped_degenerate: dropped,
        bounds: bounds(&vertices),
    };
    let spec = RigidPartSpec {
        name: raw.name.clone(),
        vertices,
        triangles,
        friction_static,
        friction_sliding,
        motion: None,
        parent: None,
        movable: false,
    };
    Ok((spec, info))
}

/// Checks `friction`: both ≥ 0 and sliding ≤ static; `default` (static, sliding) when
/// absent.
pub(crate) fn friction(
    field: &str,
    raw: Option<&FrictionEntry>,
    default: (f64, f64),
) -> Result<(f64, f64), FieldError> {
    let Some(f) = raw else {
        return Ok(default);
    };
    let st = non_negative(&format!("{field}.static"), f.static_, "")?;
    let sl = non_negative(&format!("{field}.sliding"), f.sliding, "")?;
    if sl > st {
        return Err(FieldError::new(
            format!("{field}.sliding"),
            with_unit(sl, ""),
            format!("must not exceed static ({})", with_unit(st, "")),
        ));
    }
    Ok((st, sl))
}
