//! How far apart, along a network of hoses (SPEC N1), the ends of two different hoses
//! are: the hose–hose contact rule excludes beams closer along the hoses than the tightest
//! U a hose can make ([`super::HoseContactModel::excluded`]), and at a junction the beams
//! of different hoses meeting there are as close along the network as neighbours on one
//! hose — their capsules overlap at rest, and a force between them would be an artefact.
//! The distances are shortest paths over the hose ends (Dijkstra, bounded by the largest
//! gap that can matter): a hose joins its two ends by its length, a junction its ends by
//! their rest distance (0 at a welded branch point).

use crate::Model;
use std::collections::{BTreeMap, BinaryHeap};

/// The gaps between the ends of different hoses shorter than a bound.
#[derive(Clone, Debug, Default)]
pub struct NetworkGaps {
    /// (hose a, hose b), a < b → (a's end, b's end, distance along the network \[m\]);
    /// an end is `false` for the first node, `true` for the last.
    pairs: BTreeMap<(u32, u32), Vec<EndGap>>,
}

/// Hose a's end, hose b's end (`false`: the first node, `true`: the last) and the
/// distance between them along the network \[m\].
type EndGap = (bool, bool, f64);

/// Index of hose `h`'s end in the graph of ends.
fn end_index(h: usize, at_end: bool) -> usize {
    2 * h + usize::from(at_end)
}

impl NetworkGaps {
    /// The gaps of `model`'s junctions up to `bound` \[m\] (none without junctions).
    pub fn new(model: &Model, bound: f64) -> Self {
        let mut gaps = NetworkGaps::default();
        if model.junctions.is_empty() {
            return gaps;
        }
        let ends = 2 * model.hoses.len();
        // adjacency: (other end, length)
        let mut adjacent: Vec<Vec<(usize, f64)>> = vec![Vec::new(); ends];
        let mut end_of_node = std::collections::HashMap::new();
        for (h, info) in model.hoses.iter().enumerate() {
            let length: f64 = (info.first_element..info.first_element + info.element_count)
                .map(|e| model.elements[e].rest_length)
                .sum();
            adjacent[end_index(h, false)].push((end_index(h, true), length));
            adjacent[end_index(h, true)].push((end_index(h, false), length));
            end_of_node.insert(info.first_node, end_index(h, false));
            end_of_node.insert(info.first_node + info.node_count - 1, end_index(h, true));
        }
        for j in &model.junctions {
            for &a in &j.nodes {
                for &b in &j.nodes {
                    if a != b {
                        let d = (model.rest_x[a] - model.rest_x[b]).length();
                        adjacent[end_of_node[&a]].push((end_of_node[&b], d));
                    }
                }
            }
        }
        // Dijkstra from every end that lies at a junction, bounded by `bound`
        let mut distance = vec![f64::INFINITY; ends];
        let mut touched = Vec::new();
        for source in 0..ends {
            if adjacent[source].len() < 2 {
                continue; // a free end: no junction
            }
            let mut heap = BinaryHeap::new();
            distance[source] = 0.0;
            touched.push(source);
            heap.push((Reverse(0.0), source));
            while let Some((Reverse(d), e)) = heap.pop() {
                if d > distance[e] {
                    continue;
                }
                for &(next, w) in &adjacent[e] {
                    let nd = d + w;
                    if nd < distance[next] && nd <= bound {
                        if distance[next].is_infinite() {
                            touched.push(next);
                        }
                        distance[next] = nd;
                        heap.push((Reverse(nd), next));
                    }
                }
            }
            let (ha, ea) = (source / 2, source % 2 == 1);
            for &t in &touched {
                let (hb, eb) = (t / 2, t % 2 == 1);
                if ha < hb {
                    gaps.pairs.entry((ha as u32, hb as u32)).or_default().push((
                        ea,
                        eb,
                        distance[t],
                    ));
                }
            }
            for &t in &touched {
                distance[t] = f64::INFINITY;
            }
            touched.clear();
        }
        gaps
    }

    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Whether the distance along the network between a point of hose `a` and one of
    /// hose `b` ([`Self::gap`]) is below `limit`. Every path leaves through an end of each
    /// hose, so the gap is at least the nearer end's arc length on each: when that sum
    /// reaches `limit` the answer needs no look-up (floating-point addition is monotone,
    /// so the bound holds for the rounded sums too).
    pub fn shorter_than(
        &self,
        (a, along_a): (u32, (f64, f64)),
        (b, along_b): (u32, (f64, f64)),
        limit: f64,
    ) -> bool {
        let nearest_end = |(from_start, from_end): (f64, f64)| from_start.min(from_end);
        if nearest_end(along_a) + nearest_end(along_b) >= limit {
            return false;
        }
        self.gap(a, along_a, b, along_b) < limit
    }

    /// The shortest distance along the network between a point `(a_from_start,
    /// a_from_end)` of hose `a` (its arc lengths to the hose's first and last node) and
    /// one of hose `b`, through their ends; infinite when no short path joins them.
    pub fn gap(&self, a: u32, along_a: (f64, f64), b: u32, along_b: (f64, f64)) -> f64 {
        let (key, along_a, along_b) = if a < b {
            ((a, b), along_a, along_b)
        } else {
            ((b, a), along_b, along_a)
        };
        let Some(list) = self.pairs.get(&key) else {
            return f64::INFINITY;
        };
        let pick = |(from_start, from_end): (f64, f64), at_end: bool| {
            if at_end {
                from_end
            } else {
                from_start
            }
        };
        list.iter()
            .map(|&(ea, eb, d)| pick(along_a, ea) + d + pick(along_b, eb))
            .fold(f64::INFINITY, f64::min)
    }
}

/// A max-heap key ordered the other way round (for Dijkstra's smallest-first queue).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Reverse(f64);

impl Eq for Reverse {}

impl PartialOrd for Reverse {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Reverse {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other.0.total_cmp(&self.0)
    }
}
