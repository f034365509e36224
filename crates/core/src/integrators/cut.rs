//! A model and state of one component of the network alone ([`super::component`]): the
//! hose segments (contiguous runs of a hose's nodes), junctions, stiffened sections, load
//! cases and contact memory of the component's nodes, renumbered, the rigid parts as
//! they are. Its held boundary nodes keep their load cases, so its static equilibrium is
//! the whole scene's restricted to the component: what lies beyond a held node is not
//! moved by what moves the component (a hand) and does not load it. The static solver
//! solves the components out of balance on such a cut ([`super::statics`]); the haptic
//! stream the hand's component.
//!
//! What the cut model cannot reproduce exactly is refused (`None`, the caller solves the
//! whole scene): yielding or relaxing elements (their history is laid out per model) and
//! parts riding on junction bodies.

use crate::contact::HoseContactModel;
use crate::loads::{LoadCase, LoadCaseId};
use crate::rod::element_block::PackedElements;
use crate::{HoseInfo, Junction, Model, State};
use glam::DVec3;

/// The component's model and state, and where its nodes lie in the whole scene.
#[derive(Clone, Debug)]
pub struct Cut {
    pub model: Model,
    pub state: State,
    /// Per cut node, its node in the whole scene (sorted).
    pub nodes: Vec<usize>,
    /// Per cut hose, the scene's hose it is a run of.
    pub hose_of: Vec<usize>,
    /// Per cut element, the scene's element.
    element_of: Vec<usize>,
    /// Per cut body, the scene's body.
    body_from: Vec<usize>,
    /// The load cases on the component, in the scene's order: (scene handle, cut handle).
    cases: Vec<(LoadCaseId, LoadCaseId)>,
}

impl Cut {
    /// Whether a cut of `model` can be exact (see the module doc).
    pub fn carries(model: &Model) -> bool {
        model.inelastic.history_len == 0
            && model.elements.iter().all(|e| e.inelastic.is_none())
            && !model.junction_shapes.any()
    }

