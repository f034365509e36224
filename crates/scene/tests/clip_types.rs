//! Issue 11 item 5 in scene files: `[[clips]] type` (fixed | rotating | sliding |
//! cable_tie), a sliding guide's `friction`, `holding_force_n`; old clips stay fixed;
//! errors name the field.

use pliant_assembly::clip::ClipKind;
use pliant_scene::load_scene_str;

fn scene(extra: &str) -> String {
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

[[clips]]
name = "c"
origin = [150, 0, -20]
opening = [0, 0, 1]
orientation = [1, 0, 0]
opening_width = 30
inner_diameter = 36
{extra}
"#
    )
}

#[test]
fn clip_types_load_with_their_friction_and_holding_force() {
    let load = |extra: &str| {
        load_scene_str(&scene(extra), "clips.toml")
            .unwrap_or_else(|e| panic!("{extra}: {e}"))
            .clips[0]
            .spec
    };
    let old = load("snap_force_n = 40");
    assert_eq!((old.kind(), old.friction(), old.holding_force()), (ClipKind::Fixed, 0.0, None));
    assert_eq!(load("snap_force_n = 40\ntype = \"rotating\"").kind(), ClipKind::Rotating);
    let guide = load("snap_force_n = 40\ntype = \"sliding\"");
    assert_eq!((guide.kind(), guide.friction()), (ClipKind::Sliding, 0.4));
    let guide = load("snap_force_n = 40\ntype = \"sliding\"\nfriction = 0.25\nholding_force_n = 120");
    assert_eq!((guide.friction(), guide.holding_force()), (0.25, Some(120.0)));
    let tie = load("type = \"cable_tie\"");
    assert_eq!((tie.kind(), tie.snap_force()), (ClipKind::CableTie, 0.0));
}

#[test]
fn bad_clip_types_name_the_field() {
    for (extra, field) in [
        ("snap_force_n = 40\ntype = \"glued\"", "clips[0].type"),
        ("snap_force_n = 40\nfriction = 0.3", "clips[0].friction"),
        ("snap_force_n = 40\ntype = \"sliding\"\nfriction = -0.3", "clips[0].friction"),
        ("snap_force_n = 40\nholding_force_n = 0", "clips[0].holding_force_n"),
        ("type = \"rotating\"", "clips[0].snap_force_n"),
    ] {
        let err = load_scene_str(&scene(extra), "bad.toml").unwrap_err().to_string();
        assert!(err.contains(field), "`{err}` lacks `{field}`");
    }
}
