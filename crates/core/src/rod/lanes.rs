//! Four f64 lanes — [`F4`] — and 3-vectors and quaternions of them, for the element
//! kernel that evaluates four elements at once ([`crate::rod::element_block`]).
//!
//! Plain portable code: every operation is a loop over the four lanes, written so that
//! inside a function compiled for AVX2 + FMA (`#[target_feature]`, chosen at run time)
//! each becomes one 256-bit instruction. Fused multiply–adds are `f64::mul_add`, which is
//! correctly rounded everywhere — an FMA instruction where the CPU has one, the C
//! library's `fma` otherwise — so the kernel gives the same bits on every machine, only
//! more slowly without FMA hardware.

use std::ops::{Add, Div, Mul, Neg, Not, Sub};

/// Four f64 lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct F4(pub [f64; 4]);

/// Four lane masks (all bits set = true).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct M4(pub [u64; 4]);

macro_rules! lanewise {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for F4 {
            type Output = F4;
            #[inline(always)]
            fn $f(self, o: F4) -> F4 {
                let (a, b) = (self.0, o.0);
                F4([a[0] $op b[0], a[1] $op b[1], a[2] $op b[2], a[3] $op b[3]])
            }
        }
        impl $tr<f64> for F4 {
            type Output = F4;
            #[inline(always)]
            fn $f(self, o: f64) -> F4 {
                self $op F4::splat(o)
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for F4 {
    type Output = F4;
    #[inline(always)]
    fn neg(self) -> F4 {
        let a = self.0;
        F4([-a[0], -a[1], -a[2], -a[3]])
    }
}

#[inline(always)]
fn mask(b: bool) -> u64 {
    0u64.wrapping_sub(b as u64)
}

impl F4 {
    pub const ZERO: F4 = F4([0.0; 4]);

    #[inline(always)]
    pub fn splat(v: f64) -> F4 {
        F4([v; 4])
    }

    /// self · a + b, correctly rounded (one rounding).
    #[inline(always)]
    pub fn mul_add(self, a: F4, b: F4) -> F4 {
        let (s, a, b) = (self.0, a.0, b.0);
        F4([
            s[0].mul_add(a[0], b[0]),
            s[1].mul_add(a[1], b[1]),
            s[2].mul_add(a[2], b[2]),
            s[3].mul_add(a[3], b[3]),
        ])
    }

    #[inline(always)]
    pub fn sqrt(self) -> F4 {
        let a = self.0;
        F4([a[0].sqrt(), a[1].sqrt(), a[2].sqrt(), a[3].sqrt()])
    }

    /// Lanes where self < o.
    #[inline(always)]
    pub fn lt(self, o: F4) -> M4 {
        let (a, b) = (self.0, o.0);
        M4([
            mask(a[0] < b[0]),
            mask(a[1] < b[1]),
            mask(a[2] < b[2]),
            mask(a[3] < b[3]),
        ])
    }

    /// Lanes where self ≤ o (false for NaN).
    #[inline(always)]
    pub fn le(self, o: F4) -> M4 {
        let (a, b) = (self.0, o.0);
        M4([
            mask(a[0] <= b[0]),
            mask(a[1] <= b[1]),
            mask(a[2] <= b[2]),
            mask(a[3] <= b[3]),
        ])
    }
}

impl M4 {
    #[inline(always)]
    pub fn and(self, o: M4) -> M4 {
        let (a, b) = (self.0, o.0);
        M4([a[0] & b[0], a[1] & b[1], a[2] & b[2], a[3] & b[3]])
    }

    /// Whether any lane is set.
    #[inline(always)]
    pub fn any(self) -> bool {
        let a = self.0;
        (a[0] | a[1] | a[2] | a[3]) != 0
    }

    /// Whether every lane is set.
    #[inline(always)]
    pub fn all(self) -> bool {
        let a = self.0;
        (a[0] & a[1] & a[2] & a[3]) == !0
    }

    /// Whether lane `k` is set.
    #[inline(always)]
    pub fn lane(self, k: usize) -> bool {
        self.0[k] != 0
    }

    /// `a` where the mask is set, `b` elsewhere.
    #[inline(always)]
    pub fn select(self, a: F4, b: F4) -> F4 {
        let m = self.0;
        let sel = |k: usize| f64::from_bits((m[k] & a.0[k].to_bits()) | (!m[k] & b.0[k].to_bits()));
        F4([sel(0), sel(1), sel(2), sel(3)])
    }
}

impl Not for M4 {
    type Output = M4;
    /// Lanes not set.
    #[inline(always)]
    fn not(self) -> M4 {
        let a = self.0;
        M4([!a[0], !a[1], !a[2], !a[3]])
    }
}

/// A 3-vector of lanes.
#[derive(Clone, Copy, Debug)]
pub struct V4 {
    pub x: F4,
    pub y: F4,
    pub z: F4,
}

impl V4 {
    #[inline(always)]
    pub fn new(x: F4, y: F4, z: F4) -> V4 {
        V4 { x, y, z }
    }
    #[inline(always)]
    pub fn dot(self, o: V4) -> F4 {
        self.x.mul_add(o.x, self.y.mul_add(o.y, self.z * o.z))
    }
    #[inline(always)]
    pub fn cross(self, o: V4) -> V4 {
        V4::new(
            self.y.mul_add(o.z, -(self.z * o.y)),
            self.z.mul_add(o.x, -(self.x * o.z)),
            self.x.mul_add(o.y, -(self.y * o.x)),
        )
    }
    #[inline(always)]
    pub fn scale(self, s: F4) -> V4 {
        V4::new(self.x * s, self.y * s, self.z * s)
    }
    /// self · s + o.
    #[inline(always)]
    pub fn scale_add(self, s: F4, o: V4) -> V4 {
        V4::new(
            self.x.mul_add(s, o.x),
            self.y.mul_add(s, o.y),
            self.z.mul_add(s, o.z),
        )
    }
    #[inline(always)]
    pub fn select(m: M4, a: V4, b: V4) -> V4 {
        V4::new(m.select(a.x, b.x), m.select(a.y, b.y), m.select(a.z, b.z))
    }
}

impl Add for V4 {
    type Output = V4;
    #[inline(always)]
    fn add(self, o: V4) -> V4 {
        V4::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for V4 {
    type Output = V4;
    #[inline(always)]
    fn sub(self, o: V4) -> V4 {
        V4::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Neg for V4 {
    type Output = V4;
    #[inline(always)]
    fn neg(self) -> V4 {
        V4::new(-self.x, -self.y, -self.z)
    }
}

/// A quaternion x i + y j + z k + w of lanes.
#[derive(Clone, Copy, Debug)]
pub struct Q4 {
    pub x: F4,
    pub y: F4,
    pub z: F4,
    pub w: F4,
}

impl Q4 {
    #[inline(always)]
    pub fn vector(self) -> V4 {
        V4::new(self.x, self.y, self.z)
    }
    #[inline(always)]
    pub fn dot(self, o: Q4) -> F4 {
        self.x
            .mul_add(o.x, self.y.mul_add(o.y, self.z.mul_add(o.z, self.w * o.w)))
    }
    #[inline(always)]
    pub fn scale(self, s: F4) -> Q4 {
        Q4 {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
            w: self.w * s,
        }
    }
    #[inline(always)]
    pub fn conjugate(self) -> Q4 {
        Q4 {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: self.w,
        }
    }
    /// Conjugate of self, times o: self⁻¹ · o for unit self.
    #[inline(always)]
    pub fn conj_mul(self, o: Q4) -> Q4 {
        self.conjugate() * o
    }
    /// The quaternion scaled to unit length.
    #[inline(always)]
    pub fn normalize(self) -> Q4 {
        self.scale(F4::splat(1.0) / self.dot(self).sqrt())
    }
}

impl Mul for Q4 {
    type Output = Q4;
    /// Hamilton product self · o.
    #[inline(always)]
    fn mul(self, o: Q4) -> Q4 {
        let (a, b) = (self, o);
        Q4 {
            w: a.w
                .mul_add(b.w, -(a.x.mul_add(b.x, a.y.mul_add(b.y, a.z * b.z)))),
            x: a.w
                .mul_add(b.x, a.x.mul_add(b.w, a.y.mul_add(b.z, -(a.z * b.y)))),
            y: a.w
                .mul_add(b.y, a.y.mul_add(b.w, a.z.mul_add(b.x, -(a.x * b.z)))),
            z: a.w
                .mul_add(b.z, a.z.mul_add(b.w, a.x.mul_add(b.y, -(a.y * b.x)))),
        }
    }
}

/// A 3 × 3 matrix of lanes, stored by columns.
#[derive(Clone, Copy, Debug)]
pub struct M34 {
    pub c: [V4; 3],
}

impl M34 {
    /// The rotation matrix of a unit quaternion.
    #[inline(always)]
    pub fn from_quat(q: Q4) -> M34 {
        let (x2, y2, z2) = (q.x + q.x, q.y + q.y, q.z + q.z);
        let (xx, yy, zz) = (q.x * x2, q.y * y2, q.z * z2);
        let (xy, xz, yz) = (q.x * y2, q.x * z2, q.y * z2);
        let (wx, wy, wz) = (q.w * x2, q.w * y2, q.w * z2);
        let one = F4::splat(1.0);
        M34 {
            c: [
                V4::new(one - (yy + zz), xy + wz, xz - wy),
                V4::new(xy - wz, one - (xx + zz), yz + wx),
                V4::new(xz + wy, yz - wx, one - (xx + yy)),
            ],
        }
    }
    /// M v.
    #[inline(always)]
    pub fn mul(&self, v: V4) -> V4 {
        self.c[0].scale_add(v.x, self.c[1].scale_add(v.y, self.c[2].scale(v.z)))
    }
    /// Mᵀ v.
    #[inline(always)]
    pub fn mul_transpose(&self, v: V4) -> V4 {
        V4::new(self.c[0].dot(v), self.c[1].dot(v), self.c[2].dot(v))
    }
}

/// The vectors `a[idx[k]]` in lanes k = 0 … 3.
#[inline(always)]
pub fn gather3(a: &[glam::DVec3], idx: [usize; 4]) -> V4 {
    let p = idx.map(|i| a[i]);
    V4::new(
        F4([p[0].x, p[1].x, p[2].x, p[3].x]),
        F4([p[0].y, p[1].y, p[2].y, p[3].y]),
        F4([p[0].z, p[1].z, p[2].z, p[3].z]),
    )
}

/// The quaternions `a[idx[k]]` in lanes k = 0 … 3.
#[inline(always)]
pub fn gather4(a: &[glam::DQuat], idx: [usize; 4]) -> Q4 {
    let p = idx.map(|i| a[i]);
    Q4 {
        x: F4([p[0].x, p[1].x, p[2].x, p[3].x]),
        y: F4([p[0].y, p[1].y, p[2].y, p[3].y]),
        z: F4([p[0].z, p[1].z, p[2].z, p[3].z]),
        w: F4([p[0].w, p[1].w, p[2].w, p[3].w]),
    }
}

/// Lane `k` of `v`.
#[inline(always)]
pub fn lane(v: V4, k: usize) -> glam::DVec3 {
    glam::DVec3::new(v.x.0[k], v.y.0[k], v.z.0[k])
}

/// Writes lane k of `v` to `a[k]`, k = 0 … 3 (`a` holds at least four vectors).
#[inline(always)]
pub fn scatter3(v: V4, a: &mut [glam::DVec3]) {
    for (k, p) in a[..4].iter_mut().enumerate() {
        *p = lane(v, k);
    }
}

/// Writes lane k of `q` to `a[k]`, k = 0 … 3 (`a` holds at least four quaternions).
#[inline(always)]
pub fn scatter4(q: Q4, a: &mut [glam::DQuat]) {
    for (k, p) in a[..4].iter_mut().enumerate() {
        *p = glam::DQuat::from_xyzw(q.x.0[k], q.y.0[k], q.z.0[k], q.w.0[k]);
    }
}

/// The lanes of `v` moved up by one, `first` into lane 0 (lane 3 drops out).
#[inline(always)]
pub fn shift_up(first: f64, v: V4) -> V4 {
    let up = |a: F4| F4([first, a.0[0], a.0[1], a.0[2]]);
    V4::new(up(v.x), up(v.y), up(v.z))
}
