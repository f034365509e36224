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
//! (Newton solvers) by [`PlasticHinges::commit`], at the accepted configuration; loads
//! and tangents read it and never write it, so a rejected Newton iterate, a line search
//! or a stability probe leaves no trace. The tangent of the loads (dual numbers through
//! the return mapping, [`crate::rod::fibre_law`]) is the consistent algorithmic tangent.

use crate::autodiff::{Quat, Scalar, V3};
use crate::material::YieldLaw;
use crate::rod::element::{BeamElement, ElementEnds, ElementLoads, ElementLoadsOf};
use crate::rod::fibre_law::FibreLaw;
use crate::rod::fibre_section::FibreSection;
use crate::rod::node_view::NodeView;
use crate::Section;
use glam::{DQuat, DVec3};

/// Where a yielding element finds its section and its history.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlasticHinge {
    /// Index into [`PlasticHinges::sections`].
    pub section: usize,
    /// First history value of the element in `State::plastic_strain`.
    pub history: usize,
}

/// The model's yielding elements and their sections (built with the model).
#[derive(Clone, Debug, Default)]
pub struct PlasticHinges {
    pub sections: Vec<FibreSection>,
    /// The yielding elements' indices, in element order.
    pub elements: Vec<usize>,
    /// Hose h's yielding elements are `elements[hose_elements[h]..hose_elements[h + 1]]`.
    pub hose_elements: Vec<usize>,
    /// History values all hinges keep (the length of `State::plastic_strain`).
    pub history_len: usize,
    /// The history of an element never yielded (zeros), for callers without a state.
    virgin: Vec<f64>,
}

impl PlasticHinges {
    /// No yielding element yet.
    pub fn new() -> Self {
        Self {
            hose_elements: vec![0],
            ..Self::default()
        }
    }

    /// Whether any element yields.
    pub fn any(&self) -> bool {
        !self.elements.is_empty()
    }

    /// Gives the elements `first..` of `elements` (one hose's, the last ones built) their
    /// hinges if the hose's material yields by `law` (sections by `section_of`, elastic
    /// moduli `e`, `g`), and closes the hose's range.
    pub fn add_hose(
        &mut self,
        elements: &mut [BeamElement],
        first: usize,
        law: Option<&YieldLaw>,
        (e, g): (f64, f64),
        section_of: impl Fn(usize) -> Section,
    ) {
        if let Some(law) = law {
            let fibre_law = FibreLaw::new(e, g, law);
            for (i, el) in elements[first..].iter_mut().enumerate() {
                let s = section_of(i);
                let fibres = FibreSection::tube(s.d_inner, s.d_outer, fibre_law);
                if self.sections.last() != Some(&fibres) {
                    self.sections.push(fibres);
                }
                let section = self.sections.len() - 1;
                el.plastic = Some(PlasticHinge {
                    section,
                    history: self.history_len,
                });
                let len = self.sections[section].history_len();
                self.history_len += len;
                if self.virgin.len() < len {
                    self.virgin.resize(len, 0.0);
                }
                self.elements.push(first + i);
            }
        }
        self.hose_elements.push(self.elements.len());
    }

    /// The committed history of `hinge` in `history` (the virgin one if `history` is
    /// empty: a configuration without a state).
    pub fn history_of<'a>(&'a self, hinge: &PlasticHinge, history: &'a [f64]) -> &'a [f64] {
        let len = self.sections[hinge.section].history_len();
        if history.is_empty() {
            &self.virgin[..len]
        } else {
            &history[hinge.history..hinge.history + len]
        }
    }

    /// The loads of yielding `element` (hinge `hinge`) — [`BeamElement::loads_of`] with
    /// the hinge's law (module doc), generic so that dual numbers give its tangent.
    #[inline]
    pub fn loads_of<T: Scalar>(
        &self,
        element: &BeamElement,
        hinge: &PlasticHinge,
        history: &[f64],
        (x, q, v, w): ([V3<T>; 2], [Quat<T>; 2], [V3<T>; 2], [V3<T>; 2]),
        beta: f64,
    ) -> ElementLoadsOf<T> {
        let section = &self.sections[hinge.section];
        let history = self.history_of(hinge, history);
        let l0 = element.rest_length;
        let anti = [
            3.0 * element.bending_stiffness[0] / l0,
            3.0 * element.bending_stiffness[1] / l0,
        ];
        element.loads_with(x, q, v, w, beta, |theta, damped| {
            let (da, db) = element.end_moments(damped[0], damped[1]);
            let k = (theta[1] - theta[0]).scale_f(1.0 / l0);
            let m = section.moments(k, history);
            let s = theta[0] + theta[1];
            let zero = T::cst(0.0);
            let anti = V3::new(zero, s.y * anti[0], s.z * anti[1]);
            (da + anti - m, db + anti + m)
        })
    }

