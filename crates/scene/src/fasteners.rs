//! Building connector stubs (SPEC L6), connectors (plugged; [`crate::connectors`]) and
//! clips (SPEC L7): positions and sizes converted to metres, directions normalised, names
//! and hose references checked, as the assembly layer's [`StubSpec`] and [`ClipSpec`].

use crate::connectors::build_connector;
use crate::error::FieldError;
use crate::format::{BeadEntry, ClipEntry, ClipType, HoseEndName, SceneFile, StubEntry};
use crate::parts::friction;
use crate::scene::{HoseEnd, SceneClip, SceneConnector, SceneStub};
use crate::units::LengthUnit;
use crate::validate::{finite_vec, non_negative, non_zero_vec, positive, vec_with_unit, with_unit};
use pliant_assembly::clip::{ClipKind, ClipSpec};
use pliant_assembly::stub::{Bead, StubSpec, MAX_PROFILE};
use pliant_core::HoseSpec;

/// Default static friction coefficient of a hose on a stub. Assumption: the
/// dissertation names the coefficients (γ_H, γ_G, sections 4.3.5 and 5.3.1) but gives no
/// values; 0.6 / 0.4 is typical of rubber on plastic.
pub const DEFAULT_STUB_FRICTION_STATIC: f64 = 0.6;
/// Default sliding friction coefficient of a hose on a stub (assumption, see
/// [`DEFAULT_STUB_FRICTION_STATIC`]).
pub const DEFAULT_STUB_FRICTION_SLIDING: f64 = 0.4;
/// Largest angle (degrees) by which a clip's `orientation` may miss being perpendicular
/// to its `opening`.
pub const CLIP_ORIENTATION_TOLERANCE_DEG: f64 = 30.0;

/// Checks the names of stubs, connectors and clips: non-empty and unique across the three
/// lists.
fn check_names(file: &SceneFile) -> Result<(), FieldError> {
    let mut all: Vec<(String, &str)> = Vec::new();
    let lists: [(&str, Vec<&str>); 3] = [
        (
            "stubs",
            file.stubs.iter().map(|s| s.name.as_str()).collect(),
        ),
        (
            "connectors",
            file.connectors.iter().map(|c| c.name.as_str()).collect(),
        ),
        (
            "clips",
            file.clips.iter().map(|c| c.name.as_str()).collect(),
        ),
    ];
    for (list, names) in lists {
        all.extend(
            names
                .into_iter()
                .enumerate()
                .map(|(i, n)| (format!("{list}[{i}].name"), n)),
        );
    }
    for (k, (field, name)) in all.iter().enumerate() {
        if name.trim().is_empty() {
            return Err(FieldError::new(
                field.as_str(),
                format!("\"{name}\""),
                "a stub, connector or clip name must not be empty",
            ));
        }
        if let Some((first, _)) = all[..k].iter().find(|(_, n)| n == name) {
            return Err(FieldError::new(
                field.as_str(),
                format!("\"{name}\""),
                format!(
                    "duplicate name (also {first}); stubs, connectors and clips share one set of names"
                ),
            ));
        }
    }
    Ok(())
}

/// Resolves a hose name.
fn hose_index(field: &str, name: &str, hoses: &[HoseSpec]) -> Result<usize, FieldError> {
    hoses.iter().position(|h| h.name == name).ok_or_else(|| {
        let names: Vec<&str> = hoses.iter().map(|h| h.name.as_str()).collect();
        FieldError::new(
            field,
            format!("\"{name}\""),
            format!("unknown hose; hoses: {}", names.join(", ")),
        )
    })
}

/// The part a fastener sits on (`part = "door"` at `field`), as an index into `parts`
/// (the built parts' names, in the model's order).
pub(crate) fn part_index(
    field: &str,
    name: Option<&String>,
    parts: &[&str],
) -> Result<Option<usize>, FieldError> {
    let Some(name) = name else {
        return Ok(None);
    };
    match parts.iter().position(|p| p == name) {
        Some(k) => Ok(Some(k)),
        None => Err(FieldError::new(
            field,
            format!("\"{name}\""),
            format!("names no part; parts are: {}", parts.join(", ")),
        )),
    }
}

/// Outer diameter (m) of a hose at a node.
pub(crate) fn d_outer_at(hose: &HoseSpec, node: usize) -> f64 {
    hose.node_section(node).d_outer
}

