//! Gravity and mass-proportional damping per node (P4, P6): f ← f + m (g − α v),
//! M ← M − (α I) ω — the explicit step's body-load pass ([`crate::rod::forces::add_body_loads_of`]),
//! four nodes at a time.
//!
//! Four nodes' 3-vectors are twelve consecutive f64, i.e. three [`F4`]s: the lanes take
//! the components as they lie in memory, with the node's mass (α I) and the gravity
//! component repeated to match. Every lane does the reference's operations in the
//! reference's order (no fused multiply–add), so the result is bit for bit that of
//! [`add_body_loads_scalar`], which also does the last `n mod 4` nodes.

use crate::rod::lanes::F4;
use glam::DVec3;

/// The constants of the pass: gravity g and the mass-damping coefficient α.
#[derive(Clone, Copy, Debug)]
pub struct BodyLoad {
    pub gravity: DVec3,
    pub alpha: f64,
}

/// The node arrays of the pass (all of the same length as `force`).
pub struct BodyNodes<'a> {
    pub mass: &'a [f64],
    pub inertia: &'a [f64],
    pub v: &'a [DVec3],
    pub w: &'a [DVec3],
    pub force: &'a mut [DVec3],
    pub moment: &'a mut [DVec3],
}

/// The reference: node by node.
pub fn add_body_loads_scalar(b: BodyLoad, n: BodyNodes) {
    let len = n.force.len();
    let (mass, inertia, v, w) = (&n.mass[..len], &n.inertia[..len], &n.v[..len], &n.w[..len]);
    let moment = &mut n.moment[..len];
    for i in 0..len {
        n.force[i] += mass[i] * (b.gravity - b.alpha * v[i]);
        moment[i] -= b.alpha * inertia[i] * w[i];
    }
}

/// The twelve f64 of four consecutive 3-vectors as three lanes (written out: closures
/// would not inherit the caller's target features).
#[inline(always)]
fn load12(a: &[DVec3]) -> [F4; 3] {
    let a = &a[..4];
    [
        F4([a[0].x, a[0].y, a[0].z, a[1].x]),
        F4([a[1].y, a[1].z, a[2].x, a[2].y]),
        F4([a[2].z, a[3].x, a[3].y, a[3].z]),
    ]
}

#[inline(always)]
fn store12(l: [F4; 3], a: &mut [DVec3]) {
    let a = &mut a[..4];
    let [p, q, r] = [l[0].0, l[1].0, l[2].0];
    a[0] = DVec3::new(p[0], p[1], p[2]);
    a[1] = DVec3::new(p[3], q[0], q[1]);
    a[2] = DVec3::new(q[2], q[3], r[0]);
    a[3] = DVec3::new(r[1], r[2], r[3]);
}

/// Four per-node scalars, each repeated for its node's three components.
#[inline(always)]
fn spread(s: [f64; 4]) -> [F4; 3] {
    [
        F4([s[0], s[0], s[0], s[1]]),
        F4([s[1], s[1], s[2], s[2]]),
        F4([s[2], s[3], s[3], s[3]]),
    ]
}

#[inline(always)]
fn body_loads_lanes(b: BodyLoad, n: BodyNodes) {
    let len = n.force.len();
    let whole = len / 4 * 4;
    let g = b.gravity;
    let gravity = [
        F4([g.x, g.y, g.z, g.x]),
        F4([g.y, g.z, g.x, g.y]),
        F4([g.z, g.x, g.y, g.z]),
    ];
    for i in (0..whole).step_by(4) {
        let r = i..i + 4;
        let (m, d) = (&n.mass[r.clone()], &n.inertia[r.clone()]);
        let mass = spread([m[0], m[1], m[2], m[3]]);
        let a = b.alpha;
        let damping = spread([a * d[0], a * d[1], a * d[2], a * d[3]]);
        let (v, w) = (load12(&n.v[r.clone()]), load12(&n.w[r.clone()]));
        let (mut f, mut m) = (load12(&n.force[r.clone()]), load12(&n.moment[r.clone()]));
        for k in 0..3 {
            f[k] = f[k] + mass[k] * (gravity[k] - v[k] * b.alpha);
            m[k] = m[k] - damping[k] * w[k];
        }
        store12(f, &mut n.force[r.clone()]);
        store12(m, &mut n.moment[r]);
    }
    add_body_loads_scalar(
        b,
        BodyNodes {
            mass: &n.mass[whole..],
            inertia: &n.inertia[whole..],
            v: &n.v[whole..],
            w: &n.w[whole..],
            force: &mut n.force[whole..],
            moment: &mut n.moment[whole..],
        },
    );
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn body_loads_avx2(b: BodyLoad, n: BodyNodes) {
    body_loads_lanes(b, n)
}

#[inline(never)]
fn body_loads_portable(b: BodyLoad, n: BodyNodes) {
    body_loads_lanes(b, n)
}

/// Adds the body loads to `n.force` and `n.moment` (the same bits as
/// [`add_body_loads_scalar`]).
pub fn add_body_loads(b: BodyLoad, n: BodyNodes) {
    #[cfg(target_arch = "x86_64")]
    if std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma") {
        // SAFETY: the CPU has AVX2 and FMA.
        return unsafe { body_loads_avx2(b, n) };
    }
    body_loads_portable(b, n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lanes (AVX2, portable) give the bits of the node-by-node reference, for
    /// lengths with and without a remainder.
    #[test]
    fn lanes_give_the_reference_bits() {
        let mut state = 3u64;
        let mut r = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let b = BodyLoad {
            gravity: DVec3::new(0.3, -9.81, 0.07),
            alpha: 0.37,
        };
        for len in [0, 1, 4, 7, 13] {
            let mass: Vec<f64> = (0..len).map(|_| 0.01 + r().abs()).collect();
            let inertia: Vec<f64> = (0..len).map(|_| 1e-6 + r().abs() * 1e-5).collect();
            let mut v3 = |s: f64| DVec3::new(r(), r(), r()) * s;
            let v: Vec<DVec3> = (0..len).map(|_| v3(3.0)).collect();
            let w: Vec<DVec3> = (0..len).map(|_| v3(50.0)).collect();
            let f0: Vec<DVec3> = (0..len).map(|_| v3(10.0)).collect();
            let m0: Vec<DVec3> = (0..len).map(|_| v3(0.1)).collect();
            let run = |f: fn(BodyLoad, BodyNodes)| {
                let (mut force, mut moment) = (f0.clone(), m0.clone());
                let nodes = BodyNodes {
                    mass: &mass,
                    inertia: &inertia,
                    v: &v,
                    w: &w,
                    force: &mut force,
                    moment: &mut moment,
                };
                f(b, nodes);
                let bits = |a: &[DVec3]| -> Vec<[u64; 3]> {
                    a.iter().map(|p| p.to_array().map(f64::to_bits)).collect()
                };
                (bits(&force), bits(&moment))
            };
            let reference = run(add_body_loads_scalar);
            assert_eq!(run(add_body_loads), reference, "{len}");
            assert_eq!(run(body_loads_portable), reference, "{len}");
        }
    }
}
