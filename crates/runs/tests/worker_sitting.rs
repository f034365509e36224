//! A seated worker (`[worker] posture = "sitting"`, docs/worker.md, "Sitting"): the
//! 50th-percentile man on the default seat (his ANSUR II popliteal height) draws the free
//! end of a hose at table height (720 mm), 550 mm in front of the seat and 200 mm to
//! his right, 36 mm towards himself — a push by the ergonomics module's rule. He reaches
//! it with the trunk upright: class sitting at every posed instant, and the push is
//! judged by table 3.7's sitting row (under EN 1005-3: "arm work, sitting, one arm, with
//! trunk support"). The same grab point with the seat 1.2 m further back is out of
//! reach — by the distance no trunk rotation over the seat can close, to 1 µm — and he
//! does not step.

mod support;

use glam::DVec3;
use pliant_assembly::ergonomics::{
    ErgonomicLimits, ErgonomicProfile, LoadKind, Population, Posture,
};
use pliant_assembly::{RunSummary, Stage, Verdict};
use pliant_core::SolverKind;
use pliant_scene::load_scene_str;
use pliant_testkit::scene_text::{
    fix, grab, hose, move_hand, run_for, solver, worker, SceneText, Table,
};
use pliant_worker::{Manikin, PostureClass, Seat};

/// The grab point \[mm\].
const AT: [f64; 3] = [400.0, -200.0, 720.0];

/// The hose from x = 1000 mm (fixed) to the grab point, the seated man at `seat_x` mm,
/// the `[ergonomics]` table `ergonomics`; `draw` whether the hand draws the end 36 mm
/// towards him (else it holds it). The hand grabs the end before the hose can sag.
fn scene(seat_x: f64, ergonomics: Table, draw: bool) -> String {
    let hand = if draw {
        move_hand(0, [-36.0, 0.0, 0.0], 0.2)
    } else {
        run_for(0.2)
    };
    SceneText::mm()
        .with(solver("static"))
        .with(ergonomics)
        .with(
            worker("male 50")
                .text("posture", "sitting")
                .point("position", [seat_x, 0.0, 0.0])
                .point("facing", [1.0, 0.0, 0.0]),
        )
        .with(hose("h", "hose3", [1000.0, AT[1], AT[2]], AT).number("elements", 12.0))
        .with(fix("h", 0))
        .with(grab(0, AT))
        .with(run_for(0.1))
        .with(hand)
        .with(run_for(0.1))
        .into()
}

fn men() -> Table {
    Table::single("ergonomics").text("population", "men")
}

fn run_scene(text: &str) -> (pliant_assembly::Workcell, RunSummary) {
    let s = load_scene_str(text, "sitting.toml").unwrap();
    pliant_runs::run_with(&s, Some(SolverKind::Static)).unwrap()
}

#[test]
fn a_seated_worker_reaches_the_table_and_is_judged_by_the_sitting_rows() {
    let text = scene(-150.0, men(), true);
    let (cell, run) = run_scene(&text);
    let w = run.worker.as_ref().unwrap();
    assert!(w.findings().is_empty(), "{:?}", w.findings());
    assert!(w.reach[0].worst < 1e-3, "{:?}", w.reach);
    assert_eq!(w.seat.map(|s| s.height), Some(w.body.popliteal_height));
    let c = &w.class_instants;
    assert!(c.sitting > 0 && c.sitting == w.instants, "{c:?}");
    assert!(cell
        .worker_series()
        .iter()
        .all(|s| s.posture_class == PostureClass::Sitting));
    // seated with the feet on the floor: both methods' leg scores 1
    let (r, e) = (w.worst_rula.unwrap(), w.worst_reba.unwrap());
    assert_eq!((r.score.legs, e.score.legs), (1, 1));

    // the push against table 3.7's sitting row, men, occasional
    let limits = ErgonomicLimits::builtin().unwrap();
    let duty = ErgonomicProfile::default().duty;
    let sitting = limits.push_limit(Posture::Sitting.push(), Population::Men, duty);
    let standing = limits.push_limit(Posture::Standing.push(), Population::Men, duty);
    assert_ne!(sitting, standing);
    let h = &run.hand_peaks[0];
    assert_eq!(h.worst_kind, Some(LoadKind::Push), "{h:?}");
    assert_eq!(h.worst_class, Some(PostureClass::Sitting));
    assert_eq!(h.worst_limit, sitting);
    let v = Verdict::judge(&run, None, Stage::Final);
    if h.push.magnitude > sitting {
        let line = v
            .reasons
            .iter()
            .find(|r| r.starts_with("hand 0: push of "))
            .unwrap_or_else(|| panic!("{:?}", v.reasons));
        assert!(
            line.contains(&format!(
                "exceeds the limit {sitting:.1} N allowed for sitting (table 3.7, sitting row;"
            )),
            "{line}"
        );
    } else {
        assert!(!v.reasons.iter().any(|r| r.starts_with("hand 0")), "{v:?}");
    }
    eprintln!(
        "push {:.1} N against the sitting row's {sitting:.1} N (standing row {standing:.1} N): {:?}",
        h.push.magnitude, v.reasons
    );
    // summary.json carries the seat and the class, worker.csv each instant's class, the
    // report the seat
    let dir = support::static_outputs(&text, "sitting.toml", &cell, &run);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    let json = &summary["worker"];
    assert_eq!(json["seat"]["height"], w.body.popliteal_height);
    assert_eq!(json["class_instants"]["sitting"], w.instants);
    let csv = std::fs::read_to_string(dir.path().join("worker.csv")).unwrap();
    assert!(
        csv.lines().skip(1).all(|row| row.ends_with(",sitting")),
        "{csv}"
    );
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("seated on a seat 435 mm high"));
    assert!(html.contains(&format!("sitting at {}", w.instants)));

    // under EN 1005-3 the seated class chooses the arm-work row with trunk support
    let en = men().text("standard", "en1005-3");
    let (_, en_run) = run_scene(&scene(-150.0, en, true));
    let zones = &en_run.hand_peaks[0].zones;
    let push = zones.iter().find(|z| z.kind == LoadKind::Push).unwrap();
    assert_eq!(
        push.action,
        "arm work, sitting, one arm, with trunk support"
    );
    assert_eq!(
        push.limit.f_b,
        limits.en1005().basic_force(
            pliant_assembly::ergonomics::En1005Action::ArmTrunkSupport,
            true
        )
    );
}