/// Shortest stub \[m\]: shorter ones are meaningless (and their force law divides by it).
pub const MIN_STUB_LENGTH: f64 = 1e-3;
/// Largest clip snap force \[N\]: a hand pushes at most a few hundred newtons.
pub const MAX_SNAP_FORCE: f64 = 1e4;

/// A length in metres, written in the file's unit (rounded to 1e-9 of it, so that
/// 0.035 m reads `35 mm`, not `35.00000000000001 mm`).
pub(crate) fn in_unit(metres: f64, unit: LengthUnit) -> String {
    let v = ((metres / unit.to_metres()) * 1e9).round() / 1e9;
    with_unit(v, unit.symbol())
}

/// A scene's stubs, connectors and clips.
pub type SceneFasteners = (Vec<SceneStub>, Vec<SceneConnector>, Vec<SceneClip>);

/// Checks and builds every stub, connector and clip (names unique across the three).
pub fn build_fasteners(
    file: &SceneFile,
    hoses: &[HoseSpec],
    parts: &[&str],
) -> Result<SceneFasteners, FieldError> {
    check_names(file)?;
    let unit = file.length_unit;
    let stubs = file
        .stubs
        .iter()
        .enumerate()
        .map(|(i, s)| build_stub(i, s, hoses, unit, parts))
        .collect::<Result<Vec<_>, _>>()?;
    let connectors = file
        .connectors
        .iter()
        .enumerate()
        .map(|(i, c)| build_connector(i, c, hoses, unit, parts))
        .collect::<Result<Vec<_>, _>>()?;
    let clips = file
        .clips
        .iter()
        .enumerate()
        .map(|(i, c)| build_clip(i, c, hoses, unit, parts))
        .collect::<Result<Vec<_>, _>>()?;
    Ok((stubs, connectors, clips))
}

/// The hose end a stub or connector entry names with `hose` and `end` (the fields at
/// `at("hose")`, `at("end")`), or the end of the scene's only hose; `what` finishes "the
/// hose end that goes …" (e.g. "onto the stub").
pub(crate) fn hose_end(
    at: impl Fn(&str) -> String,
    hose: Option<&String>,
    end: Option<HoseEndName>,
    hoses: &[HoseSpec],
    what: &str,
) -> Result<HoseEnd, FieldError> {
    let (hose, at_end) = match (hose, end) {
        (None, None) if hoses.len() > 1 => {
            return Err(FieldError::about(
                at("hose"),
                format!(
                    "the scene has several hoses: name the hose end that goes {what} (`hose` and `end`)"
                ),
            ))
        }
        (None, None) => (0, true),
        (Some(_), None) => {
            return Err(FieldError::about(
                at("end"),
                format!(
                    "required with `hose`: \"start\" or \"end\", the hose end that goes {what}"
                ),
            ))
        }
        (None, Some(_)) => {
            return Err(FieldError::about(
                at("hose"),
                format!("required with `end`: the hose whose end goes {what}"),
            ))
        }
        (Some(name), Some(end)) => (hose_index(&at("hose"), name, hoses)?, end == HoseEndName::End),
    };
    Ok(HoseEnd { hose, at_end })
}

