//! Relaxing elements (SPEC X2): the wall's moduli relax under held strain as a Prony
//! series E(t) = E₀ (1 − Σᵢ gᵢ (1 − e^{−t/τᵢ})) ([`crate::material::PronyTerm`]) —
//! linear viscoelasticity of the generalised Maxwell solid, every modulus by the same
//! function (a constant Poisson's ratio).
//!
//! The element's strain measures s = (ε, θ_a, θ_b) — the axial strain with its arch part
//! and the end rotations in the co-rotated frame, which carry torsion and both bending
//! modes — each have a viscous part αᵢ per term, which follows them as
//! α̇ᵢ = (s − αᵢ)/τᵢ. The element's law is the linear one at the strains
//! s − Σᵢ gᵢ αᵢ. Over a step of length h from the committed sⁿ, αᵢⁿ, with s linear in
//! time over the step, the recursion
//!
//! αᵢ = aᵢ αᵢⁿ + (1 − aᵢ − bᵢ) sⁿ + bᵢ s,  aᵢ = e^{−h/τᵢ},  bᵢ = 1 − (τᵢ/h)(1 − aᵢ)
//!
//! is exact (the convolution integral over the step; Simo & Hughes, *Computational
//! Inelasticity*, 1998, §10.3.2, and Taylor, Pister & Goudreau 1970): exact for strain
//! held or ramped linearly, second order otherwise. The law is then the linear one at
//! c·s − d with c = 1 − Σᵢ gᵢ bᵢ and d = Σᵢ gᵢ (aᵢ αᵢⁿ + (1 − aᵢ − bᵢ) sⁿ): linear in s,
//! so the consistent tangent is the elastic one scaled by c, and the loads are the
//! gradient of the potential W_lin(c s − d)/c. Damping acts on the rates through the
//! instantaneous stiffness, as for every element.
//!
//! The history (sⁿ and the αᵢⁿ, 7 values each) is committed once per accepted step or
//! converged equilibrium ([`crate::rod::inelastic`]), with h the time since the last
//! commit; loads and tangents at a later time read it with that age and never write it.

use crate::autodiff::{Scalar, V3};
use crate::material::PronyTerm;
use crate::rod::element::{AxialShift, BeamElement, ElementLoadsOf, EndsOf};
use glam::{DQuat, DVec3};

/// Strain measures: ε, θ_a (3), θ_b (3).
const STRAINS: usize = 7;

/// History values an element relaxing by `terms` keeps: sⁿ and one αᵢⁿ per term.
pub fn history_len(terms: &[PronyTerm]) -> usize {
    STRAINS * (1 + terms.len())
}

/// The integrator's weights (aᵢ, bᵢ) of a term of time `tau` over a step `h` ≥ 0 (module
/// doc); (1, 0) for h = 0.
fn weights(tau: f64, h: f64) -> (f64, f64) {
    if h <= 0.0 {
        return (1.0, 0.0);
    }
    let x = h / tau;
    let one_minus_a = -(-x).exp_m1();
    (1.0 - one_minus_a, 1.0 - one_minus_a / x)
}

/// The scale c and the shifts d of the law at `age` after the commit of `history`
/// (module doc).
fn predictor(terms: &[PronyTerm], history: &[f64], age: f64) -> (f64, [f64; STRAINS]) {
    let (last, alphas) = history.split_at(STRAINS);
    let mut scale = 1.0;
    let mut shift = [0.0; STRAINS];
    for (p, alpha) in terms.iter().zip(alphas.chunks_exact(STRAINS)) {
        let (a, b) = weights(p.time, age);
        scale -= p.weight * b;
        for ((d, alpha), last) in shift.iter_mut().zip(alpha).zip(last) {
            *d += p.weight * (a * alpha + (1.0 - a - b) * last);
        }
    }
    (scale, shift)
}

/// The loads of relaxing `element` (terms `terms`, committed history `history`, `age`
/// seconds ago) — [`BeamElement::loads_of`] at the strains c·s − d (module doc), generic
/// so that dual numbers give its tangent.
#[inline]
pub fn loads_of<T: Scalar>(
    element: &BeamElement,
    terms: &[PronyTerm],
    (history, age): (&[f64], f64),
    (x, q, v, w): EndsOf<T>,
    beta: f64,
) -> ElementLoadsOf<T> {
    let (c, d) = predictor(terms, history, age);
    let axial = AxialShift {
        scale: c,
        shift: d[0],
    };
    let da = V3::cst(DVec3::new(d[1], d[2], d[3]));
    let db = V3::cst(DVec3::new(d[4], d[5], d[6]));
    element.loads_with(x, q, v, w, beta, axial, |theta, damped| {
        element.end_moments(
            theta[0].scale_f(c) - da + damped[0],
            theta[1].scale_f(c) - db + damped[1],
        )
    })
}

/// The strain measures s of `element` at its ends' poses.
fn strains(element: &BeamElement, x: [DVec3; 2], q: [DQuat; 2]) -> [f64; STRAINS] {
    let d = element.deformation(x, q);
    let [ta, tb] = d.bend_twist;
    [element.axial_strain(&d), ta.x, ta.y, ta.z, tb.x, tb.y, tb.z]
}

