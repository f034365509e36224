//! Small models of the library hoses for the tests of the core and the assembly layer.

use crate::hoses::{hose1_material, hose1_section, hose3};
use glam::DVec3;
use pliant_core::loads::{Fix, LoadCase};
use pliant_core::{HoseSpec, Model, SimSettings, State, WorldSpec};

/// A model of hose 3 in `elements` beams of 25 mm along global X from the origin, with
/// `settings`.
pub fn hose3_along_x(elements: usize, settings: SimSettings) -> Model {
    let (material, section) = hose3();
    Model::build(&WorldSpec {
        hoses: vec![HoseSpec {
            name: "h".into(),
            material,
            nodes: (0..=elements)
                .map(|i| DVec3::X * (0.025 * i as f64))
                .collect(),
            sections: vec![section],
            normal_hint: Some(DVec3::Y),
        }],
        rigid_parts: vec![],
        settings,
    })
    .unwrap()
}

/// A straight hose of library hose 1 called `name` from `from` to `to` in `n` elements.
pub fn straight_hose1(name: &str, from: DVec3, to: DVec3, n: usize) -> HoseSpec {
    HoseSpec {
        name: name.into(),
        material: hose1_material(),
        nodes: (0..=n)
            .map(|i| from + (to - from) * (i as f64 / n as f64))
            .collect(),
        sections: vec![hose1_section()],
        normal_hint: None,
    }
}

/// Fixes each of `nodes` where it is now: its position and orientation in `state`.
pub fn fix_in_place(state: &mut State, nodes: impl IntoIterator<Item = usize>) {
    for node in nodes {
        state.loads.add(LoadCase::Fix(Fix {
            node,
            position: state.x[node],
            orientation: state.q[node],
        }));
    }
}

/// Two straight hoses of library hose 1 crossing at right angles, each of `elements`
/// elements and clamped at its ends: hose "a" along x from the origin to 0.4 m, hose "b"
/// along y under a's middle, `gap` \[m\] between their surfaces (negative: pressed into
/// each other).
pub fn crossing_hoses(gap: f64, elements: usize) -> (Model, State) {
    let a = straight_hose1("a", DVec3::ZERO, DVec3::new(0.4, 0.0, 0.0), elements);
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
        elements,
    );
    let model = Model::build(&WorldSpec {
        hoses: vec![a, b],
        rigid_parts: vec![],
        settings: SimSettings::default(),
    })
    .unwrap();
    let mut state = State::at_rest(&model);
    fix_in_place(&mut state, [0, elements, elements + 1, 2 * elements + 1]);
    (model, state)
}
