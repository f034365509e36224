//! The haptic mirror's cut (crates/core/src/integrators/component.rs, cut.rs) is exact: the
//! same poses answered on the whole scene and on the hand's component alone give the same
//! force and torque, to the static solver's tolerance. Two scenes: a hose held by a
//! seated clip (a fixed node) between the hand and the rest of it, beside a second hose;
//! and a network (a tee joining three hoses, fixed at their far ends) with a fixing in
//! one branch, the hand between the fixing and the tee.

use glam::{DQuat, DVec3};
use pliant_assembly::workcell::{Input, NoObserver, Workcell, WorkcellOptions};
use pliant_core::SolverKind;
use pliant_server::haptic::datagram::Status;
use pliant_server::haptic::mirror::{Mirror, SessionCopy};
use pliant_testkit::scene_text::{fix, hose, simulation, SceneText, Table};
use std::sync::Arc;

/// The `[simulation]` of both scenes: gravity, the static solver.
fn statics() -> Table {
    simulation()
        .point("gravity", [0.0, 0.0, -9.81])
        .text("solver", "static")
}

/// A straight hose of library material 1 in `elements` elements (mm).
fn hose_of(name: &str, start: [f64; 3], to: [f64; 3], elements: usize) -> Table {
    hose(name, "hose1", start, to).number("elements", elements as f64)
}

/// A hose fixed at its start with a clip seated at node 10 of 20 (a fix), the hand
/// taking it beyond the clip; a second hose fixed at both ends sags 80 mm beside it.
fn clipped() -> String {
    SceneText::mm_named("clipped hose beside another")
        .with(statics())
        .with(hose_of("clipped", [0.0; 3], [400.0, 0.0, 0.0], 20))
        .with(hose_of("beside", [0.0, 80.0, 0.0], [400.0, 80.0, 0.0], 20))
        .with_all([
            fix("clipped", 0),
            fix("clipped", 10),
            fix("beside", 0),
            fix("beside", -1),
        ])
        .into()
}

/// Three hoses joined at a tee (no body shape), fixed at their far ends, and a fixing
/// (a fix) at node 16 of the 24 of the "to engine" branch.
fn network() -> String {
    SceneText::mm_named("tee with a fixing")
        .with(statics())
        .with(hose_of("supply", [-250.0, 0.0, 0.0], [-15.0, 0.0, 0.0], 12))
        .with(hose_of("to engine", [15.0, 0.0, 0.0], [500.0, 0.0, 0.0], 24))
        .with(hose_of("bleed", [0.0, 0.0, -10.0], [0.0, 0.0, -160.0], 8))
        .with(
            Table::entry("junctions")
                .text("name", "tee")
                .inline(
                    "ends",
                    r#"[{ hose = "supply", end = "end" }, { hose = "to engine", end = "start" }, { hose = "bleed", end = "start" }]"#,
                )
                .inline("body", "{ mass_kg = 0.03 }"),
        )
        .with_all([
            fix("supply", 0),
            fix("to engine", -1),
            fix("to engine", 16),
            fix("bleed", -1),
        ])
        .into()
}

/// The settled scene with hand 0 holding it at `grab`, as the session publishes it.
fn copy_of(text: &str, grab: DVec3) -> Arc<SessionCopy> {
    let scene = pliant_scene::load_scene_str(text, "test scene").expect("scene loads");
    let setup = scene.workcell_setup().expect("workcell setup");
    let mut cell = Workcell::new(
        setup,
        WorkcellOptions {
            solver: Some(SolverKind::Static),
            ..Default::default()
        },
    )
    .expect("workcell");
    cell.steps(20, &mut NoObserver).expect("settles"); // the timeline's fixes, settled
    cell.apply(Input::Grab {
        hand: 0,
        at: grab,
        grip: Default::default(),
    })
    .expect("grab");
    cell.steps(1, &mut NoObserver).expect("holds");
    Arc::new(SessionCopy {
        model: cell.model().clone(),
        state: cell.state().clone(),
        hands: cell.hands().map(|(k, h)| (k, h.clone())).collect(),
        epoch: 0,
        taken: 0,
    })
}

/// Answers poses on a circle of 2 cm about `grab` (turning the hand as it goes) with the
/// whole-scene mirror and the cut one; the force and torque agree to `1e-6` of the
/// largest force (torque: times 1 m) — the solver balances each free node to 1e-8 of
/// its problem's load scale. Returns the nodes the cut solved and the scene's.
fn same_answers(copy: Arc<SessionCopy>, grab: DVec3) -> (usize, usize) {
    let mut whole = Mirror::new(copy.clone()).expect("mirror");
    whole.set_cutting(false);
    let mut cut = Mirror::new(copy.clone()).expect("mirror");
    let mut cut_nodes = 0;
    for k in 0..24 {
        let angle = k as f64 / 24.0 * std::f64::consts::TAU;
        let position = grab + 0.02 * DVec3::new(angle.cos() - 1.0, angle.sin(), 0.3 * angle.sin());
        let turn = DQuat::from_rotation_z(0.2 * angle.sin());
        let a = whole.answer(0, position, Some(turn));
        let b = cut.answer(0, position, Some(turn));
        assert_eq!(a.status, Status::Ok, "whole scene, pose {k}: {a:?}");
        assert_eq!(b.status, Status::Ok, "cut, pose {k}: {b:?}");
        assert_eq!(a.hose, b.hose);
        let scale = a.force.length().max(1e-3);
        let (df, dt) = ((a.force - b.force).length(), (a.torque - b.torque).length());
        assert!(
            df <= 1e-6 * scale && dt <= 1e-6 * scale,
            "pose {k}: force {} vs {} N (|Δ| {df:e}), torque {} vs {} N·m (|Δ| {dt:e})",
            a.force,
            b.force,
            a.torque,
            b.torque
        );
        eprintln!(
            "pose {k}: |F| {:.4} N, |ΔF| {df:.2e} N, |ΔT| {dt:.2e} N·m, Newton {} / {}",
            a.force.length(),
            a.iterations,
            b.iterations
        );
        cut_nodes = cut.solved_nodes();
    }
    (cut_nodes, whole.solved_nodes())
}

#[test]
fn a_clip_between_hand_and_hose_cuts_the_problem_exactly() {
    let grab = DVec3::new(0.38, 0.0, 0.0);
    let copy = copy_of(&clipped(), grab);
    let grab = copy.hands[0].1.hand.pose_at(copy.state.time).0;
    let (cut, whole) = same_answers(copy, grab);
    // the clipped hose's nodes from the clip on (11 of 42): the hose beside is 80 mm
    // away, beyond contact reach
    assert_eq!(whole, 42);
    assert_eq!(cut, 11, "the cut holds the hose beyond the clip alone");
}

#[test]
fn a_fixing_in_a_branch_cuts_the_network_exactly() {
    let grab = DVec3::new(0.2, 0.0, 0.0);
    let copy = copy_of(&network(), grab);
    let grab = copy.hands[0].1.hand.pose_at(copy.state.time).0;
    let (cut, whole) = same_answers(copy, grab);
    // supply 13 + bleed 9 + "to engine" up to its fixing 17; not the 8 nodes beyond
    assert_eq!(whole, 13 + 25 + 9);
    assert_eq!(cut, 13 + 17 + 9, "the cut ends at the fixing");
}
