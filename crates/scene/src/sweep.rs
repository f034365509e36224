//! Building a scene's range-of-motion study (`[sweep]`, SPEC K2): the swept part and the
//! parts whose clearance is watched resolved by name, the clearance limit and the
//! envelopes' voxel size in metres.

use crate::error::FieldError;
use crate::fasteners::part_index;
use crate::format::SweepSection;
use crate::units::LengthUnit;
use crate::validate::{non_negative, positive};
use pliant_assembly::sweep::envelope::{grid_cells, voxel_size};
use pliant_assembly::sweep::voxels::MAX_CELLS;
use pliant_assembly::sweep::{CoordinateKind, SweepSettings};
use pliant_assembly::{Action, Timeline};
use pliant_core::spec::{HoseSpec, RigidPartSpec};

/// Checks and builds `[sweep]` against the built `hoses` and `parts` (the swept part
/// must move; the envelopes' voxel must fit their grid over the hoses as placed);
/// a part the `timeline` moves is swept against its angle when the timeline only turns
/// it, its travel when it only shifts it, else time.
pub fn build_sweep(
    raw: Option<&SweepSection>,
    hoses: &[HoseSpec],
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
    let envelope_voxel = match raw.envelope_voxel {
        Some(h) => Some(positive("sweep.envelope_voxel", h, unit.symbol())? * unit.to_metres()),
        None => None,
    };
    check_envelope_grid(envelope_voxel, hoses, unit)?;
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
        envelope_voxel,
    }))
}

/// Refuses a voxel size `chosen` \[m\] whose envelope grid over the hoses as placed (a
/// lower bound on the grid of any sweep of them) exceeds [`MAX_CELLS`], before anything
/// is allocated; the error gives the smallest voxel that fits.
fn check_envelope_grid(
    chosen: Option<f64>,
    hoses: &[HoseSpec],
    unit: LengthUnit,
) -> Result<(), FieldError> {
    let Some(chosen) = chosen else {
        return Ok(()); // the default is checked as the samples come (as before)
    };
    let radii = hoses
        .iter()
        .flat_map(|h| h.sections.iter().map(|s| s.outer_radius()));
    let (thinnest, thickest) = radii.fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| {
        (lo.min(r), hi.max(r))
    });
    let points = hoses.iter().flat_map(|h| h.nodes.iter().copied());
    let (lo, hi) = points.fold(
        (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    );
    if !lo.is_finite() {
        return Ok(()); // no hose: nothing is swept
    }
    let h = voxel_size(Some(chosen), thinnest);
    let cells = grid_cells(lo, hi, thickest, h);
    if cells <= MAX_CELLS as f64 {
        return Ok(());
    }
    // the smallest voxel that fits: the cells fall as 1/h³ (a little faster: the reach)
    let mut fits = h * (cells / MAX_CELLS as f64).cbrt();
    while grid_cells(lo, hi, thickest, fits) > MAX_CELLS as f64 {
        fits *= 1.01;
    }
    let to_unit = |m: f64| m / unit.to_metres();
    // three significant digits, rounded up (so the size offered fits)
    let fits = to_unit(fits);
    let decimals = (2 - fits.log10().floor() as i32).max(0);
    let scale = 10f64.powi(decimals);
    let fits = (fits * scale).ceil() / scale;
    Err(FieldError::new(
        "sweep.envelope_voxel",
        format!("{} {}", to_unit(chosen), unit.symbol()),
        format!(
            "the envelopes' grid over the hoses as placed would hold {cells:.3e} voxels (at most {MAX_CELLS}): choose a voxel of at least {fits:.prec$} {}",
            unit.symbol(),
            prec = decimals as usize
        ),
    ))
}
