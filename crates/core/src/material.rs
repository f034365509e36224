//! Hose material (SPEC M3): bimodular elastic law and density, all SI; a metal may
//! also yield ([`YieldLaw`], SPEC X1), a rubber relax ([`PronyTerm`], SPEC X2), a bundle
//! of wires rub ([`Hysteresis`], SPEC X2).

use serde::{Deserialize, Serialize};

/// Elastic material of a hose wall. All values SI: moduli in Pa, density in kg/m³.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Young's modulus in tension E_t \[Pa\]; used for axial extension.
    pub e_tension: f64,
    /// Young's modulus in compression E_c \[Pa\]; used for axial shortening.
    pub e_compression: f64,
    /// Explicit bending modulus \[Pa\]. `None` → the reduced (bimodular) modulus
    /// E_b = 4 E_t E_c / (√E_t + √E_c)² (SPEC M3).
    pub e_bending: Option<f64>,
    /// Poisson's ratio ν [-]; G = E_b / (2 (1 + ν)).
    pub poisson: f64,
    /// Density ρ [kg/m³].
    pub density: f64,
    /// How the material yields; `None` → elastic for ever.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plasticity: Option<YieldLaw>,
    /// How the moduli relax under held strain, as a Prony series; empty → elastic for
    /// ever. The moduli above are the instantaneous ones.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relaxation: Vec<PronyTerm>,
    /// Friction between the wall's layers or a bundle's wires in bending and torsion;
    /// `None` → no hysteresis.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hysteresis: Option<Hysteresis>,
}

/// Hysteresis in bending and torsion (SPEC X2): a friction moment M per strain
/// component of the element, added to the elastic one and following Dahl's law
/// dM/dκ = (M_s/κ_s) (1 − sgn(κ̇) M/M_s) (Dahl 1976, *AIAA Journal* 14(12); the rate-
/// independent friction model NVIDIA Newton uses for cable bundles), which traces the
/// loop of a wire bundle or a braided hose bent back and forth: the moment saturates at
/// ±M_s over a curvature of a few κ_s after each reversal.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hysteresis {
    /// Dahl's law of each bending component (about both section axes).
    pub bending: DahlLaw,
    /// Dahl's law of the twist rate; `None` → no hysteresis in torsion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion: Option<DahlLaw>,
}

/// One component of [`Hysteresis`]: the friction moment saturates at `moment` over the
/// curvature scale `curvature` (its initial stiffness is `moment / curvature`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct DahlLaw {
    /// Saturated friction moment M_s \[N·m\].
    pub moment: f64,
    /// Curvature (or twist rate) scale κ_s \[1/m\]: M_s/κ_s is the stiffness at reversal.
    pub curvature: f64,
}

/// One term of a relaxing modulus (SPEC X2): every modulus of the wall (E_t, E_c, E_b,
/// G) relaxes as E(t) = E₀ (1 − Σᵢ gᵢ (1 − e^{−t/τᵢ})) under held strain — the
/// generalised Maxwell solid in the Prony form of Simo & Hughes, *Computational
/// Inelasticity* (1998), §10.2, with dimensionless weights gᵢ (Σ gᵢ < 1: the long-term
/// modulus is E₀ (1 − Σ gᵢ)).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PronyTerm {
    /// Relative weight gᵢ of the term (0, 1).
    pub weight: f64,
    /// Relaxation time τᵢ \[s\].
    pub time: f64,
}

/// The relaxation function E(t)/E₀ = 1 − Σᵢ gᵢ (1 − e^{−t/τᵢ}) of `terms` at `t` ≥ 0.
pub fn relaxation_ratio(terms: &[PronyTerm], t: f64) -> f64 {
    1.0 - terms
        .iter()
        .map(|p| p.weight * (1.0 - (-t / p.time).exp()))
        .sum::<f64>()
}

/// Elastic–plastic behaviour of a metal wall (SPEC X1): von Mises yield of the wall's
/// fibres under their normal stress σ and torsional shear stress τ,
/// √(ξ_σ² + 3 ξ_τ²) ≤ σ_y with ξ = stress − back stress, and linear kinematic
/// hardening (Prager): back stresses H ε_p and (H/3) γ_p (Simo & Hughes, *Computational
/// Inelasticity*, 1998, §2.3 and §3.3). Unloading is elastic; the permanent set is the
/// plastic strain left in the fibres ([`crate::rod::fibre_law`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct YieldLaw {
    /// Initial yield stress in uniaxial tension σ_y \[Pa\].
    pub yield_stress: f64,
    /// Linear hardening modulus H \[Pa\]: slope of the uniaxial stress over the plastic
    /// strain (0 → perfectly plastic); the elastic–plastic tangent is E H/(E + H).
    pub hardening_modulus: f64,
}

impl Material {
    /// A material with one modulus E for tension, compression and bending.
    pub fn isotropic(e: f64, poisson: f64, density: f64) -> Self {
        Self {
            e_tension: e,
            e_compression: e,
            e_bending: None,
            poisson,
            density,
            plasticity: None,
            relaxation: Vec::new(),
            hysteresis: None,
        }
    }

    /// Bending modulus: explicit if given, else the reduced modulus of a bimodular
    /// material, E_b = 4 E_t E_c / (√E_t + √E_c)² (SPEC M3).
    pub fn bending_modulus(&self) -> f64 {
        self.e_bending.unwrap_or_else(|| {
            let s = self.e_tension.sqrt() + self.e_compression.sqrt();
            4.0 * self.e_tension * self.e_compression / (s * s)
        })
    }

    /// Shear modulus G = E_b / (2 (1 + ν)), used for torsion.
    pub fn shear_modulus(&self) -> f64 {
        self.bending_modulus() / (2.0 * (1.0 + self.poisson))
    }

    /// Axial modulus for a given elongation sign: E_t when stretched, E_c when shortened.
    pub fn axial_modulus(&self, elongation: f64) -> f64 {
        if elongation >= 0.0 {
            self.e_tension
        } else {
            self.e_compression
        }
    }

    /// Largest modulus, which sets the axial wave speed c = √(E/ρ) (SPEC P4).
    pub fn max_modulus(&self) -> f64 {
        self.e_tension
            .max(self.e_compression)
            .max(self.bending_modulus())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduced_modulus_equals_e_when_equal() {
        let m = Material::isotropic(10e6, 0.49, 1100.0);
        assert!((m.bending_modulus() - 10e6).abs() < 1e-6);
    }

    #[test]
    fn reduced_modulus_lies_between_tension_and_compression() {
        let m = Material {
            e_tension: 11.583e6,
            e_compression: 13.1363e6,
            e_bending: None,
            poisson: 0.49,
            density: 940.0,
            plasticity: None,
            relaxation: Vec::new(),
            hysteresis: None,
        };
        let eb = m.bending_modulus();
        assert!(eb > 11.583e6 && eb < 13.1363e6);
    }
}
