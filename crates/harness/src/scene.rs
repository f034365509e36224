//! Writing the Pliant scene (`scene.toml`, format v1, docs/scene-format.md) and the
//! harness model (`harness.json`).
//!
//! Mapping:
//!
//! - every segment → one `[[hoses]]` named by its KBL id (sanitised), centre line a
//!   Catmull-Rom `spline` through points sampled every ~10 mm along the trimmed centre
//!   curve (first and last exactly on the nodes), `elements` = max(4, round(L / 25 mm)),
//!   `section` given directly from the bundle model (`bundle.rs`) for the bare wires,
//!   `min_bend_radius`; every protected stretch (`Protection_area` from its start to its
//!   end location) a `spans` entry with its own section and minimum bend radius, and the
//!   protections themselves in `protections`;
//! - every node where two or more segments meet → `[[junctions]]` (welded branch point);
//! - every fixing assignment → `[[clips]]` at the curve point at its location;
//! - timeline: `fix` at the hose node nearest every fixing and at every leaf end that
//!   carries a connector, then `settle` (the harness held in its installed state).

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use glam::DVec3;
use serde::Serialize;

use crate::bundle::{BundleSection, CoveredStretch};
use crate::geometry::SegmentCurve;
use crate::model::Harness;

/// Spacing of the sampled centre-line points \[m\].
pub const SAMPLE_SPACING_M: f64 = 0.010;
/// Target element length \[m\].
pub const ELEMENT_LENGTH_M: f64 = 0.025;
/// Newton iterations the static solver may take for one equilibrium: the drawn route
/// springs out between its fixings on the first (the main harness of `data/harness/`
/// needs about 1 900), a few suffice afterwards.
pub const STATIC_ITERATIONS: usize = 5_000;
/// Fewest elements per segment.
pub const MIN_ELEMENTS: usize = 4;
/// Clip snap force \[N\] — an assumption: harness clips and holders snap on with forces of
/// a few tens of newtons; calibrate against the part's data sheet.
pub const SNAP_FORCE_N: f64 = 30.0;
/// Clip opening width as a share of the seat diameter (assumption: "a bit smaller").
pub const OPENING_SHARE: f64 = 0.8;

/// What the scene writer needs per segment.
pub struct SegmentOut<'a> {
    pub hose: String,
    pub curve: &'a SegmentCurve,
    /// The segment's section as one.
    pub section: &'a BundleSection,
    /// The hose's section where no protection lies, and its protected stretches (spans).
    pub bare: &'a BundleSection,
    pub stretches: &'a [CoveredStretch],
    pub elements: usize,
    /// The friction between the wires, when the import gives it (`--bundle-friction`).
    pub friction: Option<crate::bundle::BundleFriction>,
}

impl SegmentOut<'_> {
    /// The bundle's outer diameter \[m\] at `fraction` of the segment (a clip or a plug
    /// takes the bundle as it is where it sits).
    pub fn d_outer_at(&self, fraction: f64) -> f64 {
        crate::bundle::d_outer_at(self.bare, self.stretches, fraction)
    }
}

/// A name usable as a scene name: letters, digits, `_`, `-`, `.`; others become `_`.
pub fn sanitise(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "_".to_string()
    } else {
        s
    }
}

/// Unique names: the second `x` becomes `x_2`, and so on.
pub fn unique(names: impl IntoIterator<Item = String>) -> Vec<String> {
    let mut seen = HashSet::new();
    names
        .into_iter()
        .map(|n| {
            let mut candidate = n.clone();
            let mut k = 2;
            while !seen.insert(candidate.clone()) {
                candidate = format!("{n}_{k}");
                k += 1;
            }
            candidate
        })
        .collect()
}

/// Number of elements for a centre line of length `len` \[m\].
pub fn element_count(len: f64) -> usize {
    ((len / ELEMENT_LENGTH_M).round() as usize).max(MIN_ELEMENTS)
}

pub(crate) fn mm(v: f64) -> String {
    let s = format!("{:.4}", v * 1e3);
    if s == "-0.0000" {
        "0.0000".into()
    } else {
        s
    }
}

