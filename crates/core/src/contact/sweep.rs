//! Sort and sweep along one axis (Baraff, "Dynamic Simulation of Non-Penetrating Rigid
//! Bodies", PhD thesis, Cornell 1992, §7.2; Ericson, "Real-Time Collision Detection"
//! §7.5.1): the pairs of overlapping axis-aligned boxes, cheap when the boxes are spread
//! along one axis, as the beams of a long hanging hose are.
//!
//! The boxes are sorted by their lower bound along the axis of the largest spread of the
//! box centres; each box is compared with the boxes after it whose lower bound does not
//! exceed its upper bound (those after cannot overlap it along the axis), and the pairs that
//! overlap along the other two axes as well are reported. A box lies on either side of the
//! other's lower bound, so every overlapping pair is reported exactly once. The order is
//! kept between calls: a hose that moved a little is nearly sorted, and insertion sort
//! costs O(N + swaps).
//!
//! The cost is O(N) plus the pairs that overlap along the sweep axis. A world piled up
//! along every axis (a coiled hose, a bundle) may have O(N²) of those; the sweep then stops
//! after a budget of comparisons and the caller uses the uniform grid
//! ([`super::broad_phase`]), whose cost is bounded by the packing of the boxes.

use glam::DVec3;

/// The sweep's sorted order and copies of the boxes in it; storage allocated in `new`.
#[derive(Clone, Debug, Default)]
pub struct SweepAndPrune {
    /// Box indices by increasing lower bound along `axis`.
    order: Vec<u32>,
    /// The axis `order` was sorted along (3: never sorted).
    axis: usize,
    /// Boxes in `order`.
    s_lo: Vec<DVec3>,
    s_hi: Vec<DVec3>,
}

/// The sweep gave up: more than the budget of comparisons along the sweep axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OverBudget;

impl SweepAndPrune {
    /// A sweep over `n` boxes.
    pub fn new(n: usize) -> Self {
        SweepAndPrune {
            order: (0..n as u32).collect(),
            axis: 3,
            s_lo: vec![DVec3::ZERO; n],
            s_hi: vec![DVec3::ZERO; n],
        }
    }

    /// Calls `f(i, j)` once for every unordered pair of boxes `lo`/`hi` that overlap
    /// (`lo_i ≤ hi_j` and `lo_j ≤ hi_i` on all axes), unless that takes more than `budget`
    /// comparisons along the sweep axis, or a box is not finite: then it stops with
    /// [`OverBudget`] (some pairs may have been reported). No allocation.
    pub fn for_each_pair(
        &mut self,
        lo: &[DVec3],
        hi: &[DVec3],
        budget: usize,
        mut f: impl FnMut(usize, usize),
    ) -> Result<(), OverBudget> {
        let n = lo.len();
        if self.order.len() != n {
            return Err(OverBudget);
        }
        let (mut c_min, mut c_max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for (l, h) in lo.iter().zip(hi) {
            let c = *l + *h;
            c_min = c_min.min(c);
            c_max = c_max.max(c);
        }
        let spread = c_max - c_min;
        if !spread.is_finite() || !lo.iter().chain(hi).all(|p| p.is_finite()) {
            return Err(OverBudget);
        }
        let axis = if spread.x >= spread.y && spread.x >= spread.z {
            0
        } else if spread.y >= spread.z {
            1
        } else {
            2
        };
        let key = |i: u32| lo[i as usize][axis];
        if axis != self.axis {
            self.order
                .sort_unstable_by(|&a, &b| key(a).total_cmp(&key(b)));
            self.axis = axis;
        } else {
            // insertion sort from the last order, up to `budget` moves (then the sort)
            let mut moves = 0;
            for k in 1..n {
                let item = self.order[k];
                let v = key(item);
                let mut m = k;
                while m > 0 && key(self.order[m - 1]) > v {
                    self.order[m] = self.order[m - 1];
                    m -= 1;
                }
                self.order[m] = item;
                moves += k - m;
                if moves > budget {
                    self.order
                        .sort_unstable_by(|&a, &b| key(a).total_cmp(&key(b)));
                    break;
                }
            }
        }
        for (k, &i) in self.order.iter().enumerate() {
            self.s_lo[k] = lo[i as usize];
            self.s_hi[k] = hi[i as usize];
        }
        let mut comparisons = 0;
        for k in 0..n {
            let (l, h) = (self.s_lo[k], self.s_hi[k]);
            let top = h[axis];
            for m in k + 1..n {
                let (lm, hm) = (self.s_lo[m], self.s_hi[m]);
                if lm[axis] > top {
                    break;
                }
                comparisons += 1;
                if l.cmple(hm).all() && lm.cmple(h).all() {
                    f(self.order[k] as usize, self.order[m] as usize);
                }
            }
            if comparisons > budget {
                return Err(OverBudget);
            }
        }
        Ok(())
    }
}
