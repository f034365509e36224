//! Centre-line samples of hose frames, the first step of a swept envelope (this module's
//! [`super::envelope`] and the studies' tolerance envelopes, SPEC T2): every element of
//! every frame is sampled at n + 1 points at most h/2 apart (the same n for all frames
//! of one call, from the longest element), each rounded to the grid of spacing h/4 and
//! packed into one integer key. A sample key set is a set: the samples of several frames
//! or runs may be united before they are dilated to voxels.

use std::collections::HashSet;

/// Offset of each packed grid index: keys are (i + OFF) << 42 | (j + OFF) << 21 | (k + OFF).
pub const KEY_OFFSET: i64 = 1 << 20;
/// Most samples per element: more means an element far longer than a hose's.
const MAX_SAMPLES_PER_ELEMENT: usize = 10_000;

/// The key of grid index `ijk` (each |index| < 2²⁰).
pub fn pack(ijk: [i64; 3]) -> i64 {
    ((ijk[0] + KEY_OFFSET) << 42) | ((ijk[1] + KEY_OFFSET) << 21) | (ijk[2] + KEY_OFFSET)
}

/// The grid index of key `key`.
pub fn unpack(key: i64) -> [i64; 3] {
    let mask = (1 << 21) - 1;
    [
        ((key >> 42) & mask) - KEY_OFFSET,
        ((key >> 21) & mask) - KEY_OFFSET,
        (key & mask) - KEY_OFFSET,
    ]
}

/// x rounded to the nearest integer, ties to even (as `np.round`), for |x| < 2⁵¹: adding
/// and taking away 1.5·2⁵² leaves no fraction bits, and IEEE addition rounds ties to even.
/// (`f64::round_ties_even` is a library call on the baseline x86-64 target: ≈ 3× slower.)
fn round_ties_even(x: f64) -> f64 {
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5 · 2⁵²
    (x + MAGIC) - MAGIC
}

