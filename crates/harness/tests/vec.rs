//! VEC 2.x with 3-D geometry: a hand-written Y harness (tests/data/README.md) against its
//! exact geometry; the generator cable's KBL geometry written as VEC imports to the same
//! segments; topology-only and malformed VEC files are refused with the element, line and
//! reason.

mod common;
mod vec_writer;

use std::path::{Path, PathBuf};

use glam::DVec3;
use pliant_harness::bundle::{segment_bundle, BundleData, BundleSection};
use pliant_harness::geometry::SegmentCurve;
use pliant_harness::model::{Conductor, ProtectionKind};
use pliant_harness::{read_kbl, Harness, HarnessError};

fn test_data(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(file)
}

fn segment<'h>(h: &'h Harness, id: &str) -> &'h pliant_harness::model::Segment {
    h.segments.iter().find(|s| s.kbl_id == id).unwrap()
}

#[test]
fn the_hand_written_y_harness_has_its_exact_geometry() {
    let h = read_kbl(&test_data("y_harness_3d.vec")).unwrap();
    assert_eq!(h.kbl_version, "VEC 2.0.2");
    assert_eq!((h.nodes.len(), h.segments.len()), (4, 3));
    // Placed: p ↦ A p + o with A a quarter turn about z, o = (1000, 0, 500) mm.
    let place = |x: f64, y: f64, z: f64| DVec3::new(-y + 1000.0, x, z + 500.0) * 1e-3;
    let node = |id: &str| h.nodes.iter().find(|n| n.kbl_id == id).unwrap();
    assert!((node("GeometryNode_a").position - place(200.0, 0.0, 0.0)).length() < 1e-15);
    assert!((node("GeometryNode_b").position - place(-100.0, 100.0, 0.0)).length() < 1e-15);
    assert_eq!(node("GeometryNode_a").name.as_deref(), Some("End A"));
    let straight = segment(&h, "GeometrySegment_straight");
    assert_eq!(straight.name.as_deref(), Some("Straight"));
    assert_eq!(straight.virtual_length, Some(0.2));
    let lengths: Vec<f64> = ["straight", "arc", "spline"]
        .iter()
        .map(|s| SegmentCurve::of(&h, segment(&h, &format!("GeometrySegment_{s}"))).length)
        .collect();
    println!(
        "lengths [mm]: {:?}",
        lengths.iter().map(|l| l * 1e3).collect::<Vec<_>>()
    );
    assert!((lengths[0] / 0.2 - 1.0).abs() < 1e-12);
    assert!((lengths[2] / 0.1 - 1.0).abs() < 1e-9);
    // The arc: every sampled point on the circle (the rational evaluation is exact); the
    // polyline of 2 × 32 … chords is shorter than 50 π mm by (Δθ)²/24 ≈ 10⁻⁴.
    let arc = segment(&h, "GeometrySegment_arc");
    let centre = place(-100.0, 0.0, 0.0);
    for p in &arc.curves[0].control_points {
        assert!(((*p - centre).length() - 0.1).abs() < 1e-15, "{p}");
    }
    let exact = 0.05 * std::f64::consts::PI;
    let rel = lengths[1] / exact - 1.0;
    println!(
        "arc: {} points, length {:.6} mm, {rel:+.2e} relative",
        arc.curves[0].control_points.len(),
        lengths[1] * 1e3
    );
    assert!(rel < 0.0 && rel > -2e-4, "{rel}");
    assert!(h.warnings.iter().any(|w| w.contains("polylines")));
}

