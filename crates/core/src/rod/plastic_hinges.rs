//! Yielding elements (SPEC X1): the element's bending and torsion through a fibre
//! section ([`crate::rod::fibre_section`]) at its mean curvature, with the fibres'
//! plastic strains as history in the state.
//!
//! The linear element law ([`crate::rod::element`]) splits exactly into two modes of the
//! end rotations θ_a, θ_b (about each bending axis k, E I_k/l₀ · [[4, 2], [2, 4]]):
//!
//! * the uniform curvature κ_k = (θ_bk − θ_ak)/l₀, energy ½ E I_k κ_k² l₀, moments ∓M_k;
//! * the antisymmetric mode s_k = θ_ak + θ_bk, energy (3/2)(E I_k/l₀) s_k², moments
//!   3 (E I_k/l₀) s_k at both ends
//!
//! (½ (b − a)² + (3/2)(a + b)² = 2(a² + ab + b²)), and torsion is the twist rate
//! τ = (θ_bx − θ_ax)/l₀ with moments ∓T. A yielding element keeps the antisymmetric
//! mode elastic — on a bent line its rotations are the small difference between
//! neighbouring chords — and replaces M = E I κ and T = G J τ by the section's
//! elastic–plastic response at (τ, κ_y, κ_z) from the committed plastic strains: a
//! yielding hinge per element, permanent set included (the plastic strains are the new
//! rest curvature of the fibres), elastic unloading and springback included. Damping
//! acts on the rates through the elastic stiffness, as for every element.
//!
//! History is committed once per accepted step (explicit) or converged equilibrium
//! (Newton solvers) by [`commit`], at the accepted configuration; loads and tangents
//! read it and never write it, so a rejected Newton iterate, a line search or a
//! stability probe leaves no trace ([`crate::rod::inelastic`]). The tangent of the loads
//! (dual numbers through the return mapping, [`crate::rod::fibre_law`]) is the
//! consistent algorithmic tangent.

use crate::autodiff::{Scalar, V3};
use crate::rod::element::{AxialShift, BeamElement, ElementLoadsOf, EndsOf};
use crate::rod::fibre_section::FibreSection;
use glam::{DQuat, DVec3};

/// The loads of yielding `element` with fibre section `section` and committed plastic
/// strains `history` — [`BeamElement::loads_of`] with the hinge's law (module doc),
/// generic so that dual numbers give its tangent.
#[inline]
pub fn loads_of<T: Scalar>(
    element: &BeamElement,
    section: &FibreSection,
    history: &[f64],
    (x, q, v, w): EndsOf<T>,
    beta: f64,
) -> ElementLoadsOf<T> {
    let l0 = element.axis_length;
    let anti = [
        3.0 * element.bending_stiffness[0] / l0,
        3.0 * element.bending_stiffness[1] / l0,
    ];
    element.loads_with(x, q, v, w, beta, AxialShift::NONE, |theta, damped| {
        let (da, db) = element.end_moments(damped[0], damped[1]);
        let k = (theta[1] - theta[0]).scale_f(1.0 / l0);
        let m = section.moments(k, history);
        let s = theta[0] + theta[1];
        let zero = T::cst(0.0);
        let anti = V3::new(zero, s.y * anti[0], s.z * anti[1]);
        (da + anti - m, db + anti + m)
    })
}

/// The section strains (τ, κ_y, κ_z) of `element` at its ends' poses.
fn section_strains(element: &BeamElement, x: [DVec3; 2], q: [DQuat; 2]) -> [f64; 3] {
    let d = element.deformation(x, q);
    ((d.bend_twist[1] - d.bend_twist[0]) / element.axis_length).to_array()
}

/// Accepts the ends' poses (`x`, `q`) as the end of a step: the fibres' plastic strains
/// `history` move by their return mapping from the committed ones (module doc).
pub fn commit(
    element: &BeamElement,
    section: &FibreSection,
    (x, q): ([DVec3; 2], [DQuat; 2]),
    history: &mut [f64],
) {
    section.commit(section_strains(element, x, q), history);
}