    /// [`Self::loads_of`] in `f64` at `ends`.
    pub fn loads(
        &self,
        element: &BeamElement,
        hinge: &PlasticHinge,
        history: &[f64],
        ends: &ElementEnds,
        beta: f64,
    ) -> ElementLoads {
        let l = self.loads_of::<f64>(
            element,
            hinge,
            history,
            (
                [ends.x[0].into(), ends.x[1].into()],
                [ends.q[0].into(), ends.q[1].into()],
                [ends.v[0].into(), ends.v[1].into()],
                [ends.w[0].into(), ends.w[1].into()],
            ),
            beta,
        );
        ElementLoads {
            force: [l.force[0].into(), l.force[1].into()],
            moment: [l.moment[0].into(), l.moment[1].into()],
            axial_force: l.axial_force,
        }
    }

    /// Adds the loads of the yielding elements `range` (indices into
    /// [`Self::elements`]) at `c` to `force` and `moment`, whose entries — like `c`'s —
    /// are nodes `base..`; elements whose node a `skip` selects are left out.
    #[allow(clippy::too_many_arguments)]
    pub fn add_loads(
        &self,
        elements: &[BeamElement],
        range: std::ops::Range<usize>,
        c: &NodeView,
        base: usize,
        beta: f64,
        force: &mut [DVec3],
        moment: &mut [DVec3],
        skip: &impl Fn(usize) -> bool,
    ) {
        for &k in &self.elements[range] {
            let e = &elements[k];
            let Some(hinge) = &e.plastic else { continue };
            if skip(e.node_a) {
                continue;
            }
            let (a, b) = (e.node_a - base, e.node_b - base);
            let ends = ElementEnds {
                x: [c.x[a], c.x[b]],
                q: [c.q[a], c.q[b]],
                v: [c.v[a], c.v[b]],
                w: [c.w[a], c.w[b]],
            };
            let l = self.loads(e, hinge, c.plastic_strain, &ends, beta);
            force[a] += l.force[0];
            force[b] += l.force[1];
            moment[a] += l.moment[0];
            moment[b] += l.moment[1];
        }
    }

    /// The section strains (τ, κ_y, κ_z) of `element` at its ends' poses.
    fn section_strains(element: &BeamElement, x: [DVec3; 2], q: [DQuat; 2]) -> [f64; 3] {
        let d = element.deformation(x, q);
        ((d.theta[1] - d.theta[0]) / element.rest_length).to_array()
    }

    /// Accepts the configuration (`x`, `q`) as the end of a step: every hinge's plastic
    /// strains move by their return mapping from the committed ones (module doc).
    /// Nothing to do, and nothing done, when no element yields.
    pub fn commit(&self, elements: &[BeamElement], x: &[DVec3], q: &[DQuat], history: &mut [f64]) {
        if history.len() != self.history_len {
            return;
        }
        for &k in &self.elements {
            let e = &elements[k];
            let Some(hinge) = &e.plastic else { continue };
            let (a, b) = (e.node_a, e.node_b);
            let strains = Self::section_strains(e, [x[a], x[b]], [q[a], q[b]]);
            let section = &self.sections[hinge.section];
            let len = section.history_len();
            section.commit(strains, &mut history[hinge.history..hinge.history + len]);
        }
    }

