//! A junction body's own centre of mass and inertia (`[[junctions]] body`): read in the
//! scene's length unit, and every bad value refused with the field and the reason.

use glam::{DMat3, DVec3};
use pliant_scene::{load_scene_str, SceneError};
use pliant_testkit::scenes::{HEAD_MM, TEE_MM};

fn load(body: &str) -> Result<pliant_scene::LoadedScene, SceneError> {
    let text = format!("{HEAD_MM}{TEE_MM}body = {body}\n");
    load_scene_str(&text, "junction_body.toml")
}

fn error(body: &str) -> String {
    match load(body) {
        Ok(_) => panic!("{body} was accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_body_without_centre_or_inertia_is_lumped_as_before() {
    let scene = load("{ mass_kg = 0.04 }").unwrap();
    let spec = &scene.junctions[0];
    assert_eq!(spec.body_mass, 0.04);
    assert!(spec.body_centre.is_none() && spec.body_inertia.is_none());
    assert!(!spec.has_own_mass());
}

#[test]
fn centre_in_the_length_unit_and_inertia_as_written() {
    let scene = load(
        "{ mass_kg = 0.3, centre_of_mass = [210, 35, 0], inertia_kg_m2 = [[2e-4, 1e-5, 0], [1e-5, 3e-4, 0], [0, 0, 4e-4]] }",
    )
    .unwrap();
    let spec = &scene.junctions[0];
    assert!((spec.body_centre.unwrap() - DVec3::new(0.21, 0.035, 0.0)).length() < 1e-15);
    let j = spec.body_inertia.unwrap();
    assert_eq!(j.col(1), DVec3::new(1e-5, 3e-4, 0.0));
    assert_eq!(j.col(2), DVec3::new(0.0, 0.0, 4e-4));
    let principal = load("{ mass_kg = 0.3, inertia_kg_m2 = [2e-4, 3e-4, 4e-4] }").unwrap();
    assert_eq!(
        principal.junctions[0].body_inertia,
        Some(DMat3::from_diagonal(DVec3::new(2e-4, 3e-4, 4e-4)))
    );
    // the model carries the body: its mass is the hoses' and the body's, the outlets
    // take no share of it
    let model = scene.build_model().unwrap();
    let own = model.junctions[0].own;
    assert!(!own.lumped && own.mass == 0.3);
    let body = &model.bodies[model.junctions[0].body];
    let nodes: f64 = body.nodes.iter().map(|&i| model.mass[i]).sum();
    assert!((body.mass - nodes - 0.3).abs() < 1e-15);
}

#[test]
fn bad_inertia_and_mass_are_refused_naming_the_field() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "{ mass_kg = 0.3, inertia_kg_m2 = [1e-4, 1e-4, 3e-4] }",
            "junctions[0].body.inertia_kg_m2",
            "triangle inequality",
        ),
        (
            "{ mass_kg = 0.3, inertia_kg_m2 = [1e-4, 0, 1e-4] }",
            "junctions[0].body.inertia_kg_m2",
            "not positive definite",
        ),
        (
            "{ mass_kg = 0.3, inertia_kg_m2 = [[1e-4, 2e-5, 0], [0, 1e-4, 0], [0, 0, 1e-4]] }",
            "junctions[0].body.inertia_kg_m2",
            "not symmetric",
        ),
        (
            "{ mass_kg = 0.3, inertia_kg_m2 = [nan, 1e-4, 1e-4] }",
            "junctions[0].body.inertia_kg_m2",
            "non-finite",
        ),
        (
            "{ mass_kg = 0, centre_of_mass = [210, 0, 0] }",
            "junctions[0].body.mass_kg",
            "needs a mass > 0 kg",
        ),
        (
            "{ mass_kg = 0.3, centre_of_mass = [210, inf, 0] }",
            "junctions[0].body.centre_of_mass[1]",
            "finite",
        ),
        (
            "{ mass_kg = 0.3, inertia_kg_m2 = [1e-4, 1e-4] }",
            "junctions[0].body.inertia_kg_m2",
            "",
        ),
    ];
    for (body, field, reason) in cases {
        let e = error(body);
        assert!(e.contains(field), "{body}: {e}");
        assert!(e.contains(reason), "{body}: {e}");
    }
}
