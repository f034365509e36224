//! The worker in a snapshot (docs/protocol.md): a seated worker's snapshot carries the
//! sitting class and the seat as a box under the pelvis, its top at the seat height, and
//! thigh capsules running level from the hips to the knees; a standing worker's has no
//! seat.

use glam::DVec3;
use pliant_assembly::worker::WorkerNow;
use pliant_server::snapshot::WorkerSnapshot;
use pliant_worker::{
    body, score_posture, Manikin, Placement, Population, PostureClass, ScoreOptions, Seat, Sex,
    CAPSULE_COUNT, SEGMENTS,
};

fn now(m: &Manikin) -> WorkerNow {
    let posture = m.solve([Some(DVec3::new(0.4, -0.2, 0.72)), None]);
    WorkerNow {
        time: 0.5,
        placement: m.placement,
        steps: 0,
        posture,
        hand: [Some(0), None],
        scores: score_posture(&posture, [0.0; 2], &ScoreOptions::default()),
        class: PostureClass::of(&posture, m.placement.up),
        contacts: [None; CAPSULE_COUNT],
    }
}

#[test]
fn a_seated_worker_s_snapshot_carries_the_seat_and_the_class() {
    let b = body(Population::new(Sex::Female, 50.0).unwrap()).unwrap();
    let place = Placement::new(DVec3::new(1.0, 2.0, 0.0), DVec3::Y, DVec3::Z).unwrap();
    let seat = Seat::for_body(&b);
    let seated = Manikin::seated(b, place, seat);
    let v = serde_json::to_value(WorkerSnapshot::of(&b, Some(seat), &now(&seated))).unwrap();
    assert_eq!(v["posture_class"], "sitting");
    let f = |key: &str| -> Vec<f64> {
        v["seat"][key]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (centre, size, up) = (f("centre"), f("size"), f("up"));
    assert_eq!(f("forward"), vec![0.0, 1.0, 0.0]);
    assert_eq!(up, vec![0.0, 0.0, 1.0]);
    assert!((centre[2] + 0.5 * size[2] - seat.height).abs() < 1e-12);
    assert!((centre[0] - 1.0).abs() < 1e-12);
    let caps: Vec<f64> = v["capsules"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    for (i, s) in SEGMENTS.iter().enumerate() {
        if let pliant_worker::Segment::Thigh(_) = s {
            let c = &caps[6 * i..6 * i + 6];
            assert!((c[2] - c[5]).abs() < 1e-12, "thigh level: {c:?}");
            assert!(c[2] > seat.height, "above the seat: {c:?}");
        }
    }

    let standing = Manikin::new(b, place);
    let v = serde_json::to_value(WorkerSnapshot::of(&b, None, &now(&standing))).unwrap();
    assert!(v.get("seat").is_none(), "{v}");
    assert_ne!(v["posture_class"], "sitting");
}
