//! A Verlet skin over the beams' clear tests (L. Verlet, Phys. Rev. 159, 98, 1967):
//! after a pass that asked [`CandidateCache::clear_slack`] of every beam, the beams found
//! clear (the members) stay clear while every node stays within the smallest of their
//! slacks of where it was — one displacement check per node instead of one clear test per
//! beam, most steps.
//!
//! Exact: a member's clear test compares the larger displacement of its end points from
//! the slot's anchors with the slot's margin; each end point's displacement grows by at
//! most the node's own displacement since the pass (triangle inequality), so a node
//! displacement below the member's slack (its margin less its displacement at the pass,
//! both with relative slack for rounding) leaves the test true, to the last bit. The
//! skin lapses as soon as any slot of the cache is refreshed or cleared (its
//! [`CandidateCache::generation`] changes), and then the next pass asks every beam again.

use super::coherence::CandidateCache;
use glam::DVec3;

/// Relative slack for rounding: the skin is kept a little thinner than the slacks.
const SLACK: f64 = 1e-9;

/// The members of the last full pass and where the nodes were then.
#[derive(Clone, Debug, Default)]
pub struct ClearSkin {
    /// Node positions at the last full pass.
    reference: Vec<DVec3>,
    /// Beams found clear at the last full pass.
    member: Vec<bool>,
    /// Smallest member slack of the pass in progress.
    slack: f64,
    /// Square of the displacement below which every node keeps the members clear
    /// (−∞: no skin).
    limit_squared: f64,
    /// The cache's generation at the last full pass.
    generation: u64,
}

impl ClearSkin {
    /// A skin for `nodes` nodes and `beams` beams, lapsed.
    pub fn new(nodes: usize, beams: usize) -> Self {
        ClearSkin {
            reference: vec![DVec3::ZERO; nodes],
            member: vec![false; beams],
            slack: f64::INFINITY,
            limit_squared: f64::NEG_INFINITY,
            generation: 0,
        }
    }

    /// Whether the members of the last full pass are all still clear for nodes at `x`,
    /// without asking the cache: its lists are the ones the pass saw (`cache`'s
    /// generation unchanged, its lists in use) and every node moved less than the skin.
    pub(crate) fn holds(&self, cache: &CandidateCache, x: &[DVec3]) -> bool {
        cache.enabled
            && cache.generation() == self.generation
            && x.len() == self.reference.len()
            && x.iter()
                .zip(&self.reference)
                .all(|(x, p)| (*x - *p).length_squared() < self.limit_squared)
    }

    /// Whether beam `e` is a member (clear at the last full pass).
    pub(crate) fn is_member(&self, e: usize) -> bool {
        self.member.get(e) == Some(&true)
    }

    /// Starts a full pass with the nodes at `x`.
    pub(crate) fn begin(&mut self, cache: &CandidateCache, x: &[DVec3]) {
        self.reference.clear();
        self.reference.extend_from_slice(x);
        self.member.fill(false);
        self.slack = f64::INFINITY;
        self.generation = cache.generation();
    }

    /// Beam `e` was found clear in the pass, with `slack` ([`CandidateCache::clear_slack`]).
    pub(crate) fn add(&mut self, e: usize, slack: f64) {
        if let Some(m) = self.member.get_mut(e) {
            *m = true;
            self.slack = self.slack.min(slack);
        }
    }

    /// Ends the pass: the skin is the smallest member slack, a little thinner (none
    /// without members: the next step asks every beam again).
    pub(crate) fn end(&mut self) {
        let limit = self.slack * (1.0 - SLACK);
        self.limit_squared = if limit > 0.0 && limit.is_finite() {
            limit * limit
        } else {
            f64::NEG_INFINITY
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::coherence::Searcher;
    use crate::contact::environment::{cube, test_plate, ClosestPoint};

    /// A beam walking down onto a plate, its list kept by the cache: whenever the skin
    /// calls it clear, so does the cache's own test; the skin spares most of the tests.
    #[test]
    fn the_skin_says_what_the_clear_test_says() {
        let env = test_plate();
        let reach = 0.01;
        let mut cache = CandidateCache::new(1, &env);
        let mut skin = ClearSkin::new(2, 1);
        let (mut skipped, mut near) = (0, 0);
        for k in 0..400 {
            let s = k as f64 * 0.002;
            let a = DVec3::new(0.3 * s.sin(), 0.2 * s.cos(), 0.06 - k as f64 * 1.5e-4);
            let x = [a, a + DVec3::new(0.05, 0.0, 0.01)];
            // the pass of `rigid::resolve_velocities` for one beam
            let holds = skin.holds(&cache, &x);
            if !holds {
                skin.begin(&cache, &x);
            }
            let clear = if holds && skin.is_member(0) {
                skipped += 1;
                true
            } else {
                let slack = cache.clear_slack(0, x[0], x[1], reach);
                if let (false, Some(slack)) = (holds, slack) {
                    skin.add(0, slack);
                }
                slack.is_some()
            };
            if !holds {
                skin.end();
            }
            let asked = cache.clear_slack(0, x[0], x[1], reach).is_some();
            assert_eq!(clear, asked, "step {k}");
            if !clear {
                near += 1;
                let mut search = ClosestPoint::new(a, reach);
                let query = cube(a, reach);
                let searcher = Searcher::StartNode;
                cache.scan(
                    &env,
                    0,
                    x[0],
                    x[1],
                    reach,
                    searcher,
                    [a, a],
                    &query,
                    &mut search,
                );
            }
        }
        assert!(skipped > 200 && near > 0, "{skipped} skipped, {near} near");
    }
}