/// Strain energy of yielding `element` at its ends' poses \[J\]: the axial part and the
/// antisymmetric bending mode as for every element, the hinge's fibres by their
/// incremental potential from the committed history if `incremental` (the static
/// solver's line search: its gradient is the loads), else by the energy they store.
pub fn strain_energy(
    element: &BeamElement,
    section: &FibreSection,
    history: &[f64],
    (x, q): ([DVec3; 2], [DQuat; 2]),
    incremental: bool,
) -> f64 {
    let d = element.deformation(x, q);
    let l0 = element.axis_length;
    let s = d.bend_twist[0] + d.bend_twist[1];
    let anti = 1.5 / l0
        * (element.bending_stiffness[0] * s.y * s.y + element.bending_stiffness[1] * s.z * s.z);
    let strains = ((d.bend_twist[1] - d.bend_twist[0]) / l0).to_array();
    element.axial_energy(&d) + anti + l0 * section.energy(strains, history, incremental)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::YieldLaw;
    use crate::math::exp_map;
    use crate::rod::element::rotate;
    use crate::rod::element::{ElementEnds, ElementLoads};
    use crate::rod::inelastic::{HistoryView, InelasticElements};
    use crate::rod::test_elements::perturbed_pose;
    use crate::Material;
    use crate::Section;

    fn hinge_element(yield_stress: f64) -> (InelasticElements, BeamElement) {
        let mut mat = Material::isotropic(200e9, 0.3, 7850.0);
        let law = YieldLaw {
            yield_stress,
            hardening_modulus: 1e9,
        };
        mat.plasticity = Some(law);
        let sec = Section::new(0.006, 0.008);
        let e = BeamElement::new(
            (0, 1),
            [DVec3::ZERO, DVec3::new(0.02, 0.0, 0.0)],
            [DQuat::IDENTITY; 2],
            &sec,
            &mat,
        );
        let mut hinges = InelasticElements::new();
        let mut elements = vec![e];
        hinges.add_hose(&mut elements, 0, &mat, |_| sec);
        (hinges, elements.remove(0))
    }

    fn view(history: &[f64]) -> HistoryView<'_> {
        HistoryView {
            values: history,
            age: 0.0,
        }
    }

    fn ends(x: [DVec3; 2], q: [DQuat; 2]) -> ElementEnds {
        ElementEnds::still(x, q)
    }

    /// Below yield the hinge's loads are the linear element's (the modes split exactly).
    #[test]
    fn below_yield_the_hinge_is_the_linear_element() {
        let (hinges, e) = hinge_element(1e12);
        let hinge = e.inelastic.expect("yields");
        let x = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0199, 0.0003, -0.0002),
        ];
        let q = [
            exp_map(DVec3::new(0.01, -0.02, 0.03)),
            exp_map(DVec3::new(-0.02, 0.015, -0.01)),
        ];
        let lin = e.loads(&ends(x, q), 1e-4);
        let pl = hinges.loads(&e, &hinge, HistoryView::NONE, &ends(x, q), 1e-4);
        let scale = lin.moment[0].length().max(lin.moment[1].length());
        for k in 0..2 {
            assert!((lin.moment[k] - pl.moment[k]).length() < 1e-9 * scale);
            assert!((lin.force[k] - pl.force[k]).length() < 1e-9 * lin.force[0].length());
        }
        let energy = hinges.strain_energy(&e, &hinge, HistoryView::NONE, (x, q), false);
        let want = e.strain_energy(x, q);
        assert!((energy - want).abs() < 1e-9 * want, "{energy} vs {want}");
    }

    /// Past yield the tangent is the derivative of the loads (central differences).
    #[test]
    fn past_yield_the_tangent_is_the_derivative_of_the_loads() {
        use crate::rod::tangent::inelastic_tangent;
        let (hinges, e) = hinge_element(300e6);
        let hinge = e.inelastic.expect("yields");
        let mut history = vec![0.0; hinges.history_len];
        let x = [DVec3::ZERO, DVec3::new(0.0199, 0.0003, -0.0002)];
        let q0 = [
            exp_map(DVec3::new(0.02, -0.1, 0.05)),
            exp_map(DVec3::new(-0.02, 0.12, -0.06)),
        ];
        hinges.commit(
            std::slice::from_ref(&e),
            (&x[..], &q0[..]),
            0.0,
            &mut history,
        );
        let q = [
            exp_map(DVec3::new(0.05, -0.2, 0.1)),
            exp_map(DVec3::new(-0.05, 0.25, -0.12)),
        ];
        let (loads, k) =
            inelastic_tangent(&hinges, (&e, &hinge), view(&history), &ends(x, q), 0.0, 0.0);
        let h = 1e-7;
        let flat = ElementLoads::to_array;
        let base = flat(&loads);
        let scale = base.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut worst: f64 = 0.0;
        for j in 0..12 {
            let perturbed = |s: f64| {
                let (xp, qp) = perturbed_pose((x, q), j, s);
                flat(&hinges.loads(&e, &hinge, view(&history), &ends(xp, qp), 0.0))
            };
            let (p, m) = (perturbed(h), perturbed(-h));
            for i in 0..12 {
                let fd = -(p[i] - m[i]) / (2.0 * h);
                worst = worst.max((fd - k[(i, j)]).abs());
            }
        }
        let kmax = k.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(
            worst < 1e-5 * kmax,
            "worst {worst:e} of {kmax:e} (loads {scale:e})"
        );
    }

    /// Past yield the loads are minus the gradient of the incremental potential (so the
    /// static solver's line search and the loads agree).
    #[test]
    fn past_yield_the_loads_are_the_potential_gradient() {
        let (hinges, e) = hinge_element(300e6);
        let hinge = e.inelastic.expect("yields");
        let history = vec![0.0; hinges.history_len];
        let x = [DVec3::ZERO, DVec3::new(0.0199, 0.0003, -0.0002)];
        let q = [
            exp_map(DVec3::new(0.05, -0.2, 0.1)),
            exp_map(DVec3::new(-0.05, 0.25, -0.12)),
        ];
        let loads = hinges.loads(&e, &hinge, view(&history), &ends(x, q), 0.0);
        let w = |x, q| hinges.strain_energy(&e, &hinge, view(&history), (x, q), true);
        let h = 1e-7;
        for node in 0..2 {
            for k in 0..3 {
                let mut dir = DVec3::ZERO;
                dir[k] = h;
                let (mut qp, mut qm) = (q, q);
                qp[node] = rotate(q[node], dir);
                qm[node] = rotate(q[node], -dir);
                let fd = -(w(x, qp) - w(x, qm)) / (2.0 * h);
                let got = loads.moment[node][k];
                assert!(
                    (fd - got).abs() < 1e-2 * got.abs().max(1e-1),
                    "moment n{node} k{k}: {got} vs {fd}"
                );
            }
        }
    }
}