#[test]
fn the_hand_written_y_harness_has_its_wires_fixings_protections_and_connectors() {
    let h = read_kbl(&test_data("y_harness_3d.vec")).unwrap();
    let seg = |i: usize| h.segments[i].kbl_id.as_str();
    assert_eq!(
        [seg(0), seg(1), seg(2)],
        [
            "GeometrySegment_straight",
            "GeometrySegment_arc",
            "GeometrySegment_spline"
        ]
    );
    // Wire parts in SI units: mm → m, mm² (SIUnit, exponent 2) → m², g/m (CompositeUnit
    // gram × metre⁻¹) → kg/m.
    assert_eq!(h.wire_parts.len(), 2);
    let wire = &h.wire_parts[0];
    assert_eq!(wire.part_number.as_deref(), Some("WIRE-035"));
    assert_eq!(wire.description.as_deref(), Some("FLRY-B 0.35 mm2"));
    assert!(close(wire.own.outer_diameter, Some(1.3e-3), 1e-15));
    assert!(close(wire.own.cross_section, Some(0.35e-6), 1e-15));
    assert!(close(wire.own.bend_radius, Some(4e-3), 1e-15));
    assert!(close(wire.mass_per_length, Some(4.5e-3), 1e-15));
    assert!(wire.cores.is_empty());
    let cable = &h.wire_parts[1];
    assert!(close(cable.own.outer_diameter, Some(5e-3), 1e-15));
    assert_eq!(cable.own.cross_section, None);
    // Only a dynamic minimum bend radius given: that one.
    assert!(close(cable.own.bend_radius, Some(25e-3), 1e-15));
    assert!(close(cable.mass_per_length, Some(40e-3), 1e-15));
    assert_eq!(cable.cores.len(), 2);
    for c in &cable.cores {
        assert!(close(c.outer_diameter, Some(1.6e-3), 1e-15));
        assert!(close(c.cross_section, Some(0.5e-6), 1e-15));
    }
    // Wires and their paths (W2 routed through its connection).
    let routes: Vec<(&str, Option<&str>, usize, &[usize])> = h
        .wires
        .iter()
        .map(|w| {
            (
                w.kbl_id.as_str(),
                w.name.as_deref(),
                w.part,
                &w.segments[..],
            )
        })
        .collect();
    assert_eq!(
        routes,
        [
            ("WireRole_W1", Some("W1"), 0, &[0, 1][..]),
            ("WireRole_W2", Some("W2"), 0, &[0, 2][..]),
            ("WireRole_K1", Some("K1"), 1, &[1, 2][..]),
        ]
    );
    let through: Vec<&[usize]> = h.segments.iter().map(|s| &s.wires[..]).collect();
    assert_eq!(through, [&[0, 1][..], &[0, 2][..], &[1, 2][..]]);
    // Fixings: 50 mm before the end of the 200 mm straight segment; 25 mm along the
    // 100 mm spline (no topology length: its centre curve's).
    assert_eq!(h.fixings.len(), 2);
    let clip = &h.fixings[0];
    assert_eq!(
        (
            clip.kbl_id.as_str(),
            clip.occurrence.as_str(),
            clip.name.as_deref()
        ),
        ("Placement_clip", "PartOccurrence_clip", Some("CL1"))
    );
    assert_eq!(
        (
            clip.fixing_type.as_deref(),
            clip.part_number.as_deref(),
            clip.segment
        ),
        (Some("SPT"), Some("CLIP-1"), 0)
    );
    assert!((clip.location - 0.75).abs() < 1e-15);
    // The view's local z axis, the block's x axis, turned a quarter about z: +y.
    let o = clip.orientation.unwrap();
    assert!((o - DVec3::Y).length() < 1e-15, "{o}");
    let tie = &h.fixings[1];
    assert_eq!(
        (tie.segment, tie.description.as_deref(), tie.orientation),
        (2, Some("KABELBINDER"), None)
    );
    assert!((tie.location - 0.25).abs() < 1e-9, "{}", tie.location);
    // Protections: the tape from the middle of the straight segment through the branch
    // to the middle of the spline; the tube over the whole arc.
    let spans: Vec<(&str, usize, f64, f64, ProtectionKind)> = h
        .protections
        .iter()
        .map(|p| (p.kbl_id.as_str(), p.segment, p.from, p.to, p.kind))
        .collect();
    println!("{spans:?}");
    assert_eq!(spans.len(), 3);
    let expected = [
        ("Placement_tape/0", 0, 0.0, 0.5, ProtectionKind::Tape),
        (
            "Placement_tube",
            1,
            0.0,
            1.0,
            ProtectionKind::CorrugatedTube,
        ),
        ("Placement_tape/1", 2, 0.0, 0.5, ProtectionKind::Tape),
    ];
    for (got, want) in spans.iter().zip(&expected) {
        assert_eq!((got.0, got.1, got.4), (want.0, want.1, want.4));
        assert!((got.2 - want.2).abs() < 1e-9 && (got.3 - want.3).abs() < 1e-9);
    }
    let tube = &h.protections[1];
    assert!(close(tube.outer_diameter, Some(13.4e-3), 1e-15));
    assert!(close(tube.mass_per_length, Some(17e-3), 1e-15));
    assert_eq!(tube.protection_type.as_deref(), Some("Tube"));
    // Connectors at the three ends: 2 cavities, 1 cavity, a modular slot of 4.
    let node = |id: &str| h.nodes.iter().position(|n| n.kbl_id == id);
    let held: Vec<(&str, Option<usize>, usize)> = h
        .connectors
        .iter()
        .map(|c| (c.name.as_deref().unwrap(), c.node, c.positions))
        .collect();
    assert_eq!(
        held,
        [
            ("X1", node("GeometryNode_a"), 2),
            ("X2", node("GeometryNode_b"), 1),
            ("X3", node("GeometryNode_c"), 4),
        ]
    );
    assert_eq!(
        h.connectors[0].description.as_deref(),
        Some("2-way connector at End A")
    );
    // The terminal is named as skipped.
    assert!(
        h.skipped
            .iter()
            .any(|(id, why)| id == "PartOccurrence_terminal" && why.contains("TerminalRole")),
        "{:?}",
        h.skipped
    );
    assert_eq!(h.skipped.len(), 1, "{:?}", h.skipped);
    // The bare straight segment: two 0.35 mm² wires, 2 × 4.5 g/m.
    let b = segment_bundle(&BundleData::builtin(), &h, 0);
    assert_eq!(b.bare.wire_count, 2);
    assert!((b.bare.mass - 9e-3).abs() < 1e-15);
    assert!(b.bare.min_bend_radius >= 4e-3);
}

