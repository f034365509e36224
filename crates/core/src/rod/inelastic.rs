//! Elements whose law has a history: yielding metal (SPEC X1, a fibre section with
//! plastic strains, [`crate::rod::plastic_hinges`]), relaxing rubber (SPEC X2, a
//! Prony series with viscous strains, [`crate::rod::relaxation`]) and rubbing bundles
//! (SPEC X2, Dahl friction moments, [`crate::rod::hysteresis`]). The model lists them
//! here with their laws; the state keeps their history in one array
//! (`State::inelastic_history`) with the time it was committed.
//!
//! History is committed once per accepted step (explicit) or converged equilibrium
//! (Newton solvers) by [`InelasticElements::commit`], at the accepted configuration;
//! loads, tangents and energies read it (with its age, the time since the commit) and
//! never write it, so a rejected Newton iterate, a line search or a stability probe
//! leaves no trace. Inelastic elements are computed one at a time, after the four-lane
//! kernel's linear ones ([`crate::rod::element_block`]).

use crate::autodiff::Scalar;
use crate::material::{Hysteresis, PronyTerm};
use crate::rod::element::{BeamElement, ElementEnds, ElementLoads, ElementLoadsOf, EndsOf};
use crate::rod::fibre_law::FibreLaw;
use crate::rod::fibre_section::FibreSection;
use crate::rod::node_view::NodeView;
use crate::rod::{hysteresis, plastic_hinges, relaxation};
use crate::{Material, Section};
use glam::{DQuat, DVec3};

/// The law of an inelastic element: an index into [`InelasticElements::sections`],
/// [`InelasticElements::relaxations`] or [`InelasticElements::hystereses`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InelasticLaw {
    /// A yielding hinge with this fibre section.
    Yielding(usize),
    /// A relaxing element with these Prony terms.
    Relaxing(usize),
    /// A hysteretic element with this friction law.
    Hysteretic(usize),
}

/// Where an inelastic element finds its law and its history.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Inelastic {
    pub law: InelasticLaw,
    /// First history value of the element in `State::inelastic_history`.
    pub history: usize,
}

/// The committed history of the inelastic elements and its age: the time since it was
/// committed \[s\] (what the relaxing law integrates over; the yielding law ignores it).
#[derive(Clone, Copy, Debug)]
pub struct HistoryView<'a> {
    pub values: &'a [f64],
    pub age: f64,
}

impl HistoryView<'_> {
    /// No history: a configuration without a state (every element virgin).
    pub const NONE: HistoryView<'static> = HistoryView {
        values: &[],
        age: 0.0,
    };
}

/// The model's inelastic elements and their laws (built with the model).
#[derive(Clone, Debug, Default)]
pub struct InelasticElements {
    /// The yielding elements' fibre sections.
    pub sections: Vec<FibreSection>,
    /// The relaxing elements' Prony series.
    pub relaxations: Vec<Vec<PronyTerm>>,
    /// The hysteretic elements' friction laws.
    pub hystereses: Vec<Hysteresis>,
    /// The inelastic elements' indices, in element order.
    pub elements: Vec<usize>,
    /// Hose h's inelastic elements are `elements[hose_elements[h]..hose_elements[h + 1]]`.
    pub hose_elements: Vec<usize>,
    /// History values all elements keep (the length of `State::inelastic_history`).
    pub history_len: usize,
    /// The history of a virgin element (zeros), for callers without a state.
    virgin: Vec<f64>,
}

impl InelasticElements {
    /// No inelastic element yet.
    pub fn new() -> Self {
        Self {
            hose_elements: vec![0],
            ..Self::default()
        }
    }

    /// Whether any element is inelastic.
    pub fn any(&self) -> bool {
        !self.elements.is_empty()
    }

    /// Gives the elements `first..` of `elements` (one hose's, the last ones built) their
    /// law if the hose's `material` yields, relaxes or rubs (sections by `section_of`),
    /// and closes the hose's range. A material does one of these at most (the scene
    /// checks; yielding comes first, then relaxing).
    pub fn add_hose(
        &mut self,
        elements: &mut [BeamElement],
        first: usize,
        material: &Material,
        section_of: impl Fn(usize) -> Section,
    ) {
        let (e, g) = (material.bending_modulus(), material.shear_modulus());
        for (i, el) in elements[first..].iter_mut().enumerate() {
            let law = if let Some(law) = &material.plasticity {
                let s = section_of(i);
                let fibres = FibreSection::tube(s.d_inner, s.d_outer, FibreLaw::new(e, g, law));
                if self.sections.last() != Some(&fibres) {
                    self.sections.push(fibres);
                }
                InelasticLaw::Yielding(self.sections.len() - 1)
            } else if !material.relaxation.is_empty() {
                if self.relaxations.last() != Some(&material.relaxation) {
                    self.relaxations.push(material.relaxation.clone());
                }
                InelasticLaw::Relaxing(self.relaxations.len() - 1)
            } else if let Some(law) = material.hysteresis {
                if self.hystereses.last() != Some(&law) {
                    self.hystereses.push(law);
                }
                InelasticLaw::Hysteretic(self.hystereses.len() - 1)
            } else {
                break;
            };
            el.inelastic = Some(Inelastic {
                law,
                history: self.history_len,
            });
            let len = self.history_len_of(law);
            self.history_len += len;
            if self.virgin.len() < len {
                self.virgin.resize(len, 0.0);
            }
            self.elements.push(first + i);
        }
        self.hose_elements.push(self.elements.len());
    }

