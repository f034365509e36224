//! 3-vectors and quaternions over any [`Scalar`] — just the operations the element uses.
//! With `f64` they mirror glam's `DVec3`/`DQuat` (conversions below).

use super::Scalar;
use glam::{DQuat, DVec3};
use std::ops::{Add, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<T> {
    pub x: T,
    pub y: T,
    pub z: T,
}

/// Quaternion x i + y j + z k + w.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quat<T> {
    pub x: T,
    pub y: T,
    pub z: T,
    pub w: T,
}

impl<T: Scalar> V3<T> {
    #[inline(always)]
    pub fn new(x: T, y: T, z: T) -> Self {
        V3 { x, y, z }
    }
    #[inline(always)]
    pub fn cst(v: DVec3) -> Self {
        V3::new(T::cst(v.x), T::cst(v.y), T::cst(v.z))
    }
    #[inline(always)]
    pub fn re(self) -> DVec3 {
        DVec3::new(self.x.re(), self.y.re(), self.z.re())
    }
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        V3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    #[inline(always)]
    pub fn length_squared(self) -> T {
        self.dot(self)
    }
    #[inline(always)]
    pub fn length(self) -> T {
        self.length_squared().sqrt()
    }
    #[inline(always)]
    pub fn scale(self, s: T) -> Self {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
    #[inline(always)]
    pub fn scale_f(self, s: f64) -> Self {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl<T: Scalar> Add for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<T: Scalar> Sub for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<T: Scalar> Neg for V3<T> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        V3::new(-self.x, -self.y, -self.z)
    }
}

impl<T: Scalar> Quat<T> {
    #[inline(always)]
    pub fn from_parts(v: V3<T>, w: T) -> Self {
        Quat {
            x: v.x,
            y: v.y,
            z: v.z,
            w,
        }
    }
    #[inline(always)]
    pub fn cst(q: DQuat) -> Self {
        Quat {
            x: T::cst(q.x),
            y: T::cst(q.y),
            z: T::cst(q.z),
            w: T::cst(q.w),
        }
    }
    #[inline(always)]
    pub fn re(self) -> DQuat {
        DQuat::from_xyzw(self.x.re(), self.y.re(), self.z.re(), self.w.re())
    }
    #[inline(always)]
    pub fn vector(self) -> V3<T> {
        V3::new(self.x, self.y, self.z)
    }
    #[inline(always)]
    pub fn conjugate(self) -> Self {
        Quat {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: self.w,
        }
    }
    #[inline(always)]
    pub fn dot(self, o: Self) -> T {
        self.x * o.x + self.y * o.y + self.z * o.z + self.w * o.w
    }
    #[inline(always)]
    pub fn negate(self) -> Self {
        Quat {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: -self.w,
        }
    }
    #[inline(always)]
    pub fn normalize(self) -> Self {
        let inv = T::cst(1.0) / self.dot(self).sqrt();
        Quat {
            x: self.x * inv,
            y: self.y * inv,
            z: self.z * inv,
            w: self.w * inv,
        }
    }
    /// Rotates `v` (for unit quaternions): v + 2w (u × v) + 2 u × (u × v).
    #[inline(always)]
    pub fn rotate(self, v: V3<T>) -> V3<T> {
        let u = self.vector();
        let t = u.cross(v).scale_f(2.0);
        v + t.scale(self.w) + u.cross(t)
    }
}

/// Hamilton product.
impl<T: Scalar> Add for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Quat {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
            w: self.w + o.w,
        }
    }
}

impl<T: Scalar> Mul for Quat<T> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Quat {
            w: self.w * o.w - self.x * o.x - self.y * o.y - self.z * o.z,
            x: self.w * o.x + self.x * o.w + self.y * o.z - self.z * o.y,
            y: self.w * o.y - self.x * o.z + self.y * o.w + self.z * o.x,
            z: self.w * o.z + self.x * o.y - self.y * o.x + self.z * o.w,
        }
    }
}

impl From<DVec3> for V3<f64> {
    #[inline(always)]
    fn from(v: DVec3) -> Self {
        V3::new(v.x, v.y, v.z)
    }
}

impl From<V3<f64>> for DVec3 {
    #[inline(always)]
    fn from(v: V3<f64>) -> Self {
        DVec3::new(v.x, v.y, v.z)
    }
}

impl From<DQuat> for Quat<f64> {
    #[inline(always)]
    fn from(q: DQuat) -> Self {
        Quat {
            x: q.x,
            y: q.y,
            z: q.z,
            w: q.w,
        }
    }
}

impl From<Quat<f64>> for DQuat {
    #[inline(always)]
    fn from(q: Quat<f64>) -> Self {
        DQuat::from_xyzw(q.x, q.y, q.z, q.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_glam() {
        let a = DQuat::from_axis_angle(DVec3::new(0.3, -0.4, 0.5).normalize(), 1.1);
        let b = DQuat::from_axis_angle(DVec3::new(-0.7, 0.1, 0.2).normalize(), 0.4);
        let v = DVec3::new(0.2, -1.0, 0.6);
        let (ga, gb): (Quat<f64>, Quat<f64>) = (a.into(), b.into());
        let prod: DQuat = (ga * gb).into();
        assert!((prod - a * b).length() < 1e-15);
        let r: DVec3 = ga.rotate(v.into()).into();
        assert!((r - a * v).length() < 1e-15);
        let c: DVec3 = V3::from(v).cross(DVec3::X.into()).into();
        assert!((c - v.cross(DVec3::X)).length() < 1e-15);
    }
}
