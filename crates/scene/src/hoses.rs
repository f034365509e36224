//! Building one hose: material and cross-section, centre line, element count, rest
//! nodes with imperfections, normal hint (SPEC M1–M3).

use crate::centerline::{element_count, Centerline, CurveError, Resolution, Segment, MAX_ELEMENTS};
use crate::delivered::delivered_nodes;
use crate::error::FieldError;
use crate::files::FileAccess;
use crate::format::{HoseEntry, SectionEntry, SegmentEntry, Vec3};
use crate::materials::Materials;
use crate::route::route_segments;
use crate::scene::HoseDiscretisation;
use crate::units::{fmt_vec, LengthUnit};
use crate::validate::{
    finite_vec, node_index, non_negative, non_zero_vec, positive, vec_with_unit, with_unit,
};
use glam::DVec3;
use pliant_core::{GivenStiffness, HoseSpec, Section};

/// Default element length as a multiple of the outer diameter (SPEC M1: 1–2 d_a).
pub const DEFAULT_ELEMENT_LENGTH_PER_D_OUTER: f64 = 1.5;

/// Checks and builds `hoses[index]`.
pub fn build_hose(
    index: usize,
    raw: &HoseEntry,
    unit: LengthUnit,
    materials: &Materials,
    files: &FileAccess,
) -> Result<(HoseSpec, HoseDiscretisation), FieldError> {
    let at = |rest: &str| format!("hoses[{index}].{rest}");
    let u = unit.symbol();
    let scale = unit.to_metres();

    if raw.name.trim().is_empty() {
        return Err(FieldError::new(
            at("name"),
            "\"\"",
            "a hose name must not be empty",
        ));
    }
    let resolved = materials.resolve(&at("material"), &raw.material)?;
    let section = match (&raw.section, resolved.default_section) {
        (Some(s), _) => section(&at("section"), s, unit)?,
        (None, Some(default)) => default,
        (None, None) => {
            return Err(FieldError::about(
                at("section"),
                format!(
                    "required because material \"{}\" is not a library hose",
                    raw.material
                ),
            ))
        }
    };

    let resolution = match (raw.elements, raw.element_length) {
        (Some(_), Some(_)) => {
            return Err(FieldError::about(
                at("elements"),
                "give either elements or element_length, not both",
            ))
        }
        (Some(0), None) => return Err(FieldError::new(at("elements"), "0", "must be at least 1")),
        (Some(n), None) => Resolution::Elements(n as usize),
        (None, Some(l)) => {
            Resolution::ElementLength(positive(&at("element_length"), l, u)? * scale)
        }
        (None, None) => {
            Resolution::ElementLength(DEFAULT_ELEMENT_LENGTH_PER_D_OUTER * section.d_outer)
        }
    };

    let curve = if let Some(route) = &raw.route {
        if raw.start.is_some() || !raw.path.is_empty() {
            return Err(FieldError::about(
                at("route"),
                "give either `route` or `start` and `path`, not both",
            ));
        }
        let (start, segments) = route_segments(&at("route"), route, unit, files)?;
        Centerline::new(start, &segments).map_err(|e| {
            FieldError::about(
                at("route"),
                format!("point {}: {}", e.segment + 1, e.reason),
            )
        })?
    } else {
        if raw.path.is_empty() {
            return Err(FieldError::about(
                at("path"),
                "a hose needs at least one segment (or a `route`)",
            ));
        }
        let Some(raw_start) = raw.start else {
            return Err(FieldError::about(
                at("start"),
                "missing; a hose needs `start` and `path`, or a `route`",
            ));
        };
        let start = finite_vec(&at("start"), raw_start, u)? * scale;
        let segments = raw
            .path
            .iter()
            .enumerate()
            .map(|(k, s)| segment(&at(&format!("path[{k}]")), s, unit))
            .collect::<Result<Vec<_>, _>>()?;
        Centerline::new(start, &segments).map_err(|e| curve_error(index, raw, e, unit))?
    };
    let length = curve.length();
    let count = element_count(length, resolution, curve.min_arc_radius()).ok_or_else(|| {
        FieldError::about(
            at("path"),
            format!(
                "a centre line of {} needs more than {MAX_ELEMENTS} elements at the requested resolution (or at ≥ 4 elements per quarter circle of its tightest arc)",
                with_unit((length / scale * 1e3).round() / 1e3, u)
            ),
        )
    })?;
    let mut nodes = curve.discretise(count.count);

    // Index of the imperfection entry that last moved each node, for error messages.
    let mut moved_by: Vec<Option<usize>> = vec![None; nodes.len()];
    for (k, imp) in raw.imperfection.iter().enumerate() {
        let node = node_index(
            &at(&format!("imperfection[{k}].node")),
            imp.node,
            nodes.len(),
            &raw.name,
        )?;
        nodes[node] +=
            finite_vec(&at(&format!("imperfection[{k}].offset")), imp.offset, u)? * scale;
        moved_by[node] = Some(k);
    }
    let extent = nodes
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.length()))
        .max(length);
    for i in 1..nodes.len() {
        if (nodes[i] - nodes[i - 1]).length() <= 1e-12 * extent {
            let (moved, other) = if moved_by[i].is_some() {
                (i, i - 1)
            } else {
                (i - 1, i)
            };
            let reason = format!(
                "moves node {moved} onto node {other}: neighbouring nodes must be distinct"
            );
            return Err(match moved_by[moved] {
                Some(k) => FieldError::new(
                    at(&format!("imperfection[{k}].offset")),
                    vec_with_unit(raw.imperfection[k].offset, u),
                    reason,
                ),
                None => FieldError::about(at("imperfection"), reason),
            });
        }
    }

    let normal_hint = match raw.normal_hint {
        Some(h) => {
            let d = non_zero_vec(&at("normal_hint"), h, "")?;
            let tangent = (nodes[1] - nodes[0]).normalize();
            if d.normalize().cross(tangent).length() < 1e-6 {
                return Err(FieldError::new(
                    at("normal_hint"),
                    fmt_vec(h),
                    format!(
                        "must not be parallel to the hose's first tangent {}",
                        fmt_vec(tangent.to_array())
                    ),
                ));
            }
            Some(d.normalize())
        }
        None => None,
    };

    let mut stiffened: Vec<(usize, usize)> = Vec::with_capacity(raw.stiffened.len());
    for (k, span) in raw.stiffened.iter().enumerate() {
        let first = node_index(
            &at(&format!("stiffened[{k}].first")),
            span.first,
            nodes.len(),
            &raw.name,
        )?;
        let last = node_index(
            &at(&format!("stiffened[{k}].last")),
            span.last,
            nodes.len(),
            &raw.name,
        )?;
        if last <= first {
            return Err(FieldError::new(
                at(&format!("stiffened[{k}].last")),
                span.last.to_string(),
                format!("must come after first (node {first}): a stiffened span holds at least two nodes"),
            ));
        }
        if let Some(&(a, b)) = stiffened.iter().find(|&&(a, b)| first <= b && a <= last) {
            return Err(FieldError::new(
                at(&format!("stiffened[{k}]")),
                format!("{first}..={last}"),
                format!("overlaps the stiffened span {a}..={b}"),
            ));
        }
        stiffened.push((first, last));
    }

    let min_bend_radius = match raw.min_bend_radius {
        Some(r) => crate::validate::positive(&at("min_bend_radius"), r, u)? * scale,
        None => resolved
            .min_bend_radius
            .unwrap_or_else(|| crate::materials::min_bend_radius_rule(&section)),
    };
    let (sections, bend_radii) = span_sections(
        index,
        raw,
        unit,
        section,
        length,
        nodes.len(),
        min_bend_radius,
    )?;
    let protections = crate::protections::build_protections(index, raw, unit, length)?;
    if normal_hint.is_none() {
        if let Some(k) = sections.iter().position(non_round) {
            return Err(FieldError::about(
                at("normal_hint"),
                format!(
                    "required: element {k}'s section has EI1 ≠ EI2, and normal_hint says which way its axis 1 points"
                ),
            ));
        }
    }

    let info = HoseDiscretisation {
        bend_radii,
        protections,
        stiffened,
        name: raw.name.clone(),
        length,
        elements: count.count,
        requested_elements: count.requested,
        raised_for_arcs: count.raised_for_arcs,
        element_length: length / count.count as f64,
        min_bend_radius,
        d_outer: section.d_outer,
        delivered: match &raw.delivered {
            Some(d) => Some(delivered_nodes(
                &at("delivered"),
                d,
                unit,
                length,
                count.count,
            )?),
            None => None,
        },
    };
    let spec = HoseSpec {
        name: raw.name.clone(),
        material: resolved.material,
        nodes,
        sections,
        normal_hint,
    };
    Ok((spec, info))
}

