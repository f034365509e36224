//! Hose routes from CAD: a curve of a STEP file (by name or index) and a CSV point list;
//! the built hose follows the curve within the stated tolerance: its nodes lie on the
//! polyline through the route's points, which for a STEP curve lies within the sampling
//! tolerance (default 0.01 mm) of the CAD curve.

use glam::DVec3;
use pliant_runs::cad_converter::find_python;
use pliant_runs::load::load_scene_str_in;
use pliant_scene::LoadedScene;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// `tests/data/cad/route.step` (made by make_route_step.py beside it).
fn route_step() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cad/route.step")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("pliant-route-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scene(route: &str) -> String {
    format!(
        r#"format = "pliant-scene"
version = 1
length_unit = "mm"

[[hoses]]
name = "h"
material = "hose1"
element_length = 10
route = {route}
"#
    )
}

fn load(dir: &Path, route: &str) -> Result<LoadedScene, String> {
    load_scene_str_in(&scene(route), "scene.toml", dir).map_err(|e| e.to_string())
}

/// Distance of `p` \[m\] from the helix of make_route_step.py (radius 100 mm, pitch
/// 200 mm, one turn from (100, 0, 0) mm), by a fine search over its parameter.
fn helix_distance(p: DVec3) -> f64 {
    let (r, pitch) = (0.1, 0.2);
    let point = |t: f64| DVec3::new(r * t.cos(), r * t.sin(), pitch * t / (2.0 * PI));
    let mut best = (f64::INFINITY, 0.0);
    for k in 0..=2000 {
        let t = 2.0 * PI * k as f64 / 2000.0;
        let d = (point(t) - p).length();
        if d < best.0 {
            best = (d, t);
        }
    }
    // refine by golden-section search around the best sample
    let (mut a, mut b) = (best.1 - 0.01, best.1 + 0.01);
    for _ in 0..60 {
        let m1 = a + 0.382 * (b - a);
        let m2 = a + 0.618 * (b - a);
        if (point(m1) - p).length() < (point(m2) - p).length() {
            b = m2;
        } else {
            a = m1;
        }
    }
    (point(0.5 * (a + b)) - p).length()
}

#[test]
fn a_step_b_spline_route_is_followed_within_tolerance() {
    if let Err(e) = find_python() {
        panic!("{e}");
    }
    let d = dir("step");
    let step = route_step().display().to_string();
    let s = load(
        &d,
        &format!("{{ step = \"{step}\", curve = \"hose_route\" }}"),
    )
    .unwrap();
    let nodes = &s.world.hoses[0].nodes;
    // one helix turn: length 2π·sqrt(r² + (pitch/2π)²) = 0.6627 m
    let expected = 2.0 * PI * (0.1f64.powi(2) + (0.2 / (2.0 * PI)).powi(2)).sqrt();
    assert!(
        (s.hoses[0].length - expected).abs() < 1e-4,
        "{}",
        s.hoses[0].length
    );
    assert!(nodes.len() > 60);
    // the stated tolerance: 0.01 mm sampling of the B-spline, which itself
    // interpolates the helix (73 points) to better than 0.01 mm
    let worst = nodes.iter().map(|&p| helix_distance(p)).fold(0.0, f64::max);
    assert!(worst < 0.02e-3, "a node lies {worst} m from the helix");
    assert!((nodes[0] - DVec3::new(0.1, 0.0, 0.0)).length() < 1e-9);
}

