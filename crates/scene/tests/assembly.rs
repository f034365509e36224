//! Hands in the timeline (`grab`, `move_hand`, `release_hand`), `[ergonomics]`,
//! `[[stubs]]` and `[[clips]]`: they load into the assembly layer's types, in SI, and
//! every mistake gives an error naming the field and the reason.

use glam::DVec3;
use pliant_assembly::clip::ClipKind;
use pliant_assembly::ergonomics::{Duty, ErgonomicProfile, Population, PullPosture, PushPosture};
use pliant_assembly::{Action, Grip, MovePath};
use pliant_scene::{load_scene_file, load_scene_str, HoseEnd, LoadedScene};
use pliant_testkit::bad_inputs::{check_bad_inputs, BadInput};
use std::path::Path;

/// A valid scene with every new section; the cases below break one thing each.
const BASE: &str = r#"
format = "pliant-scene"
version = 1
length_unit = "mm"

[ergonomics]
posture = "crouching"
moments_decide = true
population = "men"
duty = "continuous"

[[hoses]]
name = "a"
material = "hose3"
start = [0, 0, 0]
path = [{ line = { to = [500, 0, 0] } }]

[[hoses]]
name = "b"
material = "hose1"
start = [0, 200, 0]
path = [{ line = { to = [300, 200, 0] } }]

[[stubs]]
name = "pump"
origin = [600, 0, 0]
axis = [2, 0, 0]
length = 40
diameter = 29
hose = "a"
end = "end"

[[stubs]]
name = "spare"
origin = [0, 500, 0]
axis = [0, 0, -1]
length = 30
diameter = 12
friction = { static = 0.7, sliding = 0.5 }
hose = "b"
end = "start"

[[clips]]
name = "c1"
origin = [250, 0, -30]
opening = [0, 0, 1]
orientation = [1, 0, 0.2]
opening_width = 30
inner_diameter = 36
snap_force_n = 40
hose = "a"

[[clips]]
name = "c2"
origin = [150, 200, -30]
opening = [0, 0, 3]
orientation = [1, 0, 0]
opening_width = 12
inner_diameter = 16
snap_force_n = 20
hose = "b"

[[timeline]]
action = "fix"
hose = "a"
node = 0

[[timeline]]
action = "grab"
hand = 0
at = [500, 0, 0]

[[timeline]]
action = "grab"
hand = 7
at = [300, 200, 0]

[[timeline]]
action = "move_hand"
hand = 0
to = [[550, 0, 0], [580, 0, 0]]
rotate = { axis = [0, 0, 1], angle_deg = 10 }
duration_s = 1.5

[[timeline]]
action = "move_hand"
hand = 7
by = [0, 0, -20]
duration_s = 0.5
wait = false

[[timeline]]
action = "release_hand"
hand = 0

[[timeline]]
action = "release_hand"
hand = 7

[[timeline]]
action = "settle"
"#;

fn base() -> LoadedScene {
    load_scene_str(BASE, "base.toml").unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-12
}

#[test]
fn hand_actions_load_in_si() {
    let s = base();
    let a = &s.timeline.actions;
    assert_eq!(a.len(), 8);
    match &a[1] {
        Action::Grab { hand: 0, at, .. } => assert!(close(*at, DVec3::new(0.5, 0.0, 0.0))),
        other => panic!("unexpected {other:?}"),
    }
    assert!(matches!(
        a[2],
        Action::Grab {
            hand: 7,
            grip: Grip::Firm,
            ..
        }
    ));
    match &a[3] {
        Action::MoveHand {
            hand: 0,
            path: Some(MovePath::To(p)),
            rotation: Some(r),
            duration,
            speed: None,
            spline: false,
            wait: true,
        } => {
            assert_eq!(p.len(), 2);
            assert!(close(p[1], DVec3::new(0.58, 0.0, 0.0)));
            assert_eq!(r.axis, DVec3::Z);
            assert!((r.angle - 10f64.to_radians()).abs() < 1e-15);
            assert_eq!(*duration, 1.5);
        }
        other => panic!("unexpected {other:?}"),
    }
    match &a[4] {
        Action::MoveHand {
            hand: 7,
            path: Some(MovePath::By(p)),
            rotation: None,
            wait: false,
            ..
        } => assert!(close(p[0], DVec3::new(0.0, 0.0, -0.02))),
        other => panic!("unexpected {other:?}"),
    }
    assert_eq!(a[5], Action::ReleaseHand { hand: 0 });
    assert_eq!(a[6], Action::ReleaseHand { hand: 7 });
}