pub(crate) fn vec_mm(v: DVec3) -> String {
    format!("[{}, {}, {}]", mm(v.x), mm(v.y), mm(v.z))
}

pub(crate) fn unit_vec(v: DVec3) -> String {
    format!("[{:.6}, {:.6}, {:.6}]", v.x, v.y, v.z)
}

fn sci(v: f64) -> String {
    format!("{v:.6e}")
}

pub(crate) fn quote(s: &str) -> String {
    // TOML basic string: escape backslash, quote and control characters.
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// A unit vector perpendicular to `t`.
fn perpendicular(t: DVec3) -> DVec3 {
    let a = if t.z.abs() < 0.9 { DVec3::Z } else { DVec3::X };
    (a - t * a.dot(t)).normalize_or_zero()
}

/// The clip type from the KBL fixing type and description: cable ties ("KABELBINDER",
/// "TIE") → `cable_tie`; cable ducts and guides ("DUCT", "KABELFUEHRUNG", "KANAL") →
/// `sliding`; anything else `fixed`.
pub fn clip_type(fixing_type: Option<&str>, description: Option<&str>) -> &'static str {
    let t = format!(
        "{} {}",
        fixing_type.unwrap_or(""),
        description.unwrap_or("")
    )
    .to_uppercase();
    if t.contains("BINDER") || t.contains("TIE") {
        "cable_tie"
    } else if t.contains("DUCT")
        || t.contains("FUEHRUNG")
        || t.contains("FÜHRUNG")
        || t.contains("KANAL")
    {
        "sliding"
    } else {
        "fixed"
    }
}

/// Everything the timeline holds: (hose index, node index) pairs, in order, without repeats
/// — the fixings, the connector ends and `cut`, the node a branch was cut off at; a harness
/// with none of these (e.g. a VEC file's geometry alone) is held at all its free ends.
pub fn held_nodes(h: &Harness, segs: &[SegmentOut], cut: Option<usize>) -> Vec<(usize, i64)> {
    let mut out: Vec<(usize, i64)> = Vec::new();
    let mut push = |x: (usize, i64)| {
        if !out.contains(&x) {
            out.push(x);
        }
    };
    if let Some(n) = cut {
        if let Some(&s) = h.segments_at_nodes()[n].first() {
            push((s, if h.segments[s].start_node == n { 0 } else { -1 }));
        }
    }
    for f in &h.fixings {
        let n = segs[f.segment].elements;
        push((f.segment, (f.location * n as f64).round() as i64));
    }
    let at = h.segments_at_nodes();
    let with_connector: HashSet<usize> = h.connectors.iter().filter_map(|c| c.node).collect();
    for (node, segments) in at.iter().enumerate() {
        if segments.len() == 1 && with_connector.contains(&node) {
            let s = segments[0];
            let seg = &h.segments[s];
            push((s, if seg.start_node == node { 0 } else { -1 }));
        }
    }
    if out.is_empty() {
        for (node, segments) in at.iter().enumerate() {
            if let [s] = segments[..] {
                out.push((
                    s,
                    if h.segments[s].start_node == node {
                        0
                    } else {
                        -1
                    },
                ));
            }
        }
    }
    out
}

/// The simulation settings of `scene.toml`: the quasi-static solver (thin wires make the
/// explicit step microseconds long; the installed state is an equilibrium, which the
/// quasi-static solver finds directly).
fn static_simulation() -> String {
    format!("solver = \"static\"\nstatic_max_iterations = {STATIC_ITERATIONS}")
}

/// The start of a scene for this harness: the header, the simulation settings
/// (`simulation`: the `[simulation]` table's lines besides the contact rule), the bundle
/// material, a hose per segment and a junction per node where segments meet.
pub(crate) fn network_toml(
    h: &Harness,
    segs: &[SegmentOut],
    licence_note: &str,
    simulation: &str,
) -> String {
    network_toml_with_slack(h, segs, licence_note, simulation, 0.0)
}