/// Calls `push` with the key of every centre-line sample of `count` frames of `nodes`
/// nodes each, node `i` of frame `f` at `point(f, i)` \[m\], for voxels of size `h` \[m\].
/// Sample k of an element from a to b is a + (b − a)·t_k with t_k = k/n as numpy's
/// `linspace(0, 1, n + 1)` gives it, its grid index rint(p / (h/4)) (ties to even, as
/// `np.round`). Element by element through time, a sample equal to the same sample of
/// the frame before is not pushed again (`last`: scratch). Keys may repeat otherwise.
pub fn for_each_sample_key(
    point: impl Fn(usize, usize) -> [f64; 3],
    count: usize,
    nodes: usize,
    h: f64,
    last: &mut Vec<i64>,
    mut push: impl FnMut(i64),
) -> Result<(), String> {
    if !(h > 0.0 && h.is_finite()) {
        return Err(format!("voxel size {h} m: must be a positive number"));
    }
    for f in 0..count {
        for i in 0..nodes {
            if point(f, i).iter().any(|v| !v.is_finite()) {
                return Err("frames hold a non-finite position".into());
            }
        }
    }
    let longest = (0..count)
        .flat_map(|f| (1..nodes).map(move |i| (f, i)))
        .map(|(f, i)| {
            let (a, b) = (point(f, i - 1), point(f, i));
            ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max);
    let n = ((longest / (h / 2.0)).ceil() as usize).max(1);
    if n > MAX_SAMPLES_PER_ELEMENT {
        return Err(format!(
            "an element {:.3} m long: not a hose's state",
            n as f64 * h / 2.0
        ));
    }
    let step = 1.0 / n as f64; // numpy's linspace: k·step, the last one exactly 1
    let t = |k: usize| if k == n { 1.0 } else { k as f64 * step };
    let fine = h / 4.0;
    let key = |p: [f64; 3]| -> Result<i64, String> {
        let mut packed = 0i64;
        for c in p {
            let x = c / fine;
            if !(x.abs() < KEY_OFFSET as f64 - 0.5) {
                return Err("the swept region is too large for voxels of this size".into());
            }
            packed = (packed << 21) | (round_ties_even(x) as i64 + KEY_OFFSET);
        }
        Ok(packed)
    };
    if nodes < 2 {
        for f in 0..count {
            for i in 0..nodes {
                push(key(point(f, i))?);
            }
        }
        return Ok(());
    }
    last.clear();
    last.resize(n + 1, i64::MIN);
    for i in 1..nodes {
        last.fill(i64::MIN);
        for f in 0..count {
            let (a, b) = (point(f, i - 1), point(f, i));
            let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            for (k, seen) in last.iter_mut().enumerate() {
                let tk = t(k);
                let q = key([a[0] + d[0] * tk, a[1] + d[1] * tk, a[2] + d[2] * tk])?;
                if q != *seen {
                    push(q);
                    *seen = q;
                }
            }
        }
    }
    Ok(())
}

/// Sorted, unique keys of the centre-line samples of `count` frames of `nodes` nodes,
/// flat in `frames` (frame, node, xyz) \[m\], for voxels of size `h` \[m\]
/// ([`for_each_sample_key`]).
pub fn sample_keys(frames: &[f64], count: usize, nodes: usize, h: f64) -> Result<Vec<i64>, String> {
    if frames.len() != 3 * count * nodes {
        return Err(format!(
            "{} values are not {count} frames of {nodes} nodes",
            frames.len()
        ));
    }
    let estimate = count
        .checked_mul(nodes.saturating_sub(1).max(1))
        .ok_or("too many samples")?;
    let mut keys = Vec::with_capacity(estimate.min(1 << 24));
    let point = |f: usize, i: usize| {
        let at = 3 * (f * nodes + i);
        [frames[at], frames[at + 1], frames[at + 2]]
    };
    for_each_sample_key(point, count, nodes, h, &mut Vec::new(), |k| keys.push(k))?;
    keys.sort_unstable();
    keys.dedup();
    Ok(keys)
}

/// The samples a range-of-motion study has seen of one hose, as a set (a hose at rest
/// adds nothing; memory grows with the region swept, not with time).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SweptSamples {
    pub keys: HashSet<i64>,
    /// Scratch of [`for_each_sample_key`].
    last: Vec<i64>,
}

impl SweptSamples {
    /// Adds the samples of the centre line through `x` \[m\] for voxels of size `h`.
    pub fn add(&mut self, x: &[glam::DVec3], h: f64) -> Result<(), String> {
        let keys = &mut self.keys;
        for_each_sample_key(
            |_, i| x[i].to_array(),
            1,
            x.len(),
            h,
            &mut self.last,
            |k| {
                keys.insert(k);
            },
        )
    }

    /// The keys, sorted.
    pub fn sorted(&self) -> Vec<i64> {
        let mut keys: Vec<i64> = self.keys.iter().copied().collect();
        keys.sort_unstable();
        keys
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_pack_and_unpack() {
        for ijk in [[0, 0, 0], [-5, 7, 1 << 19], [-(1 << 20) + 1, 3, -2]] {
            assert_eq!(unpack(pack(ijk)), ijk);
        }
    }

    #[test]
    fn an_element_is_sampled_at_most_half_a_voxel_apart_on_the_fine_grid() {
        let h = 0.004;
        // one element 10 mm along x: n = ceil(0.01 / 0.002) = 5, samples every 2 mm
        let keys = sample_keys(&[0.0, 0.0, 0.0, 0.01, 0.0, 0.0], 1, 2, h).unwrap();
        let xs: Vec<i64> = keys.iter().map(|&k| unpack(k)[0]).collect();
        assert_eq!(xs, vec![0, 2, 4, 6, 8, 10]);
        assert!(sample_keys(&[0.0, f64::NAN, 0.0], 1, 1, h).is_err());
        assert!(sample_keys(&[0.0; 6], 1, 2, 0.0).is_err());
    }
}
