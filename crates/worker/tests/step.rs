//! Stepping (SPEC E1: "the feet kept, or allowed to step"): the closed-form step that
//! brings a target onto the upright straight arm's reach sphere, its limit at 0.4 of
//! stature, no step for targets too high whatever the feet do, and the VR walking step.

use glam::DVec3;
use pliant_worker::{
    body, describe_step, max_step, reach_step, reach_turn, walk_step, Manikin, Placement,
    Population, Sex, Side, STEP_FRACTION, TURN_BEARING,
};

/// The stance `p` moved by `step`.
fn stepped(p: &Placement, step: DVec3) -> Placement {
    Placement {
        position: p.position + step,
        ..*p
    }
}

fn man() -> Manikin {
    let place = Placement::new(DVec3::ZERO, DVec3::X, DVec3::Z).unwrap();
    Manikin::new(
        body(Population::new(Sex::Male, 50.0).unwrap()).unwrap(),
        place,
    )
}

/// A target `v` above the right shoulder, straight ahead of it, `beyond` further than
/// the upright straight arm reaches at that height.
fn target(m: &Manikin, v: f64, beyond: f64) -> DVec3 {
    let b = &m.body;
    let r = b.arm_reach();
    DVec3::new(
        (r * r - v * v).sqrt() + beyond,
        -0.5 * b.dims.shoulder_width,
        b.dims.shoulder_height + v,
    )
}

#[test]
fn a_target_just_beyond_reach_is_reached_after_one_step_of_the_closed_form_length() {
    let m = man();
    let t = target(&m, 0.45, 0.25);
    // with the feet kept even a bent trunk does not reach it
    let kept = m.solve([Some(t), None]);
    assert!(kept.arms[0].residual > 1e-3, "{}", kept.arms[0].residual);
    let step = reach_step(&m.body, &m.placement, Side::Right, t).unwrap();
    // straight ahead by exactly what lies beyond the sphere
    assert!(
        (step - DVec3::new(0.25, 0.0, 0.0)).length() < 1e-12,
        "{step}"
    );
    assert!(step.length() < max_step(&m.body));
    let moved = Manikin::new(
        m.body,
        Placement {
            position: m.placement.position + step,
            ..m.placement
        },
    );
    let p = moved.solve([Some(t), None]);
    assert!(p.arms[0].residual < 1e-4, "{}", p.arms[0].residual);
    assert!(p.trunk.flexion.abs() < 1e-6, "upright: {:?}", p.trunk);
    assert_eq!(
        describe_step(&m.placement, &stepped(&m.placement, step)),
        "0.25 m forward"
    );
}

#[test]
fn a_far_target_takes_the_longest_step_and_stays_out_of_reach() {
    let m = man();
    let t = target(&m, 0.2, 2.0);
    let step = reach_step(&m.body, &m.placement, Side::Right, t).unwrap();
    let longest = STEP_FRACTION * m.body.stature;
    assert!(
        (step - DVec3::new(longest, 0.0, 0.0)).length() < 1e-12,
        "{step}"
    );
    // the grip is short by what the ideal step lacks, less what bending wins
    let moved = Manikin::new(
        m.body,
        Placement {
            position: m.placement.position + step,
            ..m.placement
        },
    );
    let r = moved.solve([Some(t), None]).arms[0].residual;
    assert!(r > 2.0 - longest - 0.6 && r < 2.0 - longest, "{r}");
}

#[test]
fn no_step_within_reach_nor_for_a_target_above_any_reach() {
    let m = man();
    let b = &m.body;
    assert!(reach_step(b, &m.placement, Side::Right, target(&m, 0.3, -0.01)).is_none());
    let overhead = DVec3::new(
        0.3,
        -0.5 * b.dims.shoulder_width,
        b.dims.shoulder_height + b.arm_reach() + 0.01,
    );
    assert!(reach_step(b, &m.placement, Side::Right, overhead).is_none());
}

