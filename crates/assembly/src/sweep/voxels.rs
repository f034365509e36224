//! The voxels a swept tube touches: a voxel (centre on the grid i·h) is occupied when
//! its centre lies within reach = r + (√3/2)(h + h/4) + h/4 of a centre-line sample
//! ([`super::centreline_samples`]; r the hose's outer radius). The reach allows for the
//! samples' spacing (h/2 along an element) and rounding (to the h/4 grid), so the union
//! of the occupied voxels' cubes contains the whole tube of radius r around every
//! sampled centre line: a tube point lies within √3/2·h of its voxel's centre, and within
//! r + h/4 + √3/8·h of a sample.
//!
//! Each sample stamps a precomputed stencil — the voxel offsets within reach of a point
//! at that sample's place inside its voxel (4³ places on the h/4 grid) — into a dense
//! bit grid over the samples' bounding box; its size is checked before it is allocated.

use super::centreline_samples::{pack, unpack};

/// Most cells of the dense grid (bits: 50 MB).
pub const MAX_CELLS: u64 = 400_000_000;

/// How far from a sample a voxel centre may lie and still be occupied \[m\]: r +
/// (√3/2)(h + h/4) + h/4, for outer radius `radius` and voxel size `h`.
pub fn reach(radius: f64, h: f64) -> f64 {
    radius + 3f64.sqrt() / 2.0 * (h + h / 4.0) + h / 4.0
}

/// Occupied voxels on a dense grid: voxel (i, j, k) is cell (i − lo) of `dims`.
#[derive(Clone, Debug, PartialEq)]
pub struct VoxelGrid {
    /// Voxel size \[m\].
    pub h: f64,
    /// The grid index of the first cell.
    pub lo: [i64; 3],
    pub dims: [usize; 3],
    bits: Vec<u64>,
}

