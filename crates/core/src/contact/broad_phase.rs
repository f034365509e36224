//! Broad phase of hose–hose contact (SPEC L5, §6): which beam capsules may touch, in
//! O(N) per step, with storage allocated once.
//!
//! A uniform grid, stored as a spatial hash with a counting sort (no per-step allocation):
//! 1. Each element's axis-aligned box (its segment grown by its radius) is given by the
//!    caller; the cell size h is, per axis, this step's largest box extent along it, so
//!    every box's half-extent is ≤ h/2 (hoses lying along x do not coarsen y and z).
//! 2. Each element is filed under the cell of its box centre, floor(c/h). Two boxes that
//!    overlap have centres at most h apart per axis, so their cells differ by at most one
//!    per axis: a box's partners lie in its own cell or one of the 26 around it.
//! 3. Cells are hashed into 2^k ≥ 2N buckets; a counting sort lists each bucket's elements
//!    contiguously. For each element, its own cell (partners with a larger index) and 13
//!    "forward" neighbours (one of each opposite pair ±d) are visited, so every unordered
//!    pair is visited exactly once; a bucket entry is used only if its cell really is the
//!    one looked for (hash collisions and two neighbours sharing a bucket never duplicate).
//!    Cells, boxes and indices are copied in bucket order, so the scans read contiguous
//!    memory.
//! 4. The boxes are compared; overlapping pairs are handed to the caller.
//!
//! Cost: O(N) to file, 14 bucket look-ups per element, and the boxes in them — bounded by
//! the packing of capsules, so linear in the number of beams at a fixed density. One very
//! stretched element grows h for all (still correct, only slower).

use glam::DVec3;
use std::ops::ControlFlow;

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
    /// Packed cell of each box.
    key: Vec<u64>,
    bucket_of: Vec<u32>,
    /// Bucket b's entries are positions `start[b]..start[b + 1]` of the sorted arrays.
    start: Vec<u32>,
    /// Sorted by bucket: box index, packed cell and corners (contiguous for the scans).
    items: Vec<u32>,
    s_key: Vec<u64>,
    s_lo: Vec<DVec3>,
    s_hi: Vec<DVec3>,
    /// 64 − log₂(number of buckets).
    shift: u32,
    /// Cell size of the last rebuild along x, y, z \[m\].
    pub cell_size: DVec3,
}

const BITS: u32 = 21;
const FIELD: u64 = (1 << BITS) - 1;

/// Cell coordinates packed into one word (21 bits each, wrapping: cells 2²¹ apart share
/// a key, which only costs a box test — such boxes never overlap).
fn pack(c: [i64; 3]) -> u64 {
    ((c[0] as u64 & FIELD) << (2 * BITS)) | ((c[1] as u64 & FIELD) << BITS) | (c[2] as u64 & FIELD)
}

fn offset(key: u64, d: [i64; 3]) -> u64 {
    let f = |shift: u32, d: i64| (((key >> shift) & FIELD).wrapping_add(d as u64) & FIELD) << shift;
    f(2 * BITS, d[0]) | f(BITS, d[1]) | f(0, d[2])
}

/// Cell of key `b` minus cell of key `a`, per axis, each field read as a signed 21-bit
/// difference (the inverse of [`offset`]: `offset(a, cell_difference(a, b)) == b`).
fn cell_difference(a: u64, b: u64) -> [i64; 3] {
    let f = |shift: u32| {
        let d = ((b >> shift).wrapping_sub(a >> shift) & FIELD) as i64;
        if d >= 1 << (BITS - 1) {
            d - (1 << BITS)
        } else {
            d
        }
    };
    [f(2 * BITS), f(BITS), f(0)]
}

/// Order in which [`BroadPhase::for_each_pair`] reports a pair: (bucket, index) of the
/// box that scans, the cell scanned (0 own, 1–13 `FORWARD`), (bucket, index) of the
/// box found.
pub type VisitRank = (u32, u32, u8, u32, u32);

/// Fibonacci hashing: the top bits of key·⌊2⁶⁴/φ⌋, which depend on every bit of the key.
fn hash(key: u64, shift: u32) -> u32 {
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> shift) as u32
}