/// [`network_toml`] with every segment `slack` (a share of its length, ≥ 0) longer than
/// its route: drawn bowed sideways between its nodes, downwards where it can, by
/// a·sin²(π s/L) ([`bow`]: the ends and their tangents stay on the route, so junctions and
/// plugs sit as the route has them).
pub(crate) fn network_toml_with_slack(
    h: &Harness,
    segs: &[SegmentOut],
    licence_note: &str,
    simulation: &str,
    slack: f64,
) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# Pliant scene generated by pliant-harness from the harness file `{}` ({}).",
        h.source,
        h.format_version()
    );
    for line in licence_note.lines() {
        let _ = writeln!(t, "# {line}");
    }
    let _ = writeln!(
        t,
        "# One hose per KBL segment (named by its id), a junction per node where segments meet,"
    );
    let _ = writeln!(
        t,
        "# a clip per fixing; sections from the bundle model (crates/harness/README.md)."
    );
    let _ = writeln!(t, "# The model behind it, with KBL ids, wires and skipped items: harness.json beside this file.\n");
    let _ = writeln!(t, "format = \"pliant-scene\"\nversion = 1");
    let stem = [".kbl", ".KBL", ".vec", ".VEC"]
        .into_iter()
        .fold(h.source.as_str(), |s, e| s.strip_suffix(e).unwrap_or(s));
    let _ = writeln!(t, "name = {}\nlength_unit = \"mm\"\n", quote(stem));
    // bundles the route draws through one another lie side by side in the vehicle
    let (solver, rest) = simulation.split_once('\n').unwrap_or((simulation, ""));
    let _ = writeln!(
        t,
        "[simulation]\n{solver}\nhose_contact = \"apart_at_rest\"\n{rest}{}",
        if rest.is_empty() { "" } else { "\n" }
    );
    // the twist check guards a hose's lay line (DIN 20066); a bundle of wires has none
    let _ = writeln!(
        t,
        "# A wire bundle has no lay line to keep straight: the twist check is off.\n[checks]\ntwist = false\n"
    );
    let _ = writeln!(t, "# Density and Poisson's ratio matter only for what a section does not give (all is given).");
    let _ = writeln!(t, "[materials.bundle]\ne_tension_mpa = 200\ne_compression_mpa = 200\npoisson = 0.4\ndensity_kg_m3 = 1400\n");
    for out in segs {
        if let Some(f) = &out.friction {
            friction_material_toml(&mut t, out, f);
        }
    }

    for (index, (s, out)) in h.segments.iter().zip(segs).enumerate() {
        let len = out.curve.length;
        let count = ((len / SAMPLE_SPACING_M).ceil() as usize + 1).max(3);
        let mut pts = out.curve.sample(count);
        // Ends exactly on the nodes, so that the hoses of a junction meet.
        if let Some(p) = pts.first_mut() {
            *p = h.nodes[s.start_node].position;
        }
        if let Some(p) = pts.last_mut() {
            *p = h.nodes[s.end_node].position;
        }
        if slack > 0.0 {
            bow(&mut pts, slack);
        }
        let sec = out.bare;
        let _ = writeln!(t, "[[hoses]]\nname = {}", quote(&out.hose));
        if let Some(n) = &s.name {
            let _ = writeln!(
                t,
                "# KBL Segment {} \"{}\", {:.1} mm, {} wires",
                s.kbl_id,
                n.replace('\n', " "),
                len * 1e3,
                sec.wire_count
            );
        }
        if out.friction.is_some() {
            let _ = writeln!(t, "material = {}", quote(&friction_material(&out.hose)));
        } else {
            let _ = writeln!(t, "material = \"bundle\"");
        }
        let _ = writeln!(t, "section = {}", section_toml(sec));
        if sec.min_bend_radius > 0.0 {
            let _ = writeln!(t, "min_bend_radius = {}", mm(sec.min_bend_radius));
        }
        let _ = writeln!(t, "elements = {}", out.elements);
        let _ = writeln!(t, "start = {}", vec_mm(pts[0]));
        let through: Vec<String> = pts[1..pts.len() - 1].iter().map(|p| vec_mm(*p)).collect();
        let _ = writeln!(
            t,
            "path = [{{ spline = {{ through = [{}], to = {} }} }}]",
            through.join(", "),
            vec_mm(pts[pts.len() - 1])
        );
        if !out.stretches.is_empty() {
            protections_toml(&mut t, h, index, out, written_length(&pts));
        }
        t.push('\n');
    }

    let at = h.segments_at_nodes();
    for (node, segments) in at.iter().enumerate() {
        if segments.len() < 2 {
            continue;
        }
        let mut ends = Vec::new();
        for &si in segments {
            let seg = &h.segments[si];
            if seg.start_node == node {
                ends.push(format!(
                    "{{ hose = {}, end = \"start\" }}",
                    quote(&segs[si].hose)
                ));
            }
            if seg.end_node == node {
                ends.push(format!(
                    "{{ hose = {}, end = \"end\" }}",
                    quote(&segs[si].hose)
                ));
            }
        }
        let n = &h.nodes[node];
        let _ = writeln!(
            t,
            "[[junctions]]\nname = {}\nends = [{}]\n",
            quote(&sanitise(&n.kbl_id)),
            ends.join(", ")
        );
    }
    t
}

