//! Sleeping hoses (SPEC I6): a hose at rest that nothing moves is frozen and costs no
//! element evaluations; a moving support or a touching hose wakes it.

use glam::DVec3;
use pliant_core::integrators::explicit::step;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::sleep::SLEEP_AFTER_STEPS;
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, State, WorldSpec};

fn hose(name: &str, y: f64, z: f64) -> HoseSpec {
    HoseSpec {
        name: name.into(),
        material: Material::isotropic(12e6, 0.49, 940.0),
        nodes: (0..=10)
            .map(|i| DVec3::new(0.05 * i as f64, y, z))
            .collect(),
        sections: vec![Section::new(0.010, 0.016)],
        normal_hint: Some(DVec3::Y),
    }
}

/// Two hoses clamped at both ends, one above the other; damped so they come to rest.
fn world() -> (Model, State) {
    let model = Model::build(&WorldSpec {
        hoses: vec![hose("low", 0.0, 0.0), hose("high", 0.0, 0.05)],
        rigid_parts: vec![],
        settings: SimSettings {
            damping_mass: 20.0,
            ..Default::default()
        },
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    for &i in &[0, 10, 11, 21] {
        state.loads.add(LoadCase::Fix(Fix {
            node: i,
            position: state.x[i],
            orientation: state.q[i],
        }));
    }
    state.sleep.enabled = true;
    (model, state)
}

#[test]
fn a_hose_at_rest_sleeps_and_stays_put() {
    let (model, mut state) = world();
    let mut slept_at = None;
    for k in 0..200_000u64 {
        step(&model, &mut state);
        if state.sleep.sleeping() == 2 {
            slept_at = Some(k);
            break;
        }
    }
    let k = slept_at.expect("both hoses fall asleep once they sag to rest");
    assert!(k >= SLEEP_AFTER_STEPS as u64);
    let frozen = state.x.clone();
    for _ in 0..1000 {
        step(&model, &mut state);
    }
    assert_eq!(state.x, frozen, "sleeping hoses do not move");
    assert!(state.v.iter().all(|v| *v == DVec3::ZERO));
}

#[test]
fn a_moving_support_wakes_its_hose_and_a_touching_hose_wakes_the_other() {
    let (model, mut state) = world();
    while state.sleep.sleeping() < 2 {
        step(&model, &mut state);
        assert!(state.time < 60.0, "hoses never slept");
    }
    // a hand grips the upper hose's middle where it lies and pushes it down onto the
    // lower hose at 0.1 m/s
    let grip = state.loads.add(LoadCase::Fix(Fix {
        node: 16,
        position: state.x[16],
        orientation: state.q[16],
    }));
    let start = state.x[16];
    let mut woke_high = false;
    let mut woke_low = false;
    for k in 1..=6000 {
        if let Some(LoadCase::Fix(f)) = state.loads.get_mut(grip) {
            f.position = start - DVec3::new(0.0, 0.0, 0.1 * k as f64 * model.time_step);
        }
        step(&model, &mut state);
        woke_high |= !state.sleep.hose_asleep[1];
        if woke_high && !state.sleep.hose_asleep[0] {
            woke_low = true;
            break;
        }
    }
    assert!(woke_high, "moving a support of the upper hose wakes it");
    assert!(
        woke_low,
        "pressing the upper hose onto the lower one wakes the lower one"
    );
}
