//! The seated worker: the default seat at the ANSUR II popliteal height, the legs on it
//! (thighs horizontal, knees at 90°, feet on the floor), the pelvis fixed on the seat
//! while the trunk bends and the arms reach, the sitting posture classes, and the leg
//! scores of RULA (McAtamney & Corlett 1993, step 11) and REBA (Hignett & McAtamney
//! 2000, table 1) for sitting.

use glam::{DQuat, DVec3};
use pliant_worker::seat::thigh_clearance;
use pliant_worker::{
    body, capsules, popliteal_height, score_posture, Body, Manikin, Placement, Population,
    PostureClass, ScoreOptions, Seat, Segment, Sex, Side,
};

fn man() -> Body {
    body(Population::new(Sex::Male, 50.0).unwrap()).unwrap()
}

fn place() -> Placement {
    Placement::new(DVec3::ZERO, DVec3::X, DVec3::Z).unwrap()
}

/// The table's popliteal heights: ANSUR II mean ± z(p) sd per sex
/// (data/anthropometry.toml: women 0.388 ± 0.021 m, men 0.435 ± 0.023 m).
#[test]
fn popliteal_heights_follow_the_table() {
    let m50 = popliteal_height(Population::new(Sex::Male, 50.0).unwrap()).unwrap();
    let f5 = popliteal_height(Population::new(Sex::Female, 5.0).unwrap()).unwrap();
    assert!((m50 - 0.435).abs() < 1e-12, "{m50}");
    assert!((f5 - (0.388 - 1.644854 * 0.021)).abs() < 1e-6, "{f5}");
    assert_eq!(man().popliteal_height, m50);
    assert_eq!(Seat::for_body(&man()).height, m50);
}

/// On the default seat: the hips a thigh clearance above the seat, the thighs
/// horizontal and forward by the thigh's length, the knees at 90° over the ankles, the
/// ankles at their standing height (feet on the floor); the shoulders as far above the
/// hips as standing.
#[test]
fn the_default_seat_gives_thighs_horizontal_knees_at_right_angles_feet_on_the_floor() {
    for (sex, p) in [(Sex::Female, 5.0), (Sex::Male, 50.0), (Sex::Male, 95.0)] {
        let b = body(Population::new(sex, p).unwrap()).unwrap();
        let seat = Seat::for_body(&b);
        let m = Manikin::seated(b, place(), seat);
        let pose = m.solve([None, None]);
        let j = &pose.joints;
        let d = &b.dims;
        let s = pose.sitting.expect("seated");
        assert!(s.feet_on_floor, "{sex:?} {p}");
        assert!((s.knee_flexion - std::f64::consts::FRAC_PI_2).abs() < 1e-6);
        assert_eq!(s.seat_height, b.popliteal_height);
        for i in 0..2 {
            let hip_z = b.popliteal_height + (d.knee_height - b.popliteal_height);
            assert!((j.hips[i].z - hip_z).abs() < 1e-12);
            assert!(
                (j.knees[i].z - j.hips[i].z).abs() < 1e-12,
                "thigh horizontal"
            );
            let thigh = j.knees[i] - j.hips[i];
            assert!((thigh.x - (d.hip_height - d.knee_height)).abs() < 1e-12);
            assert!(
                (j.ankles[i].z - d.ankle_height).abs() < 1e-9,
                "feet on the floor"
            );
            assert!(
                (j.ankles[i].x - j.knees[i].x).abs() < 1e-6,
                "shank vertical"
            );
        }
        assert!((j.lumbar.z - j.hips[0].z).abs() < 1e-12);
        let shoulder = m.shoulder_upright(Side::Right);
        assert!((shoulder.z - (j.hips[0].z + d.shoulder_height - d.hip_height)).abs() < 1e-12);
        // the legs' capsules follow: thighs from the hips to the knees, shanks down
        let caps = capsules(&b, &pose);
        for c in caps.iter() {
            match c.segment {
                Segment::Thigh(s) => {
                    assert_eq!((c.a, c.b), (j.hips[s.index()], j.knees[s.index()]))
                }
                Segment::Shank(s) => {
                    assert_eq!((c.a, c.b), (j.knees[s.index()], j.ankles[s.index()]))
                }
                _ => {}
            }
        }
        // the seat box: top at the seat height under the hips, not reaching the knees
        let bx = seat.seat_box(&b, &place());
        assert!((bx.centre.z + 0.5 * bx.size.z - seat.height).abs() < 1e-12);
        let front = bx.centre.x + 0.5 * bx.size.x;
        assert!(front > 0.0 && front < j.knees[0].x);
        assert!(thigh_clearance(&b) > 0.0);
    }
}