    /// The cut of `model` to `nodes` (sorted, a [`super::component::component`]) in
    /// `state`; `None` when the model has what a cut cannot carry (see the module doc).
    pub fn new(model: &Model, state: &State, nodes: Vec<usize>) -> Option<Cut> {
        if !Cut::carries(model) {
            return None;
        }
        let mut index = vec![usize::MAX; model.node_count()];
        for (k, &i) in nodes.iter().enumerate() {
            index[i] = k;
        }
        // hoses: each run of consecutive nodes of one hose
        let mut hoses = Vec::new();
        let mut hose_of = Vec::new();
        let mut elements = Vec::new();
        let mut element_of = Vec::new();
        let mut k = 0;
        while k < nodes.len() {
            let first = nodes[k];
            let h = model
                .hoses
                .iter()
                .position(|h| h.nodes().contains(&first))?;
            let info = &model.hoses[h];
            let mut last = k;
            while last + 1 < nodes.len()
                && nodes[last + 1] == nodes[last] + 1
                && info.nodes().contains(&nodes[last + 1])
            {
                last += 1;
            }
            let first_element = elements.len();
            for i in first..nodes[last] {
                let e = info.first_element + (i - info.first_node);
                let mut el = model.elements[e].clone();
                el.node_a = index[el.node_a];
                el.node_b = index[el.node_b];
                elements.push(el);
                element_of.push(e);
            }
            let count = last - k + 1;
            hoses.push(HoseInfo {
                name: info.name.clone(),
                first_node: k,
                node_count: count,
                first_element,
                element_count: count - 1,
            });
            hose_of.push(h);
            k = last + 1;
        }
        let pick = |v: &[f64]| nodes.iter().map(|&i| v[i]).collect::<Vec<f64>>();
        let mut bodies = Vec::new();
        let mut body_index = vec![usize::MAX; model.bodies.len()];
        for (b, body) in model.bodies.iter().enumerate() {
            if body.nodes.iter().any(|&i| index[i] != usize::MAX) {
                let mut body = body.clone();
                for i in &mut body.nodes {
                    *i = index[*i];
                    if *i == usize::MAX {
                        return None; // a body is never cut (component takes it whole)
                    }
                }
                body_index[b] = bodies.len();
                bodies.push(body);
            }
        }
        let body_of = nodes
            .iter()
            .map(|&i| model.body_of[i].map(|b| body_index[b]))
            .collect();
        let mut junctions = Vec::new();
        for j in &model.junctions {
            if body_index[j.body] != usize::MAX {
                junctions.push(Junction {
                    name: j.name.clone(),
                    nodes: j.nodes.iter().map(|&i| index[i]).collect(),
                    body: body_index[j.body],
                    own: j.own,
                    shape: None,
                });
            }
        }
        // networks: each hose joined to the smallest hose index through junctions
        let mut hose_network: Vec<usize> = (0..hoses.len()).collect();
        let hose_at = |node: usize| {
            hoses
                .iter()
                .position(|h: &HoseInfo| h.nodes().contains(&node))
        };
        loop {
            let mut changed = false;
            for j in &junctions {
                let members: Vec<usize> = j.nodes.iter().filter_map(|&i| hose_at(i)).collect();
                let least = members.iter().map(|&h| hose_network[h]).min().unwrap_or(0);
                for h in members {
                    if hose_network[h] != least {
                        hose_network[h] = least;
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        // the explicit step's pieces of work: one (the mirror never steps explicitly)
        let hose_chunks = std::iter::once(0..hoses.len()).collect();
        let packed = PackedElements::new(&elements, &hoses);
        let mut cut = Model {
            hoses,
            elements,
            mass: pick(&model.mass),
            inertia: pick(&model.inertia),
            radius: pick(&model.radius),
            rest_x: nodes.iter().map(|&i| model.rest_x[i]).collect(),
            rest_q: nodes.iter().map(|&i| model.rest_q[i]).collect(),
            gravity: model.gravity,
            damping_mass: model.damping_mass,
            mass_scaling: model.mass_scaling,
            damping_stiffness: model.damping_stiffness,
            time_step: model.time_step,
            time_step_report: model.time_step_report.clone(),
            environment: model.environment.clone(),
            kinematics: model.kinematics.clone(),
            bodies,
            body_of,
            junctions,
            junction_shapes: Default::default(),
            hose_network,
            solver: model.solver,
            hose_contact: HoseContactModel::default(),
            packed,
            inelastic: model.inelastic.clone(),
            threads: 1,
            hose_chunks,
        };
        // the contact constants of the cut's beams, under the scene's rule and stiffness
        // cap (the time step report is the scene's)
        let mut contact = HoseContactModel::new(&cut, model.hose_contact.rule);
        contact.active &= model.hose_contact.active;
        contact.max_pairs = model.hose_contact.max_pairs;
        cut.hose_contact = contact;

        let lookup = |i: usize| Some(index[i]).filter(|&k| k != usize::MAX);
        let mut sub = State::at_rest(&cut);
        let mut cases: Vec<(LoadCaseId, LoadCaseId)> = Vec::new();
        for (id, case) in state.loads.iter() {
            if !touches(case, lookup) {
                continue;
            }
            // a tie is never cut: the component follows it
            let case = renumbered(case, lookup)?;
            cases.push((*id, sub.loads.add(case)));
        }
        let body_from = body_index
            .iter()
            .enumerate()
            .filter(|(_, &k)| k != usize::MAX)
            .map(|(b, _)| b)
            .collect();
        let mut out = Cut {
            model: cut,
            state: sub,
            nodes,
            hose_of,
            element_of,
            body_from,
            cases,
        };
        out.read(state);
        Some(out)
    }

    /// The cut's handle of the scene's load case `id` (`None`: not on the component).
    pub fn case(&self, id: LoadCaseId) -> Option<LoadCaseId> {
        self.cases
            .iter()
            .find(|(from, _)| *from == id)
            .map(|(_, to)| *to)
    }

    /// The cut's element of the scene's element `e` (`None`: not on the component).
    pub fn element(&self, e: usize) -> Option<usize> {
        self.element_of.iter().position(|&from| from == e)
    }

    /// The cut's node of the scene's node `i` (`None`: not on the component).
    pub fn node(&self, i: usize) -> Option<usize> {
        self.nodes.binary_search(&i).ok()
    }

    /// Puts the cut on the whole scene's newer `state` when the component and its load
    /// cases are still the same (`nodes` the component in `state`; their poses may have
    /// moved); `false` when a new cut is needed.
    pub fn refresh(&mut self, state: &State, nodes: &[usize]) -> bool {
        if nodes != self.nodes.as_slice() {
            return false;
        }
        let index = |i: usize| self.nodes.binary_search(&i).ok();
        let mut k = 0;
        for (id, case) in state.loads.iter() {
            if !touches(case, index) {
                continue;
            }
            let Some(&(from, to)) = self.cases.get(k) else {
                return false;
            };
            let (Some(case), Some(mine)) = (renumbered(case, index), self.state.loads.get_mut(to))
            else {
                return false;
            };
            if from != *id || std::mem::discriminant(mine) != std::mem::discriminant(&case) {
                return false;
            }
            // the same case, renumbered: its values (a hand's pose, a ramp) may be newer
            *mine = case;
            k += 1;
        }
        if k != self.cases.len() {
            return false;
        }
        self.read(state);
        true
    }

    /// Takes the component's configuration and memory from the whole scene's `state`.
    fn read(&mut self, state: &State) {
        let sub = &mut self.state;
        sub.time = state.time;
        sub.step = state.step;
        sub.inelastic_time = state.inelastic_time;
        sub.part_moves.clone_from(&state.part_moves);
        let friction = state.friction.fits(state.x.len());
        for (k, &i) in self.nodes.iter().enumerate() {
            sub.x[k] = state.x[i];
            sub.q[k] = state.q[i];
            sub.v[k] = DVec3::ZERO;
            sub.w[k] = DVec3::ZERO;
            sub.force[k] = state.force[i];
            sub.moment[k] = state.moment[i];
            sub.reaction_force[k] = state.reaction_force[i];
            sub.reaction_moment[k] = state.reaction_moment[i];
            sub.held[k] = state.held[i];
            sub.contact_force[k] = state.contact_force[i];
            sub.hose_contact_force[k] = state.hose_contact_force[i];
            sub.contact.node_normal[k] = state.contact.node_normal[i];
            if friction {
                sub.friction.anchor[k] = state.friction.anchor[i];
                sub.friction.sliding[k] = state.friction.sliding[i];
            }
        }
        for (e, &from) in self.element_of.iter().enumerate() {
            sub.contact.element_normal[e] = state.contact.element_normal[from];
        }
        for (b, &from) in self.body_from.iter().enumerate() {
            sub.bodies[b] = state.bodies[from];
        }
    }

    /// Writes the cut's configuration (node poses, body states) back into the whole
    /// scene's `state`.
    pub fn write_back(&self, state: &mut State) {
        for (k, &i) in self.nodes.iter().enumerate() {
            state.x[i] = self.state.x[k];
            state.q[i] = self.state.q[k];
        }
        for (b, &from) in self.body_from.iter().enumerate() {
            state.bodies[from] = self.state.bodies[b];
        }
    }
}

/// Whether any node `case` acts on lies in the cut (`index` gives a scene node's place
/// there).
fn touches(case: &LoadCase, index: impl Fn(usize) -> Option<usize>) -> bool {
    match case {
        LoadCase::Tie(t) => t.nodes.iter().any(|&n| index(n).is_some()),
        _ => index(case.node()).is_some(),
    }
}

/// `case` renumbered into the cut; `None` when a node it acts on lies outside.
fn renumbered(case: &LoadCase, index: impl Fn(usize) -> Option<usize> + Copy) -> Option<LoadCase> {
    let mut case = case.clone();
    let ok = match &mut case {
        LoadCase::Fix(c) => set(&mut c.node, index),
        LoadCase::Drive(c) => set(&mut c.node, index),
        LoadCase::DeadLoad(c) => set(&mut c.node, index),
        LoadCase::Support(c) => set(&mut c.node, index),
        LoadCase::Mount(c) => set(&mut c.node, index),
        LoadCase::Tie(c) => {
            let [a, b] = &mut c.nodes;
            set(a, index) && set(b, index)
        }
    };
    ok.then_some(case)
}

/// Renumbers `node` by `index`; whether it lies in the cut.
fn set(node: &mut usize, index: impl Fn(usize) -> Option<usize>) -> bool {
    match index(*node) {
        Some(k) => {
            *node = k;
            true
        }
        None => false,
    }
}