/// Checks a cross-section (file units for the diameters, SI for the given stiffnesses)
/// and converts it to SI.
fn section(field: &str, s: &SectionEntry, unit: LengthUnit) -> Result<Section, FieldError> {
    let u = unit.symbol();
    let d_outer = positive(&format!("{field}.d_outer"), s.d_outer, u)?;
    let d_inner = non_negative(&format!("{field}.d_inner"), s.d_inner, u)?;
    if d_inner >= d_outer {
        return Err(FieldError::new(
            format!("{field}.d_inner"),
            with_unit(d_inner, u),
            format!("must be smaller than d_outer ({})", with_unit(d_outer, u)),
        ));
    }
    let scale = unit.to_metres();
    let given = |name: &str, v: Option<f64>, unit: &str| {
        v.map(|v| positive(&format!("{field}.{name}"), v, unit))
            .transpose()
    };
    let mut out = Section::new(d_inner * scale, d_outer * scale);
    out.given = GivenStiffness {
        axial: given("ea_n", s.ea_n, "N")?,
        bending: [
            given("ei1_n_m2", s.ei1_n_m2, "N·m²")?,
            given("ei2_n_m2", s.ei2_n_m2, "N·m²")?,
        ],
        torsion: given("gj_n_m2", s.gj_n_m2, "N·m²")?,
        mass_per_length: given("mass_kg_m", s.mass_kg_m, "kg/m")?,
    };
    Ok(out)
}

