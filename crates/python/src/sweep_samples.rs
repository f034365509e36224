//! Centre-line samples of recorded hose frames for tolerance envelopes (SPEC T2; the
//! method is described in `pliant/studies/envelope.py`): every element of every frame is
//! sampled at n + 1 points at most h/2 apart (the same n for all, from the longest
//! element), each rounded to the grid of spacing h/4 and packed into one integer key.
//! A study unites the keys of its runs and dilates them to voxels once per batch, so this
//! is the part of the envelope each run pays for; numpy spent ≈ 20 ms on it per run of the
//! engine-bay demo, mostly in allocating its (T·E·(n+1), 3) temporaries.

use numpy::ndarray::ArrayView3;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Offset of each packed grid index: keys are (i + OFF) << 42 | (j + OFF) << 21 | (k + OFF).
const OFF: i64 = 1 << 20;
/// Most samples per element: more means an element far longer than a hose's.
const MAX_SAMPLES_PER_ELEMENT: usize = 10_000;

/// x rounded to the nearest integer, ties to even (as `np.round`), for |x| < 2⁵¹: adding
/// and taking away 1.5·2⁵² leaves no fraction bits, and IEEE addition rounds ties to even.
/// (`f64::round_ties_even` is a library call on the baseline x86-64 target: ≈ 3× slower.)
fn round_ties_even(x: f64) -> f64 {
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5 · 2⁵²
    (x + MAGIC) - MAGIC
}

/// Sorted, unique keys of the centre-line samples of `frames` (T, N, 3) \[m\] for voxels of
/// size `h` \[m\]. Sample k of an element from a to b is a + (b − a)·t_k with t_k = k/n as
/// numpy's `linspace(0, 1, n + 1)` gives it, and its grid index rint(p / (h/4)) (ties to
/// even, as `np.round`), so the keys equal those of the numpy formulation bit for bit.
pub fn sample_keys(frames: ArrayView3<f64>, h: f64) -> Result<Vec<i64>, String> {
    if !(h > 0.0 && h.is_finite()) {
        return Err(format!("voxel size {h} m: must be a positive number"));
    }
    let (count, nodes, dim) = frames.dim();
    if dim != 3 {
        return Err(format!("frames must be (T, N, 3), got (T, N, {dim})"));
    }
    let standard = frames.as_standard_layout();
    let flat = standard.as_slice().ok_or("frames not in memory order")?;
    if flat.iter().any(|v| !v.is_finite()) {
        return Err("frames hold a non-finite position".into());
    }
    let point = |f: usize, i: usize| {
        let at = 3 * (f * nodes + i);
        [flat[at], flat[at + 1], flat[at + 2]]
    };
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
    let t: Vec<f64> = (0..=n)
        .map(|k| if k == n { 1.0 } else { k as f64 * step })
        .collect();
    let fine = h / 4.0;
    let key = |p: [f64; 3]| -> Result<i64, String> {
        let mut packed = 0i64;
        for c in p {
            let x = c / fine;
            if !(x.abs() < OFF as f64 - 0.5) {
                return Err("the swept region is too large for voxels of this size".into());
            }
            packed = (packed << 21) | (round_ties_even(x) as i64 + OFF);
        }
        Ok(packed)
    };
    let estimate = count
        .checked_mul(nodes.saturating_sub(1).max(1))
        .and_then(|e| e.checked_mul(n + 1))
        .ok_or("too many samples")?;
    let mut keys = Vec::with_capacity(estimate.min(1 << 24));
    if nodes < 2 {
        for f in 0..count {
            for i in 0..nodes {
                keys.push(key(point(f, i))?);
            }
        }
    } else {
        // element by element through time: a hose at rest repeats its keys frame after
        // frame, so a sample equal to the same sample of the frame before is not pushed
        let mut last = vec![i64::MIN; n + 1];
        for i in 1..nodes {
            last.fill(i64::MIN);
            for f in 0..count {
                let (a, b) = (point(f, i - 1), point(f, i));
                let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                for (k, &tk) in t.iter().enumerate() {
                    let p = [a[0] + d[0] * tk, a[1] + d[1] * tk, a[2] + d[2] * tk];
                    let q = key(p)?;
                    if q != last[k] {
                        keys.push(q);
                        last[k] = q;
                    }
                }
            }
        }
    }
    keys.sort_unstable();
    keys.dedup();
    Ok(keys)
}

/// `centreline_sample_keys(frames, h)`: sorted unique int64 keys of the centre-line
/// samples of frames (T, N, 3) \[m\] for voxels of size h \[m\] (see
/// `pliant.studies.envelope.sample_keys`). Raises ValueError for frames no hose has.
#[pyfunction]
pub fn centreline_sample_keys<'py>(
    py: Python<'py>,
    frames: PyReadonlyArray3<'py, f64>,
    h: f64,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    let keys = sample_keys(frames.as_array(), h).map_err(PyValueError::new_err)?;
    Ok(keys.into_pyarray(py))
}
