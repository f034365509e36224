//! The explicit step's node update: for each node not held, v ← v + Δt/m f,
//! ω ← ω + Δt/I M (Euler's equations for the isotropic lumped inertia), then
//! x ← x + Δt v and q ← normalise(exp(Δt ω) q) — the leapfrog of [`super::explicit`],
//! with fused multiply–adds.
//!
//! Four consecutive nodes at a time, one per lane of [`Lane4`] (a 256-bit register where
//! the CPU has AVX2 and FMA): a node's chain (Δt/I, ω, the exponential series, the
//! quaternion product, its norm, √, ÷) is long, and node by node only about three
//! nodes' chains fit the processor's reorder window; in lanes each instruction advances
//! four chains, and the divider (Δt/m, Δt/I, the norm's √ and ÷) serves four nodes at
//! once. Every lane does one node's IEEE operations in a fixed order, so a node's result
//! depends on nothing but its own data — not on its lane, its neighbours, the
//! instruction set, or how the nodes are split between threads. A block of four with a
//! held node is advanced whole and the held node restored; the last block, when the
//! count is not a multiple of four, overlaps the one before and restores the nodes
//! already advanced (a range of fewer than four nodes goes through a copy). The
//! exponential map uses the reference's Taylor series of cos h and sin h/(2h),
//! h = |Δt ω|/2 < 0.05 (truncation < 1e-19); a node turning faster in one step is
//! advanced by the reference [`crate::math::exp_map`] (exact for any angle).

use crate::math::exp_map;
use crate::rod::lane_arith::Lane4;
use crate::rod::lanes::F4;
use glam::{DQuat, DVec3};

/// The node arrays a step updates, for the nodes of one range.
pub struct Nodes<'a> {
    pub mass: &'a [f64],
    pub inertia: &'a [f64],
    pub held: &'a [bool],
    pub force: &'a [DVec3],
    pub moment: &'a [DVec3],
    pub x: &'a mut [DVec3],
    pub q: &'a mut [DQuat],
    pub v: &'a mut [DVec3],
    pub w: &'a mut [DVec3],
}

/// What to advance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Advance {
    /// Velocities only (contact corrects them before the positions move).
    Velocities,
    /// Positions only, from the current velocities.
    Positions,
    /// Both, in one pass.
    Both,
}

/// Four nodes' data, node k in lane k.
struct Four<'a> {
    mass: [f64; 4],
    inertia: [f64; 4],
    force: &'a [DVec3; 4],
    moment: &'a [DVec3; 4],
    x: &'a mut [DVec3; 4],
    q: &'a mut [DQuat; 4],
    v: &'a mut [DVec3; 4],
    w: &'a mut [DVec3; 4],
}

/// a · s + b, component by component, each correctly rounded (one rounding).
#[inline(always)]
fn scale_add<L: Lane4>(a: [L; 3], s: L, b: [L; 3]) -> [L; 3] {
    [
        a[0].mul_add(s, b[0]),
        a[1].mul_add(s, b[1]),
        a[2].mul_add(s, b[2]),
    ]
}

/// exp(φ) for |φ|/2 < 0.05 (the reference's series) as (x, y, z, w), and h² = |φ|²/4.
#[inline(always)]
fn exp_series<L: Lane4>(phi: [L; 3]) -> ([L; 4], L) {
    let [a, b, c] = phi;
    let h2 = a.mul_add(a, b.mul_add(b, c * c)) * L::splat(0.25);
    let one = L::splat(1.0);
    let term = |k: f64, p: L| (h2 * L::splat(k)).mul_add(p, one);
    // cos h = 1 − h²/2 (1 − h²/12 (1 − h²/30 (1 − h²/56)))
    let cos = h2.mul_add(L::splat(-1.0 / 56.0), one);
    let cos = term(-0.5, term(-1.0 / 12.0, term(-1.0 / 30.0, cos)));
    // sin h/(2h) = ½ (1 − h²/6 (1 − h²/20 (1 − h²/42 (1 − h²/72))))
    let s = h2.mul_add(L::splat(-1.0 / 72.0), one);
    let s = term(-1.0 / 6.0, term(-1.0 / 20.0, term(-1.0 / 42.0, s)));
    let s = s * L::splat(0.5);
    ([a * s, b * s, c * s, cos], h2)
}

/// The Hamilton product a · b with fused multiply–adds, normalised (x, y, z, w).
#[inline(always)]
fn mul_normalize<L: Lane4>(a: [L; 4], b: [L; 4]) -> [L; 4] {
    let ([ax, ay, az, aw], [bx, by, bz, bw]) = (a, b);
    let w = aw.mul_add(bw, -(ax.mul_add(bx, ay.mul_add(by, az * bz))));
    let x = aw.mul_add(bx, ax.mul_add(bw, ay.mul_add(bz, -(az * by))));
    let y = aw.mul_add(by, ay.mul_add(bw, az.mul_add(bx, -(ax * bz))));
    let z = aw.mul_add(bz, az.mul_add(bw, ax.mul_add(by, -(ay * bx))));
    let s = L::splat(1.0) / x.mul_add(x, y.mul_add(y, z.mul_add(z, w * w))).sqrt();
    [x * s, y * s, z * s, w * s]
}