impl VoxelGrid {
    /// The voxels within [`reach`] of the samples `samples` (keys on the h/4 grid) for a
    /// tube of outer radius `radius` \[m\], voxel size `h` \[m\]. Refuses a grid of more than
    /// [`MAX_CELLS`] cells (the error says so).
    pub fn of_samples(samples: &[i64], radius: f64, h: f64) -> Result<VoxelGrid, String> {
        if !(h > 0.0 && h.is_finite() && radius >= 0.0 && radius.is_finite()) {
            return Err(format!(
                "voxel size {h} m and radius {radius} m: must be positive and finite"
            ));
        }
        // in voxel units: a sample at s/4, a voxel centre at v; in iff |4v − s|² ≤ (4R)²
        let r4 = 4.0 * reach(radius, h) / h;
        let m = r4.ceil() as i64 / 4 + 2;
        let mut stencils: Vec<Vec<[i64; 3]>> = Vec::with_capacity(64);
        for c in 0..64 {
            let c = [c / 16, (c / 4) % 4, c % 4];
            let mut offsets = Vec::new();
            for i in -m..=m {
                for j in -m..=m {
                    for k in -m..=m {
                        let d = [4 * i - c[0], 4 * j - c[1], 4 * k - c[2]];
                        let d2 = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) as f64;
                        if d2 <= r4 * r4 {
                            offsets.push([i, j, k]);
                        }
                    }
                }
            }
            stencils.push(offsets);
        }
        let (mut lo, mut hi) = ([i64::MAX; 3], [i64::MIN; 3]);
        for &s in samples {
            let v = unpack(s).map(|x| x.div_euclid(4));
            for a in 0..3 {
                lo[a] = lo[a].min(v[a] - m);
                hi[a] = hi[a].max(v[a] + m);
            }
        }
        if samples.is_empty() {
            (lo, hi) = ([0; 3], [-1; 3]);
        }
        let dims = [0, 1, 2].map(|a| (hi[a] - lo[a] + 1).max(0) as usize);
        let cells = dims.iter().map(|&d| d as u64).product::<u64>();
        if cells > MAX_CELLS {
            return Err(format!(
                "the swept region is too large for voxels of this size: {cells} voxels of {:.2} mm (at most {MAX_CELLS}); choose larger voxels",
                1e3 * h
            ));
        }
        let mut grid = VoxelGrid {
            h,
            lo,
            dims,
            bits: vec![0; (cells as usize).div_ceil(64)],
        };
        for &s in samples {
            let f = unpack(s);
            let base = f.map(|x| x.div_euclid(4));
            let c = f.map(|x| x.rem_euclid(4));
            for o in &stencils[(16 * c[0] + 4 * c[1] + c[2]) as usize] {
                let at = grid.cell([base[0] + o[0], base[1] + o[1], base[2] + o[2]]);
                grid.bits[at / 64] |= 1 << (at % 64);
            }
        }
        Ok(grid)
    }

    /// The cell of voxel `v`, which must lie in the grid.
    fn cell(&self, v: [i64; 3]) -> usize {
        let d = [0, 1, 2].map(|a| (v[a] - self.lo[a]) as usize);
        (d[0] * self.dims[1] + d[1]) * self.dims[2] + d[2]
    }

    /// Whether voxel `v` is occupied (false outside the grid).
    pub fn contains(&self, v: [i64; 3]) -> bool {
        let inside = (0..3).all(|a| v[a] >= self.lo[a] && v[a] < self.lo[a] + self.dims[a] as i64);
        if !inside {
            return false;
        }
        let at = self.cell(v);
        self.bits[at / 64] >> (at % 64) & 1 == 1
    }

    /// Whether the point `p` \[m\] lies in an occupied voxel's cube.
    pub fn covers(&self, p: [f64; 3]) -> bool {
        self.contains(p.map(|x| (x / self.h).round() as i64))
    }

    /// The occupied voxels' grid indices, in key order.
    pub fn voxels(&self) -> impl Iterator<Item = [i64; 3]> + '_ {
        self.bits.iter().enumerate().flat_map(move |(w, &word)| {
            let mut rest = word;
            std::iter::from_fn(move || {
                if rest == 0 {
                    return None;
                }
                let b = rest.trailing_zeros() as usize;
                rest &= rest - 1;
                let at = 64 * w + b;
                let (i, rem) = (
                    at / (self.dims[1] * self.dims[2]),
                    at % (self.dims[1] * self.dims[2]),
                );
                Some([
                    self.lo[0] + i as i64,
                    self.lo[1] + (rem / self.dims[2]) as i64,
                    self.lo[2] + (rem % self.dims[2]) as i64,
                ])
            })
        })
    }

    /// The occupied voxels' keys, sorted (as [`super::centreline_samples::pack`] packs).
    pub fn keys(&self) -> Vec<i64> {
        self.voxels().map(pack).collect()
    }

    /// How many voxels are occupied.
    pub fn count(&self) -> usize {
        self.bits.iter().map(|w| w.count_ones() as usize).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::centreline_samples::sample_keys;

    #[test]
    fn a_single_sample_occupies_the_voxels_within_reach_and_no_other() {
        let (h, r) = (0.002, 0.003);
        // a sample at (0.5, 0.25, 0) mm: fine-grid index (1, 0.5 → 0, 0)
        let keys = sample_keys(&[0.0005, 0.0, 0.0], 1, 1, h).unwrap();
        let grid = VoxelGrid::of_samples(&keys, r, h).unwrap();
        let p = [0.0005, 0.0, 0.0];
        let mut expected = 0;
        for i in -6..=6_i64 {
            for j in -6..=6_i64 {
                for k in -6..=6_i64 {
                    let c = [i as f64 * h, j as f64 * h, k as f64 * h];
                    let d = ((c[0] - p[0]).powi(2) + (c[1] - p[1]).powi(2) + c[2].powi(2)).sqrt();
                    let within = d <= reach(r, h);
                    assert_eq!(grid.contains([i, j, k]), within, "{i} {j} {k}: {d}");
                    expected += within as usize;
                }
            }
        }
        assert_eq!(grid.count(), expected);
        let keys = grid.keys();
        assert!(keys.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn a_region_too_large_is_refused_before_it_is_allocated() {
        let keys = sample_keys(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 1, 2, 0.0005).unwrap();
        let e = VoxelGrid::of_samples(&keys, 0.004, 0.0005).unwrap_err();
        assert!(e.contains("choose larger voxels"), "{e}");
    }
}
