//! KBL export: the round trip import → displaced route → export → import on the real
//! main harness (data/harness/, CC BY-SA 4.0), and the export's refusals.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::PathBuf;

use glam::DVec3;
use pliant_harness::geometry::SegmentCurve;
use pliant_harness::settled::{distance_to_polyline, polyline_length};
use pliant_harness::{export_kbl, import_kbl, read_kbl, Harness, HarnessError, SettledHarness};

mod common;
use common::*;

fn out_dir(name: &str) -> PathBuf {
    common::out_dir("harness-export-tests", name)
}

/// A smooth displacement field of position: every segment end at a node moves the same.
fn field(p: DVec3) -> DVec3 {
    DVec3::new(
        (p.y / 0.2).sin(),
        (p.z / 0.3).sin(),
        (p.x / 0.25 + 0.4).sin(),
    ) * 3e-3
}

/// A unit vector across the tangent t.
fn sideways(t: DVec3) -> DVec3 {
    let a = if t.z.abs() < 0.9 { DVec3::Z } else { DVec3::X };
    t.cross(a).normalize_or_zero()
}

/// The stand-in for Pliant's settled route: each imported centre line (a point every
/// 5 mm) moved by the field, plus 5 mm · sin(π s / L) sideways (zero at the ends), its
/// ends exactly on the moved nodes.
fn displaced(h: &Harness) -> SettledHarness {
    let mut out = SettledHarness::new();
    for s in &h.segments {
        let c = SegmentCurve::of(h, s);
        let n = ((c.length / 5e-3).ceil() as usize + 1).max(3);
        let p = c.sample(n);
        let mut q = Vec::with_capacity(n);
        let mut arc = 0.0;
        for i in 0..n {
            if i > 0 {
                arc += p[i].distance(p[i - 1]);
            }
            let t = (p[(i + 1).min(n - 1)] - p[i.saturating_sub(1)]).normalize_or_zero();
            q.push(p[i] + field(p[i]) + sideways(t) * 5e-3 * (PI * arc / c.length).sin());
        }
        let a = h.nodes[s.start_node].position;
        let b = h.nodes[s.end_node].position;
        q[0] = a + field(a);
        q[n - 1] = b + field(b);
        out.insert(s.kbl_id.clone(), q);
    }
    out
}

/// The text of every element with this name, by id.
fn element_texts<'a>(text: &'a str, name: &str) -> HashMap<String, &'a str> {
    let doc = roxmltree::Document::parse(text).unwrap();
    doc.descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == name)
        .map(|n| {
            (
                n.attribute("id").unwrap_or("").to_string(),
                &text[n.range()],
            )
        })
        .collect()
}

#[test]
fn main_harness_round_trip() {
    let src = data(MAIN);
    let h = read_kbl(&src).unwrap();
    let route = displaced(&h);
    let dir = out_dir("main");
    let out = dir.join("settled.kbl");
    let report = export_kbl(&src, &route, &out).unwrap();
    println!("{report}");
    assert_eq!(report.segments_replaced, 183);
    assert_eq!(report.segments_kept, 0);
    assert_eq!(report.nodes_moved, 184);
    assert!(
        report.max_node_spread_m < 1e-12,
        "{}",
        report.max_node_spread_m
    );
    assert!(report.warnings.iter().all(|w| w.contains("checksum")));

    // Read back: the same topology and the displaced route.
    let h2 = read_kbl(&out).unwrap();
    assert_eq!(h2.segments.len(), h.segments.len());
    assert_eq!(h2.nodes.len(), h.nodes.len());
    let mut worst_point: f64 = 0.0;
    let mut worst_length: f64 = 0.0;
    let mut worst_virtual: f64 = 0.0;
    for (s, s2) in h.segments.iter().zip(&h2.segments) {
        assert_eq!(s.kbl_id, s2.kbl_id);
        assert_eq!((s.start_node, s.end_node), (s2.start_node, s2.end_node));
        assert_eq!(s.wires, s2.wires, "{}", s.kbl_id);
        let poly = route.get(&s.kbl_id).unwrap();
        let c = SegmentCurve::of(&h2, s2);
        assert!(!c.trimmed && !c.straight_fallback, "{}", s.kbl_id);
        for p in c.sample(200) {
            worst_point = worst_point.max(distance_to_polyline(poly, p));
        }
        let l = polyline_length(poly);
        worst_length = worst_length.max((c.length - l).abs() / l);
        worst_virtual = worst_virtual.max((s2.virtual_length.unwrap() - l).abs() / l);
    }
    println!(
        "worst point {:.3e} mm, length {:.3e} %, Virtual_length {:.3e} %",
        worst_point * 1e3,
        worst_length * 100.0,
        worst_virtual * 100.0
    );
    assert!(
        worst_point < 1e-4,
        "a point is {} mm off",
        worst_point * 1e3
    );
    assert!(worst_length < 1e-3);
    assert!(worst_virtual < 1e-3);
    for (n, n2) in h.nodes.iter().zip(&h2.nodes) {
        assert_eq!(n.kbl_id, n2.kbl_id);
        let want = n.position + field(n.position);
        assert!(n2.position.distance(want) < 1e-8, "{}", n.kbl_id);
    }

    // The importer sees the same harness: junctions, fixings, protections, wires.
    let r1 = import_kbl(&src, &dir.join("before")).unwrap();
    let r2 = import_kbl(&out, &dir.join("after")).unwrap();
    assert_eq!(
        (r2.junctions, r2.branch_points, r2.max_junction_degree),
        (r1.junctions, r1.branch_points, r1.max_junction_degree)
    );
    assert_eq!(r2.fixings, r1.fixings);
    assert_eq!(r2.protections, r1.protections);
    assert_eq!(r2.wires, r1.wires);
    assert_eq!(r2.connectors_on_nodes, r1.connectors_on_nodes);
    assert_eq!(r2.skipped, r1.skipped);
    assert!(r2.trimmed_segments.is_empty(), "{:?}", r2.trimmed_segments);
    let fix: Vec<_> = h
        .fixings
        .iter()
        .map(|f| (&f.kbl_id, f.segment, f.location))
        .collect();
    let fix2: Vec<_> = h2
        .fixings
        .iter()
        .map(|f| (&f.kbl_id, f.segment, f.location))
        .collect();
    assert_eq!(fix, fix2);

    // Everything but the geometry is byte for byte as it was.
    let a = std::fs::read_to_string(&src).unwrap();
    let b = std::fs::read_to_string(&out).unwrap();
    for name in [
        "Harness",
        "Routing",
        "General_wire",
        "Unit",
        "Fixing_assignment",
        "Protection_area",
        "Cross_section_area_information",
    ] {
        let (ea, eb) = (element_texts(&a, name), element_texts(&b, name));
        assert_eq!(ea.len(), eb.len(), "{name}");
        for (id, t) in &ea {
            assert_eq!(Some(t), eb.get(id), "{name} {id}");
        }
    }
    let lines_a: Vec<&str> = a.lines().take(6).collect();
    let lines_b: Vec<&str> = b.lines().take(6).collect();
    assert_eq!(lines_a, lines_b, "prolog and root start unchanged");
}

