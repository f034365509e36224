//! A branch of a harness (`pliant import … --branch ID`): the part beyond a branch point or
//! a segment, imported on its own with the cut held — the rest of the harness, already
//! installed, holds it there.
//!
//! - `ID` names a **node** (its KBL id or `<Id>` text): the node is cut out and every part
//!   of the harness hanging off it except the largest (the trunk, most segments; on a tie
//!   the longest) is the branch — all the outlets of that branch point at once.
//! - `ID` names a **segment**: the segment and everything beyond it, away from the larger
//!   rest of the harness: of its two nodes, the cut is the one whose removal leaves the
//!   segment in the smaller part.
//!
//! The branch keeps its segments, nodes, fixings, protections and the connectors on its
//! nodes (re-indexed); every wire stays in the model, routed through the branch's segments
//! only (a wire that leaves the branch is cut where the branch ends).

use std::collections::{HashMap, HashSet};

use crate::error::HarnessError;
use crate::model::Harness;

/// A branch: the sub-harness and the node where it was cut off (an index into its own
/// nodes), held in the scenes.
#[derive(Debug, Clone)]
pub struct Branch {
    pub harness: Harness,
    pub cut: usize,
    /// The id asked for, and what it named ("node" or "segment").
    pub id: String,
    pub named: &'static str,
    /// Segments of the whole harness.
    pub of_segments: usize,
}

/// Segments reachable from `start` (segment indices) without passing node `cut`.
fn part_from(h: &Harness, at: &[Vec<usize>], start: usize, cut: usize) -> HashSet<usize> {
    let mut seen = HashSet::from([start]);
    let mut stack = vec![start];
    while let Some(s) = stack.pop() {
        let seg = &h.segments[s];
        for n in [seg.start_node, seg.end_node] {
            if n == cut {
                continue;
            }
            for &t in &at[n] {
                if seen.insert(t) {
                    stack.push(t);
                }
            }
        }
    }
    seen
}

fn length_of(h: &Harness, part: &HashSet<usize>) -> f64 {
    part.iter()
        .filter_map(|&s| h.segments[s].virtual_length)
        .sum()
}

