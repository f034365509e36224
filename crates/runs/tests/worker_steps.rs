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
use pliant_testkit::scene_text::{solver, worker, SceneText};
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