impl BroadPhase {
    /// A broad phase for `n` boxes.
    pub fn new(n: usize) -> Self {
        let buckets = (2 * n).next_power_of_two().max(16);
        BroadPhase {
            lo: vec![DVec3::ZERO; n],
            hi: vec![DVec3::ZERO; n],
            key: vec![0; n],
            bucket_of: vec![0; n],
            start: vec![0; buckets + 1],
            items: vec![0; n],
            s_key: vec![0; n],
            s_lo: vec![DVec3::ZERO; n],
            s_hi: vec![DVec3::ZERO; n],
            shift: 64 - buckets.trailing_zeros(),
            cell_size: DVec3::ZERO,
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
        self.set_cell_size();
        let buckets = self.start.len() - 1;
        self.start.fill(0);
        for i in 0..n {
            let (key, b) = self.cell(i);
            self.key[i] = key;
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
            let k = self.start[b] as usize;
            self.items[k] = i as u32;
            self.s_key[k] = self.key[i];
            self.s_lo[k] = self.lo[i];
            self.s_hi[k] = self.hi[i];
        }
    }

    /// Step 1 of a rebuild: the cell size of the boxes `lo`/`hi`. O(N), no allocation.
    /// Enough for [`Self::cell`] and [`Self::visit_rank`].
    pub fn set_cell_size(&mut self) {
        // Cell size per axis: the largest box extent along it (a box elongated along one
        // axis does not coarsen the grid along the others).
        let mut h = DVec3::ZERO;
        for (lo, hi) in self.lo.iter().zip(&self.hi) {
            h = h.max(*hi - *lo);
        }
        // Guard against degenerate extents; NaN boxes land in cell 0 (the health check
        // reports the divergence).
        let fallback = if h.max_element() > 0.0 && h.max_element().is_finite() {
            h.max_element()
        } else {
            1.0
        };
        self.cell_size = DVec3::select(
            h.cmpgt(DVec3::splat(1e-9 * fallback)) & h.is_finite_mask(),
            h,
            DVec3::splat(fallback),
        );
    }

    /// Step 2 for box `i`: its packed cell, floor(c/h) of its centre c, and bucket.
    pub fn cell(&self, i: usize) -> (u64, u32) {
        let c = (0.5 * (self.lo[i] + self.hi[i]) * self.cell_size.recip()).floor();
        let key = pack([c.x as i64, c.y as i64, c.z as i64]);
        (key, hash(key, self.shift))
    }

    /// Where [`Self::for_each_pair`] reports the pair of boxes `i`, `j` (after
    /// [`Self::set_cell_size`] or [`Self::rebuild`]): `Some((rank, first, second))`, the pair
    /// being reported as `f(first, second)` and pairs reported in increasing `rank`;
    /// `None` if it does not report it whether or not the boxes overlap (their cells are
    /// not neighbours). The sorted arrays hold bucket by bucket, each bucket in increasing
    /// box index (the counting sort fills backwards), so a box's position is
    /// (bucket, index); a box scans its own cell (rank 0), then the `FORWARD` cells in
    /// order (ranks 1–13), each in increasing position.
    pub fn visit_rank(&self, i: usize, j: usize) -> Option<(VisitRank, usize, usize)> {
        let ((ki, bi), (kj, bj)) = (self.cell(i), self.cell(j));
        let bucket = |k: usize| if k == i { bi } else { bj };
        let at = |first: usize, cell: u8, second: usize| {
            let rank = (
                bucket(first),
                first as u32,
                cell,
                bucket(second),
                second as u32,
            );
            Some((rank, first, second))
        };
        if ki == kj {
            // one bucket: the smaller index scans the entries after it
            let (a, b) = (i.min(j), i.max(j));
            return at(a, 0, b);
        }
        let d = cell_difference(ki, kj);
        if let Some(f) = FORWARD.iter().position(|&e| e == d) {
            return at(i, f as u8 + 1, j);
        }
        let m = [-d[0], -d[1], -d[2]];
        FORWARD
            .iter()
            .position(|&e| e == m)
            .and_then(|f| at(j, f as u8 + 1, i))
    }

    /// Calls `f(i, j)` (i ≠ j, each unordered pair once) for every pair of overlapping
    /// boxes, as filed by the last [`Self::rebuild`].
    pub fn for_each_pair(&self, mut f: impl FnMut(usize, usize)) {
        let _ = self.try_for_each_pair(|i, j| {
            f(i, j);
            ControlFlow::Continue(())
        });
    }

    /// [`Self::for_each_pair`] until `f` breaks; whether it did.
    pub fn try_for_each_pair(
        &self,
        mut f: impl FnMut(usize, usize) -> ControlFlow<()>,
    ) -> ControlFlow<()> {
        let n = self.items.len();
        for k in 0..n {
            let key = self.s_key[k];
            let (lo, hi) = (self.s_lo[k], self.s_hi[k]);
            let i = self.items[k] as usize;
            let mut scan = |from: usize, to: usize, key: u64| {
                for m in from..to {
                    if self.s_key[m] == key
                        && lo.cmple(self.s_hi[m]).all()
                        && self.s_lo[m].cmple(hi).all()
                    {
                        f(i, self.items[m] as usize)?;
                    }
                }
                ControlFlow::Continue(())
            };
            // own cell: entries after this one in its bucket
            let b = self.bucket_of[i] as usize;
            scan(k + 1, self.start[b + 1] as usize, key)?;
            for d in FORWARD {
                let nk = offset(key, d);
                let b = hash(nk, self.shift) as usize;
                scan(self.start[b] as usize, self.start[b + 1] as usize, nk)?;
            }
        }
        ControlFlow::Continue(())
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