/// Checks and builds `stubs[index]`.
pub fn build_stub(
    index: usize,
    raw: &StubEntry,
    hoses: &[HoseSpec],
    unit: LengthUnit,
    parts: &[&str],
) -> Result<SceneStub, FieldError> {
    let at = |rest: &str| format!("stubs[{index}].{rest}");
    let part = part_index(&at("part"), raw.part.as_ref(), parts)?;
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let origin = finite_vec(&at("origin"), raw.origin, u)? * scale;
    let axis = non_zero_vec(&at("axis"), raw.axis, "")?;
    let length = positive(&at("length"), raw.length, u)?;
    if length * scale < MIN_STUB_LENGTH {
        return Err(FieldError::new(
            at("length"),
            with_unit(raw.length, u),
            "a stub shorter than 1 mm holds no hose (the press fit needs a length to act over)",
        ));
    }
    let diameter = positive(&at("diameter"), raw.diameter, u)?;
    let (friction_static, friction_sliding) = friction(
        &at("friction"),
        raw.friction.as_ref(),
        (DEFAULT_STUB_FRICTION_STATIC, DEFAULT_STUB_FRICTION_SLIDING),
    )?;
    // the hose end that goes onto the stub: named, or the only hose's end
    let hose_end = hose_end(at, raw.hose.as_ref(), raw.end, hoses, "onto the stub")?;
    let (hose, at_end) = (hose_end.hose, hose_end.at_end);
    let hose_spec = &hoses[hose];
    let node = if at_end { hose_spec.nodes.len() - 1 } else { 0 };
    let d_outer = d_outer_at(hose_spec, node);
    if diameter * scale >= d_outer {
        return Err(FieldError::new(
            at("diameter"),
            with_unit(diameter, u),
            format!(
                "must be smaller than the outer diameter of hose \"{}\" at its {} ({}): the hose could not go on",
                hose_spec.name,
                if at_end { "end" } else { "start" },
                in_unit(d_outer, unit)
            ),
        ));
    }
    let spec = StubSpec::new(
        origin,
        axis,
        length * scale,
        diameter * scale,
        friction_static,
        friction_sliding,
    )
    .map_err(|e| FieldError::about(format!("stubs[{index}]"), e.to_string()))?;
    let (entries, key) = match (&raw.bead, &raw.profile) {
        (Some(_), Some(_)) => {
            return Err(FieldError::about(
                at("bead"),
                "give either `bead` or `profile` (a list of beads), not both",
            ))
        }
        (Some(b), None) => (std::slice::from_ref(b), "bead".to_owned()),
        (None, Some(list)) => (list.as_slice(), String::new()),
        (None, None) => (&[][..], String::new()),
    };
    if entries.len() > MAX_PROFILE {
        return Err(FieldError::new(
            at("profile"),
            format!("{} beads", entries.len()),
            format!("at most {MAX_PROFILE} beads or barbs on one stub"),
        ));
    }
    let mut profile: Vec<Bead> = Vec::with_capacity(entries.len());
    for (k, b) in entries.iter().enumerate() {
        let key = if key.is_empty() {
            format!("profile[{k}]")
        } else {
            key.clone()
        };
        let bead = build_bead(&at(&key), b, unit, spec.length(), profile.last())?;
        profile.push(bead);
    }
    Ok(SceneStub {
        name: raw.name.clone(),
        spec,
        hose_end,
        profile,
        part,
    })
}

/// Checks and builds one bead of a stub's profile at `field` (e.g. `stubs[0].profile[1]`),
/// SI; it must end within the stub's `length` \[m\] and start after `previous` ends.
fn build_bead(
    field: &str,
    b: &BeadEntry,
    unit: LengthUnit,
    length: f64,
    previous: Option<&Bead>,
) -> Result<Bead, FieldError> {
    let at_b = |k: &str| format!("{field}.{k}");
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let bead = Bead::new(
        non_negative(&at_b("at"), b.at, u)? * scale,
        positive(&at_b("height"), b.height, u)? * scale,
        positive(&at_b("width"), b.width, u)? * scale,
        positive(&at_b("entry_angle_deg"), b.entry_angle_deg, "°")?.to_radians(),
        positive(&at_b("back_angle_deg"), b.back_angle_deg, "°")?.to_radians(),
    )
    .map_err(|e| FieldError::about(field, e.to_string()))?;
    if bead.end() > length {
        return Err(FieldError::about(
            field,
            "the bead must end within the stub's length",
        ));
    }
    if let Some(prev) = previous.filter(|p| bead.at < p.end()) {
        return Err(FieldError::new(
            at_b("at"),
            in_unit(bead.at, unit),
            format!(
                "must not lie before the previous bead's end ({}): beads follow one another from the mouth inwards",
                in_unit(prev.end(), unit)
            ),
        ));
    }
    Ok(bead)
}