#[test]
fn imperial_units_scale_geometry_and_part_data() {
    // The Y harness with its millimetre unit made the inch: every length ×25.4.
    let y = std::fs::read_to_string(test_data("y_harness_3d.vec")).unwrap();
    let mm = "<Unit xsi:type=\"vec:SIUnit\" id=\"Unit_mm\">\n    <SiUnitName>Metre</SiUnitName>\n    <SiPrefix>Milli</SiPrefix>";
    let inch = "<Unit xsi:type=\"vec:ImperialUnit\" id=\"Unit_mm\">\n    <ImperialUnitName>Inch</ImperialUnitName>";
    assert!(y.contains(mm));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("inch.vec");
    std::fs::write(&path, y.replacen(mm, inch, 1)).unwrap();
    let (a, b) = (
        read_kbl(&test_data("y_harness_3d.vec")).unwrap(),
        read_kbl(&path).unwrap(),
    );
    for (p, q) in a.nodes.iter().zip(&b.nodes) {
        assert!((q.position - p.position * 25.4).length() < 1e-12, "{q:?}");
    }
    assert!(close(
        b.wire_parts[0].own.outer_diameter,
        Some(1.3 * 0.0254),
        1e-15
    ));
    // Fixings sit at the same shares of their segments.
    for (f, g) in a.fixings.iter().zip(&b.fixings) {
        assert!((f.location - g.location).abs() < 1e-12);
    }
}

/// |a − b| ≤ tol · max(|a|, |b|), both absent, or both present.
fn close(a: Option<f64>, b: Option<f64>, tol: f64) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= tol * a.abs().max(b.abs()),
        (None, None) => true,
        _ => false,
    }
}

fn same_conductor(a: &Conductor, b: &Conductor, what: &str) {
    assert!(
        close(a.outer_diameter, b.outer_diameter, 1e-12),
        "{what}: {a:?} vs {b:?}"
    );
    assert!(
        close(a.cross_section, b.cross_section, 1e-12),
        "{what}: {a:?} vs {b:?}"
    );
    assert!(
        close(a.bend_radius, b.bend_radius, 1e-12),
        "{what}: {a:?} vs {b:?}"
    );
}

fn same_section(a: &BundleSection, b: &BundleSection, what: &str) {
    let pairs = [
        ("d_outer", a.d_outer, b.d_outer),
        ("EA", a.ea, b.ea),
        ("EI", a.ei, b.ei),
        ("GJ", a.gj, b.gj),
        ("mass", a.mass, b.mass),
        ("min bend radius", a.min_bend_radius, b.min_bend_radius),
    ];
    for (name, x, y) in pairs {
        assert!(close(Some(x), Some(y), 1e-12), "{what} {name}: {x} vs {y}");
    }
    assert_eq!(a.wire_count, b.wire_count, "{what}");
    assert_eq!(a.protection, b.protection, "{what}");
}

