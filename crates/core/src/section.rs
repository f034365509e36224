//! Cross-sections (SPEC M2, S3): a circular tube by default — area, second moments and
//! mass from its diameters and the material — with any of EA, EI₁, EI₂, GJ and the mass
//! per length given directly instead, for cables, flat ribbons and bundles whose
//! stiffness is not that of a solid tube.
//!
//! Section axes: axis 1 is the node frame's y axis, axis 2 its z axis (the hose's
//! `normal_hint` sets axis 1 at the first node; the rest-shape frames carry it along the
//! hose by parallel transport). EI₁ resists bending *about* axis 1, EI₂ about axis 2.

use crate::Material;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Circular tube cross-section, diameters in metres (the contact envelope and, unless
/// [`Section::given`] says otherwise, the source of stiffness and mass).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// Inner diameter d_i \[m\] (0 for a solid rod).
    pub d_inner: f64,
    /// Outer diameter d_a \[m\].
    pub d_outer: f64,
    /// Stiffness and mass given directly (each `None` → from the tube and the material).
    #[serde(default)]
    pub given: GivenStiffness,
}

/// Section properties given directly instead of from the tube and the material (S3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct GivenStiffness {
    /// Axial stiffness EA \[N\], the same in tension and compression.
    pub axial: Option<f64>,
    /// Bending stiffnesses EI₁ (about section axis 1 = y) and EI₂ (about axis 2 = z)
    /// \[N·m²\].
    pub bending: [Option<f64>; 2],
    /// Torsional stiffness GJ \[N·m²\].
    pub torsion: Option<f64>,
    /// Mass per length μ \[kg/m\].
    pub mass_per_length: Option<f64>,
}

impl GivenStiffness {
    /// Whether anything is given.
    pub fn any(&self) -> bool {
        *self != GivenStiffness::default()
    }

    /// Each given value with its name, for checks.
    pub fn named(&self) -> [(&'static str, Option<f64>); 5] {
        [
            ("EA", self.axial),
            ("EI1", self.bending[0]),
            ("EI2", self.bending[1]),
            ("GJ", self.torsion),
            ("mass per length", self.mass_per_length),
        ]
    }
}

/// What an element needs of its section: stiffnesses and inertia per length, resolved
/// from a [`Section`] and a [`Material`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionProperties {
    /// E_t·A \[N\], used when stretched.
    pub axial_tension: f64,
    /// E_c·A \[N\], used when shortened.
    pub axial_compression: f64,
    /// EI₁, EI₂ \[N·m²\] (about section axes 1 = y and 2 = z).
    pub bending: [f64; 2],
    /// G·J \[N·m²\].
    pub torsion: f64,
    /// μ = ρ·A \[kg/m\].
    pub mass_per_length: f64,
    /// Rotary inertia per length about a transverse axis, ρ·I [kg·m]: for a tube ρ I; for a
    /// section with given stiffness μ·max(I/A, EI/EA) (I/A of the tube envelope, EI the
    /// larger bending stiffness) — so that the lumped rotary inertia's floor
    /// ([`crate::rod::mass::half_element_mass`]) keeps rotations from shrinking the time step.
    pub rotary_inertia_per_length: f64,
}

impl SectionProperties {
    /// The properties of `section` made of `material` (SPEC M2, M3; given values win).
    pub fn of(section: &Section, material: &Material) -> Self {
        let area = section.area();
        let i = section.second_moment();
        let e_b = material.bending_modulus();
        let g = section.given;
        let (axial_tension, axial_compression) = match g.axial {
            Some(ea) => (ea, ea),
            None => (material.e_tension * area, material.e_compression * area),
        };
        let bending = [
            g.bending[0].unwrap_or(e_b * i),
            g.bending[1].unwrap_or(e_b * i),
        ];
        let mass_per_length = g.mass_per_length.unwrap_or(material.density * area);
        let rotary_inertia_per_length = if g.any() {
            let stiff = bending[0].max(bending[1]) / axial_tension;
            mass_per_length * (i / area).max(stiff)
        } else {
            material.density * i
        };
        Self {
            axial_tension,
            axial_compression,
            bending,
            torsion: g
                .torsion
                .unwrap_or(material.shear_modulus() * section.polar_moment()),
            mass_per_length,
            rotary_inertia_per_length,
        }
    }
}

impl Section {
    pub fn new(d_inner: f64, d_outer: f64) -> Self {
        Self {
            d_inner,
            d_outer,
            given: GivenStiffness::default(),
        }
    }

    /// Area A = π/4 (d_a² − d_i²) \[m²\].
    pub fn area(&self) -> f64 {
        PI / 4.0 * (self.d_outer.powi(2) - self.d_inner.powi(2))
    }

    /// Second moment of area I = π/64 (d_a⁴ − d_i⁴) \[m⁴\].
    pub fn second_moment(&self) -> f64 {
        PI / 64.0 * (self.d_outer.powi(4) - self.d_inner.powi(4))
    }

    /// Polar moment J = 2 I \[m⁴\].
    pub fn polar_moment(&self) -> f64 {
        2.0 * self.second_moment()
    }

    /// Outer radius \[m\].
    pub fn outer_radius(&self) -> f64 {
        0.5 * self.d_outer
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tube_has_the_textbook_stiffness_and_given_values_win() {
        let mat = Material::isotropic(10e6, 0.5 - 1e-9, 1000.0);
        let tube = Section::new(0.01, 0.02);
        let p = SectionProperties::of(&tube, &mat);
        assert!((p.bending[0] - 10e6 * tube.second_moment()).abs() < 1e-9);
        assert_eq!(p.bending[0], p.bending[1]);
        assert!((p.mass_per_length - 1000.0 * tube.area()).abs() < 1e-12);
        let mut ribbon = tube;
        ribbon.given.bending = [Some(0.01), Some(0.5)];
        ribbon.given.mass_per_length = Some(0.2);
        let r = SectionProperties::of(&ribbon, &mat);
        assert_eq!(r.bending, [0.01, 0.5]);
        assert_eq!(r.mass_per_length, 0.2);
        assert_eq!(r.axial_tension, p.axial_tension);
        assert!(r.rotary_inertia_per_length >= 0.2 * 0.5 / r.axial_tension);
    }
}
