//! The anthropometry and the manikin's inverse kinematics: statures per percentile from
//! the table, reach limits, targets reached within a tenth of a millimetre, residuals
//! for targets out of reach, joint limits kept, determinism.

use glam::DVec3;
use pliant_worker::{assign_hands, body, stature, Manikin, Placement, Population, Sex, Side};

fn population(sex: Sex, p: f64) -> Population {
    Population::new(sex, p).unwrap()
}

fn manikin(sex: Sex, p: f64) -> Manikin {
    let place = Placement::new(DVec3::ZERO, DVec3::X, DVec3::Z).unwrap();
    Manikin::new(body(population(sex, p)).unwrap(), place)
}

/// ANSUR II means at the 50th percentile; the 5th and 95th at mean ∓ 1.6449 sd
/// (data/anthropometry.toml: women 1.6285 ± 0.0642 m, men 1.7562 ± 0.0686 m).
#[test]
fn statures_follow_the_table() {
    let f5 = stature(population(Sex::Female, 5.0)).unwrap();
    let m50 = stature(population(Sex::Male, 50.0)).unwrap();
    let m95 = stature(population(Sex::Male, 95.0)).unwrap();
    assert!((f5 - (1.6285 - 1.644854 * 0.0642)).abs() < 1e-6, "{f5}");
    assert!((m50 - 1.7562).abs() < 1e-9, "{m50}");
    assert!((m95 - (1.7562 + 1.644854 * 0.0686)).abs() < 1e-6, "{m95}");
    let b = body(population(Sex::Male, 50.0)).unwrap();
    assert!((b.dims.shoulder_height - 0.818 * m50).abs() < 1e-12);
    assert!((b.dims.upper_arm - 0.186 * m50).abs() < 1e-12);
}

#[test]
fn populations_are_read_and_refused_with_reasons() {
    let p = Population::parse("worker.population", "female 5").unwrap();
    assert_eq!(p.sex, Sex::Female);
    assert_eq!(p.describe(), "the 5th-percentile woman");
    assert_eq!(
        Population::parse("w", "male 95").unwrap().describe(),
        "the 95th-percentile man"
    );
    assert_eq!(
        Population::parse("w", "male 1").unwrap().describe(),
        "the 1st-percentile man"
    );
    for bad in [
        "female", "child 5", "male 0", "male 100", "male x", "male 5 6",
    ] {
        let e = Population::parse("worker.population", bad)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("worker.population = \""), "{bad}: {e}");
    }
    assert!(Placement::new(DVec3::ZERO, DVec3::Z, DVec3::Z).is_err());
    assert!(Placement::new(DVec3::NAN, DVec3::X, DVec3::Z).is_err());
}

/// Targets within reach are reached to 0.1 mm: in front at chest height, to the side,
/// low in front (the trunk bends), overhead.
#[test]
fn reachable_targets_are_reached() {
    for (sex, p) in [(Sex::Female, 5.0), (Sex::Male, 50.0), (Sex::Male, 95.0)] {
        let m = manikin(sex, p);
        let h = m.body.stature;
        let targets = [
            DVec3::new(0.4 * h * 0.5, -0.1, 0.7 * h),
            DVec3::new(0.1, -0.45 * h * 0.5, 0.75 * h),
            DVec3::new(0.35, -0.1, 0.45 * h),
            DVec3::new(0.05, -0.15, 1.05 * h),
        ];
        for t in targets {
            let pose = m.solve([Some(t), None]);
            let arm = &pose.arms[Side::Right.index()];
            assert!(
                arm.residual < 1e-4,
                "{sex:?} {p}: {t} residual {}",
                arm.residual
            );
            assert!((arm.grip - t).length() < 1e-4, "{t}: grip {}", arm.grip);
            let l = &m.body.limits;
            assert!(pose.trunk.flexion <= l.trunk_flexion + 1e-12);
            assert!(pose.trunk.flexion >= -l.trunk_extension - 1e-12);
            assert!(pose.trunk.twist.abs() <= l.trunk_twist + 1e-12);
            assert!(arm.elbow_flexion <= l.elbow_flexion + 1e-9);
            // the arm's links keep their lengths
            let b = &m.body;
            assert!(((arm.elbow - arm.shoulder).length() - b.dims.upper_arm).abs() < 1e-9);
            assert!(((arm.wrist - arm.elbow).length() - b.dims.forearm).abs() < 1e-9);
        }
    }
}

/// A comfortable target leaves the trunk upright; a low one bends it forward.
#[test]
fn the_trunk_bends_only_when_it_must() {
    let m = manikin(Sex::Male, 50.0);
    let h = m.body.stature;
    let near = m.solve([Some(DVec3::new(0.35, -0.2, 0.7 * h)), None]);
    assert!(near.trunk.flexion.abs() < 1e-3, "{:?}", near.trunk);
    let low = m.solve([Some(DVec3::new(0.4, -0.2, 0.25 * h)), None]);
    assert!(low.trunk.flexion > 30f64.to_radians(), "{:?}", low.trunk);
    assert!(low.arms[0].residual < 1e-4, "{low:?}");
}

