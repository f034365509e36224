//! SPEC E1–E2: a scene's `[worker]`. A hand target 1.9 m up is beyond the
//! 5th-percentile woman (shoulder 0.818 H, arm to the grip 0.386 H at H = 1.523 m: 1.83 m
//! at most) and within the 95th-percentile man's reach; a shelf at chest height in front
//! of a fixed worker is inside his trunk; the verdict says so with distance, part and
//! time, and `summary.json`, `worker.csv` and the report carry it. Without `[worker]`
//! nothing of it appears.

mod support;

use pliant_assembly::{Stage, Verdict};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scenes::held_hose_lowered;

/// A 400 mm hose along x at height `z` mm, fixed at its start, its end grabbed and
/// lowered by 20 mm; `extra` added at the top (a `[worker]`, parts).
fn scene(z: f64, extra: &str) -> String {
    held_hose_lowered(extra, "h", [100.0, -200.0, z], [500.0, -200.0, z], 0.3)
}

fn run(text: &str) -> (pliant_assembly::Workcell, pliant_assembly::RunSummary) {
    let s = load_scene_str(text, "worker.toml").unwrap();
    pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap()
}

#[test]
fn out_of_reach_for_the_small_woman_not_for_the_tall_man() {
    let worker = |who: &str| format!("[worker]\npopulation = \"{who}\"\nfacing = [1, 0, 0]\n");
    let (_, small) = run(&scene(1900.0, &worker("female 5")));
    let v = Verdict::judge(&small, None, Stage::Final);
    assert_eq!(v.feasible, Some(false), "{v:?}");
    let line = v
        .reasons
        .iter()
        .find(|r| r.starts_with("out of reach for the 5th-percentile woman by "))
        .unwrap_or_else(|| panic!("{:?}", v.reasons));
    assert!(line.contains(" mm at t = "), "{line}");
    let w = small.worker.as_ref().unwrap();
    let reach = &w.reach[0];
    // auto placement: the grab 0.6 arm reaches ahead of the feet, on the floor z = 0
    let p = w.placement.unwrap();
    assert!(p.position.z.abs() < 1e-12);
    assert!((0.5 - p.position.x - 0.6 * w.body.arm_reach()).abs() < 1e-9);
    // the shoulder–target distance less the arm, give or take what bending wins
    let shoulder = glam::DVec3::new(
        p.position.x,
        -0.5 * w.body.dims.shoulder_width,
        w.body.dims.shoulder_height,
    );
    let upright_gap = (glam::DVec3::new(0.5, -0.2, 1.9) - shoulder).length() - w.body.arm_reach();
    assert!(
        reach.worst > 0.05 && reach.worst <= upright_gap + 0.03,
        "{reach:?} vs {upright_gap}"
    );
    assert!(
        v.worker[0].starts_with("posture of the 5th-percentile woman: RULA "),
        "{:?}",
        v.worker
    );

    let (_, tall) = run(&scene(1900.0, &worker("male 95")));
    let v = Verdict::judge(&tall, None, Stage::Final);
    assert!(
        !v.reasons.iter().any(|r| r.contains("out of reach")),
        "{:?}",
        v.reasons
    );
    let w = tall.worker.as_ref().unwrap();
    assert!(w.reach[0].worst < 1e-3, "{:?}", w.reach);
    assert!(w.findings().is_empty());
    // reaching up, the upper arm is raised above 90°: RULA's upper arm scores 4
    assert!(
        w.worst_rula.unwrap().score.upper_arm >= 4,
        "{:?}",
        w.worst_rula
    );
}

