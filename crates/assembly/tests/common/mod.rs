//! Library hoses of the dissertation (table 3.2–3.4) for the fastener tests, typed out.

use pliant_core::{Material, Section};

/// Library hose 3 (coolant hose, d 27/35 mm, E_t 6.9442 MPa, E_c 8.6913 MPa, ν 0.49).
pub fn hose3() -> (Material, Section) {
    (
        Material {
            e_tension: 6.9442e6,
            e_compression: 8.6913e6,
            e_bending: None,
            poisson: 0.49,
            density: 1100.0,
        },
        Section::new(0.027, 0.035),
    )
}
