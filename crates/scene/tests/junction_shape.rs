//! A junction body's shape (`[[junctions]] body = { …, part = "NAME" }`): the part rides on
//! the body, the body's own hose nodes inside it ignore it, the Newton solvers refuse it,
//! and every bad part is refused naming the field and the reason.

use pliant_core::integrators::{ImplicitOptions, ImplicitSolver, StaticSolver};
use pliant_scene::{load_scene_str, LoadedScene, SceneError};
use pliant_testkit::scenes::{HEAD_MM, TEE_MM};

/// A 20 × 10 × 10 mm box between the tee's outlets (x = 200 … 220 mm), and more parts.
const BOX: &str = r#"
[[parts]]
name = "tee_box"
box = { size = [20, 10, 10] }
position = [210, 0, 0]
"#;

fn load(body: &str, parts: &str) -> Result<LoadedScene, SceneError> {
    let text = format!("{HEAD_MM}{TEE_MM}body = {body}\n{parts}");
    load_scene_str(&text, "junction_shape.toml")
}

fn error(body: &str, parts: &str) -> String {
    match load(body, parts) {
        Ok(_) => panic!("{body} with {parts} was accepted"),
        Err(e) => e.to_string(),
    }
}

const SHAPED: &str = r#"{ mass_kg = 0.02, centre_of_mass = [210, 0, 0], inertia_kg_m2 = [3e-7, 8e-7, 8e-7], part = "tee_box" }"#;

#[test]
fn the_shape_rides_on_the_body_and_its_own_outlets_ignore_it() {
    let scene = load(SHAPED, BOX).unwrap();
    assert_eq!(scene.junctions[0].shape, Some(0));
    let model = scene.build_model().unwrap();
    assert_eq!(model.junctions[0].shape, Some(0));
    assert!(model.part_moves(0), "the shape is a moving part");
    assert!(model.junction_shapes.any());
    let outlets = model.junctions[0].nodes.clone();
    for &i in &outlets {
        assert!(model.junction_shapes.excludes_node(0, i), "outlet node {i}");
    }
    // hose a's node before its outlet lies 50 mm from the box: it touches the shape
    let before = outlets[0] - 1;
    assert!(!model.junction_shapes.excludes_node(0, before));
    assert!(!model.junction_shapes.excludes_beam(0, before - 1, before));
    // at rest the shape is where the scene put it
    let state = pliant_core::State::at_rest(&model);
    let pose = model.part_placement(&state, 0, 0.0).pose;
    assert!(pose.translation.length() < 1e-12, "{pose:?}");
    assert!(pose.rotation.abs_diff_eq(glam::DQuat::IDENTITY, 1e-12));
}

#[test]
fn the_newton_solvers_refuse_a_shape_naming_the_junction_and_the_part() {
    let model = load(SHAPED, BOX).unwrap().build_model().unwrap();
    for message in [
        StaticSolver::new(&model).err().map(|e| e.to_string()),
        ImplicitSolver::new(&model, ImplicitOptions::default())
            .err()
            .map(|e| e.to_string()),
    ] {
        let message = message.expect("refused");
        assert!(
            message.contains("junction 'tee'")
                && message.contains("part 'tee_box'")
                && message.contains("explicit"),
            "{message}"
        );
    }
}

#[test]
fn bad_shapes_are_refused_naming_the_field() {
    let moving = format!(
        "{BOX}motion = {{ kind = \"slide\", direction = [1, 0, 0], distance = {{ times_s = [0, 1], values = [0, 10] }} }}\n"
    );
    let carried = format!("{BOX}parent = \"frame\"\n[[parts]]\nname = \"frame\"\nbox = {{ size = [10, 10, 10] }}\nposition = [0, 100, 0]\n");
    let carrier = format!("{BOX}\n[[parts]]\nname = \"lid\"\nbox = {{ size = [10, 10, 10] }}\nposition = [210, 0, 20]\nparent = \"tee_box\"\n");
    let cases: &[(&str, String, &str)] = &[
        (
            r#"{ part = "nothing" }"#,
            BOX.to_string(),
            "no part of this name",
        ),
        (r#"{ part = "tee_box" }"#, moving, "has a `motion`"),
        (r#"{ part = "tee_box" }"#, carried, "has a `parent`"),
        (
            r#"{ part = "tee_box" }"#,
            carrier,
            "part \"lid\" has it as its `parent`",
        ),
    ];
    for (body, parts, reason) in cases {
        let e = error(body, parts);
        assert!(e.contains("junctions[0].body.part"), "{e}");
        assert!(e.contains(reason), "{reason}: {e}");
    }
}