/// Accepts the ends' poses as the end of a step `age` seconds after the last commit: the
/// viscous strains move by the recursion of the module doc, and the strains are kept.
pub fn commit(
    element: &BeamElement,
    terms: &[PronyTerm],
    (x, q): ([DVec3; 2], [DQuat; 2]),
    age: f64,
    history: &mut [f64],
) {
    let s = strains(element, x, q);
    let (last, alphas) = history.split_at_mut(STRAINS);
    for (p, alpha) in terms.iter().zip(alphas.chunks_exact_mut(STRAINS)) {
        let (a, b) = weights(p.time, age);
        for ((alpha, s), last) in alpha.iter_mut().zip(s).zip(&*last) {
            *alpha = a * *alpha + (1.0 - a - b) * last + b * s;
        }
    }
    last.copy_from_slice(&s);
}

/// The potential W_lin(c s − d)/c of relaxing `element` at its ends' poses \[J\], whose
/// gradient is the loads (module doc); right after a commit (age 0) the energy the
/// element's springs hold.
pub fn strain_energy(
    element: &BeamElement,
    terms: &[PronyTerm],
    (history, age): (&[f64], f64),
    (x, q): ([DVec3; 2], [DQuat; 2]),
) -> f64 {
    let (c, d) = predictor(terms, history, age);
    let s = strains(element, x, q);
    let at = |k: usize| c * s[k] - d[k];
    let theta = [
        DVec3::new(at(1), at(2), at(3)),
        DVec3::new(at(4), at(5), at(6)),
    ];
    element.energy_at(at(0), theta) / c
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::relaxation_ratio;
    use crate::math::exp_map;
    use crate::rod::element::ElementEnds;
    use crate::rod::inelastic::{HistoryView, InelasticElements};
    use crate::rod::test_elements::check_tangent_and_potential;
    use crate::{Material, Section};

    const TERMS: [PronyTerm; 2] = [
        PronyTerm {
            weight: 0.3,
            time: 0.5,
        },
        PronyTerm {
            weight: 0.2,
            time: 5.0,
        },
    ];

    fn relaxing_element() -> (InelasticElements, BeamElement) {
        let mut mat = Material::isotropic(10e6, 0.45, 1100.0);
        mat.relaxation = TERMS.to_vec();
        let sec = Section::new(0.01, 0.016);
        let e = BeamElement::new(
            (0, 1),
            [DVec3::ZERO, DVec3::new(0.02, 0.0, 0.0)],
            [DQuat::IDENTITY; 2],
            &sec,
            &mat,
        );
        let mut elements = vec![e];
        let mut registry = InelasticElements::new();
        registry.add_hose(&mut elements, 0, &mat, |_| sec);
        (registry, elements.remove(0))
    }

    fn bent() -> ([DVec3; 2], [DQuat; 2]) {
        (
            [DVec3::ZERO, DVec3::new(0.0201, 0.0003, -0.0002)],
            [
                exp_map(DVec3::new(0.05, -0.2, 0.1)),
                exp_map(DVec3::new(-0.05, 0.25, -0.12)),
            ],
        )
    }

    /// Held strain relaxes as E(t)/E₀: the end moment of an element bent at t = 0 and
    /// held, committed at uneven steps, is the elastic one times the relaxation ratio.
    #[test]
    fn held_strain_relaxes_by_the_prony_series() {
        let (registry, e) = relaxing_element();
        let inelastic = e.inelastic.expect("relaxes");
        let (x, q) = bent();
        let ends = ElementEnds::still(x, q);
        let elastic = e.loads(&ends, 0.0);
        let mut history = vec![0.0; registry.history_len];
        // the jump at t = 0: no time has passed, nothing relaxes
        registry.commit(
            std::slice::from_ref(&e),
            (&x[..], &q[..]),
            0.0,
            &mut history,
        );
        let mut t = 0.0;
        for h in [0.01, 0.3, 0.02, 1.7, 4.0] {
            t += h;
            let view = HistoryView {
                values: &history,
                age: h,
            };
            let l = registry.loads(&e, &inelastic, view, &ends, 0.0);
            let ratio = relaxation_ratio(&TERMS, t);
            for k in 0..2 {
                let want = elastic.moment[k] * ratio;
                let err = (l.moment[k] - want).length();
                assert!(
                    err < 1e-9 * want.length(),
                    "t {t}: {:?} vs {want:?}",
                    l.moment[k]
                );
            }
            registry.commit(std::slice::from_ref(&e), (&x[..], &q[..]), h, &mut history);
        }
    }

    /// The tangent is the derivative of the loads (central differences), and the loads
    /// are minus the gradient of the potential, mid-step after a commit at another pose.
    #[test]
    fn the_tangent_and_the_potential_match_the_loads() {
        let (registry, e) = relaxing_element();
        let inelastic = e.inelastic.expect("relaxes");
        let mut history = vec![0.0; registry.history_len];
        let (x0, q0) = (
            [DVec3::ZERO, DVec3::new(0.0199, 0.0001, 0.0)],
            [exp_map(DVec3::new(0.0, -0.1, 0.02)), DQuat::IDENTITY],
        );
        registry.commit(
            std::slice::from_ref(&e),
            (&x0[..], &q0[..]),
            0.0,
            &mut history,
        );
        registry.commit(
            std::slice::from_ref(&e),
            (&x0[..], &q0[..]),
            0.7,
            &mut history,
        );
        let (x, q) = bent();
        let view = HistoryView {
            values: &history,
            age: 0.2,
        };
        check_tangent_and_potential(&registry, (&e, &inelastic), view, (x, q), 1e-7);
    }
}