    /// Strain energy of yielding `element` at its ends' poses \[J\]: the axial part and
    /// the antisymmetric bending mode as for every element, the hinge's fibres by their
    /// incremental potential from the committed history if `incremental` (the static
    /// solver's line search: its gradient is the loads), else by the energy they store.
    pub fn strain_energy(
        &self,
        element: &BeamElement,
        hinge: &PlasticHinge,
        history: &[f64],
        (x, q): ([DVec3; 2], [DQuat; 2]),
        incremental: bool,
    ) -> f64 {
        let d = element.deformation(x, q);
        let l0 = element.rest_length;
        let s = d.theta[0] + d.theta[1];
        let anti = 1.5 / l0
            * (element.bending_stiffness[0] * s.y * s.y + element.bending_stiffness[1] * s.z * s.z);
        let strains = ((d.theta[1] - d.theta[0]) / l0).to_array();
        let section = &self.sections[hinge.section];
        element.axial_energy(&d)
            + anti
            + l0 * section.energy(strains, self.history_of(hinge, history), incremental)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::exp_map;
    use crate::rod::element::rotate;
    use crate::Material;

    fn hinge_element(yield_stress: f64) -> (PlasticHinges, BeamElement) {
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
        let mut hinges = PlasticHinges::new();
        let mut elements = vec![e];
        hinges.add_hose(
            &mut elements,
            0,
            Some(&law),
            (mat.bending_modulus(), mat.shear_modulus()),
            |_| sec,
        );
        (hinges, elements.remove(0))
    }

    fn ends(x: [DVec3; 2], q: [DQuat; 2]) -> ElementEnds {
        ElementEnds::still(x, q)
    }

    /// Below yield the hinge's loads are the linear element's (the modes split exactly).
    #[test]
    fn below_yield_the_hinge_is_the_linear_element() {
        let (hinges, e) = hinge_element(1e12);
        let hinge = e.plastic.expect("yields");
        let x = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.0199, 0.0003, -0.0002),
        ];
        let q = [
            exp_map(DVec3::new(0.01, -0.02, 0.03)),
            exp_map(DVec3::new(-0.02, 0.015, -0.01)),
        ];
        let lin = e.loads(&ends(x, q), 1e-4);
        let pl = hinges.loads(&e, &hinge, &[], &ends(x, q), 1e-4);
        let scale = lin.moment[0].length().max(lin.moment[1].length());
        for k in 0..2 {
            assert!((lin.moment[k] - pl.moment[k]).length() < 1e-9 * scale);
            assert!((lin.force[k] - pl.force[k]).length() < 1e-9 * lin.force[0].length());
        }
        let energy = hinges.strain_energy(&e, &hinge, &[], (x, q), false);
        let want = e.strain_energy(x, q);
        assert!((energy - want).abs() < 1e-9 * want, "{energy} vs {want}");
    }

    /// Past yield the tangent is the derivative of the loads (central differences).
    #[test]
    fn past_yield_the_tangent_is_the_derivative_of_the_loads() {
        use crate::rod::tangent::plastic_tangent;
        let (hinges, e) = hinge_element(300e6);
        let hinge = e.plastic.expect("yields");
        let mut history = vec![0.0; hinges.history_len];
        let x = [DVec3::ZERO, DVec3::new(0.0199, 0.0003, -0.0002)];
        let q0 = [
            exp_map(DVec3::new(0.02, -0.1, 0.05)),
            exp_map(DVec3::new(-0.02, 0.12, -0.06)),
        ];
        hinges.commit(&[e.clone()], &x, &q0, &mut history);
        let q = [
            exp_map(DVec3::new(0.05, -0.2, 0.1)),
            exp_map(DVec3::new(-0.05, 0.25, -0.12)),
        ];
        let (loads, k) = plastic_tangent(&hinges, (&e, &hinge), &history, &ends(x, q), 0.0, 0.0);
        let h = 1e-7;
        let flat = |l: &ElementLoads| {
            let mut v = [0.0; 12];
            for (b, w) in [l.force[0], l.moment[0], l.force[1], l.moment[1]]
                .iter()
                .enumerate()
            {
                v[3 * b..3 * b + 3].copy_from_slice(&w.to_array());
            }
            v
        };
        let base = flat(&loads);
        let scale = base.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut worst: f64 = 0.0;
        for j in 0..12 {
            let perturbed = |s: f64| {
                let (mut xp, mut qp) = (x, q);
                let node = j / 6;
                let mut d = DVec3::ZERO;
                d[j % 3] = s;
                if j % 6 < 3 {
                    xp[node] += d;
                } else {
                    qp[node] = rotate(q[node], d);
                }
                flat(&hinges.loads(&e, &hinge, &history, &ends(xp, qp), 0.0))
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
        let hinge = e.plastic.expect("yields");
        let history = vec![0.0; hinges.history_len];
        let x = [DVec3::ZERO, DVec3::new(0.0199, 0.0003, -0.0002)];
        let q = [
            exp_map(DVec3::new(0.05, -0.2, 0.1)),
            exp_map(DVec3::new(-0.05, 0.25, -0.12)),
        ];
        let loads = hinges.loads(&e, &hinge, &history, &ends(x, q), 0.0);
        let w = |x, q| hinges.strain_energy(&e, &hinge, &history, (x, q), true);
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
