//! How many beam pairs hose–hose contact lists at rest, counted before a model is built
//! (the memory estimate must count the pairs). The pair list
//! ([`super::HoseContactScratch`]) holds every pair of beams whose boxes, grown by the
//! skin, overlap and that are not excluded ([`super::hose_hose`] module doc): a few per
//! beam for hoses laid apart, but every pair for hoses laid on top of each other — 5 000
//! hoses of 4 beams along one line make 2·10⁸ pairs, several GB. The count here files
//! the same boxes of the rest geometry in a [`BroadPhase`] and applies the same-hose
//! exclusion (beams closer along the hose than π (r_i + r_j)/2); junctions' exclusions
//! are not applied (an overcount of a few pairs per junction).

use super::BroadPhase;
use crate::spec::HoseSpec;
use std::f64::consts::PI;
use std::ops::ControlFlow;

/// Memory per listed pair \[bytes\]: the pair (2 × u32) in a growing `Vec` (up to twice
/// its length). The ranks the sweep sorts the pairs by while it builds the list (28 bytes
/// a pair) are bounded by the sweep's budget of 16 comparisons per beam (beyond it the
/// grid lists the pairs without ranks), so they belong to the per-element size. Measured:
/// 1 000 hoses of 4 beams on one line (5·10⁶ pairs) peak at 64 MB in all.
pub const BYTES_PER_CONTACT_PAIR: u64 = 16;

/// The beam pairs of `hoses` (rest geometry) the pair list would hold, counted up to
/// `limit` (the count stops there: a caller refusing the scene needs no more).
pub fn rest_pair_count(hoses: &[HoseSpec], limit: u64) -> u64 {
    let beams: usize = hoses.iter().map(|h| h.nodes.len().saturating_sub(1)).sum();
    if beams < 2 {
        return 0;
    }
    // per beam: hose, rest arc length at both ends, radius
    let mut hose_of = Vec::with_capacity(beams);
    let mut arc = Vec::with_capacity(beams);
    let mut radius = Vec::with_capacity(beams);
    let mut broad = BroadPhase::new(beams);
    let mut skin = f64::INFINITY;
    for (h, hose) in hoses.iter().enumerate() {
        let mut s = 0.0;
        for (e, pair) in hose.nodes.windows(2).enumerate() {
            let l = (pair[1] - pair[0]).length();
            let r = 0.5 * hose.element_section(e).d_outer;
            hose_of.push(h);
            arc.push((s, s + l));
            radius.push(r);
            skin = skin.min(r);
            s += l;
        }
    }
    let skin = if skin.is_finite() { skin } else { 0.0 };
    let mut k = 0;
    for hose in hoses {
        for pair in hose.nodes.windows(2) {
            let grow = glam::DVec3::splat(radius[k] + skin);
            broad.lo[k] = pair[0].min(pair[1]) - grow;
            broad.hi[k] = pair[0].max(pair[1]) + grow;
            k += 1;
        }
    }
    broad.rebuild();
    let mut count = 0u64;
    let _ = broad.try_for_each_pair(|i, j| {
        let excluded = hose_of[i] == hose_of[j] && {
            let (i, j) = if arc[i].0 < arc[j].0 { (i, j) } else { (j, i) };
            arc[j].0 - arc[i].1 < 0.5 * PI * (radius[i] + radius[j])
        };
        if !excluded {
            count += 1;
        }
        if count >= limit {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    count
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Material, Section};
    use glam::DVec3;

    fn hose(y: f64, elements: usize) -> HoseSpec {
        HoseSpec {
            name: format!("h{y}"),
            material: Material::isotropic(5e6, 0.45, 1100.0),
            nodes: (0..=elements)
                .map(|k| DVec3::new(0.5 * k as f64 / elements as f64, y, 0.0))
                .collect(),
            sections: vec![Section {
                d_inner: 0.01,
                d_outer: 0.02,
                given: Default::default(),
            }],
            normal_hint: None,
        }
    }

    #[test]
    fn hoses_laid_apart_list_no_pair_and_hoses_on_each_other_list_every_pair() {
        let apart: Vec<HoseSpec> = (0..50).map(|k| hose(0.1 * k as f64, 4)).collect();
        assert_eq!(rest_pair_count(&apart, u64::MAX), 0);
        let stacked: Vec<HoseSpec> = (0..50).map(|_| hose(0.0, 4)).collect();
        // 200 beams: every pair of beams of different hoses whose boxes overlap (each
        // beam overlaps its own place and its neighbours' on every other hose)
        let n = rest_pair_count(&stacked, u64::MAX);
        assert!(n >= 50 * 49 / 2 * 4, "{n}");
        assert_eq!(rest_pair_count(&stacked, 1000), 1000);
    }
}