/// Advances four nodes (all of them: the caller picks what to keep).
#[inline(always)]
fn advance_four<L: Lane4>(n: Four, dt: f64, what: Advance) {
    let step = L::splat(dt);
    let mut v = L::load_vectors(n.v);
    let mut w = L::load_vectors(n.w);
    if what != Advance::Positions {
        let dt_m = step / L::from_f4(F4(n.mass));
        let dt_i = step / L::from_f4(F4(n.inertia));
        v = scale_add(L::load_vectors(n.force), dt_m, v);
        w = scale_add(L::load_vectors(n.moment), dt_i, w);
        L::store_vectors(v, n.v);
        L::store_vectors(w, n.w);
    }
    if what != Advance::Velocities {
        let x = scale_add(v, step, L::load_vectors(n.x));
        L::store_vectors(x, n.x);
        let (e, h2) = exp_series(w.map(|c| c * step));
        let q = mul_normalize(e, L::load_quats(n.q));
        let outside = !h2.to_f4().lt(F4::splat(2.5e-3));
        if !outside.any() {
            L::store_quats(q, n.q);
        } else {
            let before = *n.q;
            L::store_quats(q, n.q);
            for k in 0..4 {
                if outside.lane(k) {
                    // a large turn in one step: the reference exponential map
                    n.q[k] = (exp_map(dt * n.w[k]) * before[k]).normalize();
                }
            }
        }
    }
}

/// The four nodes `first..first + 4` as a block of lanes.
#[inline(always)]
fn four<'a>(n: &'a mut Nodes, first: usize) -> Four<'a> {
    let r = first..first + 4;
    let four = |a: &[f64]| [a[first], a[first + 1], a[first + 2], a[first + 3]];
    Four {
        mass: four(n.mass),
        inertia: four(n.inertia),
        force: (&n.force[r.clone()]).try_into().expect("four nodes"),
        moment: (&n.moment[r.clone()]).try_into().expect("four nodes"),
        x: (&mut n.x[r.clone()]).try_into().expect("four nodes"),
        q: (&mut n.q[r.clone()]).try_into().expect("four nodes"),
        v: (&mut n.v[r.clone()]).try_into().expect("four nodes"),
        w: (&mut n.w[r]).try_into().expect("four nodes"),
    }
}

/// Advances the nodes `first..first + 4` but the first `done` of them (advanced already)
/// and the held ones, which are computed in their lanes and restored.
#[inline(always)]
fn advance_block<L: Lane4>(n: &mut Nodes, first: usize, done: usize, dt: f64, what: Advance) {
    let held = &n.held[first..first + 4];
    let keep = [0, 1, 2, 3].map(|k| k < done || held[k]);
    if keep == [false; 4] {
        advance_four::<L>(four(n, first), dt, what);
        return;
    }
    if keep == [true; 4] {
        return;
    }
    let r = first..first + 4;
    let saved = (
        <[DVec3; 4]>::try_from(&n.x[r.clone()]).expect("four nodes"),
        <[DQuat; 4]>::try_from(&n.q[r.clone()]).expect("four nodes"),
        <[DVec3; 4]>::try_from(&n.v[r.clone()]).expect("four nodes"),
        <[DVec3; 4]>::try_from(&n.w[r]).expect("four nodes"),
    );
    advance_four::<L>(four(n, first), dt, what);
    for k in (0..4).filter(|&k| keep[k]) {
        let i = first + k;
        (n.x[i], n.q[i], n.v[i], n.w[i]) = (saved.0[k], saved.1[k], saved.2[k], saved.3[k]);
    }
}

/// Advances the `count` < 4 nodes (a range that short) that are not held, in a copy of
/// four lanes (the last node repeated).
#[inline(always)]
fn advance_few<L: Lane4>(n: &mut Nodes, count: usize, dt: f64, what: Advance) {
    let node = |k: usize| k.min(count - 1);
    let (mut x, mut q) = (
        [0, 1, 2, 3].map(|k| n.x[node(k)]),
        [0, 1, 2, 3].map(|k| n.q[node(k)]),
    );
    let (mut v, mut w) = (
        [0, 1, 2, 3].map(|k| n.v[node(k)]),
        [0, 1, 2, 3].map(|k| n.w[node(k)]),
    );
    let block = Four {
        mass: [0, 1, 2, 3].map(|k| n.mass[node(k)]),
        inertia: [0, 1, 2, 3].map(|k| n.inertia[node(k)]),
        force: &[0, 1, 2, 3].map(|k| n.force[node(k)]),
        moment: &[0, 1, 2, 3].map(|k| n.moment[node(k)]),
        x: &mut x,
        q: &mut q,
        v: &mut v,
        w: &mut w,
    };
    advance_four::<L>(block, dt, what);
    for i in (0..count).filter(|&i| !n.held[i]) {
        (n.x[i], n.q[i], n.v[i], n.w[i]) = (x[i], q[i], v[i], w[i]);
    }
}

