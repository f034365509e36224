//! A static step that ends out of balance
//! makes the live snapshot's verdict uncertain — the flag and the reason, in the JSON the
//! viewer reads — as it does `summary.json`'s and the report's.
//!
//! A 0.5 m hose (10 elements) lies along an incline (a tilted box, μ_s = 0.5, μ_k = 0.4) under gravity.
//! At tan φ = 1.2 μ_s no equilibrium exists (the slope pulls harder than friction can
//! hold): the static solve cannot converge, and the verdict must say so. At
//! tan φ = 0.8 μ_s the hose sticks, every solve converges and the verdict stays certain
//! (the same scene, so the test can fail both ways). As the `friction_newton` validation
//! case, at the scene level. The session runs paused and advances only by `step`
//! commands; waits are for conditions, with a hang guard only.

mod static_session;

use glam::{DQuat, DVec3};
use pliant_scene::load_scene_str_in;
use pliant_server::snapshot::Snapshot;
use serde_json::json;
use std::sync::Arc;
const MU_STATIC: f64 = 0.5;
/// Hose 1's outer radius \[mm\]: the hose lies on the surface.
const RADIUS_MM: f64 = 8.0;

/// The incline's fall line and surface normal (unit vectors).
fn incline(slope: f64) -> (DVec3, DVec3) {
    let tilt = DQuat::from_axis_angle(DVec3::Y, -slope.atan());
    (tilt * DVec3::NEG_X, tilt * DVec3::Z)
}

/// The incline of slope tan φ = `slope`: a 4 m × 4 m box whose top face passes through
/// the origin, tilted about y so that it falls towards −x; the hose along the fall line.
fn scene(slope: f64) -> String {
    let phi = slope.atan();
    let (down, normal) = incline(slope);
    let centre = -normal * 50.0; // the box is 100 mm thick
    let start = down * 250.0 + normal * RADIUS_MM;
    let end = -down * 250.0 + normal * RADIUS_MM;
    let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
    format!(
        r#"
format = "pliant-scene"
version = 1
name = "a hose on an incline"
length_unit = "mm"

[[parts]]
name = "incline"
box = {{ size = [4000, 4000, 100] }}
position = {centre}
rotation = {{ axis = [0, 1, 0], angle_deg = {angle} }}
friction = {{ static = {MU_STATIC}, sliding = 0.4 }}

[[hoses]]
name = "hose"
material = "hose1"
start = {start}
path = [{{ line = {{ to = {end} }} }}]
elements = 10
"#,
        centre = v(centre),
        angle = -phi.to_degrees(),
        start = v(start),
        end = v(end),
    )
}

/// The snapshot after the first static input step on the incline of slope `slope`.
async fn first_step_on(slope: f64) -> Arc<Snapshot> {
    let text = scene(slope);
    let scene = load_scene_str_in(&text, "incline.toml", std::path::Path::new(".")).unwrap();
    let session = static_session::start(&scene);
    static_session::step(&session, 1).await
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_unconverged_static_step_makes_the_live_verdict_uncertain() {
    let snapshot = first_step_on(1.2 * MU_STATIC).await;
    assert_eq!(
        snapshot.epoch, 0,
        "no divergence, no reset: {:?}",
        snapshot.notice
    );
    assert!(snapshot.verdict.uncertain, "{:?}", snapshot.verdict);
    assert!(
        snapshot.verdict.reasons[0].contains("uncertain: the Newton solver did not reach balance"),
        "the reason comes first: {:?}",
        snapshot.verdict.reasons
    );
    let json: serde_json::Value = serde_json::from_str(snapshot.json()).unwrap();
    assert_eq!(json["verdict"]["uncertain"], true, "{}", json["verdict"]);
    // the same reason as data: the solver's doubt, with the steps it concerns
    let first = &json["verdict"]["findings"]["reasons"][0];
    assert_eq!(
        (&first["kind"], &first["doubt"]),
        (&json!("solver"), &json!("out_of_balance")),
        "{first}"
    );
    assert!(first["steps"].as_u64().is_some_and(|n| n >= 1), "{first}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_converged_static_step_leaves_the_live_verdict_certain() {
    let snapshot = first_step_on(0.8 * MU_STATIC).await;
    assert!(!snapshot.verdict.uncertain, "{:?}", snapshot.verdict);
    let json: serde_json::Value = serde_json::from_str(snapshot.json()).unwrap();
    assert_eq!(json["verdict"]["uncertain"], false, "{}", json["verdict"]);
    // the hose sticks where it lay (its middle within 0.1 mm: the friction spring's give)
    let (_, normal) = incline(0.8 * MU_STATIC);
    let mid = DVec3::from_array(snapshot.hoses[0].positions[5]);
    let moved = (mid - normal * RADIUS_MM * 1e-3).length();
    assert!(moved < 1e-4, "the hose moved {moved} m");
}