#[test]
fn the_same_point_1_2_m_further_is_out_of_reach_and_the_seated_worker_does_not_step() {
    let (cell, run) = run_scene(&scene(-1350.0, men(), false));
    let w = run.worker.as_ref().unwrap();
    assert_eq!(w.step_count, 0);
    assert!(w.steps.is_empty());
    let p = w.placement.unwrap();
    assert_eq!(p.position, DVec3::new(-1.35, 0.0, 0.0));
    let reach = &w.reach[0];
    // the hand holds the hose where it grabbed it, still at the end of the run
    let target = cell.hand_records()[0].load.position;
    assert!(
        (target - DVec3::from_array(AT) * 1e-3).length() < 1e-3,
        "{target}"
    );
    // what the seated manikin at that seat leaves (the inverse kinematics, whose far
    // residual crates/worker/tests/sitting.rs checks against a brute-force search)
    let seat = w.seat.unwrap();
    let m = Manikin::seated(w.body, p, seat);
    let expected = m.solve([Some(target), None]).arms[0].residual;
    assert!(
        (reach.worst - expected).abs() < 1e-6,
        "{} vs {expected}",
        reach.worst
    );
    // exactly: the trunk turns within its range until the right shoulder lies on the
    // line from the lumbar joint (fixed on the seat) to the target, which leaves
    // |T − lumbar| − lumbar-to-shoulder − arm, the least any trunk rotation can leave
    let lumbar = m.lumbar();
    let rho = (m.shoulder_upright(pliant_worker::Side::Right) - lumbar).length();
    let bound = (target - lumbar).length() - rho - w.body.arm_reach();
    assert!(bound > 0.2, "the premise: {bound}");
    assert!(
        (reach.worst - bound).abs() < 1e-6,
        "{} vs {bound}",
        reach.worst
    );
    eprintln!(
        "out of reach by {:.9} m (manikin {expected:.9} m, bound {bound:.9} m)",
        reach.worst
    );
    let v = Verdict::judge(&run, None, Stage::Final);
    assert_eq!(v.feasible, Some(false), "{v:?}");
    let mm = format!("{:.0} mm", 1e3 * reach.worst);
    assert!(
        v.reasons
            .iter()
            .any(|r| r.starts_with(&format!("out of reach for the 50th-percentile man by {mm}"))),
        "{:?}",
        v.reasons
    );
    let c = &w.class_instants;
    assert_eq!(c.sitting_bent_trunk, w.instants, "{c:?}");
    assert_eq!(seat, Seat::for_body(&w.body));
}

/// `steps = true` with a seated worker, a seat height while standing, an unknown posture
/// and a seat too high are refused, each naming its field.
#[test]
fn bad_seated_workers_are_refused() {
    let with = |extra: &[(&str, &str)]| -> String {
        let mut t = worker("male 50");
        for (k, v) in extra {
            t = t.inline(k, v);
        }
        SceneText::mm()
            .with(t)
            .with(hose("h", "hose3", [1000.0, AT[1], AT[2]], AT))
            .into()
    };
    for (extra, field) in [
        (
            vec![("posture", "\"sitting\""), ("steps", "true")],
            "worker.steps",
        ),
        (vec![("seat_height", "450")], "worker.seat_height"),
        (vec![("posture", "\"kneeling\"")], "worker.posture"),
        (
            vec![("posture", "\"sitting\""), ("seat_height", "950")],
            "worker.seat_height",
        ),
        (
            vec![("posture", "\"sitting\""), ("seat_height", "0")],
            "worker.seat_height",
        ),
    ] {
        let e = load_scene_str(&with(&extra), "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{extra:?}: {e}");
    }
    assert!(load_scene_str(
        &with(&[("posture", "\"sitting\""), ("seat_height", "450")]),
        "ok.toml"
    )
    .is_ok());
}
