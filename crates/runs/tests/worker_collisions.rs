//! SPEC E1 ("against the parts (and the hoses)"): the worker's body against a
//! part that moves, where it is at each posed instant, and against a hose's tube — each
//! reported with segment, part or hose, depth and time, the depth against exact
//! geometry.
//!
//! The 50th-percentile man stands at the origin facing +x; his trunk capsule's axis is
//! the vertical x = y = 0 from hip height (0.530 H) to a trunk radius below the shoulder
//! line (0.818 H), radius 0.070 H. His right hand holds the end of a short hose in front
//! of his right hip, well within reach (the trunk stays upright, its axis exactly
//! vertical), away from everything else.

use pliant_assembly::{Stage, Verdict};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scenes::held_hose_lowered;

/// The scene: the worker, the held hose, and `extra` (parts, another hose, its fixings).
fn scene(extra: &str) -> String {
    let worker = "[worker]\npopulation = \"male\"\npercentile = 50\nposition = [0, 0, 0]\nfacing = [1, 0, 0]\n";
    held_hose_lowered(
        &format!("{worker}\n{extra}"),
        "held",
        [150.0, -300.0, 1100.0],
        [350.0, -300.0, 1100.0],
        0.5,
    )
}

fn run(text: &str) -> (pliant_assembly::Workcell, pliant_assembly::RunSummary) {
    let s = load_scene_str(text, "worker_collisions.toml").unwrap();
    pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap()
}

/// The trunk's collision.
fn trunk(w: &pliant_assembly::worker::WorkerSummary) -> &pliant_assembly::worker::BodyCollision {
    w.collisions
        .iter()
        .find(|c| c.segment == "trunk")
        .unwrap_or_else(|| panic!("{:?}", w.collisions))
}

/// A plate 20 mm thick, 200 mm wide (y), 300 mm high (z from 1000 to 1300 mm) slides
/// 500 mm towards the worker in the first 0.3 s: its front face ends at x = 50 mm, a
/// trunk radius less 50 mm into the trunk. At its start (x ≥ 550 mm) it touches nobody:
/// what is found is where the part is, not where the scene put it.
#[test]
fn a_part_sliding_into_the_trunk_is_found_where_it_is() {
    let plate = r#"
[[parts]]
name = "plate"
box = { size = [20, 200, 300] }
position = [560, 0, 1150]
motion = { kind = "slide", direction = [-1, 0, 0], distance = { times_s = [0, 0.3], values = [0, 500] } }
"#;
    let (_, run) = run(&scene(plate));
    let w = run.worker.as_ref().unwrap();
    let c = trunk(w);
    assert_eq!((c.part.as_str(), c.obstacle), ("plate", "part"));
    assert!(
        (c.depth - (w.body.radii.trunk - 0.05)).abs() < 1e-9,
        "{c:?}, trunk radius {}",
        w.body.radii.trunk
    );
    // deepest once the slide is over; first inside when the face passed the radius
    assert!(c.time >= 0.3 - 1e-9, "{c:?}");
    assert!(c.first_time > 0.0 && c.first_time < 0.3, "{c:?}");
    let v = Verdict::judge(&run, None, Stage::Final);
    let line = v
        .reasons
        .iter()
        .find(|r| r.starts_with("body collision: the 50th-percentile man's trunk is "))
        .unwrap_or_else(|| panic!("{:?}", v.reasons));
    assert!(line.contains("mm inside 'plate' at t = "), "{line}");
}

/// A second hose, fixed at both ends, runs along y at x = 80 mm, 1200 mm up, through the
/// trunk's reach: the tube overlaps the trunk capsule by the two radii less 80 mm (the
/// hose sags in the plane x = 80 mm, which keeps the distance to the vertical axis).
#[test]
fn a_hose_across_the_trunk_is_a_body_collision() {
    let across = r#"
[[hoses]]
name = "across"
material = "hose3"
elements = 20
start = [80, -400, 1200]
path = [{ line = { to = [80, 400, 1200] } }]

[[timeline]]
action = "fix"
hose = "across"
node = 0

[[timeline]]
action = "fix"
hose = "across"
node = -1
"#;
    let (cell, run) = run(&scene(across));
    let w = run.worker.as_ref().unwrap();
    let c = trunk(w);
    assert_eq!((c.part.as_str(), c.obstacle), ("across", "hose"));
    let model = cell.model();
    let hose = model.hoses.iter().find(|h| h.name == "across").unwrap();
    let tube = model.radius[hose.first_node];
    assert!(
        (c.depth - (w.body.radii.trunk + tube - 0.08)).abs() < 1e-9,
        "{c:?}, trunk radius {}, tube {tube}",
        w.body.radii.trunk
    );
    let v = Verdict::judge(&run, None, Stage::Final);
    assert!(
        v.reasons.iter().any(|r| r
            .starts_with("body collision: the 50th-percentile man's trunk is ")
            && r.contains("mm into hose 'across' at t = ")),
        "{:?}",
        v.reasons
    );
    // the held hose runs through the right hand: never a collision of the arm
    assert!(
        !w.collisions.iter().any(|c| c.part == "held"),
        "{:?}",
        w.collisions
    );
}