#[test]
fn a_shelf_in_the_trunk_is_a_body_collision() {
    let extra = r#"
[worker]
population = "male"
percentile = 50
position = [0, 0, 0]
facing = [1, 0, 0]

[[parts]]
name = "shelf"
box = { size = [400, 400, 20] }
position = [250, 0, 1200]
"#;
    let text = scene(1000.0, extra);
    let (cell, run1) = run(&text);
    let v = Verdict::judge(&run1, None, Stage::Final);
    assert_eq!(v.feasible, Some(false));
    let line = v
        .reasons
        .iter()
        .find(|r| r.starts_with("body collision: the 50th-percentile man's trunk is "))
        .unwrap_or_else(|| panic!("{:?}", v.reasons));
    assert!(line.contains("inside 'shelf' at t = "), "{line}");
    let w = run1.worker.as_ref().unwrap();
    let c = w.collisions.iter().find(|c| c.segment == "trunk").unwrap();
    // the trunk's axis stands at x = 0, the shelf begins at x = 50 mm: depth r − 0.05
    assert!(
        (c.depth - (w.body.radii.trunk - 0.05)).abs() < 1e-9,
        "{c:?}"
    );
    // decide = false: the same as a warning, feasible
    let (_, run2) = run(&text.replace("facing = [1, 0, 0]", "facing = [1, 0, 0]\ndecide = false"));
    let v2 = Verdict::judge(&run2, None, Stage::Final);
    assert!(
        v2.warnings.iter().any(|w| w.starts_with("body collision")),
        "{v2:?}"
    );
    assert!(!v2.reasons.iter().any(|r| r.starts_with("body collision")));
    // same scene, same numbers
    let (_, again) = run(&text);
    assert_eq!(again.worker, run1.worker);

    // the outputs: summary.json's worker with typed findings, worker.csv, the report
    let dir = support::static_outputs(&text, "worker.toml", &cell, &run1);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    let worker = &summary["worker"];
    assert_eq!(worker["who"], "the 50th-percentile man");
    assert_eq!(worker["findings"][0]["kind"], "collision");
    assert_eq!(worker["findings"][0]["part"], "shelf");
    let csv = std::fs::read_to_string(dir.path().join("worker.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("time_s,right_hand,right_residual_m,"));
    assert_eq!(rows.len() as u64, w.instants + 1);
    let cells: Vec<&str> = rows[1].split(',').collect();
    assert_eq!(
        cells[cells.len() - 2],
        format!("{:.6}", c.depth),
        "{}",
        rows[1]
    );
    // reaching at chest height, upright
    assert_eq!(cells[cells.len() - 1], "upright", "{}", rows[1]);
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("<h2>Worker</h2>") && html.contains("RULA (blue"));
    assert!(html.contains("The worst posture (RULA ") && html.contains("<title>trunk</title>"));
}

#[test]
fn without_a_worker_nothing_changes() {
    let (cell, run) = run(&scene(1000.0, ""));
    assert!(run.worker.is_none());
    assert!(cell.worker_series().is_empty());
    let v = Verdict::judge(&run, None, Stage::Final);
    assert!(v.worker.is_empty());
    let json = serde_json::to_value(&v).unwrap();
    assert!(json.get("worker").is_none());
}

#[test]
fn bad_worker_fields_are_named() {
    for (bad, field) in [
        ("population = \"child 5\"", "worker.population"),
        (
            "population = \"female 5\"\npercentile = 5",
            "worker.percentile",
        ),
        (
            "population = \"male\"\npercentile = 120",
            "worker.percentile",
        ),
        (
            "population = \"male\"\nposture = \"kneeling\"",
            "worker.posture",
        ),
        (
            "population = \"male\"\ncoupling = \"sticky\"",
            "worker.coupling",
        ),
        ("population = \"male\"\nfacing = [0, 0, 1]", "worker.facing"),
        (
            "population = \"male\"\nposition = \"there\"",
            "worker.position",
        ),
    ] {
        let text = scene(1000.0, &format!("[worker]\n{bad}\n"));
        let e = load_scene_str(&text, "bad.toml").unwrap_err().to_string();
        assert!(e.contains(field), "{bad}: {e}");
    }
}

/// The worker is part of the workcell's state: a replay of the log, and a checkpoint
/// restored mid-study, give the same posed instants bit for bit (explicit and static).
#[test]
fn the_worker_replays_and_restores_bit_for_bit() {
    use pliant_assembly::workcell::replay::replay_log_of;
    use pliant_assembly::{run_timeline, NoObserver, Timeline, WorkcellOptions};
    let text = scene(1500.0, "[worker]\npopulation = \"female 50\"\n");
    let s = load_scene_str(&text, "worker.toml").unwrap();
    for solver in [SolverKind::Static, SolverKind::Explicit] {
        let options = WorkcellOptions {
            solver: Some(solver),
            initial_loads: false,
            ..Default::default()
        };
        let mut live = s.workcell(options).unwrap();
        let half = s.timeline.actions.len() - 1;
        let first = Timeline {
            actions: s.timeline.actions[..half].to_vec(),
        };
        let rest = Timeline {
            actions: s.timeline.actions[half..].to_vec(),
        };
        run_timeline(&mut live, &first, &mut NoObserver).unwrap();
        let saved = live.checkpoint();
        run_timeline(&mut live, &rest, &mut NoObserver).unwrap();
        assert!(live.worker_series().len() > 10, "{solver}");
        let mut again = s.workcell(options).unwrap();
        replay_log_of(&live, &mut again).unwrap();
        assert_eq!(again.worker_series(), live.worker_series(), "{solver}");
        assert_eq!(again.summary().worker, live.summary().worker);
        let end = live.worker_series().to_vec();
        live.restore(&saved).unwrap();
        run_timeline(&mut live, &rest, &mut NoObserver).unwrap();
        assert_eq!(live.worker_series(), &end[..], "{solver}");
    }
}