/// Everything the import uses is the same in the KBL reading `k` and the VEC reading
/// `v` of one harness: segments (geometry, lengths, wires), wire parts, wires, fixings,
/// protections, connectors, and each segment's bundle sections.
fn same_content(k: &Harness, v: &Harness) {
    assert_eq!(v.nodes.len(), k.nodes.len());
    for (a, b) in k.nodes.iter().zip(&v.nodes) {
        assert_eq!(a.kbl_id, b.kbl_id);
        assert!((a.position - b.position).length() < 1e-12);
    }
    assert_eq!(v.segments.len(), k.segments.len());
    let mut worst: f64 = 0.0;
    for (a, b) in k.segments.iter().zip(&v.segments) {
        assert_eq!(
            (&a.kbl_id, &a.name, a.start_node, a.end_node, &a.wires),
            (&b.kbl_id, &b.name, b.start_node, b.end_node, &b.wires)
        );
        assert!(
            close(a.virtual_length, b.virtual_length, 1e-12),
            "{}",
            a.kbl_id
        );
        assert!(
            close(a.cross_section_area, b.cross_section_area, 1e-12),
            "{}",
            a.kbl_id
        );
        let (ca, cb) = (SegmentCurve::of(k, a), SegmentCurve::of(v, b));
        assert_eq!(ca.straight_fallback, cb.straight_fallback);
        worst = worst.max((cb.length / ca.length - 1.0).abs());
        for (p, q) in ca.sample(20).iter().zip(&cb.sample(20)) {
            assert!((*p - *q).length() < 1e-12, "{}: {p} vs {q}", a.kbl_id);
        }
    }
    println!("worst relative length difference KBL vs VEC: {worst:e}");
    assert!(worst < 1e-9);
    assert_eq!(v.wire_parts.len(), k.wire_parts.len());
    for (a, b) in k.wire_parts.iter().zip(&v.wire_parts) {
        assert_eq!(
            (&a.kbl_id, &a.part_number, &a.description, a.cores.len()),
            (&b.kbl_id, &b.part_number, &b.description, b.cores.len())
        );
        assert!(
            close(a.mass_per_length, b.mass_per_length, 1e-12),
            "{}",
            a.kbl_id
        );
        same_conductor(&a.own, &b.own, &a.kbl_id);
        for (x, y) in a.cores.iter().zip(&b.cores) {
            same_conductor(x, y, &a.kbl_id);
        }
    }
    assert_eq!(v.wires.len(), k.wires.len());
    for (a, b) in k.wires.iter().zip(&v.wires) {
        assert_eq!(
            (&a.kbl_id, &a.name, a.part, &a.segments),
            (&b.kbl_id, &b.name, b.part, &b.segments)
        );
    }
    assert_eq!(v.fixings.len(), k.fixings.len());
    for (a, b) in k.fixings.iter().zip(&v.fixings) {
        assert_eq!(
            (
                &a.kbl_id,
                &a.occurrence,
                &a.name,
                &a.part_number,
                &a.description
            ),
            (
                &b.kbl_id,
                &b.occurrence,
                &b.name,
                &b.part_number,
                &b.description
            )
        );
        assert_eq!((&a.fixing_type, a.segment), (&b.fixing_type, b.segment));
        assert!((a.location - b.location).abs() < 1e-12, "{}", a.kbl_id);
        let direction = |o: Option<DVec3>| o.map(|o| o.normalize());
        match (direction(a.orientation), direction(b.orientation)) {
            (Some(x), Some(y)) => assert!((x - y).length() < 1e-12, "{x} vs {y}"),
            (x, y) => assert_eq!(x, y),
        }
    }
    assert_eq!(v.protections.len(), k.protections.len());
    for (a, b) in k.protections.iter().zip(&v.protections) {
        assert_eq!(
            (&a.kbl_id, &a.occurrence, &a.part_number, &a.description),
            (&b.kbl_id, &b.occurrence, &b.part_number, &b.description)
        );
        if a.protection_type.is_some() {
            assert_eq!(a.protection_type, b.protection_type);
        }
        assert_eq!((a.kind, a.segment), (b.kind, b.segment));
        assert!((a.from - b.from).abs() < 1e-12 && (a.to - b.to).abs() < 1e-12);
        assert!(close(a.mass_per_length, b.mass_per_length, 1e-12));
        assert!(close(a.outer_diameter, b.outer_diameter, 1e-12));
    }
    assert_eq!(v.connectors.len(), k.connectors.len());
    for (a, b) in k.connectors.iter().zip(&v.connectors) {
        assert_eq!(
            (&a.kbl_id, &a.name, &a.description, a.node, a.positions),
            (&b.kbl_id, &b.name, &b.description, b.node, b.positions)
        );
    }
    let data = BundleData::builtin();
    for i in 0..k.segments.len() {
        let (a, b) = (segment_bundle(&data, k, i), segment_bundle(&data, v, i));
        same_section(&a.section, &b.section, &k.segments[i].kbl_id);
        same_section(&a.bare, &b.bare, &k.segments[i].kbl_id);
        assert_eq!(a.stretches.len(), b.stretches.len());
        for (x, y) in a.stretches.iter().zip(&b.stretches) {
            assert!((x.from - y.from).abs() < 1e-12 && (x.to - y.to).abs() < 1e-12);
            same_section(&x.section, &y.section, &k.segments[i].kbl_id);
        }
    }
}

