//! Broad phase of hose–hose contact (SPEC L5, §6): which beam capsules may touch, in
//! O(N) per step, with storage allocated once.
//!
//! A uniform grid, stored as a spatial hash with a counting sort (no per-step allocation):
//! 1. Each element's axis-aligned box (its segment grown by its radius) is given by the
//!    caller; the cell size h is this step's largest box extent along any axis, so every
//!    box's half-extent is ≤ h/2.
//! 2. Each element is filed under the cell of its box centre, floor(c/h). Two boxes that
//!    overlap have centres at most h apart per axis, so their cells differ by at most one
//!    per axis: a box's partners lie in its own cell or one of the 26 around it.
//! 3. Cells are hashed into 2^k ≥ 2N buckets; a counting sort lists each bucket's elements
//!    contiguously. For each element, its own cell (partners with a larger index) and 13
//!    "forward" neighbours (one of each opposite pair ±d) are visited, so every unordered
//!    pair is visited exactly once; a bucket entry is used only if its cell really is the
//!    one looked for (hash collisions and two neighbours sharing a bucket never duplicate).
//! 4. The boxes are compared; overlapping pairs are handed to the caller.
//!
//! Cost: O(N) to file, 14 bucket look-ups per element, and the boxes in them — bounded by
//! the packing of capsules, so linear in the number of beams at a fixed density. One very
//! stretched element grows h for all (still correct, only slower).

use glam::DVec3;

/// The 13 neighbour offsets with (dz, dy, dx) lexicographically positive, plus none of
/// their opposites.
const FORWARD: [[i64; 3]; 13] = [
    [1, 0, 0],
    [-1, 1, 0],
    [0, 1, 0],
    [1, 1, 0],
    [-1, -1, 1],
    [0, -1, 1],
    [1, -1, 1],
    [-1, 0, 1],
    [0, 0, 1],
    [1, 0, 1],
    [-1, 1, 1],
    [0, 1, 1],
    [1, 1, 1],
];

/// Uniform-grid broad phase over a fixed number of boxes; all storage allocated in `new`.
#[derive(Clone, Debug, Default)]
pub struct BroadPhase {
    /// Lower and upper corners of each box, written by the caller before [`Self::rebuild`].
    pub lo: Vec<DVec3>,
    pub hi: Vec<DVec3>,
    cell: Vec<[i64; 3]>,
    bucket_of: Vec<u32>,
    /// Bucket b's entries are `items[start[b]..start[b + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
    mask: u64,
    /// Cell size of the last rebuild [m].
    pub cell_size: f64,
}

fn hash(c: [i64; 3], mask: u64) -> u32 {
    let h = (c[0] as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (c[1] as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ (c[2] as u64).wrapping_mul(0x1656_67B1_9E37_79F9);
    ((h ^ (h >> 29)) & mask) as u32
}

impl BroadPhase {
    /// A broad phase for `n` boxes.
    pub fn new(n: usize) -> Self {
        let buckets = (2 * n).next_power_of_two().max(16);
        BroadPhase {
            lo: vec![DVec3::ZERO; n],
            hi: vec![DVec3::ZERO; n],
            cell: vec![[0; 3]; n],
            bucket_of: vec![0; n],
            start: vec![0; buckets + 1],
            items: vec![0; n],
            mask: buckets as u64 - 1,
            cell_size: 0.0,
        }
    }

    pub fn len(&self) -> usize {
        self.lo.len()
    }

    pub fn is_empty(&self) -> bool {
        self.lo.is_empty()
    }

    /// Files the boxes `lo`/`hi` into the grid. O(N), no allocation.
    pub fn rebuild(&mut self) {
        let n = self.lo.len();
        let mut h: f64 = 0.0;
        for i in 0..n {
            let ext = self.hi[i] - self.lo[i];
            h = h.max(ext.max_element());
        }
        // Guard against all-degenerate boxes; NaN boxes land in cell 0 (the health
        // check reports the divergence).
        let h = if h > 0.0 && h.is_finite() { h } else { 1.0 };
        self.cell_size = h;
        let inv = 1.0 / h;
        let buckets = self.start.len() - 1;
        self.start.fill(0);
        for i in 0..n {
            let c = 0.5 * (self.lo[i] + self.hi[i]) * inv;
            let cell = [c.x.floor() as i64, c.y.floor() as i64, c.z.floor() as i64];
            let b = hash(cell, self.mask);
            self.cell[i] = cell;
            self.bucket_of[i] = b;
            self.start[b as usize] += 1;
        }
        // Inclusive prefix sums (bucket ends), then fill backwards: start[b] becomes the
        // bucket's beginning and start[b + 1] its end.
        let mut sum = 0;
        for b in 0..buckets {
            sum += self.start[b];
            self.start[b] = sum;
        }
        self.start[buckets] = n as u32;
        for i in (0..n).rev() {
            let b = self.bucket_of[i] as usize;
            self.start[b] -= 1;
            self.items[self.start[b] as usize] = i as u32;
        }
    }

    fn overlap(&self, i: usize, j: usize) -> bool {
        self.lo[i].cmple(self.hi[j]).all() && self.lo[j].cmple(self.hi[i]).all()
    }

    /// Calls `f(i, j)` (i ≠ j, each unordered pair once) for every pair of overlapping
    /// boxes, as filed by the last [`Self::rebuild`].
    pub fn for_each_pair(&self, mut f: impl FnMut(usize, usize)) {
        for i in 0..self.lo.len() {
            let c = self.cell[i];
            // own cell: partners with a larger index
            let b = self.bucket_of[i] as usize;
            for &j in &self.items[self.start[b] as usize..self.start[b + 1] as usize] {
                let j = j as usize;
                if j > i && self.cell[j] == c && self.overlap(i, j) {
                    f(i, j);
                }
            }
            for d in FORWARD {
                let nc = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
                let b = hash(nc, self.mask) as usize;
                for &j in &self.items[self.start[b] as usize..self.start[b + 1] as usize] {
                    let j = j as usize;
                    if self.cell[j] == nc && self.overlap(i, j) {
                        f(i, j);
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_offsets_are_half_of_the_neighbourhood() {
        for d in FORWARD {
            let m = [-d[0], -d[1], -d[2]];
            assert!(!FORWARD.contains(&m));
            assert_ne!(d, [0, 0, 0]);
        }
        let mut all = std::collections::HashSet::new();
        for d in FORWARD {
            all.insert(d);
            all.insert([-d[0], -d[1], -d[2]]);
        }
        assert_eq!(all.len(), 26);
    }
}
