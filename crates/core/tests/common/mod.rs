//! What several test files share.

use glam::DVec3;

/// Deterministic pseudo-random numbers in [0, 1).
#[allow(dead_code)]
pub struct Lcg(pub u64);
#[allow(dead_code)]
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn vec(&mut self) -> DVec3 {
        DVec3::new(self.next(), self.next(), self.next())
    }
}

/// Library hose 1 (dissertation table 3.3: oil return hose, d 10/16 mm).
#[allow(dead_code)]
pub fn hose1_material() -> pliant_core::Material {
    pliant_core::Material {
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

/// A straight hose of library hose 1 from `from` to `to` in `n` elements.
#[allow(dead_code)]
pub fn straight_hose1(name: &str, from: DVec3, to: DVec3, n: usize) -> pliant_core::HoseSpec {
    pliant_core::HoseSpec {
        name: name.into(),
        material: hose1_material(),
        nodes: (0..=n)
            .map(|i| from + (to - from) * (i as f64 / n as f64))
            .collect(),
        sections: vec![pliant_core::Section::new(0.010, 0.016)],
        normal_hint: None,
    }
}