/// Whether a section bends differently about its two axes (it then needs an orientation).
fn non_round(s: &Section) -> bool {
    let [a, b] = s.given.bending;
    a.is_some() != b.is_some() || a.zip(b).is_some_and(|(a, b)| a != b)
}

/// The section of every element: `default` except where a span of `raw.spans` holds the
/// element's midpoint (nodes at equal spacing over `length`). Span ends falling inside an
/// element are rounded to the nearest node that way. With them, the minimum bend radius
/// of every element (`hose_bend_radius` where no span gives one), empty when no span
/// gives one.
fn span_sections(
    index: usize,
    raw: &HoseEntry,
    unit: LengthUnit,
    default: Section,
    length: f64,
    nodes: usize,
    hose_bend_radius: f64,
) -> Result<(Vec<Section>, Vec<f64>), FieldError> {
    if raw.spans.is_empty() {
        return Ok((vec![default], Vec::new()));
    }
    let mut bend_radii: Vec<f64> = Vec::new();
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let elements = nodes - 1;
    let element_length = length / elements as f64;
    let mut sections = vec![default; elements];
    let mut taken: Vec<(f64, f64)> = Vec::with_capacity(raw.spans.len());
    for (k, span) in raw.spans.iter().enumerate() {
        let at = |rest: &str| format!("hoses[{index}].spans[{k}].{rest}");
        let (from, to) = stretch(&at(""), span.from, span.to, unit, length)?;
        if let Some(&(a, b)) = taken.iter().find(|&&(a, b)| from < b && a < to) {
            return Err(FieldError::new(
                format!("hoses[{index}].spans[{k}]"),
                format!("{}..{}", with_unit(span.from, u), with_unit(span.to, u)),
                format!(
                    "overlaps the span {}..{}",
                    with_unit(a / scale, u),
                    with_unit(b / scale, u)
                ),
            ));
        }
        taken.push((from, to));
        let section = section(&at("section"), &span.section, unit)?;
        let bend_radius = match span.min_bend_radius {
            Some(r) => Some(positive(&at("min_bend_radius"), r, u)? * scale),
            None => None,
        };
        if bend_radius.is_some() && bend_radii.is_empty() {
            bend_radii = vec![hose_bend_radius; elements];
        }
        let mut covered = 0;
        for e in 0..elements {
            let middle = (e as f64 + 0.5) * element_length;
            if (from..to).contains(&middle) {
                sections[e] = section;
                if let Some(r) = bend_radius {
                    bend_radii[e] = r;
                }
                covered += 1;
            }
        }
        if covered == 0 {
            return Err(FieldError::new(
                format!("hoses[{index}].spans[{k}]"),
                format!("{}..{}", with_unit(span.from, u), with_unit(span.to, u)),
                format!(
                    "holds no element's middle (elements are {} long): make it longer or the elements shorter",
                    with_unit(element_length / scale, u)
                ),
            ));
        }
    }
    Ok((sections, bend_radii))
}

