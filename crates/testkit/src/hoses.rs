//! Library hoses of the dissertation (tables 3.2–3.4), typed out as core materials and
//! sections, so that a test states the numbers it relies on without loading a scene.

use pliant_core::{Material, Section};

/// Library hose 1 (table 3.3: oil return hose, d_i 10 mm, d_a 16 mm, E_t 11.583 MPa,
/// E_c 13.1363 MPa, ν 0.49, ρ 940 kg/m³): its material.
pub fn hose1_material() -> Material {
    Material {
        e_tension: 11.583e6,
        e_compression: 13.1363e6,
        e_bending: None,
        poisson: 0.49,
        density: 940.0,
        plasticity: None,
        relaxation: Vec::new(),
        hysteresis: None,
    }
}

/// Library hose 1's section (d_i 10 mm, d_a 16 mm).
pub fn hose1_section() -> Section {
    Section::new(0.010, 0.016)
}

/// Library hose 1: material and section.
pub fn hose1() -> (Material, Section) {
    (hose1_material(), hose1_section())
}

/// Library hose 3 (coolant hose, d_i 27 mm, d_a 35 mm, E_t 6.9442 MPa, E_c 8.6913 MPa,
/// ν 0.49, ρ 1100 kg/m³): material and section.
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