/// Checks and builds `clips[index]`.
pub fn build_clip(
    index: usize,
    raw: &ClipEntry,
    hoses: &[HoseSpec],
    unit: LengthUnit,
    parts: &[&str],
) -> Result<SceneClip, FieldError> {
    let at = |rest: &str| format!("clips[{index}].{rest}");
    let part = part_index(&at("part"), raw.part.as_ref(), parts)?;
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let origin = finite_vec(&at("origin"), raw.origin, u)? * scale;
    let opening = non_zero_vec(&at("opening"), raw.opening, "")?.normalize();
    let orientation = non_zero_vec(&at("orientation"), raw.orientation, "")?.normalize();
    let off_perpendicular = orientation
        .dot(opening)
        .abs()
        .clamp(0.0, 1.0)
        .asin()
        .to_degrees();
    if off_perpendicular > CLIP_ORIENTATION_TOLERANCE_DEG {
        return Err(FieldError::new(
            at("orientation"),
            vec_with_unit(raw.orientation, ""),
            format!(
                "must be roughly perpendicular to opening {}: it is {:.1}° off (at most {CLIP_ORIENTATION_TOLERANCE_DEG}° allowed)",
                vec_with_unit(raw.opening, ""),
                off_perpendicular
            ),
        ));
    }
    let opening_width = positive(&at("opening_width"), raw.opening_width, u)?;
    let inner_diameter = positive(&at("inner_diameter"), raw.inner_diameter, u)?;
    if opening_width >= inner_diameter {
        return Err(FieldError::new(
            at("opening_width"),
            with_unit(opening_width, u),
            format!(
                "must be smaller than inner_diameter ({})",
                with_unit(inner_diameter, u)
            ),
        ));
    }
    let kind = match raw.kind {
        ClipType::Fixed => ClipKind::Fixed,
        ClipType::Rotating => ClipKind::Rotating,
        ClipType::Sliding => ClipKind::Sliding,
        ClipType::CableTie => ClipKind::CableTie,
    };
    let snap_force = match (raw.snap_force_n, kind) {
        (Some(k), _) => {
            let k = non_negative(&at("snap_force_n"), k, "N")?;
            if k > MAX_SNAP_FORCE {
                return Err(FieldError::new(
                    at("snap_force_n"),
                    with_unit(k, "N"),
                    format!("above {MAX_SNAP_FORCE} N no clip is fitted by hand (a fixed clamp is a `fix` in the timeline)"),
                ));
            }
            k
        }
        (None, ClipKind::CableTie) => 0.0,
        (None, _) => {
            return Err(FieldError::about(
                at("snap_force_n"),
                format!(
                    "required for a clip of type {}: the force against the hose at the opening (N)",
                    kind.name()
                ),
            ))
        }
    };
    let friction = match (raw.friction, kind) {
        (Some(mu), ClipKind::Sliding) => non_negative(&at("friction"), mu, "")?,
        (None, ClipKind::Sliding) => DEFAULT_STUB_FRICTION_SLIDING,
        (Some(_), _) => {
            return Err(FieldError::about(
                at("friction"),
                format!(
                    "only a sliding guide has friction along the hose; this clip is of type {}",
                    kind.name()
                ),
            ))
        }
        (None, _) => 0.0,
    };
    let holding = match raw.holding_force_n {
        Some(h) => Some(positive(&at("holding_force_n"), h, "N")?),
        None => None,
    };
    // the hose that goes into the clip: named, or the only hose
    let h = match &raw.hose {
        None if hoses.len() > 1 => {
            return Err(FieldError::about(
                at("hose"),
                "the scene has several hoses: name the hose that goes into the clip",
            ))
        }
        None => 0,
        Some(name) => hose_index(&at("hose"), name, hoses)?,
    };
    let spec = &hoses[h];
    let d_max = (0..spec.nodes.len())
        .map(|n| d_outer_at(spec, n))
        .fold(0.0, f64::max);
    if d_max <= opening_width * scale {
        return Err(FieldError::new(
            at("opening_width"),
            with_unit(opening_width, u),
            format!(
                "must be smaller than the outer diameter of hose \"{}\" ({}): the hose would pass through the opening and never be held",
                spec.name,
                in_unit(d_max, unit)
            ),
        ));
    }
    let hose = h;
    let spec = ClipSpec::new(
        origin,
        opening,
        orientation,
        opening_width * scale,
        inner_diameter * scale,
        snap_force,
    )
    .and_then(|c| c.with_fixing(kind, friction, holding))
    .map_err(|e| FieldError::about(format!("clips[{index}]"), e.to_string()))?;
    Ok(SceneClip {
        name: raw.name.clone(),
        spec,
        hose,
        part,
        by_hand: raw.by_hand,
    })
}
