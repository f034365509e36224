//! The report's pictures draw a moving part where it was at their instant, not where the
//! scene placed it: the worker's worst posture and the swept envelopes (the scene
//! pictures at the worst bend: `crates/cli/tests/motion_examples.rs`). Compared on the
//! outlines' projected corners, not on pixels.

use pliant_assembly::report::part_outline::{PartOutline, View};
use pliant_assembly::report::Drawing;
use pliant_core::SolverKind;
use pliant_scene::{load_scene_file, load_scene_str};
use pliant_testkit::scene_text::{box_part, solver, worker, SceneText};
use pliant_testkit::scenes::held_hose;
use std::path::Path;

/// Asserts that every corner of `drawn` (seen from above) is a corner of `rest` turned by
/// `theta` about the z axis through `pivot` (x, y), to `tol` \[m\].
fn turned_about_z(drawn: &PartOutline, rest: &PartOutline, theta: f64, pivot: [f64; 2], tol: f64) {
    assert_eq!(
        View::all()[0].up,
        glam::DVec3::Y,
        "the first view is from above"
    );
    let (c, s) = (theta.cos(), theta.sin());
    let turned: Vec<[f64; 2]> = rest.hulls[0]
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - pivot[0], p[1] - pivot[1]);
            [pivot[0] + c * x - s * y, pivot[1] + s * x + c * y]
        })
        .collect();
    let drawn = &drawn.hulls[0];
    assert_eq!(drawn.len(), turned.len(), "{drawn:?} vs {turned:?}");
    for p in drawn {
        let nearest = turned
            .iter()
            .map(|q| (p[0] - q[0]).hypot(p[1] - q[1]))
            .fold(f64::INFINITY, f64::min);
        assert!(nearest < tol, "{p:?} not in {turned:?}");
    }
}

/// A worker grabs a hose and lowers it while a door 2 m behind him opens about its
/// hinge (z through (−2, 0), linearly 20° → 80° over 0.3 s): the picture of his worst
/// posture draws the door at the angle of that instant, from the keyframes.
#[test]
fn the_worst_posture_picture_draws_the_door_at_its_angle_then() {
    let door = box_part("door", [800.0, 30.0, 600.0], [-1600.0, 15.0, 300.0]).inline(
        "motion",
        r#"{ kind = "hinge", axis = [0, 0, 1], point = [-2000, 0, 0], angle_deg = { times_s = [0, 0.3], values = [20, 80], smooth = false } }"#,
    );
    let base = SceneText::mm()
        .with(solver("static"))
        .with(worker("male").point("facing", [1.0, 0.0, 0.0]))
        .with(door);
    let (start, end) = ([100.0, -200.0, 1000.0], [500.0, -200.0, 1000.0]);
    let text: String = held_hose(base, "h", start, end, [0.0, 0.0, -20.0], 0.3).into();
    let scene = load_scene_str(&text, "worker_door.toml").unwrap_or_else(|e| panic!("{e}"));
    let (cell, run) =
        pliant_runs::run_with(&scene, Some(SolverKind::Static)).unwrap_or_else(|e| panic!("{e}"));
    let worker = run.worker.as_ref().expect("the worker's account");
    let time = worker.worst_rula.expect("a worst posture").time;
    let drawing = Drawing::of(cell.model(), &run);
    let posed = drawing
        .worker_parts
        .as_ref()
        .expect("parts at the worst posture");
    // the hinge's angle then, from the keyframes (linear, held after 0.3 s)
    let theta = (20.0 + 60.0 * (time / 0.3).clamp(0.0, 1.0)).to_radians();
    eprintln!(
        "worst posture at t = {time:.3} s, door at {:.1}°",
        theta.to_degrees()
    );
    turned_about_z(&posed[0], &drawing.parts[0], theta, [-2.0, 0.0], 1e-9);
    // not where the scene placed it: its far edge (x = −1.2 m closed) has swung round
    let far = posed[0].hulls[0]
        .iter()
        .map(|p| p[1])
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(far > 0.25, "{:?}", posed[0].hulls[0]);
}

/// The envelope picture draws the parts where they were at the sweep's worst bend, not
/// where the scene placed them: seen from above, the door's outline then is its outline
/// at rest turned about the hinge (the z axis through the origin) by the door angle the
/// sweep recorded at that instant; the pillar, which stands still, is drawn at rest.
#[test]
fn the_envelope_picture_draws_the_door_at_the_angle_of_the_worst_bend() {
    let scene = load_scene_file(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/door_hinge.toml"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let (cell, run) =
        pliant_runs::run_with(&scene, Some(SolverKind::Static)).unwrap_or_else(|e| panic!("{e}"));
    let drawing = Drawing::of(cell.model(), &run);
    let sweep = run.checks.sweep.as_ref().unwrap();
    let (time, posed) = drawing
        .envelope_parts
        .as_ref()
        .expect("posed envelope parts");
    let theta = sweep.coordinate_at(*time).unwrap();
    eprintln!(
        "envelope picture at t = {time:.2} s, door angle {:.1}°",
        theta.to_degrees()
    );
    // the door bends the hose tightest wide open (70°)
    assert!(theta.to_degrees() > 60.0, "{}", theta.to_degrees());
    let (door, pillar) = (1, 0);
    // the angle is the row's, recorded to f64: the corners agree to a nanometre
    turned_about_z(&posed[door], &drawing.parts[door], theta, [0.0, 0.0], 1e-9);
    let drawn = &posed[door].hulls[0];
    // where it differs: the door's far edge (x = 820 mm closed) is near y = 0.8 m now
    let reach = drawn.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
    assert!(reach > 0.7, "{drawn:?}");
    let rest_reach = drawing.parts[door].hulls[0]
        .iter()
        .map(|p| p[1])
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(rest_reach < 0.05, "at rest the door lies along x");
    assert_eq!(
        posed[pillar], drawing.parts[pillar],
        "the pillar stands still"
    );
}
