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
