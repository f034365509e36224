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
use std::collections::HashMap;

/// The sorted global nodes of the component of `seeds` (a hand's held nodes, nodes out of
/// balance, held nodes that move) in `state`: the seeds, every node reached from them
/// without passing a held node (a seed is passed even when held: it moves), and the held
/// nodes where it stops.
pub fn component(model: &Model, state: &State, seeds: &[usize]) -> Vec<usize> {
    let n = model.node_count();
    let mut held = vec![false; n];
    let mut ties: HashMap<usize, Vec<usize>> = HashMap::new();
    for (_, case) in state.loads.iter() {
        match case {
            LoadCase::Fix(_) | LoadCase::Drive(_) | LoadCase::Mount(_) => held[case.node()] = true,
            LoadCase::Tie(t) => {
                ties.entry(t.nodes[0]).or_default().push(t.nodes[1]);
                ties.entry(t.nodes[1]).or_default().push(t.nodes[0]);
            }
            LoadCase::DeadLoad(_) | LoadCase::Support(_) => {}
        }
    }
    // the elements at each node: a hose's interior node has two, an end one
    let mut node_elements = vec![[usize::MAX; 2]; n];
    for (e, el) in model.elements.iter().enumerate() {
        node_elements[el.node_a][1] = e;
        node_elements[el.node_b][0] = e;
    }
    let grid = model
        .hose_contact
        .active
        .then(|| BeamGrid::new(model, state));
    let mut searched = vec![false; model.elements.len()];
    let mut near = Vec::new();
    let mut inside = vec![false; n];
    let mut stack: Vec<usize> = Vec::new();
    let mut seed = vec![false; n];
    for &s in seeds {
        seed[s] = true;
    }
    let reach = |node: usize, inside: &mut Vec<bool>, stack: &mut Vec<usize>| {
        if !inside[node] {
            inside[node] = true;
            stack.push(node);
        }
    };
    for &s in seeds {
        reach(s, &mut inside, &mut stack);
    }
    while let Some(node) = stack.pop() {
        // a held node is a boundary: nothing beyond it moves with the hand (held seeds
        // are the hand's own nodes or nodes driven elsewhere: the problem's driven
        // boundary)
        let expand = !held[node] || seed[node];
        if let Some(b) = model.body_of[node] {
            // a rigid body moves as one: all its nodes, held or not
            for &m in &model.bodies[b].nodes {
                reach(m, &mut inside, &mut stack);
            }
        }
        if !expand {
            continue;
        }
        for e in node_elements[node] {
            if e == usize::MAX {
                continue;
            }
            let el = &model.elements[e];
            reach(el.node_a, &mut inside, &mut stack);
            reach(el.node_b, &mut inside, &mut stack);
            if let Some(grid) = &grid {
                if !searched[e] {
                    searched[e] = true;
                    grid.near(model, state, e, &mut near);
                    for &f in &near {
                        let other = &model.elements[f];
                        reach(other.node_a, &mut inside, &mut stack);
                        reach(other.node_b, &mut inside, &mut stack);
                    }
                }
            }
        }
        if let Some(tied) = ties.get(&node) {
            for &m in tied {
                reach(m, &mut inside, &mut stack);
            }
        }
    }
    (0..n).filter(|&i| inside[i]).collect()
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
/// within [`contact_reach`] of each other.
struct BeamGrid {
    cell: f64,
    cells: HashMap<(i64, i64, i64), Vec<usize>>,
}

impl BeamGrid {
    fn new(model: &Model, state: &State) -> BeamGrid {
        let r_max = model.radius.iter().copied().fold(0.0, f64::max);
        let longest = model
            .elements
            .iter()
            .map(|el| (state.x[el.node_b] - state.x[el.node_a]).length())
            .fold(0.0, f64::max);
        let cell = longest + 2.0 * r_max + model.hose_contact.skin;
        let mut grid = BeamGrid {
            cell,
            cells: HashMap::new(),
        };
        if cell > 0.0 && cell.is_finite() {
            for e in 0..model.elements.len() {
                grid.cells
                    .entry(grid.key(model, state, e))
                    .or_default()
                    .push(e);
            }
        }
        grid
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
        if !(self.cell > 0.0 && self.cell.is_finite()) {
            return;
        }
        let (cx, cy, cz) = self.key(model, state, e);
        let el = &model.elements[e];
        let (a0, a1) = (state.x[el.node_a], state.x[el.node_b]);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(beams) = self.cells.get(&(cx + dx, cy + dy, cz + dz)) else {
                        continue;
                    };
                    for &f in beams {
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
}

/// Distance between the segments p0p1 and q0q1 (their closest points by the contact
/// model's own [`closest_segment_segment`]).
fn segment_distance(p0: DVec3, p1: DVec3, q0: DVec3, q1: DVec3) -> f64 {
    let (s, t) = closest_segment_segment(p0, p1, q0, q1);
    (p0.lerp(p1, s) - q0.lerp(q1, t)).length()
}
