//! The timeline's `grab` by hose node, `align_hand` and the clips' `by_hand` (what
//! `install.toml` of an imported wire harness uses): they load into the assembly layer's
//! actions in SI, every mistake names the field and the reason, and they act as documented
//! when run — a hand takes a hose end wherever it hangs and turns it onto a direction, a
//! `by_hand` clip the hose is drawn through is not seated until a hand presses it in.

use glam::DVec3;
use pliant_assembly::{Action, FastenerState, MovePath, NodeRef};
use pliant_scene::load_scene_str;

const HEAD: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[simulation]
solver = "static"

[[hoses]]
name = "a"
material = "hose3"
elements = 10
start = [0, 0, 0]
path = [{ line = { to = [500, 0, 0] } }]
"#;

fn load(timeline: &str) -> Result<Vec<Action>, String> {
    load_scene_str(&format!("{HEAD}\n{timeline}"), "scene.toml")
        .map(|s| s.timeline.actions)
        .map_err(|e| e.to_string())
}

#[test]
fn a_grab_by_node_and_an_aligned_move_load_in_si() {
    let actions = load(
        r#"
[[timeline]]
action = "grab"
hand = 1
hose = "a"
node = -1

[[timeline]]
action = "align_hand"
hand = 1
direction = [0, 0, 2]
to = [500, 0, 100]
duration_s = 0.5

[[timeline]]
action = "align_hand"
hand = 1
direction = [1, 0, 0]
duration_s = 0.2
"#,
    )
    .unwrap();
    assert!(matches!(
        actions[0],
        Action::GrabNode {
            hand: 1,
            node: NodeRef { hose: 0, node: 10 },
            ..
        }
    ));
    match &actions[1] {
        Action::AlignHand {
            hand: 1,
            direction,
            path: Some(MovePath::To(points)),
            duration,
        } => {
            assert_eq!(*direction, DVec3::Z);
            assert!((points[0] - DVec3::new(0.5, 0.0, 0.1)).length() < 1e-12);
            assert_eq!(*duration, 0.5);
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(actions[2], Action::AlignHand { path: None, .. }));
}

#[test]
fn mistakes_name_the_field() {
    let grab = |fields: &str| {
        load(&format!(
            "[[timeline]]\naction = \"grab\"\nhand = 0\n{fields}"
        ))
    };
    let e = grab("at = [0, 0, 0]\nhose = \"a\"\nnode = 0").unwrap_err();
    assert!(
        e.contains("timeline[0].at") && e.contains("not both"),
        "{e}"
    );
    let e = grab("hose = \"a\"").unwrap_err();
    assert!(e.contains("needs `node` too"), "{e}");
    let e = grab("node = 3").unwrap_err();
    assert!(e.contains("needs `hose` too"), "{e}");
    let e = grab("").unwrap_err();
    assert!(
        e.contains("timeline[0].at: missing field `at`: a grab needs `at`, or `hose` and `node`"),
        "{e}"
    );
    let e = grab("hose = \"b\"\nnode = 0").unwrap_err();
    assert!(
        e.contains("timeline[0].hose") && e.contains("unknown hose"),
        "{e}"
    );
    let e = grab("hose = \"a\"\nnode = 11").unwrap_err();
    assert!(
        e.contains("timeline[0].node = 11") && e.contains("out of range"),
        "{e}"
    );
    let align = |fields: &str| {
        load(&format!(
            "[[timeline]]\naction = \"grab\"\nhand = 0\nhose = \"a\"\nnode = 0\n\n[[timeline]]\naction = \"align_hand\"\nhand = 0\n{fields}"
        ))
    };
    let e = align("direction = [0, 0, 0]\nduration_s = 1").unwrap_err();
    assert!(
        e.contains("timeline[1].direction") && e.contains("zero vector"),
        "{e}"
    );
    let e = align("direction = [1, 0, 0]\nduration_s = 0").unwrap_err();
    assert!(e.contains("timeline[1].duration_s"), "{e}");
    let e =
        align("direction = [1, 0, 0]\nduration_s = 1\nto = [0, 0, 0]\nby = [0, 0, 0]").unwrap_err();
    assert!(e.contains("not both"), "{e}");
    // a hand that holds nothing cannot turn
    let e = load(
        "[[timeline]]\naction = \"align_hand\"\nhand = 2\ndirection = [1, 0, 0]\nduration_s = 1",
    )
    .unwrap_err();
    assert!(
        e.contains("timeline[0].hand = 2") && e.contains("no earlier `grab` with hand = 2"),
        "{e}"
    );
}

/// A hose drawn straight through a `by_hand` clip's seat: not seated at the start (a
/// plain clip would be), the hose sags away under gravity from the end a hand holds; the
/// hand then takes the hose at the clip, brings it in front of the jaws and presses it in:
/// seated, at its snap force. The hand taking the free end by its node finds it where it
/// hangs, and turning it onto +z points its end beam up.
#[test]
fn a_by_hand_clip_takes_the_hose_only_when_pressed_in() {
    let text = format!(
        "{HEAD}
[[clips]]
name = \"c\"
hose = \"a\"
origin = [250, 0, 0]
opening = [0, 0, 1]
orientation = [1, 0, 0]
inner_diameter = 35
opening_width = 28
snap_force_n = 40
by_hand = true

[[timeline]]
action = \"fix\"
hose = \"a\"
node = 0

[[timeline]]
action = \"run\"
duration_s = 0.05

[[timeline]]
action = \"grab\"
hand = 0
hose = \"a\"
node = 5

[[timeline]]
action = \"move_hand\"
hand = 0
to = [250, 0, 30]
duration_s = 0.3

[[timeline]]
action = \"move_hand\"
hand = 0
to = [250, 0, 0]
duration_s = 0.3

[[timeline]]
action = \"release_hand\"
hand = 0

[[timeline]]
action = \"grab\"
hand = 1
hose = \"a\"
node = -1

[[timeline]]
action = \"align_hand\"
hand = 1
direction = [0, 0, 1]
duration_s = 0.3
"
    );
    let scene = load_scene_str(&text, "scene.toml").unwrap();
    let (cell, summary) = pliant_runs::run_with(&scene, None).unwrap();
    let clip = summary
        .fasteners
        .iter()
        .find(|f| f.name == "c")
        .expect("the clip's report");
    assert_eq!(clip.final_state, FastenerState::Seated);
    assert!((clip.max_force / 40.0 - 1.0).abs() < 0.05, "{clip:?}");
    // the free end hung below the route before the hand took it, and its end beam points
    // up after the turn
    let model = cell.model();
    let hose = &model.hoses[0];
    let (end, inner) = (hose.node(10), hose.node(9));
    let x = &cell.state().x;
    let axis = (x[end] - x[inner]).normalize();
    assert!(axis.dot(DVec3::Z) > 0.999, "{axis}");
}