/// Overhead out of reach: upright, the residual is the target's height above the highest
/// grip the straight, vertical arm gives; bending sideways (which lifts the far
/// shoulder) may win a little more but not all — 1.9 m is beyond the 5th-percentile
/// woman and within the 95th-percentile man's reach.
#[test]
fn out_of_reach_reports_the_distance() {
    let f5 = manikin(Sex::Female, 5.0);
    let target = DVec3::new(0.0, -0.5 * f5.body.dims.shoulder_width, 1.9);
    let pose = f5.solve([Some(target), None]);
    let highest = f5.body.dims.shoulder_height + f5.body.arm_reach();
    let expected = 1.9 - highest;
    assert!(expected > 0.03, "the test's premise: {highest}");
    let upright = f5.posture(Default::default(), [Some(target), None]);
    assert!((upright.arms[0].residual - expected).abs() < 1e-9);
    let r = pose.arms[0].residual;
    assert!(
        r <= expected && r > 0.5 * expected,
        "residual {r}, upright {expected}"
    );
    let m95 = manikin(Sex::Male, 95.0);
    let t95 = DVec3::new(0.0, -0.5 * m95.body.dims.shoulder_width, 1.9);
    assert!(m95.solve([Some(t95), None]).arms[0].residual < 1e-4);
    // far in front at shoulder height: beyond arm plus the trunk's bend
    let far = f5.solve([Some(DVec3::new(2.0, -0.2, 1.2)), None]);
    assert!(far.arms[0].residual > 0.5, "{}", far.arms[0].residual);
}

/// Same targets, same posture, bit for bit; two targets go to the arm on their side.
#[test]
fn deterministic_and_sided() {
    let m = manikin(Sex::Female, 50.0);
    let place = m.placement;
    let (r, l) = (DVec3::new(0.4, -0.3, 0.9), DVec3::new(0.5, 0.25, 1.1));
    let hands = assign_hands(&place, &[l, r]);
    assert_eq!(hands, [Some(r), Some(l)]);
    assert_eq!(assign_hands(&place, &[l]), [None, Some(l)]);
    let a = m.solve(hands);
    let b = m.solve(hands);
    assert_eq!(format!("{a:?}"), format!("{b:?}"));
    assert!(a.worst_residual() < 1e-4, "{a:?}");
}

/// A placement facing −y: the same reach, rotated.
#[test]
fn placement_rotates_the_manikin() {
    let body = body(population(Sex::Male, 50.0)).unwrap();
    let place = Placement::new(
        DVec3::new(1.0, 2.0, 0.5),
        DVec3::new(0.0, -3.0, 0.0),
        DVec3::Z,
    )
    .unwrap();
    let m = Manikin::new(body, place);
    let s = m.shoulder_upright(Side::Right);
    // facing −y, the right is −x
    assert!(s.x < 1.0 && (s.z - (0.5 + body.dims.shoulder_height)).abs() < 1e-12);
    let t = place.point(DVec3::new(0.45, -0.2, 1.0));
    let pose = m.solve([Some(t), None]);
    assert!(pose.arms[0].residual < 1e-4);
}

/// The capsules come in the order of `SEGMENTS`, each with its segment's radius.
#[test]
fn capsules_follow_the_segment_list() {
    let m = manikin(Sex::Female, 5.0);
    let posture = m.solve([Some(DVec3::new(0.4, -0.2, 1.2)), None]);
    let caps = pliant_worker::capsules(&m.body, &posture);
    for (c, s) in caps.iter().zip(pliant_worker::SEGMENTS) {
        assert_eq!(c.segment, s);
        assert_eq!(c.radius, s.radius(&m.body.radii), "{}", s.name());
    }
}

/// A headset's eyes where the manikin's are at 30° of trunk flexion, looking ahead and
/// down: the search bends the trunk to put his eyes there and the head looks along the
/// headset's gaze.
#[test]
fn a_head_target_bends_the_trunk_to_the_headset() {
    use pliant_worker::{HeadTarget, TrunkAngles};
    let m = manikin(Sex::Male, 50.0);
    let gaze = DVec3::new(1.0, 0.0, -0.5);
    let bent = TrunkAngles {
        flexion: 30f64.to_radians(),
        lateral: 0.0,
        twist: 0.0,
    };
    let aim = |eyes| Some(HeadTarget { eyes, gaze });
    let eyes = m
        .posture_with_head(bent, [None, None], aim(DVec3::ZERO))
        .joints
        .head;
    let p = m.solve_with_head([None, None], aim(eyes));
    assert!(
        (p.joints.head - eyes).length() < 1e-3,
        "{:?}",
        p.joints.head
    );
    assert!(
        (p.trunk.flexion - bent.flexion).abs() < 1f64.to_radians(),
        "{:?}",
        p.trunk
    );
    assert_eq!(
        p,
        m.solve_with_head([None, None], aim(eyes)),
        "deterministic"
    );
    // the upright eyes, looking 45° to the left: the neck turns, the trunk stays upright
    let upright = m.posture(TrunkAngles::default(), [None, None]).joints.head;
    let p = m.solve_with_head(
        [None, None],
        Some(HeadTarget {
            eyes: upright,
            gaze: DVec3::new(1.0, 1.0, 0.0),
        }),
    );
    assert_eq!(p.trunk, TrunkAngles::default());
    assert!(
        (p.neck_twist - 45f64.to_radians()).abs() < 1e-12,
        "{}",
        p.neck_twist
    );
    assert!(p.neck_flexion.abs() < 1e-12);
}
