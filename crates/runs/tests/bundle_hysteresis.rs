//! Bundles with hysteresis (SPEC X2): a 200 mm bundle whose twist rubs (Dahl friction)
//! twisted by 90° at its end and let go keeps a set where the friction holds the twist's
//! spring, G J τ + z(τ) = 0 on the unloading branch — solved here in closed form by
//! bisection — while its elastic twin springs back to straight; bad friction data are
//! refused with the field named.

use pliant_scene::load_scene_str;
use pliant_testkit::scenes::WEIGHTLESS_MM;

/// A 200 mm bundle of `wires` (whose `hysteresis` is the TOML given, or none), fixed at
/// its start, its end turned about the axis by `angle_deg` over 1 s and let go.
fn scene(hysteresis: &str, angle_deg: f64) -> String {
    format!(
        r#"{WEIGHTLESS_MM}solver = "static"

[materials.wires]
e_tension_mpa = 50
e_compression_mpa = 50
poisson = 0.4
density_kg_m3 = 2000
{hysteresis}

[[hoses]]
name = "bundle"
material = "wires"
section = {{ d_inner = 0, d_outer = 10 }}
elements = 8
start = [0, 0, 0]
path = [{{ line = {{ to = [200, 0, 0] }} }}]

[[timeline]]
action = "fix"
hose = "bundle"
node = 0

[[timeline]]
action = "move"
hose = "bundle"
node = -1
rotate = {{ axis = [1, 0, 0], angle_deg = {angle_deg} }}
duration_s = 1

[[timeline]]
action = "release"
hose = "bundle"
node = -1

[[timeline]]
action = "run"
duration_s = 0.1
"#
    )
}

const FRICTION: &str = "hysteresis = { bending_moment_n_m = 0.01, bending_curvature_1_m = 1, \
                        torsion_moment_n_m = 0.02, torsion_curvature_1_m = 0.5 }";

/// The end's twist at the end of the timeline \[rad\].
fn end_twist(text: &str) -> f64 {
    let scene = load_scene_str(text, "bundle.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    let q = cell.state().q[cell.state().q.len() - 1];
    2.0 * q.x.atan2(q.w)
}

#[test]
fn a_twisted_bundle_let_go_keeps_the_set_its_friction_holds() {
    let length = 0.2;
    let turned = 90f64.to_radians();
    // G J of the solid 10 mm rod, E = 50 MPa, ν = 0.4
    let g = 50e6 / (2.0 * 1.4);
    let gj = g * std::f64::consts::PI * 0.01f64.powi(4) / 32.0;
    let (m, ks) = (0.02, 0.5);
    // loading branch from rest to τ₁, then the unloading branch from (τ₁, z₁)
    let t1 = turned / length;
    let z1 = m * (1.0 - (-t1 / ks).exp());
    let unloading = |t: f64| -m - (-m - z1) * ((t - t1) / ks).exp();
    let (mut lo, mut hi) = (0.0, t1);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if gj * mid + unloading(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let set = 0.5 * (lo + hi) * length;
    assert!(set > 0.1, "the friction holds a visible set: {set} rad");

    let elastic = end_twist(&scene("", 90.0));
    let rubbing = end_twist(&scene(FRICTION, 90.0));
    assert!(
        elastic.abs() < 1e-6,
        "the elastic twin springs back: {elastic}"
    );
    assert!(
        (rubbing - set).abs() < 1e-6 * turned,
        "set {rubbing} rad vs Dahl's {set} rad"
    );
}

#[test]
fn bad_friction_data_are_refused_with_the_field_named() {
    for (friction, field) in [
        (
            "hysteresis = { bending_moment_n_m = -1, bending_curvature_1_m = 1 }",
            "materials.wires.hysteresis.bending_moment_n_m",
        ),
        (
            "hysteresis = { bending_moment_n_m = 0.01, bending_curvature_1_m = 0 }",
            "materials.wires.hysteresis.bending_curvature_1_m",
        ),
        (
            "hysteresis = { bending_moment_n_m = 0.01, bending_curvature_1_m = 1, \
             torsion_moment_n_m = 0.01 }",
            "materials.wires.hysteresis.torsion_curvature_1_m",
        ),
        (
            "yield_stress_mpa = 200\nhysteresis = { bending_moment_n_m = 0.01, \
             bending_curvature_1_m = 1 }",
            "materials.wires.hysteresis",
        ),
    ] {
        let err = match load_scene_str(&scene(friction, 90.0), "bundle.toml") {
            Ok(_) => panic!("{friction} was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(err.contains(field), "{friction}: {err}");
    }
}