/// The name of the material of hose `hose` with friction between its wires.
fn friction_material(hose: &str) -> String {
    format!("bundle_{hose}")
}

/// `[materials."bundle_HOSE"]`: the bundle material with the default friction of the
/// hose's protection (modelling choices, `data/bundle.toml`).
fn friction_material_toml(t: &mut String, out: &SegmentOut, f: &crate::bundle::BundleFriction) {
    let _ = writeln!(
        t,
        "# {}: friction between the wires, the default of its protection ({}; modelling choices in the bundle data, not measured)",
        out.hose,
        out.section.protection.map_or("none", |p| p.key())
    );
    let _ = writeln!(
        t,
        "[materials.{}]\ne_tension_mpa = 200\ne_compression_mpa = 200\npoisson = 0.4\ndensity_kg_m3 = 1400",
        quote(&friction_material(&out.hose))
    );
    let _ = writeln!(
        t,
        "hysteresis = {{ bending_moment_n_m = {}, bending_curvature_1_m = {}, torsion_moment_n_m = {}, torsion_curvature_1_m = {} }}\n",
        sci(f.bending.moment),
        sci(f.bending.curvature),
        sci(f.torsion.moment),
        sci(f.torsion.curvature)
    );
}

/// A `section = { … }` inline table with every stiffness given.
fn section_toml(sec: &BundleSection) -> String {
    format!(
        "{{ d_inner = 0, d_outer = {}, ea_n = {}, ei1_n_m2 = {}, ei2_n_m2 = {}, gj_n_m2 = {}, mass_kg_m = {} }}",
        mm(sec.d_outer),
        sci(sec.ea),
        sci(sec.ei),
        sci(sec.ei),
        sci(sec.gj),
        sci(sec.mass)
    )
}

/// The length \[m\] of the centre line the scene builds from `pts` as written (rounded
/// to the digits of [`mm`]): the arc length `spans` and `protections` are measured along.
pub(crate) fn written_length(pts: &[DVec3]) -> f64 {
    use pliant_scene::centerline::{Centerline, Segment};
    let scale = pliant_scene::LengthUnit::Millimetre.to_metres();
    let written = |p: &DVec3| {
        let c = |v: f64| mm(v).parse::<f64>().unwrap_or(v * 1e3) * scale;
        DVec3::new(c(p.x), c(p.y), c(p.z))
    };
    let n = pts.len();
    let through: Vec<DVec3> = pts[1..n - 1].iter().map(written).collect();
    let line = Centerline::new(
        written(&pts[0]),
        &[Segment::Spline {
            through,
            to: written(&pts[n - 1]),
        }],
    );
    // the scene refuses what it cannot build; the polyline is then as good a measure
    line.map(|l| l.length())
        .unwrap_or_else(|_| pts.windows(2).map(|w| (w[1] - w[0]).length()).sum())
}

