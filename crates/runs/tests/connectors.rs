//! Connectors (`[[connectors]]`): a hand plugs a hose end into its counterpart against a
//! measured mating force. With no gravity and the hose held by the hand alone, the hand
//! pushing slowly along the axis feels the mating force curve itself; released past the
//! latch the plug is latched, released short of it half-mated.

use pliant_assembly::FastenerState;
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{action, grab, hose, move_hand, run_for, SceneText, Table};
use pliant_testkit::scenes::WEIGHTLESS_MM;

/// The mating curve of the scenes below: (travel mm, force N); peak 150 N at 6 mm, the
/// latch clicks at 6.5 mm.
const CURVE: [(f64, f64); 5] = [
    (0.0, 5.0),
    (5.0, 140.0),
    (6.0, 150.0),
    (6.5, 20.0),
    (8.0, 30.0),
];

/// A 300 mm hose3 along x, free in space without gravity, its end at the counterpart's
/// mouth; hand 0 grabs it at the end and pushes `push_mm` along the axis over 2 s, then
/// lets go; `extra` goes at the end of the file.
fn scene(push_mm: f64, extra: &str) -> String {
    let curve: Vec<String> = CURVE.iter().map(|(s, f)| format!("[{s}, {f}]")).collect();
    let counterpart = Table::entry("connectors")
        .text("name", "X1")
        .point("origin", [300.0, 0.0, 0.0])
        .point("axis", [1.0, 0.0, 0.0])
        .number("travel", 8.0)
        .inline("mating_force", &format!("[{}]", curve.join(", ")))
        .number("latch_at", 6.5)
        .number("retention_force_n", 110.0)
        .text("hose", "h")
        .text("end", "end");
    let hose = hose("h", "hose3", [0.0; 3], [300.0, 0.0, 0.0]).number("elements", 10.0);
    let scene = SceneText::piece()
        .with(hose)
        .with(counterpart)
        .with(grab(0, [295.0, 0.0, 0.0]))
        .with(move_hand(0, [push_mm, 0.0, 0.0], 2.0))
        .with(action("release_hand").number("hand", 0.0))
        .with(run_for(0.2))
        .raw(extra);
    format!("{WEIGHTLESS_MM}{}", String::from(scene))
}

/// The curve at travel s \[mm\], linear between its points (N).
fn curve_at(s: f64) -> f64 {
    let k = CURVE.iter().rposition(|&(t, _)| t <= s).unwrap();
    let ((s0, f0), (s1, f1)) = (CURVE[k], CURVE[(k + 1).min(CURVE.len() - 1)]);
    if s1 == s0 {
        f0
    } else {
        f0 + (f1 - f0) * (s - s0) / (s1 - s0)
    }
}

#[test]
fn a_plug_pushed_past_its_latch_is_latched_and_the_hand_felt_the_mating_curve() {
    let scene = load_scene_str(&scene(7.5, ""), "plug.toml").unwrap();
    assert_eq!(scene.connectors.len(), 1);
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap();
    let x1 = run.fasteners.iter().find(|f| f.name == "X1").unwrap();
    assert_eq!(x1.kind, pliant_assembly::FastenerKind::Connector);
    assert_eq!(x1.final_state, FastenerState::Latched);
    assert!(x1.assembled);
    // the hand pushes at ≤ 7 mm/s: inertia and damping are far below a newton, the peak it
    // feels is the curve's peak (150 N at 6 mm) within 2 %
    let hand = &run.hand_peaks[0];
    assert!(
        (hand.push.magnitude / curve_at(6.0) - 1.0).abs() < 0.02,
        "hand push peak {} N against the curve's 150 N",
        hand.push.magnitude
    );
    // and the connector's own largest force is the same
    assert!(
        (x1.max_force / 150.0 - 1.0).abs() < 0.02,
        "{}",
        x1.max_force
    );
    // the verdict names the connector the hand was plugging at its worst moment
    let verdict = pliant_assembly::Verdict::judge(&run, None, pliant_assembly::Stage::Final);
    assert!(
        verdict
            .reasons
            .iter()
            .chain(&verdict.warnings)
            .any(|r| r.starts_with("hand 0: push of") && r.ends_with("plugging connector 'X1'")),
        "{:?} {:?}",
        verdict.reasons,
        verdict.warnings
    );
}

#[test]
fn a_plug_released_short_of_its_latch_is_half_mated_and_the_verdict_says_so() {
    let scene = load_scene_str(&scene(4.0, ""), "plug.toml").unwrap();
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap();
    let x1 = run.fasteners.iter().find(|f| f.name == "X1").unwrap();
    assert_eq!(x1.final_state, FastenerState::HalfMated);
    assert!(!x1.assembled);
    // the hand stopped at 4 mm: it felt the curve there, not the peak beyond
    let felt = run.hand_peaks[0].push.magnitude;
    assert!(
        (felt / curve_at(4.0) - 1.0).abs() < 0.03,
        "{felt} N vs {} N",
        curve_at(4.0)
    );
    let verdict = pliant_assembly::Verdict::judge(&run, None, pliant_assembly::Stage::Final);
    assert_eq!(verdict.feasible, Some(false));
    assert!(
        verdict.reasons.iter().any(|r| {
            r
            == "connector 'X1': the hose did not end plugged and latched (final state: half_mated)"
        }),
        "{:?}",
        verdict.reasons
    );
}

#[test]
fn a_latched_plug_holds_against_a_pull_below_its_retention_force() {
    // latched, then pulled back with 60 N (< 110 N retention) for a while: it stays
    let pull = r#"
[[timeline]]
action = "load"
hose = "h"
node = -1
force_n = [-60, 0, 0]
ramp_s = 0.1

[[timeline]]
action = "run"
duration_s = 0.3
"#;
    let scene = load_scene_str(&scene(7.5, pull), "plug.toml").unwrap();
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap();
    let x1 = run.fasteners.iter().find(|f| f.name == "X1").unwrap();
    assert_eq!(x1.final_state, FastenerState::Latched);
}

#[test]
fn bad_connectors_are_refused_naming_the_field() {
    let cases = [
        ("travel = 8", "travel = 0.5", "connectors[0].travel"),
        ("latch_at = 6.5", "latch_at = 9", "connectors[0].latch_at"),
        ("[6.5, 20]", "[6, 20]", "connectors[0].mating_force[3]"),
        ("[8, 30]", "[9, 30]", "connectors[0].mating_force[4]"),
        (
            "retention_force_n = 110",
            "retention_force_n = -1",
            "connectors[0].retention_force_n",
        ),
        ("name = \"X1\"", "name = \"\"", "connectors[0].name"),
        (
            "hose = \"h\"\nend = \"end\"",
            "hose = \"nope\"\nend = \"end\"",
            "connectors[0].hose",
        ),
    ];
    for (from, to, field) in cases {
        let text = scene(7.5, "").replace(from, to);
        assert_ne!(text, scene(7.5, ""), "{from} not in the scene");
        let err = load_scene_str(&text, "plug.toml").unwrap_err().to_string();
        assert!(err.contains(field), "{from} → {to}: {err}");
    }
    // names are shared with stubs and clips
    let clip = r#"
[[clips]]
name = "X1"
hose = "h"
origin = [150, 0, 0]
opening = [0, 0, 1]
orientation = [1, 0, 0]
inner_diameter = 35
opening_width = 30
snap_force_n = 30
"#;
    let err = load_scene_str(&scene(7.5, clip), "plug.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("duplicate name"), "{err}");
}
