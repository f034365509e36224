//! The static line search's first-touch step ([`first_touch_step`]): the fraction of a
//! Newton increment at which two hoses apart now would touch, linearised at their closest
//! points. Two straight hoses crossing at right angles with a gap between their surfaces,
//! the upper one's free nodes moved straight down: every pair closes at the increment's
//! rate, the crossing pair first (a pair farther apart closes more slowly), so the step is
//! gap / rate; moved apart, no pair closes.

use nalgebra::Vector6;
use pliant_core::newton::system::{first_touch_step, NewtonSystem};
use pliant_core::{Model, State};
use pliant_testkit::models::crossing_hoses;

const ELEMENTS: usize = 20;

/// The crossing hoses ([`crossing_hoses`]) with the hose–hose candidates of one
/// assembly, and which nodes are prescribed (the clamped ends).
fn crossing(gap: f64) -> (Model, State, Vec<bool>) {
    let (model, mut state) = crossing_hoses(gap, ELEMENTS);
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
