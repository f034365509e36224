//! The explicit step's node update: for each node not held, v ← v + Δt/m f,
//! ω ← ω + Δt/I M (Euler's equations for the isotropic lumped inertia), then
//! x ← x + Δt v and q ← normalise(exp(Δt ω) q) — the leapfrog of [`super::explicit`],
//! with fused multiply–adds.
//!
//! Node by node: the operations are those of the four-lane kernel this replaces
//! ([`crate::rod::lanes`] arithmetic, each lane an independent IEEE operation), in the
//! same order, so the results are the same to the last bit — without gathering the
//! nodes' vectors into lanes and scattering them back, which cost more than the
//! arithmetic for a handful of nodes, and with held nodes costing one check. A node's
//! result depends on nothing but its own data — not on how the nodes are split between
//! threads. The exponential map uses the reference's Taylor series of cos h and
//! sin h/(2h), h = |Δt ω|/2 < 0.05 (truncation < 1e-19); a node turning faster in one
//! step is advanced by the reference [`crate::math::exp_map`] (exact for any angle).

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

/// a · s + b, component by component, each correctly rounded (one rounding).
#[inline(always)]
fn scale_add(a: DVec3, s: f64, b: DVec3) -> DVec3 {
    DVec3::new(
        a.x.mul_add(s, b.x),
        a.y.mul_add(s, b.y),
        a.z.mul_add(s, b.z),
    )
}

/// exp(φ) for |φ|/2 < 0.05 (the reference's series), and whether φ is inside that range.
#[inline(always)]
fn exp_series(phi: DVec3) -> (DQuat, bool) {
    let h2 = phi.x.mul_add(phi.x, phi.y.mul_add(phi.y, phi.z * phi.z)) * 0.25;
    let ok = h2 < 2.5e-3;
    // cos h = 1 − h²/2 (1 − h²/12 (1 − h²/30 (1 − h²/56)))
    let c = h2.mul_add(-1.0 / 56.0, 1.0);
    let c = (h2 * (-1.0 / 30.0)).mul_add(c, 1.0);
    let c = (h2 * (-1.0 / 12.0)).mul_add(c, 1.0);
    let c = (h2 * (-0.5)).mul_add(c, 1.0);
    // sin h/(2h) = ½ (1 − h²/6 (1 − h²/20 (1 − h²/42 (1 − h²/72))))
    let s = h2.mul_add(-1.0 / 72.0, 1.0);
    let s = (h2 * (-1.0 / 42.0)).mul_add(s, 1.0);
    let s = (h2 * (-1.0 / 20.0)).mul_add(s, 1.0);
    let s = (h2 * (-1.0 / 6.0)).mul_add(s, 1.0) * 0.5;
    (DQuat::from_xyzw(phi.x * s, phi.y * s, phi.z * s, c), ok)
}

/// The Hamilton product a · b with fused multiply–adds, normalised: the operations of
/// [`crate::rod::lanes::Q4::mul`] and [`crate::rod::lanes::Q4::normalize`] for one quaternion.
#[inline(always)]
fn mul_normalize(a: DQuat, b: DQuat) -> DQuat {
    let w =
        a.w.mul_add(b.w, -(a.x.mul_add(b.x, a.y.mul_add(b.y, a.z * b.z))));
    let x =
        a.w.mul_add(b.x, a.x.mul_add(b.w, a.y.mul_add(b.z, -(a.z * b.y))));
    let y =
        a.w.mul_add(b.y, a.y.mul_add(b.w, a.z.mul_add(b.x, -(a.x * b.z))));
    let z =
        a.w.mul_add(b.z, a.z.mul_add(b.w, a.x.mul_add(b.y, -(a.y * b.x))));
    let s = 1.0 / x.mul_add(x, y.mul_add(y, z.mul_add(z, w * w))).sqrt();
    DQuat::from_xyzw(x * s, y * s, z * s, w * s)
}

#[inline(always)]
fn advance_nodes(n: &mut Nodes, dt: f64, what: Advance) {
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
    for j in 0..count {
        if n.held[j] {
            continue;
        }
        if what != Advance::Positions {
            n.v[j] = scale_add(n.force[j], dt / n.mass[j], n.v[j]);
            n.w[j] = scale_add(n.moment[j], dt / n.inertia[j], n.w[j]);
        }
        if what != Advance::Velocities {
            n.x[j] = scale_add(n.v[j], dt, n.x[j]);
            let w = n.w[j];
            let (e, inside) = exp_series(w * dt);
            n.q[j] = if inside {
                mul_normalize(e, n.q[j])
            } else {
                // a large turn in one step: the reference exponential map
                (exp_map(dt * w) * n.q[j]).normalize()
            };
        }
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn advance_avx2(n: &mut Nodes, dt: f64, what: Advance) {
    advance_nodes(n, dt, what)
}

#[inline(never)]
fn advance_portable(n: &mut Nodes, dt: f64, what: Advance) {
    advance_nodes(n, dt, what)
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
    /// in the test) to rounding, and the kernels (AVX2 + FMA, portable) agree bit for bit.
    #[test]
    fn update_matches_the_reference_update() {
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
