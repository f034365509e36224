//! SPEC E1, "the feet kept (or allowed to step, reported as a step)": with `[worker]
//! steps = true` a hand target beyond the reach of a fixed worker is reached after one
//! step of the closed-form length (the target brought onto the upright straight arm's
//! reach sphere), reported in the verdict and the summary; a target far away takes the
//! longest step (0.4 of stature) and is still out of reach by what the manikin at the
//! stepped stance leaves; the study replays bit for bit.

use glam::DVec3;
use pliant_assembly::{Stage, Verdict};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{grab, hose, move_hand, solver, worker, SceneText};
use pliant_testkit::scenes::held_hose;
use pliant_worker::{body, Manikin, Placement, Population, Sex};

fn man() -> pliant_worker::Body {
    body(Population::new(Sex::Male, 50.0).unwrap()).unwrap()
}

/// A grab point `v` above the right shoulder of the 50th-percentile man standing at the
/// origin facing +x, straight ahead of it, `beyond` further than the upright straight
/// arm reaches at that height \[m\].
fn target(v: f64, beyond: f64) -> DVec3 {
    let b = man();
    let r = b.arm_reach();
    DVec3::new(
        (r * r - v * v).sqrt() + beyond,
        -0.5 * b.dims.shoulder_width,
        b.dims.shoulder_height + v,
    )
}

/// A 300 mm hose along x ending at `t`, fixed at its start, its end grabbed and held.
fn scene(t: DVec3, steps: bool) -> String {
    let mm = (t * 1e3).to_array();
    let worker = worker("male 50")
        .point("position", [0.0, 0.0, 0.0])
        .point("facing", [1.0, 0.0, 0.0])
        .flag("steps", steps);
    let base = SceneText::mm().with(solver("static")).with(worker);
    let start = [mm[0] + 300.0, mm[1], mm[2]];
    held_hose(base, "h", start, mm, [0.0; 3], 0.1).into()
}

/// As [`scene`] with steps on, the start not fixed (the hand carries the hose), and then
/// the hand moved by `by` \[mm\] over 0.2 s.
fn scene_then(t: DVec3, by: [f64; 3]) -> String {
    let mm = (t * 1e3).to_array();
    let worker = worker("male 50")
        .point("position", [0.0, 0.0, 0.0])
        .point("facing", [1.0, 0.0, 0.0])
        .flag("steps", true);
    let start = [mm[0] + 300.0, mm[1], mm[2]];
    SceneText::mm()
        .with(solver("static"))
        .with(worker)
        .with(hose("h", "hose3", start, mm).number("elements", 10.0))
        .with(grab(0, mm))
        .with(move_hand(0, [0.0; 3], 0.1))
        .with(move_hand(0, by, 0.2))
        .into()
}

fn run(text: &str) -> (pliant_assembly::Workcell, pliant_assembly::RunSummary) {
    let s = load_scene_str(text, "steps.toml").unwrap();
    pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap()
}

#[test]
fn a_target_just_beyond_reach_is_reached_after_one_step() {
    let t = target(0.45, 0.25);
    let (_, kept) = run(&scene(t, false));
    let w = kept.worker.as_ref().unwrap();
    assert!(w.reach[0].worst > 1e-3, "{:?}", w.reach);
    assert_eq!(w.step_count, 0);

    let (_, stepped) = run(&scene(t, true));
    let w = stepped.worker.as_ref().unwrap();
    assert!(w.reach[0].worst < 1e-4, "{:?}", w.reach);
    assert!(w.findings().is_empty(), "{:?}", w.findings());
    assert_eq!(w.step_count, 1);
    let s = &w.steps[0];
    // straight ahead, by what lay beyond the upright reach sphere
    assert!((s.to - DVec3::new(0.25, 0.0, 0.0)).length() < 1e-9, "{s:?}");
    assert!((s.length - 0.25).abs() < 1e-9, "{s:?}");
    assert_eq!(w.placement.unwrap().position, s.to);
    let v = Verdict::judge(&stepped, None, Stage::Final);
    assert_eq!(v.feasible, Some(true), "{v:?}");
    assert!(
        v.worker
            .iter()
            .any(|l| l
                == "the 50th-percentile man steps 0.25 m forward at t = 0.01 s (to reach hand 0)"),
        "{:?}",
        v.worker
    );
}

