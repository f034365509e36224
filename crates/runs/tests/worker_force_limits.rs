//! SPEC E2: "the posture class feeds the force limits". One worker draws the free ends
//! of three equal hoses, each 600 mm long and fixed at its far end, 36 mm towards
//! himself: at chest height (standing upright), at knee height (the trunk bent) and
//! overhead (the arm above the shoulder). Drawing the end outwards along the hose is a
//! push by the ergonomics module's rule (the force points along the hose, out of its
//! nearer end). The three forces are equal (same hose, same stretch), but the limit
//! follows the posture class: the standing row of table 3.7 upright, the crouching row
//! bent or overhead (`ergonomics::table_posture`); the profile's column is men,
//! occasional. Without the worker all three are judged by the profile's standing row.
//! The chest-height hose lies to the worker's left (his left hand draws it), out of the
//! way of his head when he bends to the knee-height one on his right: a hose is an
//! obstacle to the body too.

use pliant_assembly::ergonomics::{
    ErgonomicLimits, ErgonomicProfile, LoadKind, Population, Posture,
};
use pliant_assembly::workcell::Reason;
use pliant_assembly::{RunSummary, Stage, Verdict};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_worker::PostureClass;

/// Hose `name` at `y`, height `z` mm, from x = 1000 (fixed) to x = 400 mm (grabbed).
fn hose_at(name: &str, y: f64, z: f64) -> String {
    format!(
        r#"
[[hoses]]
name = "{name}"
material = "hose3"
elements = 12
start = [1000, {y}, {z}]
path = [{{ line = {{ to = [400, {y}, {z}] }} }}]
"#
    )
}

/// A pause, then hand `hand` grabs the end at `y`, height `z` mm, draws it 36 mm towards
/// the worker and lets go.
fn draw(hand: usize, y: f64, z: f64) -> String {
    format!(
        r#"
[[timeline]]
action = "run"
duration_s = 0.1

[[timeline]]
action = "grab"
hand = {hand}
at = [400, {y}, {z}]

[[timeline]]
action = "move_hand"
hand = {hand}
by = [-36, 0, 0]
duration_s = 0.2

[[timeline]]
action = "release_hand"
hand = {hand}
"#
    )
}

/// The three draws; `worker` the `[worker]` section or nothing.
fn scene(worker: &str) -> String {
    let heights = [
        ("chest", 200.0, 1200.0),
        ("knee", -200.0, 500.0),
        ("overhead", -200.0, 1950.0),
    ];
    let mut s = String::from(
        "format = \"pliant-scene\"\nversion = 1\nlength_unit = \"mm\"\n\n[simulation]\nsolver = \"static\"\n\n[ergonomics]\npopulation = \"men\"\n\n",
    );
    s.push_str(worker);
    for (name, y, z) in heights {
        s.push_str(&hose_at(name, y, z));
    }
    // every hose held from the start (the static solver needs each one supported)
    for (name, _, _) in heights {
        s.push_str(&format!(
            "\n[[timeline]]\naction = \"fix\"\nhose = \"{name}\"\nnode = 0\n"
        ));
    }
    for (hand, (_, y, z)) in heights.iter().enumerate() {
        s.push_str(&draw(hand, *y, *z));
    }
    // the last release runs out
    s.push_str("\n[[timeline]]\naction = \"run\"\nduration_s = 0.1\n");
    s
}

const WORKER: &str =
    "[worker]\npopulation = \"male 50\"\nposition = [0, 0, 0]\nfacing = [1, 0, 0]\n\n";

fn run(text: &str) -> (pliant_assembly::Workcell, RunSummary) {
    let s = load_scene_str(text, "force_limits.toml").unwrap();
    pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap()
}

/// The push limit of table 3.7 for men, occasional duty (the default), in the row of
/// `posture`.
fn push_limit(posture: Posture) -> f64 {
    let duty = ErgonomicProfile::default().duty;
    ErgonomicLimits::builtin()
        .unwrap()
        .push_limit(posture.push(), Population::Men, duty)
}