/// A position along a hose of length `length` \[m\] at share `share`, in mm, rounded down
/// so that the end of the hose stays within it.
fn along(share: f64, length: f64) -> String {
    format!("{:.4}", (share * length * 1e7).floor() / 1e4)
}

/// `spans` (every protected stretch holding an element's middle: a section of its own)
/// and `protections` (the `Protection_area`s, those of one kind joined where they
/// overlap) of segment `segment`, on a hose `length` \[m\] long.
fn protections_toml(t: &mut String, h: &Harness, segment: usize, out: &SegmentOut, length: f64) {
    let element = 1.0 / out.elements as f64;
    let holds_middle = |from: f64, to: f64| {
        (0..out.elements).any(|e| (from..to).contains(&((e as f64 + 0.5) * element)))
    };
    let spans: Vec<String> = out
        .stretches
        .iter()
        .filter(|c| holds_middle(c.from, c.to))
        .map(|c| {
            let radius = if c.section.min_bend_radius > 0.0 {
                format!("min_bend_radius = {}, ", mm(c.section.min_bend_radius))
            } else {
                String::new()
            };
            format!(
                "{{ from = {}, to = {}, {radius}section = {} }}",
                along(c.from, length),
                along(c.to, length),
                section_toml(&c.section)
            )
        })
        .collect();
    if !spans.is_empty() {
        let _ = writeln!(t, "spans = [\n  {},\n]", spans.join(",\n  "));
    }
    let mut areas: Vec<(crate::model::ProtectionKind, f64, f64)> = h
        .protections
        .iter()
        .filter(|p| p.segment == segment && p.to > p.from)
        .map(|p| (p.kind, p.from.clamp(0.0, 1.0), p.to.clamp(0.0, 1.0)))
        .collect();
    areas.sort_by(|a, b| a.0.key().cmp(b.0.key()).then(a.1.total_cmp(&b.1)));
    let mut joined: Vec<(crate::model::ProtectionKind, f64, f64)> = Vec::new();
    for a in areas {
        match joined.last_mut() {
            Some(last) if last.0 == a.0 && a.1 <= last.2 => last.2 = last.2.max(a.2),
            _ => joined.push(a),
        }
    }
    let list: Vec<String> = joined
        .iter()
        .map(|(kind, from, to)| {
            format!(
                "{{ kind = \"{}\", from = {}, to = {} }}",
                kind.key(),
                along(*from, length),
                along(*to, length)
            )
        })
        .collect();
    let _ = writeln!(t, "protections = [{}]", list.join(", "));
}

/// Bows the points of a centre line sideways by a·sin²(π s/L), towards −z where the line
/// is not vertical (a bundle sags), else across it, with the amplitude a (of either sign)
/// that makes the polyline through them `slack` longer than it is: a ≈ 2 L √slack / π on a
/// straight line; a curved line grows or shrinks to first order as it is bowed away from or
/// towards its centre of curvature, so a is solved for (the length is quadratic in a to
/// second order: fitted from three bows, then refined by the secant rule).
fn bow(pts: &mut [DVec3], slack: f64) {
    let n = pts.len();
    if n < 3 {
        return;
    }
    let original = pts.to_vec();
    let shape: Vec<DVec3> = (0..n)
        .map(|i| {
            if i == 0 || i == n - 1 {
                return DVec3::ZERO;
            }
            let s = i as f64 / (n - 1) as f64;
            let t = (original[i + 1] - original[i - 1]).normalize_or(DVec3::X);
            let down = -DVec3::Z - t * (-DVec3::Z).dot(t);
            let side = if down.length() > 0.1 {
                down.normalize()
            } else {
                perpendicular(t)
            };
            side * (std::f64::consts::PI * s).sin().powi(2)
        })
        .collect();
    let length = |a: f64| -> f64 {
        let mut l = 0.0;
        for i in 1..n {
            l += ((original[i] + shape[i] * a) - (original[i - 1] + shape[i - 1] * a)).length();
        }
        l
    };
    let l0 = length(0.0);
    let target = l0 * (1.0 + slack);
    let a0 = 2.0 * l0 * slack.sqrt() / std::f64::consts::PI;
    // l(a) ≈ l0 + k a + c a²
    let (lp, lm) = (length(a0), length(-a0));
    let k = (lp - lm) / (2.0 * a0);
    let c = (lp + lm - 2.0 * l0) / (2.0 * a0 * a0);
    let sign = if k >= 0.0 { 1.0 } else { -1.0 };
    let (k, c) = (k.abs(), c.max(1e-12));
    let mut a = (-k + (k * k + 4.0 * c * (target - l0)).sqrt()) / (2.0 * c);
    // secant refinement on the side chosen
    let mut prev = (0.0, l0 - target);
    for _ in 0..8 {
        let f = length(sign * a) - target;
        if f.abs() <= 1e-9 * l0 || (f - prev.1).abs() < f64::MIN_POSITIVE {
            break;
        }
        let next = a - f * (a - prev.0) / (f - prev.1);
        prev = (a, f);
        a = next.max(0.0);
    }
    for (p, (o, d)) in pts.iter_mut().zip(original.iter().zip(&shape)) {
        *p = *o + *d * (sign * a);
    }
}

