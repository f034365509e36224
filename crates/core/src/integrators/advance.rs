//! The explicit step's node update four nodes at a time (issue 15): for each node not
//! held, v ← v + Δt/m f, ω ← ω + Δt/I M (Euler's equations for the isotropic lumped
//! inertia), then x ← x + Δt v and q ← normalise(exp(Δt ω) q) — the leapfrog of
//! [`super::explicit`], in lanes ([`crate::lanes`]) with fused multiply–adds.
//!
//! Every node goes through the same lane arithmetic (a range's last group repeats its
//! last node in the unused lanes and writes nothing back from them), so a node's result
//! depends on nothing but its own data — not on how the nodes are grouped or split
//! between threads. The exponential map uses the reference's Taylor series of cos h and
//! sin h/(2h), h = |Δt ω|/2 < 0.05 (truncation < 1e-19); a node turning faster in one
//! step is advanced by the reference [`crate::math::exp_map`] (exact for any angle).

use crate::lanes::{gather3 as gather, gather4, lane, scatter3, scatter4, F4, M4, Q4, V4};
use crate::math::exp_map;
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

/// exp(φ) for |φ|/2 < 0.05 (the reference's series), and the lanes inside that range.
#[inline(always)]
fn exp_series(phi: V4) -> (Q4, M4) {
    let h2 = phi.dot(phi) * 0.25;
    let ok = h2.lt(F4::splat(2.5e-3));
    let one = F4::splat(1.0);
    // cos h = 1 − h²/2 (1 − h²/12 (1 − h²/30 (1 − h²/56)))
    let c = h2.mul_add(F4::splat(-1.0 / 56.0), one);
    let c = (h2 * (-1.0 / 30.0)).mul_add(c, one);
    let c = (h2 * (-1.0 / 12.0)).mul_add(c, one);
    let c = (h2 * (-0.5)).mul_add(c, one);
    // sin h/(2h) = ½ (1 − h²/6 (1 − h²/20 (1 − h²/42 (1 − h²/72))))
    let s = h2.mul_add(F4::splat(-1.0 / 72.0), one);
    let s = (h2 * (-1.0 / 42.0)).mul_add(s, one);
    let s = (h2 * (-1.0 / 20.0)).mul_add(s, one);
    let s = (h2 * (-1.0 / 6.0)).mul_add(s, one) * 0.5;
    (
        Q4 {
            x: phi.x * s,
            y: phi.y * s,
            z: phi.z * s,
            w: c,
        },
        ok,
    )
}

#[inline(always)]
fn advance_lanes(n: &mut Nodes, dt: f64, what: Advance) {
    let count = n.x.len();
    let dt4 = F4::splat(dt);
    let mut i = 0;
    while i < count {
        let idx = [0, 1, 2, 3].map(|k| (i + k).min(count - 1));
        let lanes = (count - i).min(4);
        let mut free = [false; 4];
        for (k, f) in free.iter_mut().enumerate().take(lanes) {
            *f = !n.held[i + k];
        }
        if !free.contains(&true) {
            i += 4;
            continue;
        }
        let mut v = gather(n.v, idx);
        let mut w = gather(n.w, idx);
        if what != Advance::Positions {
            let dtm = dt4 / F4(idx.map(|j| n.mass[j]));
            let dti = dt4 / F4(idx.map(|j| n.inertia[j]));
            v = gather(n.force, idx).scale_add(dtm, v);
            w = gather(n.moment, idx).scale_add(dti, w);
        }
        let mut x = V4::new(F4::ZERO, F4::ZERO, F4::ZERO);
        let mut q = Q4 {
            x: F4::ZERO,
            y: F4::ZERO,
            z: F4::ZERO,
            w: F4::ZERO,
        };
        let mut ok = M4([!0; 4]);
        if what != Advance::Velocities {
            x = v.scale_add(dt4, gather(n.x, idx));
            let q0 = gather4(n.q, idx);
            let (e, inside) = exp_series(w.scale(dt4));
            q = e.mul(q0).normalize();
            ok = inside;
        }
        // through memory (see `element_block::Job::run`): stored as vectors, the lanes
        // stay in 256-bit registers
        let (v, w, x, q, ok) = std::hint::black_box((v, w, x, q, ok));
        if free == [true; 4] && ok.all() {
            // four free nodes in the series' range (the common case): stored at once
            if what != Advance::Positions {
                scatter3(v, &mut n.v[i..]);
                scatter3(w, &mut n.w[i..]);
            }
            if what != Advance::Velocities {
                scatter3(x, &mut n.x[i..]);
                scatter4(q, &mut n.q[i..]);
            }
            i += 4;
            continue;
        }
        for k in 0..lanes {
            if !free[k] {
                continue;
            }
            let j = i + k;
            if what != Advance::Positions {
                n.v[j] = lane(v, k);
                n.w[j] = lane(w, k);
            }
            if what != Advance::Velocities {
                n.x[j] = lane(x, k);
                n.q[j] = if ok.lane(k) {
                    DQuat::from_xyzw(q.x.0[k], q.y.0[k], q.z.0[k], q.w.0[k])
                } else {
                    // a large turn in one step: the reference exponential map
                    (exp_map(dt * n.w[j]) * n.q[j]).normalize()
                };
            }
        }
        i += 4;
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn advance_avx2(n: &mut Nodes, dt: f64, what: Advance) {
    advance_lanes(n, dt, what)
}

#[inline(never)]
fn advance_portable(n: &mut Nodes, dt: f64, what: Advance) {
    advance_lanes(n, dt, what)
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

    /// The lanes agree with the reference update (explicit.rs before issue 15) to
    /// rounding, and the kernels (AVX2 + FMA, portable) agree bit for bit.
    #[test]
    fn lanes_match_the_reference_update() {
        let n = 11;
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
        let run = |f: fn(&mut Nodes, f64, Advance), what: &[Advance]| {
            let (mut x, mut q, mut v, mut w) = (x0.clone(), q0.clone(), v0.clone(), w0.clone());
            for &a in what {
                let mut nodes = Nodes {
                    mass: &mass,
                    inertia: &inertia,
                    held: &held,
                    force: &force,
                    moment: &moment,
                    x: &mut x,
                    q: &mut q,
                    v: &mut v,
                    w: &mut w,
                };
                f(&mut nodes, dt, a);
            }
            (x, q, v, w)
        };
        let fused = run(advance, &[Advance::Both]);
        let split = run(advance, &[Advance::Velocities, Advance::Positions]);
        let portable = run(advance_portable, &[Advance::Both]);
        assert_eq!(fused, split);
        assert_eq!(fused, portable);
        for i in 0..n {
            if held[i] {
                assert_eq!((fused.0[i], fused.1[i]), (x0[i], q0[i]));
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