#[test]
fn partial_route_keeps_the_other_segments() {
    let src = data(GENERATOR);
    let h = read_kbl(&src).unwrap();
    // One segment bent sideways in its middle, its ends on its nodes as they are.
    let s = &h.segments[0];
    let c = SegmentCurve::of(&h, s);
    let mut p = c.sample(41);
    let n = p.len();
    for (i, q) in p.iter_mut().enumerate().take(n - 1).skip(1) {
        *q += DVec3::Z * 4e-3 * (PI * i as f64 / (n - 1) as f64).sin();
    }
    p[0] = h.nodes[s.start_node].position;
    p[n - 1] = h.nodes[s.end_node].position;
    let mut route = SettledHarness::new();
    route.insert(s.kbl_id.clone(), p.clone());
    let out = out_dir("generator").join("one.kbl");
    let r = export_kbl(&src, &route, &out).unwrap();
    println!("{r}");
    assert_eq!(
        (r.segments_replaced, r.segments_kept),
        (1, h.segments.len() - 1)
    );
    assert_eq!((r.nodes_moved, r.max_node_move_m), (0, 0.0));
    assert!(
        r.warnings.iter().all(|w| w.contains("checksum")),
        "{:?}",
        r.warnings
    );
    let h2 = read_kbl(&out).unwrap();
    for (a, b) in h.segments.iter().zip(&h2.segments).skip(1) {
        assert_eq!(a.curves.len(), b.curves.len(), "{}", a.kbl_id);
        for (ca, cb) in a.curves.iter().zip(&b.curves) {
            assert_eq!(ca.control_points, cb.control_points, "{}", a.kbl_id);
        }
        assert_eq!(a.virtual_length, b.virtual_length);
    }
    let c2 = SegmentCurve::of(&h2, &h2.segments[0]);
    assert_eq!(h2.segments[0].curves.len(), 1);
    assert_eq!(h2.segments[0].curves[0].degree, 1);
    assert!((c2.length - polyline_length(&p)).abs() < 1e-8);

    // Moving a node that a kept segment also ends on: the report says so.
    let node = s.end_node;
    let shift = DVec3::new(0.0, 2e-3, 0.0);
    let mut q = p.clone();
    q[n - 1] += shift;
    route.insert(s.kbl_id.clone(), q);
    let r = export_kbl(&src, &route, &out_dir("generator").join("moved.kbl")).unwrap();
    let kept_at_node = h
        .segments
        .iter()
        .skip(1)
        .filter(|t| t.start_node == node || t.end_node == node)
        .count();
    assert_eq!(
        r.warnings
            .iter()
            .filter(|w| w.contains("not in the settled route"))
            .count(),
        kept_at_node,
        "{:?}",
        r.warnings
    );
}

#[test]
fn bad_routes_are_refused_by_name() {
    let src = data(GENERATOR);
    let h = read_kbl(&src).unwrap();
    let out = out_dir("refused").join("x.kbl");
    let mut route = SettledHarness::new();
    route.insert("Segment_999", vec![DVec3::ZERO, DVec3::X]);
    let e = export_kbl(&src, &route, &out).unwrap_err();
    println!("{e}");
    assert!(matches!(e, HarnessError::Settled { ref kbl_id, .. } if kbl_id == "Segment_999"));
    assert!(e.to_string().contains("has no Segment with this id"));

    // Every segment reversed: the ends disagree at the nodes.
    let mut route = SettledHarness::from_harness(&h, 10e-3);
    let reversed: Vec<(String, Vec<DVec3>)> = route
        .iter()
        .map(|(id, p)| (id.to_string(), p.iter().rev().copied().collect()))
        .collect();
    for (id, p) in reversed {
        route.insert(id, p);
    }
    let e = export_kbl(&src, &route, &out).unwrap_err();
    println!("{e}");
    assert!(e.to_string().contains("must agree within 0.1 mm"), "{e}");
    assert!(!out.exists(), "nothing written on error");

    let mut route = SettledHarness::new();
    route.insert(h.segments[0].kbl_id.clone(), vec![DVec3::ZERO]);
    let e = export_kbl(&src, &route, &out).unwrap_err();
    assert!(e.to_string().contains("at least two"), "{e}");
}
