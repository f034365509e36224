//! Library hoses of the dissertation (table 3.2–3.4) for the fastener tests, typed out.
// each test crate uses a part of these helpers
#![allow(dead_code)]

use glam::DVec3;
use pliant_core::{HoseSpec, Material, Model, Section, SimSettings, WorldSpec};

/// Library hose 3 (coolant hose, d 27/35 mm, E_t 6.9442 MPa, E_c 8.6913 MPa, ν 0.49).
pub fn hose3() -> (Material, Section) {
    (
        Material {
            e_tension: 6.9442e6,
            e_compression: 8.6913e6,
            e_bending: None,
            poisson: 0.49,
            density: 1100.0,
            plasticity: None,
            relaxation: Vec::new(),
            hysteresis: None,
        },
        Section::new(0.027, 0.035),
    )
}

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
