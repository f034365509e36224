//! What an element's cross-section carries at the element's middle: the bending moment
//! and torque of its law (elastic, yielding, relaxing or rubbing) with the curvature
//! and twist rate it reads — the moment–curvature pair of every element of a state, for
//! output (e.g. the springback a metal line will show when let go, M/EI element by
//! element: Lubliner 1990, "Plasticity Theory", §4.1, elastic unloading).
//!
//! The element's internal loads are self-equilibrated (f_a + f_b = 0), so the section
//! moment at its middle is the mean of what its two ends carry:
//! M = (m_a − m_b)/2, m_a and m_b the moments the element exerts on its nodes — the
//! moment of the uniform-curvature mode, the antisymmetric mode's end moments cancelling
//! (Przemieniecki 1968, "Theory of Matrix Structural Analysis", §5.4: the beam's end
//! moments are the midspan moment ± half the shear times the length). Of that mean, the
//! part the axial force N puts in through the element's shallow-arch strain
//! ([`crate::rod::element`]: ∂(N l₀ ε)/∂θ = N l₀ (4θ_a − θ_b, 4θ_b − θ_a)/30, whose
//! mean is N l₀ l κ/12) is not the section's: it is taken off, so that what remains is
//! the moment of the section's law — M = EI κ for an elastic element, whatever its axial
//! force (exact for an element straight at rest). Its sign follows the curvature's.
//! Damping is left out (the loads at rest).

use crate::rod::element::{ElementEnds, ElementLoads};
use crate::{Model, State};
use glam::DVec3;

/// The section loads and strains of one element (global axes).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SectionLoads {
    /// Bending moment vector \[N·m\], across the chord (its length is the moment).
    pub bending_moment: DVec3,
    /// Torque about the chord \[N·m\].
    pub torque: f64,
    /// Curvature vector \[1/m\] the element's law reads — the relative rotation of its
    /// ends over the rest length, across the chord, from the rest shape; for an elastic
    /// element `bending_moment` = EI × this.
    pub curvature: DVec3,
    /// Twist rate about the chord \[rad/m\], from the rest shape.
    pub twist_rate: f64,
}

/// The section loads of element `e` of `model` in `state` (module doc), an inelastic
/// element's with the state's committed history.
pub fn section_loads(model: &Model, state: &State, e: usize) -> SectionLoads {
    let el = &model.elements[e];
    let (a, b) = (el.node_a, el.node_b);
    let (x, q) = ([state.x[a], state.x[b]], [state.q[a], state.q[b]]);
    let ends = ElementEnds::still(x, q);
    let loads: ElementLoads = match &el.inelastic {
        Some(law) => model
            .inelastic
            .loads(el, law, state.inelastic_view(), &ends, 0.0),
        None => el.loads(&ends, 0.0),
    };
    let d = el.deformation(x, q);
    let axis = d.chord_dir;
    let m = 0.5 * (loads.moment[0] - loads.moment[1]);
    let strain = d.frame * ((d.bend_twist[1] - d.bend_twist[0]) / el.axis_length);
    let torque = m.dot(axis);
    let twist_rate = strain.dot(axis);
    let curvature = strain - twist_rate * axis;
    let arch = loads.axial_force * el.rest_length * el.axis_length / 12.0;
    SectionLoads {
        bending_moment: m - torque * axis - arch * curvature,
        torque,
        curvature,
        twist_rate,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{HoseSpec, Material, Section, SimSettings, WorldSpec};
    use glam::DQuat;

    const N: usize = 10;
    const L: f64 = 0.2;

    fn straight_hose() -> Model {
        Model::build(&WorldSpec {
            hoses: vec![HoseSpec {
                name: "h".into(),
                material: Material::isotropic(200e9, 0.3, 7850.0),
                nodes: (0..=N)
                    .map(|i| DVec3::new(L * i as f64 / N as f64, 0.0, 0.0))
                    .collect(),
                sections: vec![Section::new(0.006, 0.008)],
                normal_hint: Some(DVec3::Z),
            }],
            rigid_parts: vec![],
            settings: SimSettings::default(),
        })
        .unwrap()
    }

    /// The straight elastic hose along x bent into an arc of curvature κ about z: every
    /// element carries M = EI κ about +z, no torque (to 10⁻⁶: the co-rotational
    /// element's end moments are the gradient of its energy by the physical rotations, a
    /// term of higher order in the end rotations κ l₀/2 = 0.04 apart from EI κ).
    #[test]
    fn an_elastic_arc_carries_ei_kappa() {
        let model = straight_hose();
        let kappa = 4.0;
        let mut state = State::at_rest(&model);
        for i in 0..=N {
            let phi = kappa * L * i as f64 / N as f64;
            state.x[i] = DVec3::new(phi.sin() / kappa, (1.0 - phi.cos()) / kappa, 0.0);
            state.q[i] = DQuat::from_rotation_z(phi) * model.rest_q[i];
        }
        let ei = model.elements[0].bending_stiffness[1];
        for e in 0..N {
            let s = section_loads(&model, &state, e);
            assert!((s.curvature.length() - kappa).abs() < 1e-9 * kappa, "{s:?}");
            assert!(s.curvature.z > 0.0, "bent about +z: {s:?}");
            let m = s.bending_moment;
            assert!(
                (m - ei * s.curvature).length() < 1e-6 * ei * kappa,
                "{s:?}: EI κ = {}",
                ei * kappa
            );
            assert!(
                s.torque.abs() < 1e-9 * ei * kappa && s.twist_rate.abs() < 1e-9,
                "{s:?}"
            );
        }
    }

    /// The arc stretched along its chords (axial force N = EA ε ≠ 0): the section still
    /// carries EI κ, the axial force's shallow-arch moment taken off.
    #[test]
    fn a_stretched_arc_carries_ei_kappa() {
        let model = straight_hose();
        let (kappa, stretch) = (4.0, 1.002);
        let mut state = State::at_rest(&model);
        for i in 0..=N {
            let phi = kappa * L * i as f64 / N as f64;
            let x = DVec3::new(phi.sin() / kappa, (1.0 - phi.cos()) / kappa, 0.0);
            state.x[i] = stretch * x;
            state.q[i] = DQuat::from_rotation_z(phi) * model.rest_q[i];
        }
        let ei = model.elements[0].bending_stiffness[1];
        for e in 0..N {
            let s = section_loads(&model, &state, e);
            let m = s.bending_moment;
            assert!(
                (m - ei * s.curvature).length() < 1e-6 * ei * kappa,
                "{s:?}: EI κ = {}",
                ei * kappa
            );
        }
    }

    /// The straight elastic hose twisted uniformly at τ: every element carries T = GJ τ.
    #[test]
    fn an_elastic_twisted_hose_carries_gj_tau() {
        let model = straight_hose();
        let tau = 3.0;
        let mut state = State::at_rest(&model);
        for i in 0..=N {
            state.q[i] = DQuat::from_rotation_x(tau * L * i as f64 / N as f64) * model.rest_q[i];
        }
        let gj = model.elements[0].torsion_stiffness;
        for e in 0..N {
            let s = section_loads(&model, &state, e);
            assert!((s.twist_rate - tau).abs() < 1e-9 * tau, "{s:?}");
            assert!(
                (s.torque - gj * tau).abs() < 1e-9 * gj * tau,
                "{s:?}: GJ τ = {}",
                gj * tau
            );
            assert!(
                s.bending_moment.length() < 1e-9 * gj * tau && s.curvature.length() < 1e-9,
                "{s:?}"
            );
        }
    }
}