#[inline(always)]
fn advance_nodes<L: Lane4>(n: &mut Nodes, dt: f64, what: Advance) {
    let count = n.x.len();
    assert!(
        n.held.len() >= count
            && n.mass.len() >= count
            && n.inertia.len() >= count
            && n.force.len() >= count
            && n.moment.len() >= count
            && n.q.len() >= count
            && n.v.len() >= count
            && n.w.len() >= count
    );
    if count < 4 {
        if count > 0 {
            advance_few::<L>(n, count, dt, what);
        }
        return;
    }
    for first in (0..count).step_by(4) {
        // the last block, when count mod 4 ≠ 0, overlaps the one before: its first
        // nodes are advanced already
        let start = first.min(count - 4);
        advance_block::<L>(n, start, first - start, dt, what);
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn advance_avx2(n: &mut Nodes, dt: f64, what: Advance) {
    advance_nodes::<crate::rod::lane_arith::Avx4>(n, dt, what)
}

#[inline(never)]
fn advance_portable(n: &mut Nodes, dt: f64, what: Advance) {
    advance_nodes::<F4>(n, dt, what)
}

/// Advances the nodes of `n` that are not held by one step `dt`.
pub fn advance(n: &mut Nodes, dt: f64, what: Advance) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has AVX2 and FMA.
        return unsafe { advance_avx2(n, dt, what) };
    }
    advance_portable(n, dt, what)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The update agrees with the reference update (the plain per-node loop, written out
    /// in the test) to rounding; the kernels (AVX2 + FMA, portable) agree bit for bit; and
    /// each node gets the same bits whether it is advanced with its neighbours (blocks of
    /// four with held nodes, a block with none, a node beyond the series, the last
    /// `n mod 4` nodes) or alone.
    #[test]
    fn update_matches_the_reference_update() {
        let n = 14;
        let mut state = 7u64;
        let mut r = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let dt = 1e-4;
        let mass: Vec<f64> = (0..n).map(|_| 0.01 + r().abs()).collect();
        let inertia: Vec<f64> = (0..n).map(|_| 1e-6 + r().abs() * 1e-5).collect();
        let held: Vec<bool> = (0..n).map(|i| i % 5 == 2).collect();
        let mut v3 = |s: f64| DVec3::new(r(), r(), r()) * s;
        let force: Vec<DVec3> = (0..n).map(|_| v3(10.0)).collect();
        let moment: Vec<DVec3> = (0..n).map(|_| v3(0.01)).collect();
        let x0: Vec<DVec3> = (0..n).map(|_| v3(1.0)).collect();
        let v0: Vec<DVec3> = (0..n).map(|_| v3(2.0)).collect();
        // one node spinning too fast for the series
        let mut w0: Vec<DVec3> = (0..n).map(|_| v3(100.0)).collect();
        w0[6] = DVec3::new(3000.0, -2000.0, 500.0);
        let q0: Vec<DQuat> = (0..n)
            .map(|_| exp_map(DVec3::new(r(), r(), r()) * 5.0))
            .collect();
        type Update = fn(&mut Nodes, f64, Advance);
        let run = |f: Update, what: &[Advance], nodes: std::ops::Range<usize>| {
            let r = nodes;
            let (mut x, mut q) = (x0[r.clone()].to_vec(), q0[r.clone()].to_vec());
            let (mut v, mut w) = (v0[r.clone()].to_vec(), w0[r.clone()].to_vec());
            for &a in what {
                let mut nodes = Nodes {
                    mass: &mass[r.clone()],
                    inertia: &inertia[r.clone()],
                    held: &held[r.clone()],
                    force: &force[r.clone()],
                    moment: &moment[r.clone()],
                    x: &mut x,
                    q: &mut q,
                    v: &mut v,
                    w: &mut w,
                };
                f(&mut nodes, dt, a);
            }
            (x, q, v, w)
        };
        let fused = run(advance, &[Advance::Both], 0..n);
        let split = run(advance, &[Advance::Velocities, Advance::Positions], 0..n);
        let portable = run(advance_portable, &[Advance::Both], 0..n);
        assert_eq!(fused, split);
        assert_eq!(fused, portable);
        for i in 0..n {
            let alone = run(advance, &[Advance::Both], i..i + 1);
            assert_eq!(
                (alone.0[0], alone.1[0], alone.2[0], alone.3[0]),
                (fused.0[i], fused.1[i], fused.2[i], fused.3[i]),
                "node {i} alone"
            );
            if held[i] {
                assert_eq!(
                    (fused.0[i], fused.1[i], fused.2[i], fused.3[i]),
                    (x0[i], q0[i], v0[i], w0[i])
                );
                continue;
            }
            let v = v0[i] + dt / mass[i] * force[i];
            let w = w0[i] + dt / inertia[i] * moment[i];
            let x = x0[i] + dt * v;
            let q = (exp_map(dt * w) * q0[i]).normalize();
            assert!((fused.2[i] - v).length() <= 1e-15 * v.length());
            assert!((fused.3[i] - w).length() <= 1e-15 * w.length());
            assert!((fused.0[i] - x).length() <= 1e-15 * x.length());
            assert!((fused.1[i] - q).length() <= 1e-15, "{i}");
        }
    }
}