#[test]
fn a_step_polyline_route_by_index_and_bad_picks() {
    if let Err(e) = find_python() {
        panic!("{e}");
    }
    let d = dir("poly");
    let step = route_step().display().to_string();
    let s = load(&d, &format!("{{ step = \"{step}\", index = 1 }}")).unwrap();
    assert!((s.hoses[0].length - 0.3).abs() < 1e-9);
    // every node on one of the three legs (x=0.1 after the first, y=0.1 after the second)
    for p in &s.world.hoses[0].nodes {
        let on_leg = (p.y.abs() < 1e-9 && p.z.abs() < 1e-9)
            || ((p.x - 0.1).abs() < 1e-9 && p.z.abs() < 1e-9)
            || ((p.x - 0.1).abs() < 1e-9 && (p.y - 0.1).abs() < 1e-9);
        assert!(on_leg, "{p}");
    }
    let e = load(&d, &format!("{{ step = \"{step}\", curve = \"nope\" }}")).unwrap_err();
    assert!(
        e.contains("hoses[0].route.step") && e.contains("hose_route") && e.contains("guide"),
        "{e}"
    );
    let e = load(&d, &format!("{{ step = \"{step}\", index = 7 }}")).unwrap_err();
    assert!(e.contains("out of range") && e.contains("2 curves"), "{e}");
    let e = load(
        &d,
        &format!("{{ step = \"{step}\", curve = \"guide\", index = 1 }}"),
    )
    .unwrap_err();
    assert!(e.contains("hoses[0].route.curve"), "{e}");
}

#[test]
fn a_csv_route_in_inches_is_followed() {
    let d = dir("csv");
    // a quarter circle of radius 8 in (203.2 mm) in the xy plane, every 1°, in inches
    let mut text = String::from("x [in], y [in], z [in]\n");
    for k in 0..=90 {
        let a = (k as f64).to_radians();
        text += &format!("{}, {}, 0\n", 8.0 * a.cos(), 8.0 * a.sin());
    }
    std::fs::write(d.join("route.csv"), text).unwrap();
    let s = load(&d, "{ csv = \"route.csv\" }").unwrap();
    let r = 8.0 * 0.0254;
    // nodes on the polyline through the points: within its sagitta r(1 − cos 0.5°)
    // of the circle (0.0077 mm)
    let sagitta = r * (1.0 - 0.5f64.to_radians().cos());
    for p in &s.world.hoses[0].nodes {
        let d = (p.truncate().length() - r).abs();
        assert!(d <= sagitta * 1.0001 && p.z.abs() < 1e-12, "{p}: {d}");
    }
    assert!((s.hoses[0].length - r * PI / 2.0).abs() < 1e-4);
    // the unit can be given instead of a header
    std::fs::write(d.join("mm.csv"), "0,0,0\n100,0,0\n100,50,0\n").unwrap();
    let s = load(&d, "{ csv = \"mm.csv\", units = \"m\" }").unwrap();
    assert!((s.hoses[0].length - 150.0).abs() < 1e-9);
    let s = load(&d, "{ csv = \"mm.csv\", smooth = true }").unwrap();
    assert!(s.hoses[0].length > 0.15);
    // errors name the field and the line
    std::fs::write(d.join("bad.csv"), "0,0,0\n1,x,0\n").unwrap();
    let e = load(&d, "{ csv = \"bad.csv\" }").unwrap_err();
    assert!(
        e.contains("hoses[0].route.csv") && e.contains("line 2"),
        "{e}"
    );
    let e = load(&d, "{ csv = \"mm.csv\", units = \"furlong\" }").unwrap_err();
    assert!(e.contains("hoses[0].route.units"), "{e}");
    let e = load(&d, "{ csv = \"mm.csv\", curve = \"a\" }").unwrap_err();
    assert!(e.contains("hoses[0].route.curve"), "{e}");
    std::fs::write(d.join("one.csv"), "1,2,3\n1,2,3\n").unwrap();
    let e = load(&d, "{ csv = \"one.csv\" }").unwrap_err();
    assert!(e.contains("fewer than two distinct points"), "{e}");
    // route and start/path together
    let text = scene("{ csv = \"mm.csv\" }").replace("route =", "start = [0, 0, 0]\nroute =");
    let e = load_scene_str_in(&text, "scene.toml", &d)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("hoses[0].route") && e.contains("not both"),
        "{e}"
    );
}