/// A fixing as the scene places it: the curve point at its location, the segment's
/// direction there and the side the hose enters the clip from.
pub(crate) struct ClipPlace {
    pub name: String,
    pub hose: String,
    /// The fixing's place on the centre curve \[m\].
    pub point: DVec3,
    /// The segment's direction there.
    pub tangent: DVec3,
    /// Out through the clip's opening: the fixing's orientation made perpendicular to the
    /// segment, or any perpendicular.
    pub opening: DVec3,
    /// The bundle's outer diameter \[m\].
    pub d_outer: f64,
    pub kind: &'static str,
    /// Where it comes from, for a comment.
    pub comment: String,
}

/// Every fixing, placed.
pub(crate) fn clip_places(h: &Harness, segs: &[SegmentOut]) -> Vec<ClipPlace> {
    let clip_names = unique(
        h.fixings
            .iter()
            .map(|f| sanitise(f.name.as_deref().unwrap_or(&f.kbl_id))),
    );
    h.fixings
        .iter()
        .zip(clip_names)
        .map(|(f, name)| {
            let out = &segs[f.segment];
            let (point, tangent) = out.curve.at_fraction(f.location);
            let tangent = if tangent.length() > 0.5 {
                tangent
            } else {
                DVec3::X
            };
            let opening = f
                .orientation
                .map(|o| o.normalize_or_zero())
                .map(|o| (o - tangent * o.dot(tangent)).normalize_or_zero())
                .filter(|o| o.length() > 0.5)
                .unwrap_or_else(|| perpendicular(tangent));
            ClipPlace {
                name,
                hose: out.hose.clone(),
                point,
                tangent,
                opening,
                d_outer: out.d_outer_at(f.location),
                kind: clip_type(f.fixing_type.as_deref(), f.description.as_deref()),
                comment: format!(
                    "KBL {} ({}), {} on {} at {:.4}",
                    f.kbl_id,
                    f.occurrence,
                    f.description.as_deref().unwrap_or("fixing"),
                    h.segments[f.segment].kbl_id,
                    f.location
                ),
            }
        })
        .collect()
}

/// A `[[clips]]` entry with its seat at `seat` \[m\]; `by_hand`: it takes the bundle only
/// when a hand presses it in (not as it is drawn through it or hangs by).
pub(crate) fn clip_toml(t: &mut String, c: &ClipPlace, seat: DVec3, by_hand: bool) {
    let _ = writeln!(t, "[[clips]]\nname = {}", quote(&c.name));
    let _ = writeln!(t, "# {}", c.comment);
    let _ = writeln!(t, "type = \"{}\"\nhose = {}", c.kind, quote(&c.hose));
    let _ = writeln!(
        t,
        "origin = {}\nopening = {}\norientation = {}",
        vec_mm(seat),
        unit_vec(c.opening),
        unit_vec(c.tangent)
    );
    let _ = writeln!(
        t,
        "inner_diameter = {}\nopening_width = {}",
        mm(c.d_outer),
        mm(OPENING_SHARE * c.d_outer)
    );
    if c.kind != "cable_tie" {
        let _ = writeln!(t, "snap_force_n = {SNAP_FORCE_N}");
    }
    if by_hand {
        let _ = writeln!(t, "by_hand = true");
    }
    t.push('\n');
}

