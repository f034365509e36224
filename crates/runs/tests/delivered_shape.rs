//! Pre-deformation (SPEC X2): a hose keeps the set of the shape it was delivered in. A
//! hose of straight stock routed along a semicircle of radius R and clamped at both ends
//! carries the pure bending moment E I / R at its clamps (no force); a hose delivered
//! as a flat coil of radius R_c and clamped straight carries E I / R_c; routed and
//! delivered alike, it carries nothing. Bad delivered shapes are refused with the field.

use glam::DVec3;
use pliant_scene::load_scene_str;
use pliant_testkit::scenes::{EPDM, WEIGHTLESS_MM};

/// E I of the 16/10 mm tube of E = 8 MPa \[N·m²\].
const EI: f64 = 8e6 * std::f64::consts::PI * (6.5536e-8 - 1e-8) / 64.0;

/// A 400 mm hose delivered as `delivered` (TOML, or none), routed along `path`, clamped
/// at both ends as routed, under the static solver.
fn scene(delivered: &str, start: &str, path: &str) -> String {
    format!(
        r#"{WEIGHTLESS_MM}solver = "static"
{EPDM}
[[hoses]]
name = "hose"
material = "epdm"
section = {{ d_inner = 10, d_outer = 16 }}
elements = 80
start = {start}
path = {path}
normal_hint = [0, 0, 1]
{delivered}

[[timeline]]
action = "fix"
hose = "hose"
node = 0

[[timeline]]
action = "fix"
hose = "hose"
node = -1

[[timeline]]
action = "run"
duration_s = 0.05
"#
    )
}

/// The semicircle of radius 400/π mm in the x–y plane (length 400 mm).
fn semicircle(delivered: &str) -> String {
    let r = 400.0 / std::f64::consts::PI;
    scene(
        delivered,
        "[0, 0, 0]",
        &format!(
            "[{{ arc = {{ via = [{r}, {r}, 0], to = [{}, 0, 0] }} }}]",
            2.0 * r
        ),
    )
}

fn straight(delivered: &str) -> String {
    scene(delivered, "[0, 0, 0]", "[{ line = { to = [400, 0, 0] } }]")
}

/// Reaction force and moment at the start and the end clamp.
fn reactions(text: &str) -> [(DVec3, DVec3); 2] {
    let scene = load_scene_str(text, "delivered.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    let s = cell.state();
    let last = s.x.len() - 1;
    [
        (s.reaction_force[0], s.reaction_moment[0]),
        (s.reaction_force[last], s.reaction_moment[last]),
    ]
}

#[test]
fn straight_stock_routed_round_a_semicircle_carries_ei_over_r() {
    let r = 0.4 / std::f64::consts::PI;
    for (f, m) in reactions(&semicircle("")) {
        assert!(f.length() < 1e-9 && m.length() < 1e-9, "as routed: {f} {m}");
    }
    for (f, m) in reactions(&semicircle("delivered = \"straight\"")) {
        // pure bending about z: E I / R, no force
        assert!(
            (m.length() - EI / r).abs() < 1e-4 * EI / r,
            "moment {m} vs {}",
            EI / r
        );
        assert!(
            m.normalize().z.abs() > 1.0 - 1e-9,
            "about the plane's normal: {m}"
        );
        assert!(f.length() < 1e-4 * EI / r / r, "force {f}");
    }
}

#[test]
fn a_coiled_hose_clamped_straight_carries_ei_over_the_coil_radius() {
    let rc = 0.15;
    let coil = "delivered = { coil = { radius = 150 } }";
    for (f, m) in reactions(&straight(coil)) {
        assert!(
            (m.length() - EI / rc).abs() < 1e-4 * EI / rc,
            "moment {m} vs {}",
            EI / rc
        );
        assert!(m.normalize().x.abs() < 1e-6, "bending, not twist: {m}");
        // no axial force: the element's arch strain is measured from its rest shape's
        // (from the rest chord, straightening would leave a strain (κ l)²/12, 0.09 N)
        let ea = 8e6 * std::f64::consts::PI * (0.016f64.powi(2) - 0.010f64.powi(2)) / 4.0;
        let kl = 0.005 / rc;
        assert!(f.length() < 1e-3 * ea * kl * kl / 12.0, "force {f}");
    }
}

#[test]
fn bad_delivered_shapes_are_refused_with_the_field() {
    for (delivered, field, says) in [
        (
            "delivered = { coil = { radius = -5 } }",
            "hoses[0].delivered.coil.radius",
            "",
        ),
        (
            "delivered = { coil = { radius = 10 } }",
            "hoses[0].delivered",
            "per element",
        ),
        (
            "delivered = { path = [{ line = { to = [410, 0, 0] } }] }",
            "hoses[0].delivered.path",
            "within 1 %",
        ),
    ] {
        let err = match load_scene_str(&straight(delivered), "delivered.toml") {
            Ok(_) => panic!("{delivered} was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(
            err.contains(field) && err.contains(says),
            "{delivered}: {err}"
        );
    }
}