/// A seat higher than the popliteal height leaves the feet hanging by the difference:
/// RULA's legs score 2 (not supported); REBA's stays 1 (sitting). A lower one keeps the
/// feet on the floor with the shanks forward (knee flexion asin(d / L) below 90°). A seat
/// at or above the standing hips, or not positive, is refused.
#[test]
fn seat_heights_change_the_legs_and_bad_ones_are_refused() {
    let b = man();
    let d = &b.dims;
    let high = Seat::new(&b, b.popliteal_height + 0.05, "worker.seat_height").unwrap();
    let pose = Manikin::seated(b, place(), high).solve([None, None]);
    let s = pose.sitting.unwrap();
    assert!(!s.feet_on_floor);
    assert!((pose.joints.ankles[0].z - (d.ankle_height + 0.05)).abs() < 1e-9);
    let sc = score_posture(&pose, [0.0; 2], &ScoreOptions::default());
    assert_eq!((sc.rula.legs, sc.reba.legs), (2, 1));

    let low = Seat::new(&b, b.popliteal_height - 0.08, "worker.seat_height").unwrap();
    let pose = Manikin::seated(b, place(), low).solve([None, None]);
    let s = pose.sitting.unwrap();
    let shank = d.knee_height - d.ankle_height;
    let drop = shank - 0.08;
    assert!(s.feet_on_floor);
    assert!((s.knee_flexion - (drop / shank).asin()).abs() < 1e-12);
    let ahead = pose.joints.ankles[0].x - pose.joints.knees[0].x;
    assert!((ahead - (shank * shank - drop * drop).sqrt()).abs() < 1e-9);
    let sc = score_posture(&pose, [0.0; 2], &ScoreOptions::default());
    // knee flexion beyond REBA's 30° edge but seated: REBA adds nothing for the knees
    assert!(s.knee_flexion > 30f64.to_radians());
    assert_eq!((sc.rula.legs, sc.reba.legs), (1, 1));

    let limit = d.hip_height - thigh_clearance(&b);
    for bad in [0.0, -0.2, f64::NAN, limit, limit + 0.1] {
        let e = Seat::new(&b, bad, "worker.seat_height")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("worker.seat_height = "), "{bad}: {e}");
    }
    assert!(Seat::new(&b, limit - 1e-3, "s").is_ok());
}

/// A grab point at table height (0.72 m) in front of the seated 50th-percentile man is
/// reached with the trunk upright: class sitting, RULA and REBA legs 1.
#[test]
fn a_seated_worker_reaches_a_table() {
    let b = man();
    let m = Manikin::seated(b, place(), Seat::for_body(&b));
    let target = DVec3::new(0.35, -0.2, 0.72);
    let pose = m.solve([Some(target), None]);
    assert!(pose.arms[0].residual < 1e-4, "{}", pose.arms[0].residual);
    assert!(pose.trunk.flexion.abs() < 1e-3, "{:?}", pose.trunk);
    assert_eq!(PostureClass::of(&pose, DVec3::Z), PostureClass::Sitting);
    let sc = score_posture(&pose, [20.0, 0.0], &ScoreOptions::default());
    assert_eq!((sc.rula.legs, sc.reba.legs), (1, 1));
    // the pelvis does not move: the hips stay on the seat whatever the arms do
    let standing = Manikin::new(b, place()).solve([Some(target), None]);
    assert!(standing.sitting.is_none());
    assert_eq!(pose.joints.hips, m.solve([None, None]).joints.hips);
}

/// The same point 1.2 m further forward is out of reach: the pelvis stays on the seat,
/// the trunk bends as far as its range lets it (class sitting with bent trunk), and the
/// residual is the distance from the target to the nearest grip any trunk rotation
/// within the joint limits leaves, min over the rotations of |T − S| − R (S the right
/// shoulder, R the straight arm's reach): checked by a brute-force search over the
/// ranges of motion, independent of the inverse kinematics' search, to 2 mm (the
/// brute-force grid's resolution).
#[test]
fn a_seated_worker_does_not_reach_a_point_far_beyond_the_table() {
    let b = man();
    let m = Manikin::seated(b, place(), Seat::for_body(&b));
    let target = DVec3::new(0.35 + 1.2, -0.2, 0.72);
    let pose = m.solve([Some(target), None]);
    let r = pose.arms[0].residual;
    let l = &b.limits;
    let lumbar = m.lumbar();
    let d = &b.dims;
    let local = DVec3::new(
        0.0,
        -0.5 * d.shoulder_width,
        d.shoulder_height - d.hip_height,
    );
    let n = 80;
    let mut best = f64::INFINITY;
    for i in 0..=n {
        let flex = -l.trunk_extension + (l.trunk_flexion + l.trunk_extension) * i as f64 / n as f64;
        for j in 0..=n {
            let twist = -l.trunk_twist + 2.0 * l.trunk_twist * j as f64 / n as f64;
            for k in 0..=n {
                let lat = -l.trunk_lateral + 2.0 * l.trunk_lateral * k as f64 / n as f64;
                let q = DQuat::from_rotation_z(twist)
                    * DQuat::from_rotation_x(lat)
                    * DQuat::from_rotation_y(flex);
                let s = lumbar + q * local;
                best = best.min((target - s).length() - b.arm_reach());
            }
        }
    }
    assert!(best > 0.3, "the premise: out of reach by {best}");
    assert!(
        r <= best + 1e-9 && r > best - 2e-3,
        "IK {r}, brute force {best}"
    );
    assert_eq!(
        PostureClass::of(&pose, DVec3::Z),
        PostureClass::SittingBentTrunk
    );
    assert!(pose.trunk.flexion > 20f64.to_radians(), "{:?}", pose.trunk);
    eprintln!(
        "out of reach by {r} m (brute force {best} m), trunk {:?}",
        pose.trunk
    );
}

/// Every class, in order, with its name and words; sitting whatever the arms do.
#[test]
fn sitting_classes() {
    assert_eq!(PostureClass::ALL.len(), 5);
    for (i, c) in PostureClass::ALL.iter().enumerate() {
        assert_eq!(c.index(), i);
    }
    assert_eq!(PostureClass::Sitting.name(), "sitting");
    assert_eq!(PostureClass::SittingBentTrunk.name(), "sitting_bent_trunk");
    assert!(PostureClass::SittingBentTrunk.is_sitting() && !PostureClass::BentTrunk.is_sitting());
    let b = man();
    let m = Manikin::seated(b, place(), Seat::for_body(&b));
    // overhead: standing this is arms above shoulder; seated it is sitting
    let up = m.solve([Some(DVec3::new(0.1, -0.2, 1.55)), None]);
    assert!(up.arms[0].residual < 1e-4);
    assert_eq!(PostureClass::of(&up, DVec3::Z), PostureClass::Sitting);
}
