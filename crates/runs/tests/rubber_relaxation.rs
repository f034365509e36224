//! Rubber that relaxes (SPEC X2): a 200 mm hose of a relaxing material pulled out by 2 mm
//! and held carries, long after, the long-term share 1 − Σ g of the force the same hose
//! of the elastic twin material carries, and pushed onto a stub keeps that share of its
//! holding force; the relaxation data are checked and refused with the field named.

use pliant_assembly::FastenerState;
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{action, grab, move_hand, run_for, SceneText, Table};
use pliant_testkit::scenes::{EPDM, WEIGHTLESS_MM};

/// The scene's head: a 200 mm hose of `epdm`, whose `relaxation` is a TOML array (may be
/// empty), fixed at its start, under `solver`.
fn head(relaxation: &str, solver: &str) -> String {
    format!(
        r#"{WEIGHTLESS_MM}solver = "{solver}"
{EPDM}relaxation = [{relaxation}]

[[hoses]]
name = "hose"
material = "epdm"
section = {{ d_inner = 10, d_outer = 16 }}
elements = 10
start = [0, 0, 0]
path = [{{ line = {{ to = [200, 0, 0] }} }}]

[[timeline]]
action = "fix"
hose = "hose"
node = 0
"#
    )
}

/// The hose's end pulled out by 2 mm over 1 s and held for `hold` seconds.
fn scene(relaxation: &str, hold: f64, solver: &str) -> String {
    head(relaxation, solver)
        + &format!(
            r#"
[[timeline]]
action = "move"
hose = "hose"
node = -1
by = [2, 0, 0]
duration_s = 1

[[timeline]]
action = "run"
duration_s = {hold}
"#
        )
}

const TERMS: &str = "{ weight = 0.3, time_s = 0.5 }, { weight = 0.2, time_s = 2 }";

/// The pull on the hose's end at the end of the timeline \[N\].
fn end_force(text: &str) -> f64 {
    let scene = load_scene_str(text, "rubber.toml").unwrap();
    let (cell, run) = pliant_runs::run_with(&scene, None).unwrap();
    assert_eq!(run.solver.unconverged_steps, 0, "{:?}", run.solver);
    let r = &cell.state().reaction_force;
    r[r.len() - 1].x
}

#[test]
fn a_relaxing_hose_held_stretched_keeps_the_long_term_share_of_its_force() {
    for solver in ["static", "implicit"] {
        let elastic = end_force(&scene("", 30.0, solver));
        let relaxed = end_force(&scene(TERMS, 30.0, solver));
        // 30 s is 15 of the longest relaxation time: e^{-15} of the relaxing share is left
        let ratio = relaxed / elastic;
        assert!(
            (ratio - 0.5).abs() < 1e-3,
            "{solver}: {relaxed} N of {elastic} N: ratio {ratio}, not 1 − Σ g = 0.5"
        );
        // just after the pull it has not relaxed that far
        let early = end_force(&scene(TERMS, 0.1, solver)) / elastic;
        assert!(early > 0.6 && early < 1.0, "{solver}: {early}");
    }
}

#[test]
fn relaxation_data_are_checked_with_the_field_named() {
    let cases = [
        (
            "{ weight = 1.2, time_s = 1 }",
            "materials.epdm.relaxation[0].weight",
        ),
        (
            "{ weight = 0.2, time_s = 1 }, { weight = 0.3, time_s = -1 }",
            "materials.epdm.relaxation[1].time_s",
        ),
        (
            "{ weight = 0.6, time_s = 1 }, { weight = 0.5, time_s = 10 }",
            "materials.epdm.relaxation",
        ),
    ];
    for (terms, field) in cases {
        let err = load_scene_str(&scene(terms, 1.0, "static"), "rubber.toml")
            .err()
            .unwrap_or_else(|| panic!("{terms} accepted"))
            .to_string();
        assert!(err.contains(field), "{terms}: {err}");
    }
    let both = scene(TERMS, 1.0, "static")
        .replace("relaxation = [", "yield_stress_mpa = 10\nrelaxation = [");
    let err = load_scene_str(&both, "rubber.toml")
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("either yields"), "{err}");
}

/// The hose pushed 20 mm onto a stub in 1 s by a hand, let go, and left for `hold`
/// seconds (static solver).
fn stub_scene(relaxation: &str, hold: f64) -> String {
    let stub = Table::entry("stubs")
        .text("name", "inlet")
        .point("origin", [205.0, 0.0, 0.0])
        .point("axis", [1.0, 0.0, 0.0])
        .number("length", 30.0)
        .number("diameter", 11.0)
        .text("hose", "hose")
        .text("end", "end");
    let pushed: String = SceneText::piece()
        .with(stub)
        .with(grab(0, [200.0, 0.0, 0.0]))
        .with(move_hand(0, [25.0, 0.0, 0.0], 1.0))
        .with(action("release_hand").number("hand", 0.0))
        .with(run_for(hold))
        .into();
    head(relaxation, "static") + &pushed
}

/// The stub's holding force at the end of the timeline \[N\].
fn holding_force(text: &str) -> f64 {
    let scene = load_scene_str(text, "stub.toml").unwrap();
    let (_, run) = pliant_runs::run_with(&scene, None).unwrap();
    let stub = &run.fasteners[0];
    assert_eq!(stub.final_state, FastenerState::Fixed, "{stub:?}");
    stub.holding_force
}

#[test]
fn a_relaxing_hose_on_a_stub_loses_the_relaxing_share_of_its_holding_force() {
    let elastic = holding_force(&stub_scene("", 30.0));
    assert!(elastic > 1.0, "{elastic} N");
    let relaxed = holding_force(&stub_scene(TERMS, 30.0)) / elastic;
    assert!(
        (relaxed - 0.5).abs() < 1e-3,
        "ratio {relaxed}, not 1 − Σ g = 0.5"
    );
    let early = holding_force(&stub_scene(TERMS, 0.2)) / elastic;
    assert!(
        early > 0.55 && early < 0.95,
        "ratio {early} right after the push"
    );
}
