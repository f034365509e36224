//! VEC 2.x with 3-D geometry: a hand-written Y harness (tests/data/README.md) against its
//! exact geometry; the generator cable's KBL geometry written as VEC imports to the same
//! segments; topology-only and malformed VEC files are refused with the element, line and
//! reason.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::DVec3;
use pliant_harness::geometry::SegmentCurve;
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
    assert!(h.warnings.iter().any(|w| w.contains("not read")));
}

/// The harness's nodes and centre curves written as VEC 2.0.2 (millimetres; curves as
/// NURBS without knots, the convention KBL's centre curves follow).
fn as_vec(h: &Harness) -> String {
    let mut points = String::new();
    let mut point = |id: &str, p: DVec3| {
        let mm = p * 1e3;
        let _ = writeln!(
            points,
            "<CartesianPoint id=\"{id}\"><X>{}</X><Y>{}</Y><Z>{}</Z></CartesianPoint>",
            mm.x, mm.y, mm.z
        );
    };
    let mut body = String::new();
    for n in &h.nodes {
        point(&format!("P_{}", n.kbl_id), n.position);
        let _ = writeln!(
            body,
            "<GeometryNode id=\"{0}\"><Identification>{0}</Identification><CartesianPoint>P_{0}</CartesianPoint></GeometryNode>",
            n.kbl_id
        );
    }
    for s in &h.segments {
        let _ = write!(
            body,
            "<GeometrySegment id=\"{}\"><Identification>{}</Identification><EndNode>{}</EndNode><StartNode>{}</StartNode>",
            s.kbl_id, s.kbl_id, h.nodes[s.end_node].kbl_id, h.nodes[s.start_node].kbl_id
        );
        for c in &s.curves {
            let _ = write!(
                body,
                "<Curve xsi:type=\"vec:NURBSCurve\" id=\"C_{}\"><Degree>{}</Degree>",
                c.kbl_id, c.degree
            );
            for (k, p) in c.control_points.iter().enumerate() {
                let id = format!("P_{}_{k}", c.kbl_id);
                point(&id, *p);
                let _ = write!(
                    body,
                    "<ControlPoint id=\"CP_{}_{k}\"><Weight>1</Weight><CartesianPoint3D>{id}</CartesianPoint3D></ControlPoint>",
                    c.kbl_id
                );
            }
            body.push_str("</Curve>");
        }
        body.push_str("</GeometrySegment>\n");
    }
    format!(
        "<?xml version=\"1.0\"?>\n<vec:VecContent xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" xmlns:vec=\"http://www.prostep.org/ecad-if/2011/vec\" id=\"c\">\n\
         <VecVersion>2.0.2</VecVersion>\n<DocumentVersion id=\"d\"><CompanyName>test</CompanyName><DocumentNumber>1</DocumentNumber><DocumentVersion>1</DocumentVersion>\n\
         <Specification xsi:type=\"vec:BuildingBlockSpecification3D\" id=\"b\"><Identification>b</Identification><BaseUnit>mm</BaseUnit>\n{points}{body}</Specification>\n</DocumentVersion>\n\
         <Unit xsi:type=\"vec:SIUnit\" id=\"mm\"><SiUnitName>Metre</SiUnitName><SiPrefix>Milli</SiPrefix></Unit>\n</vec:VecContent>\n"
    )
}

#[test]
fn the_generator_cable_written_as_vec_imports_to_the_same_segments() {
    let kbl = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/harness/kblxml_2.3sr-1_000971230_ltgs_generator_170718.kbl");
    let k = read_kbl(&kbl).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let vec_path = dir.path().join("generator.vec");
    std::fs::write(&vec_path, as_vec(&k)).unwrap();
    let v = read_kbl(&vec_path).unwrap();
    assert_eq!(v.segments.len(), k.segments.len());
    assert_eq!(v.nodes.len(), k.nodes.len());
    let mut worst: f64 = 0.0;
    for s in &k.segments {
        let a = SegmentCurve::of(&k, s);
        let b = SegmentCurve::of(&v, segment(&v, &s.kbl_id));
        assert_eq!(a.straight_fallback, b.straight_fallback);
        worst = worst.max((b.length / a.length - 1.0).abs());
        let (pa, pb) = (a.sample(20), b.sample(20));
        for (p, q) in pa.iter().zip(&pb) {
            assert!((*p - *q).length() < 1e-12, "{}: {p} vs {q}", s.kbl_id);
        }
    }
    println!("worst relative length difference KBL vs VEC: {worst:e}");
    assert!(worst < 1e-9);
    // And the whole import writes a scene.
    let report = pliant_harness::import_kbl(&vec_path, &dir.path().join("scene")).unwrap();
    assert!(report.scene.exists());
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