    /// History values an element of `law` keeps.
    fn history_len_of(&self, law: InelasticLaw) -> usize {
        match law {
            InelasticLaw::Yielding(s) => self.sections[s].history_len(),
            InelasticLaw::Relaxing(r) => relaxation::history_len(&self.relaxations[r]),
            InelasticLaw::Hysteretic(_) => hysteresis::HISTORY_LEN,
        }
    }

    /// The committed history of element `inelastic` in `history` (the virgin one if
    /// `history` is empty: a configuration without a state).
    pub fn history_of<'a>(&'a self, inelastic: &Inelastic, history: &'a [f64]) -> &'a [f64] {
        let len = self.history_len_of(inelastic.law);
        if history.is_empty() {
            &self.virgin[..len]
        } else {
            &history[inelastic.history..inelastic.history + len]
        }
    }

    /// The loads of inelastic `element` by its law, generic so that dual numbers give
    /// its tangent.
    #[inline]
    pub fn loads_of<T: Scalar>(
        &self,
        element: &BeamElement,
        inelastic: &Inelastic,
        history: HistoryView,
        ends: EndsOf<T>,
        beta: f64,
    ) -> ElementLoadsOf<T> {
        let own = self.history_of(inelastic, history.values);
        match inelastic.law {
            InelasticLaw::Yielding(s) => {
                plastic_hinges::loads_of(element, &self.sections[s], own, ends, beta)
            }
            InelasticLaw::Relaxing(r) => {
                let terms = &self.relaxations[r];
                relaxation::loads_of(element, terms, (own, history.age), ends, beta)
            }
            InelasticLaw::Hysteretic(h) => {
                hysteresis::loads_of(element, &self.hystereses[h], own, ends, beta)
            }
        }
    }

    /// [`Self::loads_of`] in `f64` at `ends`.
    pub fn loads(
        &self,
        element: &BeamElement,
        inelastic: &Inelastic,
        history: HistoryView,
        ends: &ElementEnds,
        beta: f64,
    ) -> ElementLoads {
        self.loads_of::<f64>(element, inelastic, history, ends.lifted(), beta)
            .into()
    }

    /// Adds the loads of the inelastic elements `range` (indices into
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
            let Some(inelastic) = &e.inelastic else {
                continue;
            };
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
            let l = self.loads(e, inelastic, c.inelastic_history, &ends, beta);
            force[a] += l.force[0];
            force[b] += l.force[1];
            moment[a] += l.moment[0];
            moment[b] += l.moment[1];
        }
    }

    /// Accepts the configuration (`x`, `q`) as the end of a step `age` seconds after the
    /// last commit: every element's history moves by its law (module doc). Nothing to
    /// do, and nothing done, when no element is inelastic.
    pub fn commit(
        &self,
        elements: &[BeamElement],
        (x, q): (&[DVec3], &[DQuat]),
        age: f64,
        history: &mut [f64],
    ) {
        if history.len() != self.history_len {
            return;
        }
        for &k in &self.elements {
            let e = &elements[k];
            let Some(inelastic) = &e.inelastic else {
                continue;
            };
            let ends = ([x[e.node_a], x[e.node_b]], [q[e.node_a], q[e.node_b]]);
            let len = self.history_len_of(inelastic.law);
            let own = &mut history[inelastic.history..inelastic.history + len];
            match inelastic.law {
                InelasticLaw::Yielding(s) => {
                    plastic_hinges::commit(e, &self.sections[s], ends, own)
                }
                InelasticLaw::Relaxing(r) => {
                    relaxation::commit(e, &self.relaxations[r], ends, age, own)
                }
                InelasticLaw::Hysteretic(h) => {
                    hysteresis::commit(e, &self.hystereses[h], ends, own)
                }
            }
        }
    }

    /// Strain energy of inelastic `element` at its ends' poses \[J\]: the incremental
    /// potential from the committed history if `incremental` (the static solver's line
    /// search: its gradient is the loads), else the energy the element stores.
    pub fn strain_energy(
        &self,
        element: &BeamElement,
        inelastic: &Inelastic,
        history: HistoryView,
        ends: ([DVec3; 2], [DQuat; 2]),
        incremental: bool,
    ) -> f64 {
        let own = self.history_of(inelastic, history.values);
        match inelastic.law {
            InelasticLaw::Yielding(s) => {
                plastic_hinges::strain_energy(element, &self.sections[s], own, ends, incremental)
            }
            InelasticLaw::Relaxing(r) => {
                let terms = &self.relaxations[r];
                relaxation::strain_energy(element, terms, (own, history.age), ends)
            }
            InelasticLaw::Hysteretic(h) => {
                hysteresis::strain_energy(element, &self.hystereses[h], own, ends, incremental)
            }
        }
    }
}