/// The text of `scene.toml`: the harness held in its installed state (`cut`: the node a
/// branch was cut off at, held too).
pub fn scene_toml(
    h: &Harness,
    segs: &[SegmentOut],
    licence_note: &str,
    cut: Option<usize>,
) -> String {
    let mut t = network_toml(h, segs, licence_note, &static_simulation());
    for c in clip_places(h, segs) {
        clip_toml(&mut t, &c, c.point, false);
    }
    let _ = writeln!(
        t,
        "# Installed state: held at every fixing and at every connector end{} (with none of these: at every free end), then at rest.",
        if cut.is_some() {
            " and where the branch was cut off"
        } else {
            ""
        }
    );
    for (s, node) in held_nodes(h, segs, cut) {
        let _ = writeln!(
            t,
            "[[timeline]]\naction = \"fix\"\nhose = {}\nnode = {node}\n",
            quote(&segs[s].hose)
        );
    }
    let _ = writeln!(t, "[[timeline]]\naction = \"settle\"");
    t
}

/// One segment in `harness.json`.
#[derive(Debug, Serialize)]
pub struct SegmentJson<'a> {
    pub kbl_id: &'a str,
    pub name: Option<&'a str>,
    pub hose: &'a str,
    pub start_node: &'a str,
    pub end_node: &'a str,
    pub length_m: f64,
    pub virtual_length_m: Option<f64>,
    pub trimmed: bool,
    pub elements: usize,
    pub wires: Vec<&'a str>,
    pub protections: Vec<&'a str>,
    pub fixings: Vec<&'a str>,
    pub section: &'a BundleSection,
}

/// `harness.json`: the segments as written (hose names, sections, wires, protections,
/// fixings by KBL id) and the whole model.
#[derive(Debug, Serialize)]
pub struct HarnessJson<'a> {
    pub format: &'static str,
    pub version: u32,
    pub licence_note: &'a str,
    /// The KBL file imported (absolute path), for `pliant export`.
    pub source: String,
    pub segments: Vec<SegmentJson<'a>>,
    pub model: &'a Harness,
}

pub fn harness_json<'a>(
    h: &'a Harness,
    segs: &'a [SegmentOut],
    licence_note: &'a str,
    source: String,
) -> HarnessJson<'a> {
    let mut prot: HashMap<usize, Vec<&str>> = HashMap::new();
    for p in &h.protections {
        prot.entry(p.segment).or_default().push(&p.kbl_id);
    }
    let mut fix: HashMap<usize, Vec<&str>> = HashMap::new();
    for f in &h.fixings {
        fix.entry(f.segment).or_default().push(&f.kbl_id);
    }
    let segments = h
        .segments
        .iter()
        .zip(segs)
        .enumerate()
        .map(|(i, (s, o))| SegmentJson {
            kbl_id: &s.kbl_id,
            name: s.name.as_deref(),
            hose: &o.hose,
            start_node: &h.nodes[s.start_node].kbl_id,
            end_node: &h.nodes[s.end_node].kbl_id,
            length_m: o.curve.length,
            virtual_length_m: s.virtual_length,
            trimmed: o.curve.trimmed,
            elements: o.elements,
            wires: s
                .wires
                .iter()
                .map(|&w| h.wires[w].kbl_id.as_str())
                .collect(),
            protections: prot.remove(&i).unwrap_or_default(),
            fixings: fix.remove(&i).unwrap_or_default(),
            section: o.section,
        })
        .collect();
    HarnessJson {
        format: "pliant-harness",
        version: 1,
        licence_note,
        source,
        segments,
        model: h,
    }
}