#[test]
fn the_posture_class_chooses_the_push_limit_along_the_timeline() {
    let (cell, with) = run(&scene(WORKER));
    // the class changes along the timeline: upright, bent, overhead — in that order
    let classes: Vec<PostureClass> =
        cell.worker_series()
            .iter()
            .map(|s| s.posture_class)
            .fold(Vec::new(), |mut seen, c| {
                if seen.last() != Some(&c) {
                    seen.push(c);
                }
                seen
            });
    assert!(
        classes.starts_with(&[PostureClass::Upright, PostureClass::BentTrunk]),
        "{classes:?}"
    );
    assert!(
        classes.contains(&PostureClass::ArmsAboveShoulder),
        "{classes:?}"
    );
    let w = with.worker.as_ref().unwrap();
    assert!(w.findings().is_empty(), "{:?}", w.findings());
    let c = &w.class_instants;
    assert!(
        c.upright > 0 && c.bent_trunk > 0 && c.arms_above_shoulder > 0,
        "{c:?}"
    );

    let (standing, crouching) = (
        push_limit(Posture::Standing),
        push_limit(Posture::Crouching),
    );
    let expected = [
        (PostureClass::Upright, standing),
        (PostureClass::BentTrunk, crouching),
        (PostureClass::ArmsAboveShoulder, crouching),
    ];
    let pushes: Vec<f64> = with.hand_peaks.iter().map(|h| h.push.magnitude).collect();
    // the three stretches push alike: only the limit differs
    let mean = pushes.iter().sum::<f64>() / 3.0;
    for p in &pushes {
        assert!((p - mean).abs() < 0.01 * mean, "{pushes:?}");
    }
    // between the two rows: feasible upright, over the limit bent and overhead
    assert!(crouching < mean && mean < standing, "{pushes:?}");
    for (h, (class, limit)) in with.hand_peaks.iter().zip(expected) {
        assert_eq!(h.worst_kind, Some(LoadKind::Push), "{h:?}");
        assert_eq!(h.worst_class, Some(class), "hand {}: {h:?}", h.hand);
        assert_eq!(h.worst_limit, limit, "hand {}", h.hand);
        assert_eq!(h.worst_magnitude, h.push.magnitude);
    }
    let v = Verdict::judge(&with, None, Stage::Final);
    assert_eq!(v.feasible, Some(false), "{v:?}");
    for (hand, words) in [(1, "bent trunk"), (2, "arms above shoulder")] {
        let line = v
            .reasons
            .iter()
            .find(|r| r.starts_with(&format!("hand {hand}: push of ")))
            .unwrap_or_else(|| panic!("{:?}", v.reasons));
        assert!(
            line.contains(&format!(
                "exceeds the limit {crouching:.1} N allowed for {words} (table 3.7, crouching row;"
            )),
            "{line}"
        );
    }
    assert!(
        !v.reasons.iter().any(|r| r.starts_with("hand 0:")),
        "{:?}",
        v.reasons
    );
    // the typed reason names the class
    let classes: Vec<Option<PostureClass>> = v
        .findings
        .reasons
        .iter()
        .filter_map(|r| match r {
            Reason::HandLoadOverLimit { load, .. } => Some(load.posture_class),
            _ => None,
        })
        .collect();
    assert_eq!(
        classes,
        [
            Some(PostureClass::BentTrunk),
            Some(PostureClass::ArmsAboveShoulder)
        ]
    );

    // without the worker: the same pushes, all judged by the profile's standing row
    let (_, without) = run(&scene(""));
    assert!(without.worker.is_none());
    for (a, b) in with.hand_peaks.iter().zip(&without.hand_peaks) {
        assert_eq!(a.push, b.push);
        assert_eq!(b.worst_class, None);
        assert_eq!(b.worst_limit, standing);
    }
    let v = Verdict::judge(&without, None, Stage::Final);
    assert_eq!(v.feasible, Some(true), "{v:?}");
    assert!(!v.reasons.iter().any(|r| r.contains("allowed for")));
}
