//! Dual numbers in four lanes: four independent dual numbers a + Σ bₖ εₖ (one per lane,
//! e.g. one per element of a block of four), each part four lanes ([`Lane4`]: the
//! portable [`F4`] or an AVX register), so that every dual operation is a handful of
//! four-lane operations.
//!
//! Only plain `+ − × ÷ √` of the lanes are used (no fused multiply–add), so the results
//! are the same bits whatever instruction set the code is compiled for.
//!
//! [`Scalar`] is implemented so that the generic vectors [`super::V3`] and
//! [`super::Quat`] carry lane duals; generic code that branches on [`Scalar::re`] cannot
//! (a lane dual has four values), and `re`, `sin`, `cos` and `atan2` panic: code over lane
//! duals branches lane by lane with masks, on [`LaneDual::re`].

use super::Scalar;
use crate::rod::lane_arith::Lane4;
use crate::rod::lanes::{F4, M4};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Four dual numbers with N derivative components: values `re`, derivatives `eps[k]`.
#[derive(Clone, Copy, Debug)]
pub struct LaneDual<const N: usize, F = F4> {
    pub re: F,
    pub eps: [F; N],
}

impl<const N: usize, F: Lane4> LaneDual<N, F> {
    /// Constants (no derivative).
    #[inline(always)]
    pub fn lanes(re: F) -> Self {
        LaneDual {
            re,
            eps: [F::splat(0.0); N],
        }
    }

    /// f(self) lane by lane, given f and f′ at the values (the chain rule).
    #[inline(always)]
    pub fn apply(self, f: F, df: F) -> Self {
        let mut eps = self.eps;
        for e in &mut eps {
            *e = *e * df;
        }
        LaneDual { re: f, eps }
    }

    /// Times lane constants.
    #[inline(always)]
    pub fn mul4(self, s: F) -> Self {
        self.apply(self.re * s, s)
    }

    /// Plus lane constants.
    #[inline(always)]
    pub fn add4(self, s: F) -> Self {
        LaneDual {
            re: self.re + s,
            eps: self.eps,
        }
    }

    /// `a` in the lanes `mask` selects, `b` in the others.
    #[inline(always)]
    pub fn select(mask: M4, a: Self, b: Self) -> Self {
        let mut eps = b.eps;
        for (e, x) in eps.iter_mut().zip(a.eps) {
            *e = F::select(mask, x, *e);
        }
        LaneDual {
            re: F::select(mask, a.re, b.re),
            eps,
        }
    }
}

impl<const N: usize, F: Lane4> Add for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let mut eps = self.eps;
        for (e, b) in eps.iter_mut().zip(o.eps) {
            *e = *e + b;
        }
        LaneDual {
            re: self.re + o.re,
            eps,
        }
    }
}

impl<const N: usize, F: Lane4> Sub for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let mut eps = self.eps;
        for (e, b) in eps.iter_mut().zip(o.eps) {
            *e = *e - b;
        }
        LaneDual {
            re: self.re - o.re,
            eps,
        }
    }
}

impl<const N: usize, F: Lane4> Mul for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut eps = [F::splat(0.0); N];
        for k in 0..N {
            eps[k] = self.eps[k] * o.re + self.re * o.eps[k];
        }
        LaneDual {
            re: self.re * o.re,
            eps,
        }
    }
}

impl<const N: usize, F: Lane4> Div for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = F::splat(1.0) / o.re;
        let re = self.re * inv;
        let mut eps = [F::splat(0.0); N];
        for k in 0..N {
            eps[k] = (self.eps[k] - re * o.eps[k]) * inv;
        }
        LaneDual { re, eps }
    }
}

impl<const N: usize, F: Lane4> Neg for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        let mut eps = self.eps;
        for e in &mut eps {
            *e = -*e;
        }
        LaneDual { re: -self.re, eps }
    }
}

impl<const N: usize, F: Lane4> Add<f64> for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: f64) -> Self {
        self.add4(F::splat(o))
    }
}

impl<const N: usize, F: Lane4> Sub<f64> for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: f64) -> Self {
        self.add4(F::splat(-o))
    }
}

impl<const N: usize, F: Lane4> Mul<f64> for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        self.mul4(F::splat(o))
    }
}

impl<const N: usize, F: Lane4> Div<f64> for LaneDual<N, F> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: f64) -> Self {
        self.mul4(F::splat(1.0 / o))
    }
}

impl<const N: usize, F: Lane4> Scalar for LaneDual<N, F> {
    #[inline(always)]
    fn cst(v: f64) -> Self {
        Self::lanes(F::splat(v))
    }
    fn re(self) -> f64 {
        panic!("a lane dual has four values: branch lane by lane on `LaneDual::re`")
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let s = self.re.sqrt();
        self.apply(s, F::splat(0.5) / s)
    }
    fn sin(self) -> Self {
        panic!("LaneDual: no sin (not needed by the lane kernels)")
    }
    fn cos(self) -> Self {
        panic!("LaneDual: no cos (not needed by the lane kernels)")
    }
    fn exp(self) -> Self {
        panic!("LaneDual: no exp (not needed by the lane kernels)")
    }
    fn atan2(self, _x: Self) -> Self {
        panic!("LaneDual: no atan2 (not needed by the lane kernels)")
    }
}
