//! The part of the scene a hand — or any change of loads — can move (SPEC H1, P5): in a
//! static equilibrium a node
//! held kinematically — in all six degrees of freedom, by a fix, drive or mount (a seated
//! clip, a stub's fixed end, a fixing pressed in, the hand itself) — transmits nothing of
//! its neighbours' motion to the others, so the network falls apart at such nodes into
//! independent problems. The component of some seed nodes (the hand's, or the nodes out
//! of balance) is what is coupled to them without passing a held node: along the elements, through the rigid bodies (a
//! junction's ends and a stiffened section's nodes are always taken together), along the
//! cable ties, and — with hose–hose contact on — across every pair of beams near enough
//! to touch ([`contact_reach`]). The held nodes where it ends belong to it as its
//! boundary (held where they are).

use crate::contact::hose_hose::closest_segment_segment;
use crate::loads::LoadCase;
use crate::{Model, State};
use glam::DVec3;

/// The sorted global nodes of the component of `seeds` (a hand's held nodes, nodes out of
/// balance, held nodes that move) in `state`: the seeds, every node reached from them
/// without passing a held node (a seed is passed even when held: it moves), and the held
/// nodes where it stops. (A search that allocates nothing once its buffers are sized:
/// [`ComponentSearch`].)
pub fn component(model: &Model, state: &State, seeds: &[usize]) -> Vec<usize> {
    ComponentSearch::default().run(model, state, seeds).to_vec()
}

/// The buffers of a [`component`] search, kept from one search to the next (the static
/// solver searches once per solve).
#[derive(Clone, Debug, Default)]
pub struct ComponentSearch {
    held: Vec<bool>,
    seed: Vec<bool>,
    inside: Vec<bool>,
    stack: Vec<usize>,
    /// The elements at each node: a hose's interior node has two, an end one.
    node_elements: Vec<[usize; 2]>,
    /// The cable ties as (node, other node), both ways, sorted.
    ties: Vec<(usize, usize)>,
    searched: Vec<bool>,
    near: Vec<usize>,
    grid: BeamGrid,
    /// The component found last, sorted.
    nodes: Vec<usize>,
}

impl ComponentSearch {
    /// The component of `seeds` in `state` ([`component`]).
    pub fn run(&mut self, model: &Model, state: &State, seeds: &[usize]) -> &[usize] {
        let n = model.node_count();
        let refill = |v: &mut Vec<bool>, len: usize| {
            v.clear();
            v.resize(len, false);
        };
        refill(&mut self.held, n);
        refill(&mut self.seed, n);
        refill(&mut self.inside, n);
        refill(&mut self.searched, model.elements.len());
        self.ties.clear();
        for (_, case) in state.loads.iter() {
            match case {
                LoadCase::Fix(_) | LoadCase::Drive(_) | LoadCase::Mount(_) => {
                    self.held[case.node()] = true
                }
                LoadCase::Tie(t) => {
                    self.ties.push((t.nodes[0], t.nodes[1]));
                    self.ties.push((t.nodes[1], t.nodes[0]));
                }
                LoadCase::DeadLoad(_) | LoadCase::Support(_) => {}
            }
        }
        self.ties.sort_unstable();
        self.node_elements.clear();
        self.node_elements.resize(n, [usize::MAX; 2]);
        for (e, el) in model.elements.iter().enumerate() {
            self.node_elements[el.node_a][1] = e;
            self.node_elements[el.node_b][0] = e;
        }
        let contact = model.hose_contact.active;
        if contact {
            self.grid.fill(model, state);
        }
        self.stack.clear();
        let (inside, stack) = (&mut self.inside, &mut self.stack);
        let mut reach = |node: usize| {
            if !inside[node] {
                inside[node] = true;
                stack.push(node);
            }
        };
        for &s in seeds {
            self.seed[s] = true;
            reach(s);
        }
        while let Some(node) = self.stack.pop() {
            let (inside, stack) = (&mut self.inside, &mut self.stack);
            let mut reach = |node: usize| {
                if !inside[node] {
                    inside[node] = true;
                    stack.push(node);
                }
            };
            // a held node is a boundary: nothing beyond it moves with the hand (held
            // seeds are the hand's own nodes or nodes driven elsewhere: the problem's
            // driven boundary)
            let expand = !self.held[node] || self.seed[node];
            if let Some(b) = model.body_of[node] {
                // a rigid body moves as one: all its nodes, held or not
                for &m in &model.bodies[b].nodes {
                    reach(m);
                }
            }
            if !expand {
                continue;
            }
            for e in self.node_elements[node] {
                if e == usize::MAX {
                    continue;
                }
                let el = &model.elements[e];
                reach(el.node_a);
                reach(el.node_b);
                if contact && !self.searched[e] {
                    self.searched[e] = true;
                    self.grid.near(model, state, e, &mut self.near);
                    for &f in &self.near {
                        let other = &model.elements[f];
                        reach(other.node_a);
                        reach(other.node_b);
                    }
                }
            }
            let first = self.ties.partition_point(|&(a, _)| a < node);
            for &(a, m) in &self.ties[first..] {
                if a != node {
                    break;
                }
                reach(m);
            }
        }
        self.nodes.clear();
        self.nodes.extend((0..n).filter(|&i| self.inside[i]));
        &self.nodes
    }
}

