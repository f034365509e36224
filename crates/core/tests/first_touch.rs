//! The static line search's first-touch step ([`first_touch_step`]): the fraction of a
//! Newton increment at which two hoses apart now would touch, linearised at their closest
//! points. Two straight hoses crossing at right angles with a gap between their surfaces,
//! the upper one's free nodes moved straight down: every pair closes at the increment's
//! rate, the crossing pair first (a pair farther apart closes more slowly), so the step is
//! gap / rate; moved apart, no pair closes.

use glam::DVec3;
use nalgebra::Vector6;
use pliant_core::newton::system::{first_touch_step, NewtonSystem};
use pliant_core::{Model, SimSettings, State, WorldSpec};
use pliant_testkit::models::{fix_in_place, straight_hose1};

const ELEMENTS: usize = 20;

/// Hose A along x, hose B along y under A's middle, `gap` between their surfaces; both
/// clamped at their ends; the hose–hose candidates of one assembly.
fn crossing(gap: f64) -> (Model, State, Vec<bool>) {
    let a = straight_hose1("a", DVec3::ZERO, DVec3::new(0.4, 0.0, 0.0), ELEMENTS);
    let probe = Model::build(&WorldSpec {
        hoses: vec![a.clone()],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    let z = -(2.0 * probe.radius[0] + gap);
    let b = straight_hose1(
        "b",
        DVec3::new(0.2, -0.2, z),
        DVec3::new(0.2, 0.2, z),
        ELEMENTS,
    );
    let model = Model::build(&WorldSpec {
        hoses: vec![a, b],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    fix_in_place(&mut state, [0, ELEMENTS, ELEMENTS + 1, 2 * ELEMENTS + 1]);
    let mut sys = NewtonSystem::new(&model).unwrap();
    sys.set_prescribed(&model, &state, 0.0);
    sys.assemble(&model, &mut state, 0.0);
    let mut prescribed = vec![false; state.x.len()];
    for i in [0, ELEMENTS, ELEMENTS + 1, 2 * ELEMENTS + 1] {
        prescribed[i] = true;
    }
    (model, state, prescribed)
}

/// Hose A's nodes moved by `dz` along z, hose B's kept.
fn a_moved(state: &State, dz: f64) -> Vec<Vector6<f64>> {
    (0..state.x.len())
        .map(|i| {
            let z = if i <= ELEMENTS { dz } else { 0.0 };
            Vector6::new(0.0, 0.0, z, 0.0, 0.0, 0.0)
        })
        .collect()
}

#[test]
fn a_hose_moved_onto_another_touches_it_at_gap_over_rate() {
    let gap = 0.5e-3;
    let (model, state, prescribed) = crossing(gap);
    assert!(
        !state.hose_contact.candidates.is_empty(),
        "the hoses 0.5 mm apart are candidates"
    );
    let down = 4e-3;
    let s = first_touch_step(&model, &state, &a_moved(&state, -down), &prescribed);
    let exact = gap / down;
    assert!(
        (s - exact).abs() <= 1e-9 * exact,
        "first touch at {s} of the step, exact {exact}"
    );
    let up = first_touch_step(&model, &state, &a_moved(&state, down), &prescribed);
    assert_eq!(up, f64::INFINITY, "moved apart: no pair closes");
}
