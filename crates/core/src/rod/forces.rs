//! Assembly of the nodal loads of all elements, gravity (P6) and damping (P4).

use crate::parallel::{Pool, SharedMut};
use crate::rod::body_loads::{self, BodyLoad, BodyNodes};
use crate::rod::element::ElementEnds;
use crate::rod::element_block::{self, Kernel};
use crate::Model;
use glam::DVec3;

use super::node_view::NodeView;

/// Writes the internal element loads (with stiffness-proportional damping β) into
/// `force` and `moment`, overwriting them. No allocation.
pub fn internal_loads(
    model: &Model,
    c: &NodeView,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
) {
    internal_loads_except(model, c, beta, force, moment, |_| false);
}

/// [`internal_loads`] leaving out the elements whose first node `skip` selects (the
/// elements of sleeping hoses, [`crate::sleep`]).
pub fn internal_loads_except(
    model: &Model,
    c: &NodeView,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    skip: impl Fn(usize) -> bool,
) {
    force.fill(DVec3::ZERO);
    moment.fill(DVec3::ZERO);
    if model.packed.element_count == model.elements.len() {
        element_block::add_loads(
            Kernel::detect(),
            &model.packed.blocks,
            &model.elements,
            c,
            0,
            beta,
            force,
            moment,
            &skip,
        );
        if model.inelastic.any() {
            let all = 0..model.inelastic.elements.len();
            let elements = &model.elements;
            model
                .inelastic
                .add_loads(elements, all, c, 0, beta, force, moment, &skip);
        }
    } else {
        add_reference_loads(model, c, beta, force, moment, skip);
    }
}

/// Adds the internal loads element by element with the reference [`crate::rod::element::BeamElement::loads`]
/// (what [`crate::rod::element_block`] computes four at a time), inelastic elements by
/// their law ([`crate::rod::inelastic`]).
pub fn add_reference_loads(
    model: &Model,
    c: &NodeView,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    skip: impl Fn(usize) -> bool,
) {
    for e in &model.elements {
        let (a, b) = (e.node_a, e.node_b);
        if skip(a) {
            continue;
        }
        let ends = ElementEnds {
            x: [c.x[a], c.x[b]],
            q: [c.q[a], c.q[b]],
            v: [c.v[a], c.v[b]],
            w: [c.w[a], c.w[b]],
        };
        let l = match &e.inelastic {
            Some(hinge) => model
                .inelastic
                .loads(e, hinge, c.inelastic_history, &ends, beta),
            None => e.loads(&ends, beta),
        };
        force[a] += l.force[0];
        force[b] += l.force[1];
        moment[a] += l.moment[0];
        moment[b] += l.moment[1];
    }
}

/// Adds gravity m g and mass-proportional damping −α m v, −α I ω.
pub fn add_body_loads(model: &Model, c: &NodeView, force: &mut [DVec3], moment: &mut [DVec3]) {
    add_body_loads_of(model, 0, c, force, moment);
}

/// [`add_body_loads`] for the nodes `base..` that `c`, `force` and `moment` hold, four
/// at a time ([`crate::rod::body_loads`]).
pub fn add_body_loads_of(
    model: &Model,
    base: usize,
    c: &NodeView,
    force: &mut [DVec3],
    moment: &mut [DVec3],
) {
    let n = force.len();
    body_loads::add_body_loads(
        BodyLoad {
            gravity: model.gravity,
            alpha: model.damping_mass,
        },
        BodyNodes {
            mass: &model.mass[base..base + n],
            inertia: &model.inertia[base..base + n],
            v: &c.v[..n],
            w: &c.w[..n],
            force,
            moment: &mut moment[..n],
        },
    );
}

/// The explicit step's loads: [`internal_loads_except`] then [`add_body_loads`], shared
/// between `model.threads` threads hose group by hose group ([`Model::hose_chunks`]) —
/// each node gets the same sums in the same order as on one thread.
pub fn step_loads(
    model: &Model,
    c: &NodeView,
    beta: f64,
    force: &mut [DVec3],
    moment: &mut [DVec3],
    skip: impl Fn(usize) -> bool + Sync,
) {
    let chunks = &model.hose_chunks;
    if model.threads <= 1 || chunks.len() <= 1 || !whole_hose_chunks(model) {
        internal_loads_except(model, c, beta, force, moment, skip);
        add_body_loads(model, c, force, moment);
        return;
    }
    let kernel = Kernel::detect();
    let (fp, mp) = (SharedMut::new(force), SharedMut::new(moment));
    Pool::global().run(model.threads, chunks.len(), &|k| {
        let hoses = chunks[k].clone();
        let nodes = chunk_nodes(model, hoses.clone());
        // SAFETY: the chunks' node ranges are disjoint and lie within the arrays
        // (`whole_hose_chunks`); `run` returns only when every chunk is done.
        let (force, moment) = unsafe { (fp.slice(nodes.clone()), mp.slice(nodes.clone())) };
        force.fill(DVec3::ZERO);
        moment.fill(DVec3::ZERO);
        let part = NodeView {
            x: &c.x[nodes.clone()],
            q: &c.q[nodes.clone()],
            v: &c.v[nodes.clone()],
            w: &c.w[nodes.clone()],
            inelastic_history: c.inelastic_history,
        };
        let hb = &model.packed.hose_blocks;
        element_block::add_loads(
            kernel,
            &model.packed.blocks[hb[hoses.start]..hb[hoses.end]],
            &model.elements,
            &part,
            nodes.start,
            beta,
            force,
            moment,
            &skip,
        );
        if model.inelastic.any() {
            let hp = &model.inelastic.hose_elements;
            let range = hp[hoses.start]..hp[hoses.end];
            let elements = &model.elements;
            model.inelastic.add_loads(
                elements,
                range,
                &part,
                nodes.start,
                beta,
                force,
                moment,
                &skip,
            );
        }
        add_body_loads_of(model, nodes.start, &part, force, moment);
    });
}

/// The nodes of hoses `hoses` (consecutive in the node arrays).
pub fn chunk_nodes(model: &Model, hoses: std::ops::Range<usize>) -> std::ops::Range<usize> {
    let last = &model.hoses[hoses.end - 1];
    model.hoses[hoses.start].first_node..last.first_node + last.node_count
}

/// Whether the hose chunks cover the nodes, each hose's elements packed and joining its
/// own nodes — as [`Model::build`] makes them (a check, so that the parallel paths never
/// see anything else).
pub fn whole_hose_chunks(model: &Model) -> bool {
    let mut next = 0;
    for h in &model.hoses {
        if h.first_node != next {
            return false;
        }
        next += h.node_count;
    }
    next == model.node_count()
        && model.packed.element_count == model.elements.len()
        && model.packed.hose_blocks.len() == model.hoses.len() + 1
        && model
            .hose_chunks
            .last()
            .is_some_and(|c| c.end == model.hoses.len())
}