/// Checks a stretch `from..to` of a hose (file units; `field` ends in `.`) against its
/// `length` \[m\] and returns it in metres.
pub(crate) fn stretch(
    field: &str,
    from: f64,
    to: f64,
    unit: LengthUnit,
    length: f64,
) -> Result<(f64, f64), FieldError> {
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let at = |rest: &str| format!("{field}{rest}");
    let from_m = non_negative(&at("from"), from, u)? * scale;
    let to_m = positive(&at("to"), to, u)? * scale;
    if to_m <= from_m {
        return Err(FieldError::new(
            at("to"),
            with_unit(to, u),
            format!("must be greater than from ({})", with_unit(from, u)),
        ));
    }
    if to_m > length * (1.0 + 1e-9) {
        return Err(FieldError::new(
            at("to"),
            with_unit(to, u),
            format!(
                "lies beyond the hose's end (its length is {})",
                with_unit(length / scale, u)
            ),
        ));
    }
    Ok((from_m, to_m.min(length)))
}

/// Checks a path segment's points (file units) and converts them to metres.
pub(crate) fn segment(
    field: &str,
    s: &SegmentEntry,
    unit: LengthUnit,
) -> Result<Segment, FieldError> {
    let (u, scale) = (unit.symbol(), unit.to_metres());
    let point =
        |name: &str, p: Vec3| finite_vec(&format!("{field}.{name}"), p, u).map(|v| v * scale);
    Ok(match s {
        SegmentEntry::Line { to } => Segment::Line {
            to: point("line.to", *to)?,
        },
        SegmentEntry::Arc { via, to } => Segment::Arc {
            via: point("arc.via", *via)?,
            to: point("arc.to", *to)?,
        },
        SegmentEntry::Spline { through, to } => Segment::Spline {
            through: through
                .iter()
                .enumerate()
                .map(|(j, p)| point(&format!("spline.through[{j}]"), *p))
                .collect::<Result<Vec<DVec3>, _>>()?,
            to: point("spline.to", *to)?,
        },
    })
}

/// The raw point named by a curve error's `part`, if it names one.
fn raw_point(s: &SegmentEntry, part: &str) -> Option<Vec3> {
    match (s, part) {
        (SegmentEntry::Line { to }, "line.to") | (SegmentEntry::Arc { to, .. }, "arc.to") => {
            Some(*to)
        }
        (SegmentEntry::Arc { via, .. }, "arc.via") => Some(*via),
        (SegmentEntry::Spline { to, .. }, "spline.to") => Some(*to),
        (SegmentEntry::Spline { through, .. }, p) => p
            .strip_prefix("spline.through[")
            .and_then(|r| r.strip_suffix(']'))
            .and_then(|j| j.parse::<usize>().ok())
            .and_then(|j| through.get(j).copied()),
        _ => None,
    }
}

/// Turns a centre-line error into a field error with the point as written.
fn curve_error(index: usize, raw: &HoseEntry, e: CurveError, unit: LengthUnit) -> FieldError {
    let field = if e.part.is_empty() {
        format!("hoses[{index}].path[{}]", e.segment)
    } else {
        format!("hoses[{index}].path[{}].{}", e.segment, e.part)
    };
    match raw.path.get(e.segment).and_then(|s| raw_point(s, &e.part)) {
        Some(p) => FieldError::new(field, vec_with_unit(p, unit.symbol()), e.reason),
        None => FieldError::about(field, e.reason),
    }
}