#[test]
fn a_step_sideways_is_worded_sideways() {
    let m = man();
    let b = &m.body;
    // a target to the left of the left shoulder at its height
    let t = DVec3::new(0.0, 0.5 * b.dims.shoulder_width + b.arm_reach() + 0.1, 1.4);
    let step = reach_step(b, &m.placement, Side::Left, t).unwrap();
    assert_eq!(
        describe_step(&m.placement, &stepped(&m.placement, step)),
        "0.10 m to the left"
    );
    assert!(step.z == 0.0);
}

#[test]
fn the_stance_walks_with_the_headset_beyond_a_lean() {
    let m = man();
    let b = &m.body;
    let head = b.dims.eye_height - b.dims.shoulder_height;
    // eyes where a lean of the manikin puts them, the neck bent or not: no step
    for flexion in [0.0f64, 20.0, 45.0, 80.0] {
        for neck in [-40.0f64, 0.0, 45.0] {
            let t = pliant_worker::TrunkAngles {
                flexion: flexion.to_radians(),
                ..Default::default()
            };
            let gaze = DVec3::new(1.0, 0.0, -neck.to_radians().tan());
            let h = pliant_worker::HeadTarget {
                eyes: DVec3::ZERO,
                gaze,
            };
            let eyes = m.posture_with_head(t, [None; 2], Some(h)).joints.head;
            assert!(
                walk_step(b, &m.placement, eyes).is_none(),
                "{flexion}° {neck}°: {eyes}"
            );
        }
    }
    // upright eyes: a step once they are more than the head's length away
    let eye = b.dims.eye_height;
    assert!(walk_step(b, &m.placement, DVec3::new(0.99 * head, 0.0, eye)).is_none());
    let step = walk_step(b, &m.placement, DVec3::new(-0.3, 0.2, eye)).unwrap();
    assert_eq!(step, DVec3::new(-0.3, 0.2, 0.0));
    // a taller user's eyes: still a step only beyond the head's length
    assert!(walk_step(b, &m.placement, DVec3::new(0.99 * head, 0.0, eye + 0.2)).is_none());
    assert!(walk_step(b, &m.placement, DVec3::new(1.01 * head, 0.0, eye + 0.2)).is_some());
}

#[test]
fn a_target_beside_or_behind_makes_the_worker_turn_to_face_it() {
    let m = man();
    let p = m.placement;
    // within ±45° of the facing: no turn
    assert_eq!(reach_turn(&p, DVec3::new(1.0, 0.99, 1.2)), None);
    assert_eq!(reach_turn(&p, DVec3::new(1.0, -0.99, 0.3)), None);
    // beside: a quarter turn; behind and to the right: the bearing
    let left = reach_turn(&p, DVec3::new(0.0, 1.0, 1.4)).unwrap();
    assert!((left - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "{left}");
    let behind = reach_turn(&p, DVec3::new(-1.0, -1.0, 1.0)).unwrap();
    assert!(
        (behind + 0.75 * std::f64::consts::PI).abs() < 1e-12,
        "{behind}"
    );
    // just past the bound turns, right above the stance does not
    let just = TURN_BEARING + 1e-6;
    assert!(reach_turn(&p, DVec3::new(just.cos(), just.sin(), 1.0)).is_some());
    assert_eq!(reach_turn(&p, DVec3::new(0.0, 0.0, 2.0)), None);
    // the turned stance faces the target; the turn and the step in words
    let turned = p.turned(left);
    assert!(
        (turned.forward - DVec3::Y).length() < 1e-12,
        "{}",
        turned.forward
    );
    assert!((p.turn_to(&turned) - left).abs() < 1e-12);
    assert_eq!(
        describe_step(&p, &turned),
        "in place, turning 90° to the left"
    );
    let there = stepped(&turned, DVec3::new(0.0, 0.3, 0.0));
    assert_eq!(
        describe_step(&p, &there),
        "0.30 m to the left, turning 90° to the left"
    );
    assert_eq!(
        describe_step(&p, &p.turned(-0.25 * std::f64::consts::PI)),
        "in place, turning 45° to the right"
    );
}
