//! Dual numbers a + Σ bₖ εₖ with εⱼ εₖ = 0: arithmetic on them carries the first
//! derivatives with respect to N seeded inputs along with the value.

use super::Scalar;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Value `re` and its derivatives `eps[k]` = ∂/∂(input k).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const N: usize> {
    pub re: f64,
    pub eps: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// Input number `k`: value `re`, derivative 1 with respect to itself.
    pub fn variable(re: f64, k: usize) -> Self {
        let mut eps = [0.0; N];
        eps[k] = 1.0;
        Dual { re, eps }
    }

    /// The chain rule for a function with value `f` and derivative `df` at `self.re`.
    #[inline(always)]
    fn chain(self, f: f64, df: f64) -> Self {
        let mut eps = self.eps;
        for e in &mut eps {
            *e *= df;
        }
        Dual { re: f, eps }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        let mut eps = self.eps;
        for (e, b) in eps.iter_mut().zip(o.eps) {
            *e += b;
        }
        Dual {
            re: self.re + o.re,
            eps,
        }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        let mut eps = self.eps;
        for (e, b) in eps.iter_mut().zip(o.eps) {
            *e -= b;
        }
        Dual {
            re: self.re - o.re,
            eps,
        }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut eps = [0.0; N];
        for k in 0..N {
            eps[k] = self.eps[k] * o.re + self.re * o.eps[k];
        }
        Dual {
            re: self.re * o.re,
            eps,
        }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let re = self.re * inv;
        let mut eps = [0.0; N];
        for k in 0..N {
            eps[k] = (self.eps[k] - re * o.eps[k]) * inv;
        }
        Dual { re, eps }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.chain(-self.re, -1.0)
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: f64) -> Self {
        Dual {
            re: self.re + o,
            eps: self.eps,
        }
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: f64) -> Self {
        Dual {
            re: self.re - o,
            eps: self.eps,
        }
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: f64) -> Self {
        self.chain(self.re * o, o)
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: f64) -> Self {
        self * (1.0 / o)
    }
}

impl<const N: usize> Scalar for Dual<N> {
    fn cst(v: f64) -> Self {
        Dual {
            re: v,
            eps: [0.0; N],
        }
    }
    fn re(self) -> f64 {
        self.re
    }
    fn sqrt(self) -> Self {
        let s = self.re.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn sin(self) -> Self {
        self.chain(self.re.sin(), self.re.cos())
    }
    fn cos(self) -> Self {
        self.chain(self.re.cos(), -self.re.sin())
    }
    fn exp(self) -> Self {
        let e = self.re.exp();
        self.chain(e, e)
    }
    fn atan2(self, x: Self) -> Self {
        // d atan2(y, x) = (x dy − y dx)/(x² + y²)
        let r2 = self.re * self.re + x.re * x.re;
        let mut eps = [0.0; N];
        for k in 0..N {
            eps[k] = (x.re * self.eps[k] - self.re * x.eps[k]) / r2;
        }
        Dual {
            re: self.re.atan2(x.re),
            eps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Derivatives of a composite expression against the hand-derived ones.
    #[test]
    fn derivatives_of_a_composite_expression() {
        let x = Dual::<2>::variable(0.7, 0);
        let y = Dual::<2>::variable(-1.3, 1);
        // f = sin(x y) / sqrt(x² + y²) + atan2(y, x) · 3 − cos(x)
        let r = (x * x + y * y).sqrt();
        let f = (x * y).sin() / r + y.atan2(x) * 3.0 - x.cos();
        let (xv, yv) = (0.7f64, -1.3f64);
        let rv = (xv * xv + yv * yv).sqrt();
        let dfdx =
            (xv * yv).cos() * yv / rv - (xv * yv).sin() * xv / rv.powi(3) - 3.0 * yv / (rv * rv)
                + xv.sin();
        let dfdy =
            (xv * yv).cos() * xv / rv - (xv * yv).sin() * yv / rv.powi(3) + 3.0 * xv / (rv * rv);
        assert!((f.eps[0] - dfdx).abs() < 1e-14, "{} {}", f.eps[0], dfdx);
        assert!((f.eps[1] - dfdy).abs() < 1e-14, "{} {}", f.eps[1], dfdy);
    }
}