#[test]
fn a_far_target_is_still_out_of_reach_after_the_longest_step() {
    let t = target(0.2, 1.5);
    let (cell, run) = run(&scene(t, true));
    let w = run.worker.as_ref().unwrap();
    assert_eq!(w.step_count, 1);
    let longest = 0.4 * w.body.stature;
    assert!((w.steps[0].length - longest).abs() < 1e-9, "{:?}", w.steps);
    // what the manikin at the stepped stance leaves, at every posed instant
    let moved = Manikin::new(
        w.body,
        Placement::new(DVec3::new(longest, 0.0, 0.0), DVec3::X, DVec3::Z).unwrap(),
    );
    let expected = moved.solve([Some(t), None]).arms[0].residual;
    assert!(expected > 1.5 - longest - 0.6, "{expected}");
    for sample in cell.worker_series() {
        let r = sample.residual[0].unwrap();
        assert!((r - expected).abs() < 1e-6, "{r} vs {expected}");
    }
    let v = Verdict::judge(&run, None, Stage::Final);
    assert_eq!(v.feasible, Some(false));
    let words = format!(
        "out of reach for the 50th-percentile man by {:.0} mm",
        expected * 1e3
    );
    assert!(
        v.reasons.iter().any(|r| r.starts_with(&words)),
        "{words}: {:?}",
        v.reasons
    );
}

/// A worker who stepped to reach steps back to where it was placed once the target comes
/// back within reach from there, and only then: the hand brings the held (unfixed) hose
/// 0.35 m back towards the worker, inside the upright reach sphere from the first stance.
#[test]
fn the_worker_steps_back_once_the_target_is_within_reach_from_where_it_was_placed() {
    let t = target(0.45, 0.25);
    let (cell, run) = run(&scene_then(t, [-350.0, 0.0, 0.0]));
    let w = run.worker.as_ref().unwrap();
    assert_eq!(w.step_count, 2, "{:?}", w.steps);
    let (forward, home) = (&w.steps[0], &w.steps[1]);
    assert_eq!(
        forward.cause,
        pliant_assembly::worker::StepCause::Reach { hand: 0 }
    );
    assert!(
        (forward.to - DVec3::new(0.25, 0.0, 0.0)).length() < 1e-9,
        "{forward:?}"
    );
    assert_eq!(home.cause, pliant_assembly::worker::StepCause::Return);
    assert_eq!(home.from, forward.to);
    assert_eq!(home.to, DVec3::ZERO, "{home:?}");
    assert_eq!(home.words, "0.25 m back");
    assert_eq!(w.placement.unwrap().position, DVec3::ZERO);
    assert!(home.time > forward.time);
    // every posed instant reaches: before the return from the stepped stance, after it
    // from the first one
    for sample in cell.worker_series() {
        let r = sample.residual[0].unwrap();
        assert!(r < 1e-3, "{r} at t = {}", sample.time);
    }
    let v = Verdict::judge(&run, None, Stage::Final);
    let words = format!(
        "the 50th-percentile man steps 0.25 m back at t = {:.2} s (back to where he was placed)",
        home.time
    );
    assert!(v.worker.contains(&words), "{words}: {:?}", v.worker);
}

/// A target beside the worker, out of reach with the feet kept, makes it turn to face the
/// target and step towards it (people turn to work beside them rather than reach there
/// sideways); reached after that one step.
#[test]
fn a_target_beside_the_worker_is_reached_after_a_quarter_turn_and_a_step() {
    let b = man();
    let (r, v) = (b.arm_reach(), 0.3);
    let t = DVec3::new(
        0.0,
        (r * r - v * v).sqrt() + 0.5 * b.dims.shoulder_width + 0.2,
        b.dims.shoulder_height + v,
    );
    let (_, kept) = run(&scene(t, false));
    assert!(kept.worker.as_ref().unwrap().reach[1].worst > 1e-3);
    let (_, turned) = run(&scene(t, true));
    let w = turned.worker.as_ref().unwrap();
    assert_eq!(w.step_count, 1, "{:?}", w.steps);
    let s = &w.steps[0];
    assert!(
        (s.turn - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
        "{s:?}"
    );
    assert!(s.words.ends_with(", turning 90° to the left"), "{s:?}");
    let p = w.placement.unwrap();
    assert!((p.forward - DVec3::Y).length() < 1e-12, "{p:?}");
    assert!(s.to.y > 0.1 && s.to.z == 0.0, "{s:?}");
    assert!(w.reach.iter().all(|a| a.worst < 1e-3), "{:?}", w.reach);
}

/// A step is state: a replay of the log gives the same steps and posed instants.
#[test]
fn stepping_replays_bit_for_bit() {
    use pliant_assembly::workcell::replay::replay_log_of;
    use pliant_assembly::{run_timeline, NoObserver, WorkcellOptions};
    let s = load_scene_str(&scene(target(0.45, 0.25), true), "steps.toml").unwrap();
    let options = WorkcellOptions {
        solver: Some(SolverKind::Static),
        initial_loads: false,
        ..Default::default()
    };
    let mut live = s.workcell(options).unwrap();
    run_timeline(&mut live, &s.timeline, &mut NoObserver).unwrap();
    assert_eq!(live.summary().worker.unwrap().step_count, 1);
    let mut again = s.workcell(options).unwrap();
    replay_log_of(&live, &mut again).unwrap();
    assert_eq!(again.worker_series(), live.worker_series());
    assert_eq!(again.summary().worker, live.summary().worker);
}