/// The branch of `h` named by `id` (see the module).
pub fn branch(h: &Harness, id: &str) -> Result<Branch, HarnessError> {
    let at = h.segments_at_nodes();
    let node = h
        .nodes
        .iter()
        .position(|n| n.kbl_id == id || n.name.as_deref() == Some(id));
    let segment = h
        .segments
        .iter()
        .position(|s| s.kbl_id == id || s.name.as_deref() == Some(id));
    let refuse = |reason: String| HarnessError::Branch {
        id: id.to_string(),
        reason,
    };
    let (keep, cut, named) = match (node, segment) {
        (Some(n), _) => {
            let mut parts: Vec<HashSet<usize>> = Vec::new();
            for &s in &at[n] {
                if !parts.iter().any(|p| p.contains(&s)) {
                    parts.push(part_from(h, &at, s, n));
                }
            }
            if parts.len() < 2 {
                return Err(refuse(format!(
                    "node {} is an end of the harness ({} segment{} meet there): name a branch point or a segment",
                    h.nodes[n].kbl_id,
                    at[n].len(),
                    if at[n].len() == 1 { "" } else { "s" }
                )));
            }
            let trunk = (0..parts.len())
                .max_by(|&a, &b| {
                    (parts[a].len(), length_of(h, &parts[a]))
                        .partial_cmp(&(parts[b].len(), length_of(h, &parts[b])))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .expect("two parts at least");
            let keep: HashSet<usize> = parts
                .into_iter()
                .enumerate()
                .filter(|(k, _)| *k != trunk)
                .flat_map(|(_, p)| p)
                .collect();
            (keep, n, "node")
        }
        (None, Some(s)) => {
            let seg = &h.segments[s];
            let a = part_from(h, &at, s, seg.start_node);
            let b = part_from(h, &at, s, seg.end_node);
            // cut at the start node: the part on the end node's side (a), and vice versa
            let (keep, cut) = if (a.len(), length_of(h, &a)) <= (b.len(), length_of(h, &b)) {
                (a, seg.start_node)
            } else {
                (b, seg.end_node)
            };
            if keep.len() == h.segments.len() {
                return Err(refuse(format!(
                    "segment {} ends the harness at both sides: nothing would hold its branch",
                    seg.kbl_id
                )));
            }
            (keep, cut, "segment")
        }
        (None, None) => {
            return Err(refuse(
                "no node or segment has this KBL id or <Id> (see harness.json of a full import for the ids)"
                    .into(),
            ))
        }
    };
    Ok(Branch {
        harness: restrict(h, &keep),
        cut: 0, // set below
        id: id.to_string(),
        named,
        of_segments: h.segments.len(),
    }
    .with_cut(h, cut))
}

impl Branch {
    fn with_cut(mut self, whole: &Harness, cut: usize) -> Self {
        let id = &whole.nodes[cut].kbl_id;
        self.cut = self
            .harness
            .nodes
            .iter()
            .position(|n| &n.kbl_id == id)
            .expect("the cut node ends a kept segment");
        self
    }
}

/// The harness restricted to the segments `keep` (re-indexed).
fn restrict(h: &Harness, keep: &HashSet<usize>) -> Harness {
    let mut segments: Vec<usize> = keep.iter().copied().collect();
    segments.sort_unstable();
    let seg_map: HashMap<usize, usize> =
        segments.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let mut nodes: Vec<usize> = segments
        .iter()
        .flat_map(|&s| [h.segments[s].start_node, h.segments[s].end_node])
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    let node_map: HashMap<usize, usize> = nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
    let mut out = h.clone();
    out.nodes = nodes.iter().map(|&n| h.nodes[n].clone()).collect();
    out.segments = segments
        .iter()
        .map(|&s| {
            let mut seg = h.segments[s].clone();
            seg.start_node = node_map[&seg.start_node];
            seg.end_node = node_map[&seg.end_node];
            seg
        })
        .collect();
    for w in &mut out.wires {
        w.segments = w
            .segments
            .iter()
            .filter_map(|s| seg_map.get(s).copied())
            .collect();
    }
    out.fixings = h
        .fixings
        .iter()
        .filter_map(|f| {
            let mut f = f.clone();
            f.segment = *seg_map.get(&f.segment)?;
            Some(f)
        })
        .collect();
    out.protections = h
        .protections
        .iter()
        .filter_map(|p| {
            let mut p = p.clone();
            p.segment = *seg_map.get(&p.segment)?;
            Some(p)
        })
        .collect();
    out.connectors = h
        .connectors
        .iter()
        .filter_map(|c| {
            let mut c = c.clone();
            c.node = Some(*node_map.get(&c.node?)?);
            Some(c)
        })
        .collect();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Connector, Node, Segment};
    use glam::DVec3;

    /// A star: node 0 in the middle, arms to nodes 1 (one segment), 2 (one) and 3 → 4
    /// (two segments, the trunk).
    fn star() -> Harness {
        let node = |k: usize| Node {
            kbl_id: format!("Node_{k}"),
            name: None,
            position: DVec3::new(k as f64, 0.0, 0.0),
        };
        let seg = |k: usize, a: usize, b: usize| Segment {
            kbl_id: format!("Segment_{k}"),
            name: None,
            start_node: a,
            end_node: b,
            virtual_length: Some(1.0),
            curves: Vec::new(),
            cross_section_area: None,
            wires: Vec::new(),
            line: 1,
        };
        Harness {
            source: "star.kbl".into(),
            kbl_version: "2.4".into(),
            nodes: (0..5).map(node).collect(),
            segments: vec![seg(1, 0, 1), seg(2, 0, 2), seg(3, 0, 3), seg(4, 3, 4)],
            wire_parts: Vec::new(),
            wires: Vec::new(),
            fixings: Vec::new(),
            protections: Vec::new(),
            connectors: vec![Connector {
                kbl_id: "X1".into(),
                name: None,
                description: None,
                node: Some(1),
                positions: 2,
            }],
            skipped: Vec::new(),
            warnings: Vec::new(),
        }
    }

    #[test]
    fn a_branch_point_gives_every_outlet_but_the_trunk() {
        let b = branch(&star(), "Node_0").unwrap();
        let ids: Vec<&str> = b
            .harness
            .segments
            .iter()
            .map(|s| s.kbl_id.as_str())
            .collect();
        assert_eq!(ids, ["Segment_1", "Segment_2"]);
        assert_eq!(b.harness.nodes[b.cut].kbl_id, "Node_0");
        assert_eq!(b.harness.connectors.len(), 1);
        assert_eq!(
            b.harness.nodes[b.harness.connectors[0].node.unwrap()].kbl_id,
            "Node_1"
        );
    }

    #[test]
    fn a_segment_gives_what_lies_beyond_it() {
        let b = branch(&star(), "Segment_4").unwrap();
        assert_eq!(b.harness.segments.len(), 1);
        assert_eq!(b.harness.nodes[b.cut].kbl_id, "Node_3");
        assert!(b.harness.connectors.is_empty());
        let b = branch(&star(), "Segment_3").unwrap();
        assert_eq!(b.harness.segments.len(), 2);
        assert_eq!(b.harness.nodes[b.cut].kbl_id, "Node_0");
    }

    #[test]
    fn ends_and_unknown_ids_are_refused() {
        let e = branch(&star(), "Node_1").unwrap_err().to_string();
        assert!(e.contains("is an end of the harness"), "{e}");
        let e = branch(&star(), "Node_9").unwrap_err().to_string();
        assert!(e.contains("no node or segment"), "{e}");
    }
}