#[test]
fn ergonomics_map_onto_the_profile() {
    let s = base();
    assert_eq!(
        s.ergonomics,
        ErgonomicProfile {
            push_posture: PushPosture::Crouching,
            pull_posture: PullPosture::CrouchingLever,
            moments_decide: true,
            population: Population::Men,
            duty: Duty::Continuous,
            ..Default::default()
        }
    );
    // Overrides after the posture; the same spellings as the profile's own parser.
    let text = BASE.replacen(
        "posture = \"crouching\"",
        "posture = \"Sitting\"\npush = \"standing\"\npull = \"standing-lever\"",
        1,
    );
    let s = load_scene_str(&text, "o.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.ergonomics.push_posture, PushPosture::Standing);
    assert_eq!(s.ergonomics.pull_posture, PullPosture::StandingLever);
    let parsed: ErgonomicProfile = "posture=sitting,push=standing,pull=standing-lever,moments_decide=true,population=men,duty=continuous"
        .parse()
        .unwrap();
    assert_eq!(s.ergonomics, parsed);
    // Absent: the default profile.
    let start = BASE.find("[ergonomics]").unwrap();
    let end = BASE.find("[[hoses]]").unwrap();
    let text = format!("{}{}", &BASE[..start], &BASE[end..]);
    let s = load_scene_str(&text, "d.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.ergonomics, ErgonomicProfile::default());
    // An empty table is the default too.
    let text = format!("{}[ergonomics]\n{}", &BASE[..start], &BASE[end..]);
    let s = load_scene_str(&text, "e.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.ergonomics, ErgonomicProfile::default());
}

#[test]
fn en1005_profile_and_tie_action_load() {
    use pliant_assembly::ergonomics::{En1005Action, En1005Velocity, Standard};
    let text = BASE
        .replacen(
            "duty = \"continuous\"",
            "duty = \"continuous\"\nstandard = \"EN1005-3\"\naction = \"arm_trunk_support\"\nuse = \"domestic\"\nvelocity = \"high\"\nfrequency_per_min = 1.5\naction_time_s = 4\nduration_h = 2",
            1,
        )
        .replacen(
            "action = \"fix\"\nhose = \"a\"\nnode = 0",
            "action = \"tie\"\nhose = \"a\"\nnode = -1\nto = { hose = \"b\", node = 3 }",
            1,
        );
    let s = load_scene_str(&text, "en.toml").unwrap_or_else(|e| panic!("{e}"));
    let e = &s.ergonomics;
    assert_eq!(e.standard, Standard::En1005_3);
    assert_eq!(e.en1005.action, En1005Action::ArmTrunkSupport);
    assert_eq!(e.en1005.percentile, 1.0); // domestic use
    assert_eq!(e.en1005.velocity, En1005Velocity::High);
    assert_eq!(
        (
            e.en1005.frequency_per_min,
            e.en1005.action_time_s,
            e.en1005.duration_h
        ),
        (1.5, 4.0, 2.0)
    );
    // the same profile as the command line's text gives
    let cli: ErgonomicProfile = "posture=crouching, population=men, duty=continuous, moments_decide=true, standard=en1005-3, action=arm_trunk_support, use=domestic, velocity=high, frequency_per_min=1.5, action_time_s=4, duration_h=2".parse().unwrap();
    assert_eq!(*e, cli);
    let last = s.timeline.actions.iter().find_map(|a| match a {
        Action::Tie { node, to } => Some((*node, *to)),
        _ => None,
    });
    let (node, to) = last.expect("a tie action");
    assert_eq!((node.hose, to.hose, to.node), (0, 1, 3));
    assert_eq!(node.node + 1, s.world.hoses[0].nodes.len());
}

#[test]
fn stubs_load_in_si_with_their_hose_end() {
    let s = base();
    assert_eq!(s.stubs.len(), 2);
    let pump = s.stub("pump").unwrap();
    assert!(close(pump.spec.origin(), DVec3::new(0.6, 0.0, 0.0)));
    assert_eq!(pump.spec.axis(), DVec3::X);
    assert!((pump.spec.length() - 0.04).abs() < 1e-15);
    assert!((pump.spec.diameter() - 0.029).abs() < 1e-15);
    assert_eq!(
        pump.spec.friction(pliant_assembly::stub::Friction::Static),
        0.6
    );
    assert_eq!(
        pump.spec.friction(pliant_assembly::stub::Friction::Sliding),
        0.4
    );
    assert_eq!(
        pump.hose_end,
        HoseEnd {
            hose: 0,
            at_end: true
        }
    );
    let nodes = s.world.hoses[0].nodes.len();
    assert_eq!(pump.hose_end.node(nodes), nodes - 1);
    let spare = &s.stubs[1];
    assert_eq!(spare.name, "spare");
    assert_eq!(spare.spec.axis(), -DVec3::Z);
    assert_eq!(
        spare.spec.friction(pliant_assembly::stub::Friction::Static),
        0.7
    );
    assert_eq!(
        spare.hose_end,
        HoseEnd {
            hose: 1,
            at_end: false
        }
    );
    // `end = "start"` is the first node.
    let text = BASE.replacen("end = \"end\"", "end = \"start\"", 1);
    let s = load_scene_str(&text, "s.toml").unwrap();
    assert_eq!(
        s.stubs[0].hose_end,
        HoseEnd {
            hose: 0,
            at_end: false
        }
    );
    assert_eq!(s.stubs[0].hose_end.node(9), 0);
}

#[test]
fn clips_load_in_si_with_perpendicular_orientation() {
    let s = base();
    assert_eq!(s.clips.len(), 2);
    let c1 = s.clip("c1").unwrap();
    assert!(close(c1.spec.origin(), DVec3::new(0.25, 0.0, -0.03)));
    assert_eq!(c1.spec.opening(), DVec3::Z);
    // The part of `orientation` along the opening is removed.
    assert!(close(c1.spec.orientation(), DVec3::X));
    assert!((c1.spec.opening_width() - 0.03).abs() < 1e-15);
    assert!((c1.spec.inner_diameter() - 0.036).abs() < 1e-15);
    assert_eq!(c1.spec.snap_force(), 40.0);
    assert_eq!(c1.hose, 0);
    assert_eq!(s.clips[1].hose, 1);
    // no `type`: a fixed clip, as before types existed
    assert_eq!(
        (c1.spec.kind(), c1.spec.friction(), c1.spec.holding_force()),
        (ClipKind::Fixed, 0.0, None)
    );
}

/// A grab's grip (default firm).
#[test]
fn grabs_load_their_grip() {
    for (grip, want) in [
        ("axial", Grip::Axial),
        ("ball", Grip::Ball),
        ("firm", Grip::Firm),
    ] {
        let text = BASE.replacen(
            "at = [500, 0, 0]",
            &format!("at = [500, 0, 0]\ngrip = \"{grip}\""),
            1,
        );
        let s = load_scene_str(&text, "grip.toml").unwrap_or_else(|e| panic!("{grip}: {e}"));
        assert!(
            matches!(s.timeline.actions[1], Action::Grab { grip, .. } if grip == want),
            "{grip}"
        );
    }
}

/// Clip types, a sliding guide's friction (default 0.4), the pull-out
/// force, a cable tie without snap force.
#[test]
fn clip_types_load_with_friction_and_holding_force() {
    let load = |to: &str| {
        let text = BASE.replacen("snap_force_n = 40\n", to, 1);
        load_scene_str(&text, "types.toml")
            .unwrap_or_else(|e| panic!("{to}: {e}"))
            .clips[0]
            .spec
    };
    assert_eq!(
        load("snap_force_n = 40\ntype = \"rotating\"\n").kind(),
        ClipKind::Rotating
    );
    let guide = load("snap_force_n = 40\ntype = \"sliding\"\n");
    assert_eq!((guide.kind(), guide.friction()), (ClipKind::Sliding, 0.4));
    let guide =
        load("snap_force_n = 40\ntype = \"sliding\"\nfriction = 0.25\nholding_force_n = 120\n");
    assert_eq!(
        (guide.friction(), guide.holding_force()),
        (0.25, Some(120.0))
    );
    let tie = load("type = \"cable_tie\"\n");
    assert_eq!((tie.kind(), tie.snap_force()), (ClipKind::CableTie, 0.0));
}

#[test]
fn metres_give_the_same_stubs_and_clips() {
    let mm = base();
    let text = BASE
        .replace("length_unit = \"mm\"", "length_unit = \"m\"")
        .replace("[600, 0, 0]", "[0.6, 0, 0]")
        .replace("length = 40", "length = 0.04")
        .replace("diameter = 29", "diameter = 0.029")
        .replace("[250, 0, -30]", "[0.25, 0, -0.03]")
        .replace("opening_width = 30", "opening_width = 0.03")
        .replace("inner_diameter = 36", "inner_diameter = 0.036")
        .replace("[500, 0, 0]", "[0.5, 0, 0]")
        // the spare stub and clip c2 on hose b
        .replace("[0, 500, 0]", "[0, 0.5, 0]")
        .replace("length = 30", "length = 0.03")
        .replace("diameter = 12", "diameter = 0.012")
        .replace("[150, 200, -30]", "[0.15, 0.2, -0.03]")
        .replace("opening_width = 12", "opening_width = 0.012")
        .replace("inner_diameter = 16", "inner_diameter = 0.016")
        .replace("[0, 200, 0]", "[0, 0.2, 0]")
        .replace("[300, 200, 0]", "[0.3, 0.2, 0]");
    let m = load_scene_str(&text, "m.toml").unwrap_or_else(|e| panic!("{e}"));
    let (a, b) = (&mm.stubs[0].spec, &m.stubs[0].spec);
    assert!(close(a.origin(), b.origin()));
    assert!((a.length() - b.length()).abs() < 1e-15);
    assert!((a.diameter() - b.diameter()).abs() < 1e-15);
    let (a, b) = (&mm.clips[0].spec, &m.clips[0].spec);
    assert!(close(a.origin(), b.origin()));
    assert!((a.opening_width() - b.opening_width()).abs() < 1e-15);
    assert!((a.inner_diameter() - b.inner_diameter()).abs() < 1e-15);
}

#[test]
fn scenes_without_the_new_sections_have_none() {
    let demo = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo.toml");
    let s = pliant_scene::load_scene_file(&demo).unwrap();
    assert!(s.stubs.is_empty());
    assert!(s.clips.is_empty());
    assert_eq!(s.ergonomics, ErgonomicProfile::default());
}

/// The bad inputs: each breaks one thing in [`BASE`].
const CASES: &[BadInput] = &[
    // Hands.
    BadInput { what: "hand index too large", edits: &[("hand = 7\nat", "hand = 8\nat")], field: Some("timeline[2].hand"), message: &["timeline[2].hand = 8: out of range: hands are numbered 0 … 7"] },
    BadInput { what: "negative hand index", edits: &[("hand = 0\nat", "hand = -1\nat")], field: Some("timeline[1].hand"), message: &["= -1: out of range"] },
    BadInput { what: "hand index out of range in move_hand", edits: &[("hand = 0\nto", "hand = 9\nto")], field: Some("timeline[3].hand"), message: &["= 9: out of range"] },
    BadInput { what: "hand index out of range in release_hand", edits: &[("action = \"release_hand\"\nhand = 0", "action = \"release_hand\"\nhand = 12")], field: Some("timeline[5].hand"), message: &["= 12: out of range"] },
    BadInput { what: "hand not a number", edits: &[("hand = 0\nat", "hand = \"left\"\nat")], field: Some("timeline[1].hand"), message: &["invalid type"] },
    BadInput { what: "grab at a non-finite point", edits: &[("at = [500, 0, 0]", "at = [500, nan, 0]")], field: Some("timeline[1].at[1]"), message: &["= nan mm: must be a finite number"] },
    BadInput { what: "unknown grip", edits: &[("at = [500, 0, 0]", "at = [500, 0, 0]\ngrip = \"loose\"")], field: Some("timeline[1].grip"), message: &["unknown variant `loose`"] },
    BadInput { what: "grab without at", edits: &[("at = [500, 0, 0]\n", "")], field: Some("timeline[1].at"), message: &["missing field `at`"] },
    BadInput { what: "move_hand of a hand that never grabbed", edits: &[("hand = 0\nto", "hand = 3\nto")], field: Some("timeline[3].hand"), message: &["timeline[3].hand = 3: cannot move a hand that holds nothing: no earlier `grab` with hand = 3"] },
    BadInput { what: "move_hand before the grab", edits: &[("action = \"grab\"\nhand = 7", "action = \"run\"\nduration_s = 1"), ("at = [300, 200, 0]\n", "")], field: Some("timeline[4].hand"), message: &["cannot move a hand that holds nothing", "no earlier `grab`"] },
    BadInput { what: "release_hand of a hand that never grabbed", edits: &[("action = \"release_hand\"\nhand = 0", "action = \"release_hand\"\nhand = 5")], field: Some("timeline[5].hand"), message: &["cannot release a hand that holds nothing"] },
    BadInput { what: "move_hand after release", edits: &[("action = \"release_hand\"\nhand = 7", "action = \"move_hand\"\nhand = 0\nby = [1, 0, 0]\nduration_s = 1")], field: Some("timeline[6].hand"), message: &["timeline[6].hand = 0: cannot move a hand that holds nothing: it let go at timeline[5] and has not grabbed since"] },
    BadInput { what: "release_hand twice", edits: &[("action = \"release_hand\"\nhand = 7", "action = \"release_hand\"\nhand = 0")], field: Some("timeline[6].hand"), message: &["cannot release a hand that holds nothing: it let go at timeline[5]"] },
    BadInput { what: "move_hand with both to and by", edits: &[("to = [[550, 0, 0], [580, 0, 0]]", "to = [550, 0, 0]\nby = [1, 0, 0]")], field: Some("timeline[3]"), message: &["a hand move takes either `to` (absolute) or `by` (relative), not both"] },
    BadInput { what: "move_hand with nothing to do", edits: &[("to = [[550, 0, 0], [580, 0, 0]]\n", ""), ("rotate = { axis = [0, 0, 1], angle_deg = 10 }\n", "")], field: Some("timeline[3]"), message: &["a hand move needs `to`, `by` or `rotate`"] },
    BadInput { what: "move_hand with both duration and speed", edits: &[("duration_s = 1.5", "duration_s = 1.5\nspeed_m_s = 0.1")], field: Some("timeline[3].speed_m_s"), message: &["either `duration_s` or `speed_m_s`, not both"] },
    BadInput { what: "move_hand with neither duration nor speed", edits: &[("duration_s = 1.5\n", "")], field: Some("timeline[3]"), message: &["needs `duration_s` or `speed_m_s`"] },
    BadInput { what: "move_hand with a zero speed", edits: &[("duration_s = 1.5", "speed_m_s = 0")], field: Some("timeline[3].speed_m_s"), message: &["must be greater than 0"] },
    BadInput { what: "move_hand with no waypoints", edits: &[("to = [[550, 0, 0], [580, 0, 0]]", "to = []")], field: Some("timeline[3].to"), message: &["needs at least one waypoint"] },
    BadInput { what: "move_hand waypoint not finite", edits: &[("[580, 0, 0]", "[580, inf, 0]")], field: Some("timeline[3].to[1][1]"), message: &["= inf mm: must be a finite number"] },
    BadInput { what: "move_hand zero duration", edits: &[("duration_s = 1.5", "duration_s = 0")], field: Some("timeline[3].duration_s"), message: &["= 0 s: must be greater than 0"] },
    BadInput { what: "move_hand zero rotation axis", edits: &[("axis = [0, 0, 1], angle_deg = 10", "axis = [0, 0, 0], angle_deg = 10")], field: Some("timeline[3].rotate.axis"), message: &["must not be the zero vector"] },
    BadInput { what: "move_hand with a node", edits: &[("hand = 0\nto", "hand = 0\nnode = 3\nto")], field: Some("timeline[3].node"), message: &["unknown field `node`"] },
    BadInput { what: "release_hand with extra field", edits: &[("action = \"release_hand\"\nhand = 0", "action = \"release_hand\"\nhand = 0\nhose = \"a\"")], field: Some("timeline[5].hose"), message: &["unknown field `hose`"] },
    // Ergonomics.
    BadInput { what: "unknown posture", edits: &[("posture = \"crouching\"", "posture = \"kneeling\"")], field: Some("ergonomics.posture"), message: &["ergonomics.posture = \"kneeling\": unknown posture `kneeling`; allowed: standing, crouching, sitting"] },
    BadInput { what: "unknown push row", edits: &[("posture = \"crouching\"", "push = \"lying\"")], field: Some("ergonomics.push"), message: &["unknown push posture `lying`; allowed: standing, crouching, sitting"] },
    BadInput { what: "unknown pull row", edits: &[("posture = \"crouching\"", "pull = \"standing\"")], field: Some("ergonomics.pull"), message: &["unknown pull posture `standing`; allowed: standing_lever, crouching_lever, handle"] },
    BadInput { what: "torque grip no longer chosen", edits: &[("moments_decide = true", "torque = \"screwdriver\"")], field: Some("ergonomics.torque"), message: &["unknown field `torque`"] },
    BadInput { what: "moments_decide not a boolean", edits: &[("moments_decide = true", "moments_decide = \"yes\"")], field: Some("ergonomics.moments_decide"), message: &["invalid type"] },
    BadInput { what: "unknown population", edits: &[("population = \"men\"", "population = \"adults\"")], field: Some("ergonomics.population"), message: &["unknown population `adults`; allowed: women, men"] },
    BadInput { what: "unknown duty", edits: &[("duty = \"continuous\"", "duty = \"daily\"")], field: Some("ergonomics.duty"), message: &["unknown duty `daily`; allowed: continuous, occasional"] },
    BadInput { what: "unknown ergonomics key", edits: &[("duty = \"continuous\"", "dutty = \"continuous\"")], field: Some("ergonomics.dutty"), message: &["unknown field `dutty`"] },
    BadInput { what: "ergonomics value not a string", edits: &[("population = \"men\"", "population = 1")], field: Some("ergonomics.population"), message: &["invalid type"] },
    // EN 1005-3.
    BadInput { what: "EN 1005-3 key without the standard", edits: &[("duty = \"continuous\"", "duty = \"continuous\"\naction = \"arm\"")], field: Some("ergonomics.action"), message: &["`action` is an EN 1005-3 parameter: give `standard=en1005-3` first"] },
    BadInput { what: "unknown standard", edits: &[("duty = \"continuous\"", "duty = \"continuous\"\nstandard = \"iso-11228\"")], field: Some("ergonomics.standard"), message: &["unknown standard `iso-11228`; allowed: dissertation, en1005_3"] },
    BadInput { what: "unknown EN 1005-3 action", edits: &[("duty = \"continuous\"", "duty = \"continuous\"\nstandard = \"en1005-3\"\naction = \"kneeling\"")], field: Some("ergonomics.action"), message: &["unknown EN 1005-3 action `kneeling`; allowed: whole_body, arm_trunk_support, arm"] },
    BadInput { what: "EN 1005-3 frequency beyond the table", edits: &[("duty = \"continuous\"", "duty = \"continuous\"\nstandard = \"en1005-3\"\nfrequency_per_min = 25")], field: Some("ergonomics.frequency_per_min"), message: &["`frequency_per_min` must lie in [0, 20] per minute"] },
    BadInput { what: "EN 1005-3 percentile out of range", edits: &[("duty = \"continuous\"", "duty = \"continuous\"\nstandard = \"en1005-3\"\npercentile = 80")], field: Some("ergonomics.percentile"), message: &["`percentile` must lie in [1, 50]"] },
    // Ties between hoses.
    BadInput { what: "tie of a node to itself", edits: &[("action = \"fix\"\nhose = \"a\"\nnode = 0", "action = \"tie\"\nhose = \"a\"\nnode = 0\nto = { hose = \"a\", node = 0 }")], field: Some("timeline[0].to"), message: &["is the tied node itself"] },
    BadInput { what: "tie to an unknown hose", edits: &[("action = \"fix\"\nhose = \"a\"\nnode = 0", "action = \"tie\"\nhose = \"a\"\nnode = 0\nto = { hose = \"c\", node = 0 }")], field: Some("timeline[0].to.hose"), message: &["unknown hose; hoses: a, b"] },
    BadInput { what: "tie to a node out of range", edits: &[("action = \"fix\"\nhose = \"a\"\nnode = 0", "action = \"tie\"\nhose = \"a\"\nnode = 0\nto = { hose = \"b\", node = 999 }")], field: Some("timeline[0].to.node"), message: &["999"] },
    BadInput { what: "tie without to", edits: &[("action = \"fix\"\nhose = \"a\"\nnode = 0", "action = \"tie\"\nhose = \"a\"\nnode = 0")], field: Some("timeline[0].to"), message: &["missing field `to`"] },
    // Stubs.
    BadInput { what: "stub zero length", edits: &[("length = 40", "length = 0")], field: Some("stubs[0].length"), message: &["stubs[0].length = 0 mm: must be greater than 0"] },
    BadInput { what: "stub negative diameter", edits: &[("diameter = 29", "diameter = -29")], field: Some("stubs[0].diameter"), message: &["= -29 mm: must be greater than 0"] },
    BadInput { what: "stub zero axis", edits: &[("axis = [2, 0, 0]", "axis = [0, 0, 0]")], field: Some("stubs[0].axis"), message: &["stubs[0].axis = [0, 0, 0]: must not be the zero vector"] },
    BadInput { what: "stub origin not finite", edits: &[("origin = [600, 0, 0]", "origin = [600, 0, nan]")], field: Some("stubs[0].origin[2]"), message: &["= nan mm: must be a finite number"] },
    BadInput { what: "stub friction sliding above static", edits: &[("static = 0.7, sliding = 0.5", "static = 0.4, sliding = 0.5")], field: Some("stubs[1].friction.sliding"), message: &["= 0.5: must not exceed static (0.4)"] },
    BadInput { what: "stub negative friction", edits: &[("static = 0.7, sliding = 0.5", "static = -0.7, sliding = 0.5")], field: Some("stubs[1].friction.static"), message: &["= -0.7: must not be negative"] },
    BadInput { what: "stub unknown hose", edits: &[("hose = \"a\"\nend", "hose = \"z\"\nend")], field: Some("stubs[0].hose"), message: &["stubs[0].hose = \"z\": unknown hose; hoses: a, b"] },
    BadInput { what: "stub bound to no hose end in a scene of two hoses", edits: &[("hose = \"b\"\nend = \"start\"\n", "")], field: Some("stubs[1].hose"), message: &["several hoses: name the hose end"] },
    BadInput { what: "clip bound to no hose in a scene of two hoses", edits: &[("snap_force_n = 20\nhose = \"b\"\n", "snap_force_n = 20\n")], field: Some("clips[1].hose"), message: &["several hoses: name the hose that goes into the clip"] },
    BadInput { what: "stub hose without end", edits: &[("end = \"end\"\n", "")], field: Some("stubs[0].end"), message: &["required with `hose`"] },
    BadInput { what: "stub end without hose", edits: &[("hose = \"a\"\nend", "end")], field: Some("stubs[0].hose"), message: &["required with `end`"] },
    BadInput { what: "stub end not start or end", edits: &[("end = \"end\"", "end = \"middle\"")], field: Some("stubs[0].end"), message: &["unknown variant `middle`", "`start`", "`end`"] },
    BadInput { what: "stub wider than the hose", edits: &[("diameter = 29", "diameter = 35")], field: Some("stubs[0].diameter"), message: &["stubs[0].diameter = 35 mm: must be smaller than the outer diameter of hose \"a\" at its end (35 mm)"] },
    BadInput { what: "duplicate stub names", edits: &[("name = \"spare\"", "name = \"pump\"")], field: Some("stubs[1].name"), message: &["\"pump\": duplicate name (also stubs[0].name)"] },
    BadInput { what: "empty stub name", edits: &[("name = \"spare\"", "name = \" \"")], field: Some("stubs[1].name"), message: &["must not be empty"] },
    BadInput { what: "unknown stub field", edits: &[("diameter = 29", "diameter = 29\nradius = 14")], field: Some("stubs[0].radius"), message: &["unknown field `radius`"] },
    BadInput { what: "stub without diameter", edits: &[("diameter = 29\n", "")], field: Some("stubs[0].diameter"), message: &["missing field `diameter`"] },
    // Clips.
    BadInput { what: "clip opening as wide as the seat", edits: &[("opening_width = 30", "opening_width = 36")], field: Some("clips[0].opening_width"), message: &["clips[0].opening_width = 36 mm: must be smaller than inner_diameter (36 mm)"] },
    BadInput { what: "clip opening wider than the seat", edits: &[("opening_width = 12", "opening_width = 20")], field: Some("clips[1].opening_width"), message: &["= 20 mm: must be smaller than inner_diameter (16 mm)"] },
    BadInput { what: "clip zero opening width", edits: &[("opening_width = 30", "opening_width = 0")], field: Some("clips[0].opening_width"), message: &["= 0 mm: must be greater than 0"] },
    BadInput { what: "clip negative inner diameter", edits: &[("inner_diameter = 36", "inner_diameter = -36")], field: Some("clips[0].inner_diameter"), message: &["= -36 mm: must be greater than 0"] },
    BadInput { what: "clip negative snap force", edits: &[("snap_force_n = 40", "snap_force_n = -40")], field: Some("clips[0].snap_force_n"), message: &["= -40 N: must not be negative"] },
    BadInput { what: "clip zero opening", edits: &[("opening = [0, 0, 1]", "opening = [0, 0, 0]")], field: Some("clips[0].opening"), message: &["= [0, 0, 0]: must not be the zero vector"] },
    BadInput { what: "clip zero orientation", edits: &[("orientation = [1, 0, 0.2]", "orientation = [0, 0, 0]")], field: Some("clips[0].orientation"), message: &["must not be the zero vector"] },
    BadInput { what: "clip orientation along the opening", edits: &[("orientation = [1, 0, 0.2]", "orientation = [1, 0, 1]")], field: Some("clips[0].orientation"), message: &["clips[0].orientation = [1, 0, 1]: must be roughly perpendicular to opening [0, 0, 1]: it is 45.0° off"] },
    BadInput { what: "clip origin not finite", edits: &[("origin = [250, 0, -30]", "origin = [inf, 0, -30]")], field: Some("clips[0].origin[0]"), message: &["= inf mm: must be a finite number"] },
    BadInput { what: "clip unknown hose", edits: &[("snap_force_n = 40\nhose = \"a\"", "snap_force_n = 40\nhose = \"q\"")], field: Some("clips[0].hose"), message: &["clips[0].hose = \"q\": unknown hose; hoses: a, b"] },
    BadInput { what: "clip opening wider than its hose", edits: &[("opening_width = 12", "opening_width = 16"), ("inner_diameter = 16", "inner_diameter = 20")], field: Some("clips[1].opening_width"), message: &["= 16 mm: must be smaller than the outer diameter of hose \"b\" (16 mm)", "never be held"] },
    BadInput { what: "duplicate clip names", edits: &[("name = \"c2\"", "name = \"c1\"")], field: Some("clips[1].name"), message: &["\"c1\": duplicate name (also clips[0].name)"] },
    BadInput { what: "clip named like a stub", edits: &[("name = \"c2\"", "name = \"pump\"")], field: Some("clips[1].name"), message: &["duplicate name (also stubs[0].name); stubs, connectors and clips share one set of names"] },
    BadInput { what: "unknown clip field", edits: &[("snap_force_n = 40", "snap_force = 40")], field: Some("clips[0].snap_force"), message: &["unknown field `snap_force`"] },
    BadInput { what: "unknown clip type", edits: &[("snap_force_n = 40", "snap_force_n = 40\ntype = \"glued\"")], field: Some("clips[0].type"), message: &["unknown variant `glued`"] },
    BadInput { what: "friction on a fixed clip", edits: &[("snap_force_n = 40", "snap_force_n = 40\nfriction = 0.3")], field: Some("clips[0].friction"), message: &["only a sliding guide has friction"] },
    BadInput { what: "negative guide friction", edits: &[("snap_force_n = 40", "snap_force_n = 40\ntype = \"sliding\"\nfriction = -0.3")], field: Some("clips[0].friction"), message: &["must not be negative"] },
    BadInput { what: "zero holding force", edits: &[("snap_force_n = 40", "snap_force_n = 40\nholding_force_n = 0")], field: Some("clips[0].holding_force_n"), message: &["must be greater than 0"] },
    BadInput { what: "rotating clip without snap force", edits: &[("snap_force_n = 40\n", "type = \"rotating\"\n")], field: Some("clips[0].snap_force_n"), message: &["required for a clip of type rotating"] },
];

#[test]
fn every_bad_input_is_named_and_explained() {
    check_bad_inputs(
        BASE,
        CASES,
        "scene.toml",
        |text| load_scene_str(text, "scene.toml"),
        |e| e.field(),
    );
}

// ---------------------------------------------------------------------------------------
// The engine-bay demo script.

fn engine_bay() -> LoadedScene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/engine_bay.toml");
    load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Whether `p` lies inside the box (lo, hi) grown by `margin`.
fn in_box(p: DVec3, (lo, hi): (DVec3, DVec3), margin: f64) -> bool {
    (p.cmpgt(lo - margin) & p.cmplt(hi + margin)).all()
}

#[test]
fn engine_bay_is_the_assembly_demo() {
    let s = engine_bay();
    let lower = s.hose_index("lower").unwrap();
    let nodes = &s.world.hoses[lower].nodes;
    let end = *nodes.last().unwrap();
    // One stub, at the lower hose's end; two clips for that hose.
    assert_eq!(s.stubs.len(), 1);
    let stub = &s.stubs[0];
    assert_eq!(
        stub.hose_end,
        HoseEnd {
            hose: lower,
            at_end: true
        }
    );
    assert_eq!(s.clips.len(), 2);
    assert!(s.clips.iter().all(|c| c.hose == lower));
    // The stub fits the hose: bore < stub < outer diameter.
    let section = s.world.hoses[lower].sections.last().unwrap();
    assert!(section.d_inner < stub.spec.diameter() && stub.spec.diameter() < section.d_outer);
    // The script: fix the radiator end, grab the free end, route, push on, let go, settle.
    let a = &s.timeline.actions;
    let lower_fixes: Vec<usize> = a
        .iter()
        .filter_map(|x| match x {
            Action::Fix { node } if node.hose == lower => Some(node.node),
            _ => None,
        })
        .collect();
    assert_eq!(
        lower_fixes,
        [0],
        "only the radiator end of the lower hose is fixed"
    );
    let kinds: Vec<&str> = a
        .iter()
        .filter_map(|x| match x {
            Action::Grab { .. } => Some("grab"),
            Action::MoveHand { .. } => Some("move_hand"),
            Action::ReleaseHand { .. } => Some("release_hand"),
            Action::Settle { .. } => Some("settle"),
            _ => None,
        })
        .collect();
    // route and push onto the stub, then press the hose into each of the two clips
    assert_eq!(
        kinds,
        [
            "grab",
            "move_hand",
            "move_hand",
            "release_hand",
            "grab",
            "move_hand",
            "release_hand",
            "grab",
            "move_hand",
            "release_hand",
            "settle"
        ]
    );
    // The grab is at the free end, which starts near (but not on) the stub.
    let Some(Action::Grab { at, .. }) = a.iter().find(|x| matches!(x, Action::Grab { .. })) else {
        unreachable!()
    };
    assert!((*at - end).length() < 0.01, "grab {at} vs free end {end}");
    let to_mouth = (end - stub.spec.origin()).length();
    assert!(
        (0.1..0.5).contains(&to_mouth),
        "free end {to_mouth} m from the stub"
    );
    // Follow the hand: the routing move ends on the stub axis in front of the mouth with
    // the end turned onto the axis; the last move runs along the axis onto the stub.
    let mut hand = *at;
    let mut path = vec![hand];
    let mut turned = DVec3::ZERO;
    // the moves of the first grab: routing and pushing onto the stub (later grabs press
    // the hose into the clips)
    let moves: Vec<&Action> = a
        .iter()
        .take_while(|x| !matches!(x, Action::ReleaseHand { .. }))
        .filter(|x| matches!(x, Action::MoveHand { .. }))
        .collect();
    for m in &moves {
        let Action::MoveHand {
            path: p, rotation, ..
        } = m
        else {
            unreachable!()
        };
        let points: Vec<DVec3> = match p {
            Some(MovePath::To(ps)) => ps.clone(),
            Some(MovePath::By(ds)) => ds.iter().map(|d| hand + *d).collect(),
            None => Vec::new(),
        };
        path.extend(&points);
        hand = *points.last().unwrap_or(&hand);
        if let Some(r) = rotation {
            turned += r.axis * r.angle;
        }
    }
    let spec = &stub.spec;
    let before = path[path.len() - 2];
    assert!(
        spec.axial_coordinate(before) < 0.0,
        "approach point is in front of the mouth"
    );
    assert!(
        spec.lateral_distance(before) < 1e-9,
        "approach point on the stub axis"
    );
    let depth = spec.axial_coordinate(hand);
    assert!(spec.lateral_distance(hand) < 1e-9);
    assert!(
        depth > 0.0 && depth < spec.length(),
        "pushed on {depth} m of {}",
        spec.length()
    );
    // The end started pointing +x; the hand turns it onto the stub axis.
    let last = nodes[nodes.len() - 1] - nodes[nodes.len() - 2];
    let rotated = glam::DQuat::from_scaled_axis(turned) * last.normalize();
    assert!(
        rotated.dot(spec.axis()) > 0.999,
        "end direction after the turn {rotated}"
    );
    // No waypoint, nor any point between waypoints, lies in a part (grown by the hose's
    // outer radius); the hose end on the stub stays clear of the engine block too.
    let r = 0.5 * section.d_outer;
    for w in path.windows(2) {
        for k in 0..=100 {
            let p = w[0].lerp(w[1], k as f64 / 100.0);
            for (part, info) in s.world.rigid_parts.iter().zip(&s.parts) {
                assert!(
                    !in_box(p, info.bounds, r),
                    "hand path point {p} inside {}",
                    part.name
                );
            }
        }
    }
    // Clips: on the lower hose's route between the radiator and the stub, clear of the
    // parts, hose thicker than the opening and seat wide enough for it.
    for c in &s.clips {
        let p = c.spec.origin();
        for info in &s.parts {
            assert!(
                !in_box(p, info.bounds, r),
                "clip {} inside {}",
                c.name,
                info.name
            );
        }
        assert!(c.spec.opening_width() < section.d_outer);
        assert!(c.spec.inner_diameter() >= section.d_outer);
    }
    // Ergonomics as written.
    assert_eq!(s.ergonomics, ErgonomicProfile::default());
    pliant_core::Model::build(&s.world).unwrap_or_else(|e| panic!("{e}"));
}
