//! SPEC V4 in scene files: `[[stubs]] bead` loads in SI onto the stub's press fit, and a
//! bad bead is an error naming the field.

use pliant_core::Model;
use pliant_scene::load_scene_str;

fn scene(bead: &str) -> String {
    format!(
        r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[[hoses]]
name = "h"
material = "hose3"
start = [0, 0, 0]
path = [{{ line = {{ to = [300, 0, 0] }} }}]

[[stubs]]
name = "s"
origin = [320, 0, 0]
axis = [1, 0, 0]
length = 30
diameter = 28
{bead}
"#
    )
}

#[test]
fn a_bead_loads_onto_the_press_fit() {
    let s = load_scene_str(
        &scene(
            "bead = { at = 8, height = 1.5, width = 3, entry_angle_deg = 20, back_angle_deg = 60 }",
        ),
        "bead.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let b = s.stubs[0].profile[0];
    assert_eq!((b.at, b.height, b.width), (0.008, 0.0015, 0.003));
    assert!((b.back_angle - 60f64.to_radians()).abs() < 1e-15);
    let model = Model::build(&s.world).unwrap();
    let (stubs, _) = s.fastener_sites(&model).unwrap();
    assert_eq!(stubs[0].fit.press_fit().unwrap().bead(), Some(&b));
}

#[test]
fn bad_beads_name_the_field() {
    for (bead, field) in [
        ("bead = { at = -1, height = 1.5, width = 3, entry_angle_deg = 20, back_angle_deg = 60 }", "stubs[0].bead.at"),
        ("bead = { at = 8, height = 0, width = 3, entry_angle_deg = 20, back_angle_deg = 60 }", "stubs[0].bead.height"),
        ("bead = { at = 8, height = 1.5, width = 3, entry_angle_deg = 20, back_angle_deg = 90 }", "stubs[0].bead"),
        ("bead = { at = 28, height = 1.5, width = 3, entry_angle_deg = 20, back_angle_deg = 60 }", "stubs[0].bead"),
        ("bead = { at = 8, height = 1.5, width = 3, entry = 20, back_angle_deg = 60 }", "stubs[0].bead"),
    ] {
        let err = load_scene_str(&scene(bead), "bad.toml").unwrap_err().to_string();
        assert!(err.contains(field), "`{err}` lacks `{field}`");
    }
}

const BARB: &str = "height = 1, width = 1, entry_angle_deg = 15, back_angle_deg = 55";

#[test]
fn a_profile_of_barbs_loads_in_order() {
    let s = load_scene_str(
        &scene(&format!(
            "profile = [{{ at = 4, {BARB} }}, {{ at = 13, {BARB} }}]"
        )),
        "barbs.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let p = &s.stubs[0].profile;
    assert_eq!(p.len(), 2);
    assert!((p[0].at - 0.004).abs() < 1e-15 && (p[1].at - 0.013).abs() < 1e-15);
    let model = Model::build(&s.world).unwrap();
    let (stubs, _) = s.fastener_sites(&model).unwrap();
    assert_eq!(
        stubs[0]
            .fit
            .press_fit()
            .unwrap()
            .beads()
            .copied()
            .collect::<Vec<_>>(),
        *p
    );
}

#[test]
fn bad_profiles_name_the_field() {
    let bead =
        "bead = { at = 8, height = 1.5, width = 3, entry_angle_deg = 20, back_angle_deg = 60 }";
    for (entry, field) in [
        (
            format!("profile = [{{ at = 4, {BARB} }}, {{ at = 5, {BARB} }}]"),
            "stubs[0].profile[1].at",
        ),
        (
            format!("profile = [{{ at = 4, {BARB} }}, {{ at = 13, height = -1, width = 1, entry_angle_deg = 15, back_angle_deg = 55 }}]"),
            "stubs[0].profile[1].height",
        ),
        (
            format!("profile = [{{ at = 29, {BARB} }}]"),
            "stubs[0].profile[0]",
        ),
        (
            format!("{bead}\nprofile = [{{ at = 20, {BARB} }}]"),
            "stubs[0].bead",
        ),
        (
            format!(
                "profile = [{}]",
                (0..9)
                    .map(|k| format!("{{ at = {}, {BARB} }}", 3 * k))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            "stubs[0].profile",
        ),
    ] {
        let err = load_scene_str(&scene(&entry), "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(field), "`{err}` lacks `{field}`");
    }
}