/// The lines of a written file that do not name the source file or format.
fn content_lines(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| {
            !l.starts_with('#') && !l.contains("source") && !l.contains("KBL") && !l.contains("VEC")
        })
        .map(str::to_string)
        .collect()
}

/// Lines equal token by token, numbers as numbers (a printed −0.000000 is 0).
fn same_line(a: &str, b: &str) -> bool {
    let split = |l: &str| -> Vec<String> {
        l.split(|c: char| c.is_whitespace() || ",[]{}=".contains(c))
            .filter(|t| !t.is_empty())
            .map(str::to_string)
            .collect()
    };
    let (x, y) = (split(a), split(b));
    x.len() == y.len()
        && x.iter()
            .zip(&y)
            .all(|(s, t)| match (s.parse::<f64>(), t.parse::<f64>()) {
                (Ok(u), Ok(v)) => u == v,
                _ => s == t,
            })
}

#[test]
fn kbl_harnesses_written_as_vec_import_to_the_same_content() {
    for file in [common::GENERATOR, common::BATTERY, common::MAIN] {
        let k = read_kbl(&common::data(file)).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let vec_path = dir.path().join(file.replace(".kbl", ".vec"));
        std::fs::write(&vec_path, vec_writer::as_vec(&k)).unwrap();
        let v = read_kbl(&vec_path).unwrap();
        println!(
            "{file}: {} segments, {} wires, {} fixings, {} protections, {} connectors; VEC skipped: {:?}",
            v.segments.len(),
            v.wires.len(),
            v.fixings.len(),
            v.protections.len(),
            v.connectors.len(),
            v.skipped
        );
        same_content(&k, &v);
        // And the whole import writes the same scene and installation.
        let kbl_report =
            pliant_harness::import_kbl(&common::data(file), &dir.path().join("kbl")).unwrap();
        let vec_report = pliant_harness::import_kbl(&vec_path, &dir.path().join("vec")).unwrap();
        for name in ["scene.toml", "install.toml"] {
            let (pa, pb) = (
                kbl_report.scene.with_file_name(name),
                vec_report.scene.with_file_name(name),
            );
            assert_eq!(pa.exists(), pb.exists(), "{file} {name}");
            if !pa.exists() {
                continue;
            }
            let a = content_lines(&pa);
            let b = content_lines(&pb);
            assert_eq!(a.len(), b.len(), "{file} {name}");
            for (x, y) in a.iter().zip(&b) {
                assert!(same_line(x, y), "{file} {name}:\n{x}\n{y}");
            }
        }
    }
}

fn refusal(name: &str, text: &str) -> HarnessError {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    read_kbl(&p).unwrap_err()
}