/// The reach within which two beams count as coupled by contact \[m\]: r₁ + r₂ (they
/// touch) plus the contact model's skin (its smallest beam radius: how far a node may
/// move before its broad phase looks again), more than the hand moves the hose between
/// two re-synchronisations of the mirror. The skin is below (π − 2) r, so two beams of
/// one straight hose that the contact model lets touch (apart by π r along it) are never
/// within reach: a clip on a straight run cuts.
pub fn contact_reach(model: &Model, a: usize, b: usize) -> f64 {
    let r = |e: usize| {
        let el = &model.elements[e];
        model.radius[el.node_a].max(model.radius[el.node_b])
    };
    r(a) + r(b) + model.hose_contact.skin
}

/// The beams in a uniform grid of cells as large as the longest beam plus the largest
/// reach, by their midpoints: only beams in the same or neighbouring cells can come
/// within [`contact_reach`] of each other. The beams are kept sorted by cell.
#[derive(Clone, Debug, Default)]
struct BeamGrid {
    cell: f64,
    beams: Vec<((i64, i64, i64), usize)>,
}

impl BeamGrid {
    /// Files the beams of `model` at their places in `state`.
    fn fill(&mut self, model: &Model, state: &State) {
        let r_max = model.radius.iter().copied().fold(0.0, f64::max);
        let longest = model
            .elements
            .iter()
            .map(|el| (state.x[el.node_b] - state.x[el.node_a]).length())
            .fold(0.0, f64::max);
        self.cell = longest + 2.0 * r_max + model.hose_contact.skin;
        self.beams.clear();
        if self.usable() {
            for e in 0..model.elements.len() {
                self.beams.push((self.key(model, state, e), e));
            }
            self.beams.sort_unstable();
        }
    }

    fn usable(&self) -> bool {
        self.cell > 0.0 && self.cell.is_finite()
    }

    fn key(&self, model: &Model, state: &State, e: usize) -> (i64, i64, i64) {
        let el = &model.elements[e];
        let mid = 0.5 * (state.x[el.node_a] + state.x[el.node_b]);
        let c = (mid / self.cell).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    }

    /// The beams the contact model lets touch beam `e` that come within
    /// [`contact_reach`] of it, into `out`.
    fn near(&self, model: &Model, state: &State, e: usize, out: &mut Vec<usize>) {
        out.clear();
        if !self.usable() {
            return;
        }
        let (cx, cy, cz) = self.key(model, state, e);
        let el = &model.elements[e];
        let (a0, a1) = (state.x[el.node_a], state.x[el.node_b]);
        for dx in -1..=1 {
            for dy in -1..=1 {
                // the three cells along z are neighbours in the sorted list: one search
                let (lo, hi) = ((cx + dx, cy + dy, cz - 1), (cx + dx, cy + dy, cz + 1));
                let first = self.beams.partition_point(|(k, _)| *k < lo);
                for &(k, f) in &self.beams[first..] {
                    if k > hi {
                        break;
                    }
                    if model.hose_contact.excluded(e, f) {
                        continue;
                    }
                    let other = &model.elements[f];
                    let (b0, b1) = (state.x[other.node_a], state.x[other.node_b]);
                    if segment_distance(a0, a1, b0, b1) <= contact_reach(model, e, f) {
                        out.push(f);
                    }
                }
            }
        }
    }
}

/// Distance between the segments p0p1 and q0q1 (their closest points by the contact
/// model's own [`closest_segment_segment`]).
fn segment_distance(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> f64 {
    let (s, t) = closest_segment_segment(p0, p1, q0, q1);
    (p0.lerp(p1, s) - q0.lerp(q1, t)).length()
}