#[test]
fn topology_only_and_malformed_vec_files_are_refused_with_the_place() {
    let y = std::fs::read_to_string(test_data("y_harness_3d.vec")).unwrap();
    // Topology only: the building block removed.
    let start = y
        .find("<Specification xsi:type=\"vec:BuildingBlockSpecification3D\"")
        .unwrap();
    let end = y[start..].find("</Specification>").unwrap() + start + "</Specification>".len();
    let topology = format!("{}{}", &y[..start], &y[end..]);
    let e = refusal("t.vec", &topology).to_string();
    assert!(
        e.contains("without 3-D geometry") && e.contains("topology only"),
        "{e}"
    );
    // Malformed: (replace this, by that) → the message names element, line and reason.
    let line_of = |needle: &str| y[..y.find(needle).unwrap()].matches('\n').count() + 1;
    let cases = [
        (
            "<X>200</X>",
            "<X>abc</X>",
            "CartesianPoint",
            "\"abc\" is not a finite number",
        ),
        (
            "<EndNode>GeometryNode_a</EndNode>",
            "<EndNode>GeometryNode_x</EndNode>",
            "GeometrySegment",
            "EndNode \"GeometryNode_x\"",
        ),
        (
            "<Degree>3</Degree>",
            "<Degree>7</Degree>",
            "Curve",
            "a curve of degree 7 needs at least 8",
        ),
        (
            "<Knots>0</Knots><Knots>0</Knots><Knots>0</Knots><Knots>1</Knots>",
            "<Knots>0</Knots><Knots>0</Knots><Knots>1</Knots>",
            "Curve",
            "5 knots for 3 control points",
        ),
        (
            "<Weight>0.70710678118654752</Weight>",
            "<Weight>-1</Weight>",
            "Curve",
            "weight -1",
        ),
        (
            "<SiPrefix>Milli</SiPrefix>",
            "<SiPrefix>Milli</SiPrefix><Exponent>2</Exponent>",
            "Unit",
            "must be a length",
        ),
        // Wires, fixings, protections, connectors: dangling references, wrong targets,
        // missing and malformed values.
        (
            "<WireSpecification>WireSpecification_cable</WireSpecification>",
            "<WireSpecification>WireSpecification_none</WireSpecification>",
            "Role",
            "WireSpecification \"WireSpecification_none\" refers to no element",
        ),
        (
            "<FixingSpecification>FixingSpecification_clip</FixingSpecification>",
            "<FixingSpecification>TapeSpecification_pvc</FixingSpecification>",
            "Role",
            "is a TapeSpecification, expected a FixingSpecification",
        ),
        (
            "<Segment>TopologySegment_arc TopologySegment_spline</Segment>",
            "<Segment>TopologySegment_arc TopologySegment_zz</Segment>",
            "Path",
            "Segment \"TopologySegment_zz\" refers to no element",
        ),
        (
            "<ValueComponent>50</ValueComponent></Offset>",
            "</Offset>",
            "Offset",
            "ValueComponent is missing",
        ),
        (
            "<Anchor>FromEndNode</Anchor>",
            "<Anchor>Middle</Anchor>",
            "Location",
            "Anchor \"Middle\": expected FromStartNode or FromEndNode",
        ),
        (
            "<MinBendRadiusStatic id=\"Value_2\"><UnitComponent>Unit_mm</UnitComponent>",
            "<MinBendRadiusStatic id=\"Value_2\"><UnitComponent>Unit_mm2</UnitComponent>",
            "MinBendRadiusStatic",
            "its unit Unit_mm2 measures Area, expected Length",
        ),
        (
            "<Factors>Unit_g Unit_per_m</Factors>",
            "<Factors>Unit_g Unit_kg</Factors>",
            "Value",
            "factor \"Unit_kg\" refers to no element",
        ),
        (
            "<NumberOfCavities>4</NumberOfCavities>",
            "<NumberOfCavities>four</NumberOfCavities>",
            "Specification",
            "NumberOfCavities \"four\" is not a finite number",
        ),
    ];
    for (this, that, element, reason) in cases {
        let e = refusal("m.vec", &y.replacen(this, that, 1));
        println!("{e}");
        let HarnessError::Element {
            element: el,
            line,
            reason: why,
            ..
        } = &e
        else {
            panic!("{e:?}");
        };
        assert_eq!(el, element, "{e}");
        assert!(why.contains(reason), "{e}");
        assert!(*line as usize <= line_of(this) && *line > 1, "{e}");
    }
    // Not well-formed XML: file, line, column.
    let e = refusal("x.vec", &y[..y.len() / 2]).to_string();
    assert!(
        e.starts_with("x.vec:") && e.contains("not well-formed"),
        "{e}"
    );
    // VEC 1.x is named.
    let e = refusal(
        "o.vec",
        &y.replace("<VecVersion>2.0.2", "<VecVersion>1.1.3"),
    )
    .to_string();
    assert!(e.contains("VEC version \"1.1.3\""), "{e}");
}
